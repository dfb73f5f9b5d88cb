"""The synthetic pattern source: a moving test card with the capture tick drawn in both eyes.

``pattern_image(tick, eye, width, height)`` is a pure function, so a client (or a test) can
rebuild the exact image of any pair from its sequence number, and ``read_tick(image)`` reads the
tick back from a received image, after JPEG and resizing too. Both eyes of a pair must read the
same tick.

The card: a smooth colour field with a checkerboard that slides right by TICK_SHIFT_PX per tick;
the right eye sees it shifted left by ``disparity_px(width)`` (a fronto-parallel scene at one
depth). Across the top, the tick as 32 black/white cells in two rows of 16, then the same two
rows inverted (a check that rejects misreads); below them "L 123" / "R 123" for people.

The source costs a known time per pair (``cost_ms``): each eye takes half, read out one after
the other and stamped when its read-out ends, so eye_skew is about cost_ms / 2.
"""

from __future__ import annotations

import functools
import time

import cv2
import numpy as np

from services.stereo_camera.calibration import unknown_calibration
from services.stereo_camera.source import LEFT, RIGHT, EyeFrame, SourceGeometry

CODE_BITS = 32
CODE_COLUMNS = 16  # cells per row; two data rows, then the two rows inverted
CODE_ROWS = 4
CODE_ROW_FRACTION = 1 / 20  # each code row is this fraction of the image height
TICK_SHIFT_PX = 3  # the card slides this far per tick
MIN_WIDTH_PX, MIN_HEIGHT_PX = 64, 48
DEFAULT_FPS = 30.0


def disparity_px(width_px: int) -> int:
    """How far left the right eye sees the card, in pixels."""
    return max(1, width_px // 32)


@functools.lru_cache(maxsize=8)
def _card(width_px: int, height_px: int) -> np.ndarray:
    """The static card (read-only), before sliding and the code band."""
    y, x = np.mgrid[0:height_px, 0:width_px].astype(np.float32)
    red = 40 + 180 * x / max(1, width_px - 1)
    green = 40 + 180 * y / max(1, height_px - 1)
    blue = 128 + 90 * np.sin(2 * np.pi * x / 53.0) * np.cos(2 * np.pi * y / 41.0)
    card = np.stack([red, green, blue], axis=-1)
    squares = ((x // 16 + y // 16) % 2 == 0)[..., None]
    card = np.where(squares, card * 0.6, card)
    card = np.clip(card, 0, 255).astype(np.uint8)
    card.setflags(write=False)
    return card


def _cell_edges(length: int, count: int) -> np.ndarray:
    return np.round(np.arange(count + 1) * length / count).astype(int)


def _code_geometry(width_px: int, height_px: int) -> tuple[np.ndarray, np.ndarray]:
    """Pixel edges of the code cells: x edges (CODE_COLUMNS + 1), y edges (CODE_ROWS + 1)."""
    row_height = height_px * CODE_ROW_FRACTION
    ys = np.round(np.arange(CODE_ROWS + 1) * row_height).astype(int)
    return _cell_edges(width_px, CODE_COLUMNS), ys


def _code_bits(tick: int) -> np.ndarray:
    value = tick % (1 << CODE_BITS)
    bits = np.array([(value >> i) & 1 for i in range(CODE_BITS)], dtype=bool)
    data = bits.reshape(2, CODE_COLUMNS)
    return np.vstack([data, ~data])


def pattern_image(tick: int, eye: str, width_px: int, height_px: int) -> np.ndarray:
    """The pattern source's `eye` image for capture tick `tick` (RGB8, height x width x 3)."""
    if eye not in (LEFT, RIGHT):
        raise ValueError(f"eye must be {LEFT!r} or {RIGHT!r}, not {eye!r}")
    shift = tick * TICK_SHIFT_PX - (disparity_px(width_px) if eye == RIGHT else 0)
    image = np.roll(_card(width_px, height_px), shift % width_px, axis=1)
    xs, ys = _code_geometry(width_px, height_px)
    for row, bits in enumerate(_code_bits(tick)):
        for column, bit in enumerate(bits):
            image[ys[row]:ys[row + 1], xs[column]:xs[column + 1]] = 255 if bit else 0
    label = f"{'L' if eye == LEFT else 'R'} {tick}"
    scale = height_px / 240
    origin = (max(2, width_px // 40), int(ys[-1] + 26 * scale) + 2)
    thickness = max(1, round(2 * scale))
    cv2.putText(image, label, origin, cv2.FONT_HERSHEY_SIMPLEX, scale, (0, 0, 0),
                thickness + 2, cv2.LINE_AA)
    cv2.putText(image, label, origin, cv2.FONT_HERSHEY_SIMPLEX, scale, (255, 255, 255),
                thickness, cv2.LINE_AA)
    return image


def read_tick(image: np.ndarray) -> int | None:
    """The tick drawn in a pattern image (RGB or BGR, any size it was resized to, JPEG is fine);
    None when the code band does not read back consistently."""
    height, width = image.shape[:2]
    xs, ys = _code_geometry(width, height)
    gray = image.mean(axis=2) if image.ndim == 3 else image.astype(float)
    bits = np.zeros((CODE_ROWS, CODE_COLUMNS), dtype=bool)
    for row in range(CODE_ROWS):
        top, bottom = ys[row], ys[row + 1]
        inset_y = (bottom - top) // 4
        for column in range(CODE_COLUMNS):
            left, right = xs[column], xs[column + 1]
            inset_x = (right - left) // 4
            cell = gray[top + inset_y:bottom - inset_y, left + inset_x:right - inset_x]
            bits[row, column] = cell.size > 0 and cell.mean() > 127
    if not np.array_equal(bits[2:], ~bits[:2]):
        return None
    flat = bits[:2].reshape(CODE_BITS)
    return int(sum(1 << i for i, bit in enumerate(flat) if bit))


class PatternSource:
    """Synthetic stereo cameras; triggered on demand (see the module docstring)."""

    live = False

    def __init__(self, width_px: int = 640, height_px: int = 480, fps: float = DEFAULT_FPS,
                 cost_ms: float = 0.0):
        if width_px < MIN_WIDTH_PX or height_px < MIN_HEIGHT_PX:
            raise ValueError(f"the pattern needs at least {MIN_WIDTH_PX}x{MIN_HEIGHT_PX} pixels, "
                             f"got {width_px}x{height_px}")
        if not fps > 0 or cost_ms < 0:
            raise ValueError(f"the pattern needs fps > 0 and cost_ms >= 0, got {fps}, {cost_ms}")
        self.width_px, self.height_px = width_px, height_px
        self.cost_s = cost_ms / 1000.0
        self.geometry = SourceGeometry(width_px, height_px,
                                       unknown_calibration(width_px, height_px), fps, "pattern")

    def open(self) -> SourceGeometry:
        return self.geometry

    def grab(self, tick: int) -> tuple[EyeFrame, EyeFrame]:
        frames = []
        start = time.perf_counter()
        for index, eye in enumerate((LEFT, RIGHT)):
            image = pattern_image(tick, eye, self.width_px, self.height_px)
            _sleep_until(start + (index + 1) * self.cost_s / 2)  # this eye's read-out
            frames.append(EyeFrame(tick, image, time.time_ns()))
        return frames[0], frames[1]

    def close(self) -> None:
        pass


def _sleep_until(deadline: float) -> None:
    remaining = deadline - time.perf_counter()
    if remaining > 0:
        time.sleep(remaining)
