"""Known pinhole cameras for the AR tests (conventions of services/stereo_camera/calibration)."""

from __future__ import annotations

import numpy as np

from clients.ar.identification import CameraProjection, ProjectionKind

# A 640x480 camera with the sim rig's 45-degree vertical field of view.
WIDTH, HEIGHT = 640, 480
FOCAL_PX = 0.5 * HEIGHT / np.tan(np.radians(22.5))  # 579.4


def look_at(eye, target, focal_px: float = FOCAL_PX, width: int = WIDTH, height: int = HEIGHT,
            up=(0.0, 0.0, 1.0)) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(P, K, R) of a camera at `eye` looking at `target`: x right, y down, z forward; R's
    columns are the camera axes in the world."""
    eye = np.asarray(eye, float)
    z = np.subtract(target, eye)
    z /= np.linalg.norm(z)
    x = np.cross(z, up)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    rotation = np.column_stack([x, y, z])
    k = np.array([[focal_px, 0.0, (width - 1) / 2], [0.0, focal_px, (height - 1) / 2],
                  [0.0, 0.0, 1.0]])
    return k @ np.hstack([rotation.T, (-rotation.T @ eye)[:, None]]), k, rotation


def perspective(eye, target, **kwargs) -> CameraProjection:
    return CameraProjection(ProjectionKind.PERSPECTIVE, look_at(eye, target, **kwargs)[0])


def in_image(pixels: np.ndarray, width: int = WIDTH, height: int = HEIGHT) -> np.ndarray:
    return ((pixels[:, 0] >= 0) & (pixels[:, 0] <= width - 1) & (pixels[:, 1] >= 0)
            & (pixels[:, 1] <= height - 1))
