"""The camera identification survives a restart: saved to JSON, loaded by a fresh process."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from clients.ar.identification import ProjectionKind, frame_points, identify_stereo
from clients.ar.persistence import (
    IdentificationFileError,
    load_identification,
    load_if_present,
    save_identification,
)
from tests.ar.helpers import HEIGHT, WIDTH, perspective

REPO = Path(__file__).resolve().parents[2]
LEFT = perspective((1.40, -0.21, 0.90), (0.645, -0.21, 0.40))
RIGHT = perspective((1.40, -0.09, 0.90), (0.645, -0.09, 0.40))
POINTS = np.array([[0.45, -0.4, 0.25], [0.85, -0.4, 0.25], [0.45, 0.1, 0.25], [0.85, 0.1, 0.25],
                   [0.6, -0.2, 0.7], [0.7, 0.0, 0.5], [0.5, -0.3, 0.45], [0.8, -0.1, 0.6]])
PROBES = np.random.default_rng(0).uniform([0.45, -0.4, 0.25], [0.85, 0.1, 0.7], (50, 3))


def _identification(kind: str = "perspective"):
    points = POINTS if kind == "perspective" else frame_points((0.6, -0.2, 0.3), 0.2)
    rng = np.random.default_rng(1)
    return identify_stereo(points, LEFT.project(points) + rng.normal(0, 0.3, (len(points), 2)),
                           RIGHT.project(points) + rng.normal(0, 0.3, (len(points), 2)),
                           WIDTH, HEIGHT, kind=kind, source="sim")


@pytest.mark.parametrize("kind", ["perspective", "affine"])
def test_a_saved_identification_projects_identically_after_loading(tmp_path, kind):
    saved = _identification(kind)
    path = save_identification(saved, tmp_path / "cameras.json")
    loaded = load_identification(path, WIDTH, HEIGHT)
    assert loaded.kind is ProjectionKind(kind)
    assert (loaded.width_px, loaded.height_px, loaded.source) == (WIDTH, HEIGHT, "sim")
    assert loaded.created_utc == saved.created_utc
    for before, after in ((saved.left, loaded.left), (saved.right, loaded.right)):
        np.testing.assert_array_equal(after.projection.matrix, before.projection.matrix)
        np.testing.assert_array_equal(after.projection.project(PROBES),
                                      before.projection.project(PROBES))
        np.testing.assert_array_equal(after.points_m, before.points_m)
        np.testing.assert_array_equal(after.pixels_px, before.pixels_px)
    assert not [p for p in tmp_path.iterdir() if p.name != "cameras.json"]  # no temp files


@pytest.mark.e2e
def test_a_fresh_process_loads_the_same_projections(tmp_path):
    saved = _identification()
    path = save_identification(saved, tmp_path / "cameras.json")
    np.save(tmp_path / "probes.npy", PROBES)
    script = (
        "import sys, numpy as np\n"
        "from clients.ar import load_identification\n"
        f"ident = load_identification(sys.argv[1], {WIDTH}, {HEIGHT})\n"
        "probes = np.load(sys.argv[2])\n"
        "np.save(sys.argv[3], np.stack([ident.left.projection.project(probes),\n"
        "                               ident.right.projection.project(probes)]))\n")
    out = tmp_path / "pixels.npy"
    subprocess.run([sys.executable, "-c", script, str(path), str(tmp_path / "probes.npy"),
                    str(out)], cwd=REPO, check=True, timeout=60)
    pixels = np.load(out)
    np.testing.assert_array_equal(pixels[0], saved.left.projection.project(PROBES))
    np.testing.assert_array_equal(pixels[1], saved.right.projection.project(PROBES))


def test_no_file_yet_means_identify_first(tmp_path):
    assert load_if_present(tmp_path / "cameras.json") is None
    with pytest.raises(IdentificationFileError, match="identify the cameras first"):
        load_identification(tmp_path / "cameras.json")


def test_a_file_for_other_images_is_refused(tmp_path):
    path = save_identification(_identification(), tmp_path / "cameras.json")
    with pytest.raises(IdentificationFileError, match=r"made for 640x480 images, but the images "
                                                      r"are 320x240: identify the cameras again"):
        load_identification(path, 320, 240)
    # the same cameras at half resolution, rescaled on purpose: pixel centres scale about
    # the image corner (u' = (u + 0.5) / 2 - 0.5)
    full = load_identification(path)
    half = full.for_size(320, 240)
    assert (half.width_px, half.height_px) == (320, 240)
    np.testing.assert_allclose(half.left.projection.project(PROBES),
                               (full.left.projection.project(PROBES) + 0.5) / 2 - 0.5, atol=1e-9)


def _corrupt(path: Path, edit) -> None:
    document = json.loads(path.read_text())
    edit(document)
    path.write_text(json.dumps(document))


@pytest.mark.parametrize("edit, message", [
    (lambda d: d.update(format="something else"), "format"),
    (lambda d: d.update(version=2), "version 2 is not supported"),
    (lambda d: d.update(model="fisheye"), "neither 'affine' nor 'perspective'"),
    (lambda d: d["left"].update(projection=[1.0] * 11), "left.projection has 11 values"),
    (lambda d: d["right"].update(projection=["x"] * 12), "right.projection must hold finite"),
    (lambda d: d["left"].pop("projection"), "missing 'projection'"),
    (lambda d: d["image"].update(width_px=-3), "image size"),
    (lambda d: d["left"].update(pixels_px=[[1.0, 2.0]]), "points_m and left.pixels_px"),
])
def test_a_corrupt_file_gets_a_clear_error(tmp_path, edit, message):
    path = save_identification(_identification(), tmp_path / "cameras.json")
    _corrupt(path, edit)
    with pytest.raises(IdentificationFileError, match=message) as raised:
        load_identification(path)
    assert str(path) in str(raised.value) and "identify the cameras again" in str(raised.value)


def test_a_truncated_file_gets_a_clear_error(tmp_path):
    path = save_identification(_identification(), tmp_path / "cameras.json")
    path.write_text(path.read_text()[:100])
    with pytest.raises(IdentificationFileError, match="is corrupt \\(not JSON"):
        load_identification(path)


def test_an_affine_file_whose_matrix_is_not_affine_is_refused(tmp_path):
    path = save_identification(_identification("affine"), tmp_path / "cameras.json")
    _corrupt(path, lambda d: d["left"].update(projection=[1.0] * 12))
    with pytest.raises(IdentificationFileError, match="third row must be"):
        load_identification(path)
