"""Remembering the camera identification across runs (section IV-B of the full paper).

The identification is saved to a JSON file and loaded on the next run, so the operator points at
the reference frame again only after a camera moves. The file (version 1):

    {
      "format": "telerobot.ar.camera_identification",
      "version": 1,
      "model": "affine" | "perspective",        # both eyes use the same model
      "image": {"width_px": 640, "height_px": 480},   # the images the pixels refer to
      "created_utc": "2024-05-01T12:00:00+00:00",    # when the cameras were identified
      "saved_utc": "...",
      "source": "sim",                          # the stream header's source, for people
      "left":  {"projection": [12 values, row-major 3x4],
                "points_m": [[x, y, z], ...],   # the reference points used (base frame)
                "pixels_px": [[u, v], ...],     # where the operator saw them in this eye
                "rms_error_px": 0.12},          # informative; recomputed on load
      "right": { ... }
    }

Floats are written with Python's repr, so a loaded identification projects exactly as the saved
one did. Writes go to a temporary file renamed over the old one: a crash never leaves half a
file. A file that cannot be used raises IdentificationFileError naming the file and the fix.
"""

from __future__ import annotations

import datetime
import json
import math
from pathlib import Path

import numpy as np

from clients.ar.identification import (
    CameraProjection,
    EyeIdentification,
    ProjectionKind,
    StereoIdentification,
)
from wire.files import replace_file

FORMAT = "telerobot.ar.camera_identification"
VERSION = 1


class IdentificationFileError(ValueError):
    """The identification file is missing, corrupt, or for other images."""


def save_identification(identification: StereoIdentification, path: Path | str) -> Path:
    """Write `identification` to `path` (atomically); returns the path."""
    path = Path(path)
    document = {
        "format": FORMAT,
        "version": VERSION,
        "model": identification.kind.value,
        "image": {"width_px": identification.width_px, "height_px": identification.height_px},
        "created_utc": identification.created_utc,
        "saved_utc": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "source": identification.source,
        "left": _eye_document(identification.left),
        "right": _eye_document(identification.right),
    }
    text = json.dumps(document, indent=2) + "\n"
    path.parent.mkdir(parents=True, exist_ok=True)
    replace_file(path, text.encode("utf-8"))
    return path


def load_identification(path: Path | str, width_px: int | None = None,
                        height_px: int | None = None) -> StereoIdentification:
    """The identification saved at `path`. With width_px and height_px, the images it was made
    for must have that size (a different size means other pixels: identify again, or rescale
    explicitly with `for_size` if the same cameras only changed resolution)."""
    path = Path(path)
    try:
        text = path.read_text()
    except FileNotFoundError:
        raise IdentificationFileError(
            f"no camera identification at {path}: identify the cameras first") from None
    except OSError as exc:
        raise IdentificationFileError(f"cannot read the camera identification {path}: "
                                      f"{exc}") from None
    try:
        document = json.loads(text)
    except ValueError as exc:
        raise IdentificationFileError(
            f"the camera identification {path} is corrupt (not JSON: {exc}); delete it and "
            "identify the cameras again") from None
    try:
        identification = _parse(document)
    except (ValueError, TypeError, KeyError) as exc:
        detail = f"missing {exc}" if isinstance(exc, KeyError) else str(exc)
        raise IdentificationFileError(
            f"the camera identification {path} is not valid ({detail}); delete it and "
            "identify the cameras again") from None
    if width_px is not None and height_px is not None and (
            (identification.width_px, identification.height_px) != (width_px, height_px)):
        raise IdentificationFileError(
            f"the camera identification {path} was made for {identification.width_px}x"
            f"{identification.height_px} images, but the images are {width_px}x{height_px}: "
            "identify the cameras again (or rescale it with for_size if only the resolution "
            "changed)")
    return identification


def load_if_present(path: Path | str, width_px: int | None = None,
                    height_px: int | None = None) -> StereoIdentification | None:
    """As load_identification, but None when no file exists yet (the first run)."""
    if not Path(path).exists():
        return None
    return load_identification(path, width_px, height_px)


# -- document ------------------------------------------------------------------------------------


def _eye_document(eye: EyeIdentification) -> dict:
    return {
        "projection": eye.projection.matrix.reshape(12).tolist(),
        "points_m": eye.points_m.tolist(),
        "pixels_px": eye.pixels_px.tolist(),
        "rms_error_px": eye.rms_error_px,
    }


def _parse(document) -> StereoIdentification:
    if not isinstance(document, dict):
        raise ValueError("the document is not a JSON object")
    if document.get("format") != FORMAT:
        raise ValueError(f"format is {document.get('format')!r}, expected {FORMAT!r}")
    version = document.get("version")
    if version != VERSION:
        raise ValueError(f"version {version!r} is not supported (this program reads "
                         f"version {VERSION})")
    try:
        kind = ProjectionKind(document["model"])
    except ValueError:
        raise ValueError(f"model {document['model']!r} is neither 'affine' nor "
                         "'perspective'") from None
    image = document["image"]
    width, height = image["width_px"], image["height_px"]
    if not (isinstance(width, int) and isinstance(height, int) and width > 0 and height > 0):
        raise ValueError(f"image size {width!r}x{height!r} is not two positive integers")
    eyes = [_parse_eye(document[name], name, kind) for name in ("left", "right")]
    return StereoIdentification(eyes[0], eyes[1], width, height,
                                str(document.get("created_utc", "")),
                                str(document.get("source", "")))


def _parse_eye(entry, name: str, kind: ProjectionKind) -> EyeIdentification:
    if not isinstance(entry, dict):
        raise ValueError(f"{name} is not an object")
    values = _numbers(entry["projection"], f"{name}.projection")
    if values.shape != (12,):
        raise ValueError(f"{name}.projection has {values.size} values, expected 12")
    try:
        projection = CameraProjection(kind, values.reshape(3, 4))
    except ValueError as exc:
        raise ValueError(f"{name}.projection: {exc}") from None
    points = _numbers(entry.get("points_m", []), f"{name}.points_m")
    pixels = _numbers(entry.get("pixels_px", []), f"{name}.pixels_px")
    if points.size % 3 or pixels.size % 2 or points.size // 3 != pixels.size // 2:
        raise ValueError(f"{name}.points_m and {name}.pixels_px must be N [x, y, z] and N "
                         "[u, v]")
    return EyeIdentification(projection, points.reshape(-1, 3), pixels.reshape(-1, 2))


def _numbers(value, what: str) -> np.ndarray:
    flat = np.asarray(value, dtype=object).reshape(-1)
    if not all(isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)
               for v in flat):
        raise ValueError(f"{what} must hold finite numbers only")
    return flat.astype(float)
