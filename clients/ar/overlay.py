"""The AR overlay: a ball at the gripper in both eyes, and the side-by-side stereo frame.

Section IV-B of the full paper: DXInterface "projects a ball at the gripper position in 2D image
and sends both images to HMD display controller", drawing into a back buffer and flipping so a
frame is never shown half drawn. Here:

- `StereoOverlay` projects a world point (the RobotModel's tool point) with each eye's identified
  projection and draws a filled ball with an outline in each image (RGB8 numpy arrays,
  (height, width, 3)). The ball's radius is its physical radius times the projection's local
  scale (`CameraProjection.pixels_per_metre`): with a perspective model it grows as the tool
  comes nearer; with the affine model it is constant (weak perspective has one scale).
- `SideBySideComposer` puts left | right into one frame (height, 2 * width, 3), the double-
  buffered stereo display's page; a video writer (cv2.VideoWriter wants BGR: `bgr=True`) or a
  side-by-side HMD consumes it.

Pixels: (0, 0) is the centre of the top-left pixel (as in identification). Balls are drawn with
cv2 at 1/16 pixel precision, antialiased.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from clients.ar.identification import CameraProjection, StereoIdentification

_SHIFT = 4  # cv2 fractional bits: coordinates in 1/16 pixel
_ONE = 1 << _SHIFT


@dataclass(frozen=True)
class BallStyle:
    """How the gripper ball looks. Colours are RGB."""

    radius_m: float = 0.015  # physical radius: the on-screen radius follows the depth
    fill_rgb: tuple[int, int, int] = (255, 60, 200)
    outline_rgb: tuple[int, int, int] = (255, 255, 255)
    outline_px: int = 1
    min_radius_px: float = 2.0  # always visible...
    max_radius_px: float = 200.0  # ...and never the whole screen


@dataclass(frozen=True)
class EyeBall:
    """Where the ball goes in one eye."""

    centre_px: np.ndarray  # (u, v)
    radius_px: float
    inside: bool  # the centre falls within the image


def locate_ball(projection: CameraProjection, point_m, style: BallStyle, width_px: int,
                height_px: int) -> EyeBall | None:
    """The ball of `style` at world point `point_m` in one eye; None when the point has no image
    (behind the camera)."""
    point = np.asarray(point_m, float).reshape(3)
    centre = projection.project(point)
    if not np.isfinite(centre).all():
        return None
    radius = style.radius_m * projection.pixels_per_metre(point)
    radius = float(np.clip(radius, style.min_radius_px, style.max_radius_px))
    inside = bool(-0.5 <= centre[0] < width_px - 0.5 and -0.5 <= centre[1] < height_px - 0.5)
    return EyeBall(centre, radius, inside)


def draw_ball(image: np.ndarray, ball: EyeBall, style: BallStyle = BallStyle()) -> np.ndarray:
    """Draw `ball` into `image` (RGB8, in place; returns it). A ball partly or wholly outside the
    image is clipped."""
    _check_image(image, "image")
    centre = tuple(int(round(c * _ONE)) for c in ball.centre_px)
    if max(abs(c) for c in centre) > (1 << 30):  # far off-screen: nothing to draw
        return image
    radius = int(round(ball.radius_px * _ONE))
    cv2.circle(image, centre, radius, style.fill_rgb, thickness=-1, lineType=cv2.LINE_AA,
               shift=_SHIFT)
    if style.outline_px > 0:
        cv2.circle(image, centre, radius, style.outline_rgb, thickness=style.outline_px,
                   lineType=cv2.LINE_AA, shift=_SHIFT)
    return image


@dataclass(frozen=True)
class StereoBall:
    """The ball in both eyes (None for an eye that cannot see the point)."""

    left: EyeBall | None
    right: EyeBall | None


class StereoOverlay:
    """Draws the gripper ball into stereo pairs with the two identified projections."""

    def __init__(self, left: CameraProjection, right: CameraProjection,
                 style: BallStyle = BallStyle()):
        self.left = left
        self.right = right
        self.style = style

    @classmethod
    def from_identification(cls, identification: StereoIdentification,
                            style: BallStyle = BallStyle()) -> StereoOverlay:
        return cls(identification.left.projection, identification.right.projection, style)

    def locate(self, point_m, width_px: int, height_px: int) -> StereoBall:
        return StereoBall(locate_ball(self.left, point_m, self.style, width_px, height_px),
                          locate_ball(self.right, point_m, self.style, width_px, height_px))

    def draw(self, left_image: np.ndarray, right_image: np.ndarray, point_m,
             copy: bool = True) -> tuple[np.ndarray, np.ndarray, StereoBall]:
        """Both images with the ball at `point_m` (copies unless `copy` is False), and where it
        went."""
        _check_image(left_image, "left image")
        _check_image(right_image, "right image")
        if left_image.shape != right_image.shape:
            raise ValueError(f"the eyes differ in size: {left_image.shape} and "
                             f"{right_image.shape}")
        height, width = left_image.shape[:2]
        if copy:
            left_image, right_image = left_image.copy(), right_image.copy()
        balls = self.locate(point_m, width, height)
        for image, ball in ((left_image, balls.left), (right_image, balls.right)):
            if ball is not None:
                draw_ball(image, ball, self.style)
        return left_image, right_image, balls


def side_by_side(left_image: np.ndarray, right_image: np.ndarray,
                 out: np.ndarray | None = None, bgr: bool = False) -> np.ndarray:
    """left | right in one (height, 2 * width, 3) uint8 frame (into `out` when given). With
    `bgr` the channels are swapped for cv2.VideoWriter / imwrite."""
    _check_image(left_image, "left image")
    _check_image(right_image, "right image")
    if left_image.shape != right_image.shape:
        raise ValueError(f"the eyes differ in size: {left_image.shape} and {right_image.shape}")
    height, width = left_image.shape[:2]
    if out is None:
        out = np.empty((height, 2 * width, 3), np.uint8)
    elif out.shape != (height, 2 * width, 3) or out.dtype != np.uint8:
        raise ValueError(f"the frame must be ({height}, {2 * width}, 3) uint8, got {out.shape} "
                         f"{out.dtype}")
    channels = slice(None, None, -1) if bgr else slice(None)
    out[:, :width] = left_image[:, :, channels]
    out[:, width:] = right_image[:, :, channels]
    return out


class SideBySideComposer:
    """Two preallocated side-by-side pages, written alternately (the paper's back buffer and
    flip). `compose` fills the back page and makes it the front one: the frame it returns stays
    intact until the next-but-one call, so a consumer (a video writer, a display thread) may
    read it while the next frame is being composed."""

    def __init__(self, width_px: int, height_px: int, bgr: bool = False):
        if width_px < 1 or height_px < 1:
            raise ValueError("the eyes need a positive size")
        self.width_px = width_px
        self.height_px = height_px
        self.bgr = bgr
        self._pages = [np.zeros((height_px, 2 * width_px, 3), np.uint8) for _ in range(2)]
        self._front = 1
        self.frames = 0

    @property
    def frame_size(self) -> tuple[int, int]:
        """(width, height) of a composed frame, as cv2.VideoWriter takes it."""
        return 2 * self.width_px, self.height_px

    @property
    def front(self) -> np.ndarray:
        """The page composed last (shown now)."""
        return self._pages[self._front]

    def compose(self, left_image: np.ndarray, right_image: np.ndarray) -> np.ndarray:
        if left_image.shape[:2] != (self.height_px, self.width_px):
            raise ValueError(f"this composer takes {self.width_px}x{self.height_px} eyes, got "
                             f"{left_image.shape[1]}x{left_image.shape[0]}")
        back = 1 - self._front
        side_by_side(left_image, right_image, out=self._pages[back], bgr=self.bgr)
        self._front = back
        self.frames += 1
        return self._pages[back]


def _check_image(image: np.ndarray, what: str) -> None:
    if not (isinstance(image, np.ndarray) and image.ndim == 3 and image.shape[2] == 3
            and image.dtype == np.uint8):
        raise ValueError(f"the {what} must be an RGB8 array (height, width, 3) uint8")
