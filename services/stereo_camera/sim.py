"""The simulated stereo rig: the work cell's two MuJoCo cameras, rendered at the arm's live pose.

``SimSource`` renders the scene cameras ``left_eye`` and ``right_eye`` (robot_model/workspace.py)
with mujoco.Renderer. Each tick reads the arm's joint positions from a callable (in the service,
``WorldJoints``: the world process's shared memory), poses the model, and renders both eyes
from that one state: the two virtual shutters are perfectly synchronized, so both eyes carry the
time the state was read and eye_skew is zero.

The renderer is created, used and closed on the capture thread only (it owns the GL context).
Offscreen rendering needs MUJOCO_GL=egl (or osmesa) in the environment before mujoco is
imported; the package sets egl unless told otherwise.

Cost (Mesa's software EGL, no GPU, a shared 2-core AMD EPYC VM under load; 640x480, both eyes,
timed around ``grab`` in three back-to-back rounds): the defaults, no shadows and no
multisampling, render a pair in 19-28 ms at p50 (35-47 pairs/s). MuJoCo's own settings, the
directional light's shadow with a 4096² map and 4x multisampling, took 190-375 ms (2.4-5
pairs/s). Either one alone is costly: 4x multisampling without shadows about 45 ms a pair
(~20 pairs/s); shadows with the default 1024² map 55-110 ms (9-18 pairs/s), with a 4096² map
140-235 ms. The shadow's extra passes, not the pixels, dominate: a smaller map or image helps
little. ``shadows=True`` and ``multisamples=4`` buy looks for rate; a GPU (EGL on a real driver)
makes every setting a few milliseconds.
"""

from __future__ import annotations

import logging
import os
import sys
import threading
import time
from collections.abc import Callable

import mujoco
import mujoco.gl_context as mujoco_gl_context
import numpy as np

from domain.robot_model.loader import load_mujoco_model, mujoco_ids
from services.stereo_camera.calibration import mujoco_stereo
from services.stereo_camera.render_scale import RenderScaler
from services.stereo_camera.source import EyeFrame, SourceGeometry
from services.world.shm_link import SharedMemoryArmLink
from wire.errors import FailedPreconditionError, UnavailableError

log = logging.getLogger(__name__)

DEFAULT_FPS = 30.0  # a cap on the pairs per second
# The defaults favour the rate on software rendering (see the module docstring): no shadows, no
# multisampling, and a modest shadow map for when shadows are asked for.
DEFAULT_SHADOW_MAP_PX = 1024
DEFAULT_MULTISAMPLES = 0

JointSource = Callable[[], np.ndarray]


def home_joints(model: mujoco.MjModel | None = None) -> np.ndarray:
    """Joint positions (rad) of the model's ``home`` keyframe: a fixed pose for demos and
    benchmarks without a world."""
    model = model if model is not None else load_mujoco_model()
    ids = mujoco_ids(model)
    return model.key_qpos[ids.home_key][ids.qpos].copy()


def gl_backend_problem() -> str | None:
    """Why offscreen rendering cannot work in this process, or None. MuJoCo picks its GL
    backend from MUJOCO_GL when it is first imported; GLFW without a display aborts the whole
    process when a context is made, so it is refused here instead."""
    backend = getattr(mujoco_gl_context, "GLContext", None)
    module = getattr(backend, "__module__", "")
    if backend is None:
        return "MuJoCo has no OpenGL backend here (MUJOCO_GL=disable?)"
    headless = not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))
    if module.endswith("glfw") and headless and sys.platform.startswith("linux"):
        return ("mujoco was imported with GLFW as its OpenGL backend and there is no display; "
                "start the process with MUJOCO_GL=egl (or osmesa)")
    return None


class SimSource:
    """The scene's stereo cameras at the joint positions `joints()` returns (rad, 6 values).

    `joints` may raise UnavailableError (the world is not running); the pair is then not rendered
    and the error reaches the clients. Not live: a tick is rendered when one is wanted.
    """

    live = False

    def __init__(self, joints: JointSource, width_px: int = 640, height_px: int = 480,
                 fps: float = DEFAULT_FPS, shadows: bool = False,
                 model: mujoco.MjModel | None = None,
                 shadow_map_px: int = DEFAULT_SHADOW_MAP_PX,
                 multisamples: int = DEFAULT_MULTISAMPLES,
                 render_scale: float | None = 1.0):
        if width_px < 1 or height_px < 1 or not fps > 0:
            raise ValueError(f"the sim cameras need a positive size and fps, got "
                             f"{width_px}x{height_px} at {fps}")
        if shadow_map_px < 1 or multisamples < 0:
            raise ValueError(f"the sim cameras need a positive shadow map and no negative "
                             f"multisampling, got {shadow_map_px} and {multisamples}")
        self._joints = joints
        self._model = model if model is not None else load_mujoco_model()
        self._ids = mujoco_ids(self._model)
        self._shadows = shadows
        self._shadow_map_px = shadow_map_px
        self._multisamples = multisamples
        self._data = mujoco.MjData(self._model)
        mujoco.mj_resetDataKeyframe(self._model, self._data, self._ids.home_key)
        mujoco.mj_kinematics(self._model, self._data)
        mujoco.mj_camlight(self._model, self._data)
        calibration = mujoco_stereo(self._model, self._data, self._ids.left_camera,
                                    self._ids.right_camera, width_px, height_px)
        self.geometry = SourceGeometry(width_px, height_px, calibration, fps, "sim")
        # a number from render_scale.LADDER fixes the scale; None makes it follow the render's
        # cost (render_scale.py)
        self._scaler = RenderScaler(1.0 / fps, fixed=render_scale)
        self._renderers: dict[float, mujoco.Renderer] = {}  # by scale, made as first needed
        self._opened = False

    def open(self) -> SourceGeometry:
        if not self._opened:
            problem = gl_backend_problem()
            if problem:
                raise FailedPreconditionError(f"cannot render the sim cameras: {problem}",
                                              reason="RENDERER_UNAVAILABLE")
            global_ = self._model.vis.global_
            global_.offwidth = max(int(global_.offwidth), self.geometry.width_px)
            global_.offheight = max(int(global_.offheight), self.geometry.height_px)
            quality = self._model.vis.quality  # read when a GL context is made (_renderer)
            quality.shadowsize = self._shadow_map_px
            quality.offsamples = self._multisamples
            self._renderer(self._scaler.scale)  # fails here, not at the first grab
            self._opened = True
        return self.geometry

    @property
    def render_scale(self) -> float:
        """The scale the next pair is rendered at."""
        return self._scaler.scale

    def _renderer(self, scale: float) -> mujoco.Renderer:
        """The renderer for `scale` of the full size (each has its own GL context)."""
        renderer = self._renderers.get(scale)
        if renderer is None:
            width = max(1, round(self.geometry.width_px * scale))
            height = max(1, round(self.geometry.height_px * scale))
            try:
                renderer = mujoco.Renderer(self._model, height, width)
            except Exception as exc:  # mujoco.FatalError, GL errors: no usable context
                raise FailedPreconditionError(
                    f"cannot create an offscreen OpenGL context for the sim cameras: {exc}. "
                    "Set MUJOCO_GL=egl (or osmesa) before the process starts",
                    reason="RENDERER_UNAVAILABLE") from None
            renderer.scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = self._shadows
            self._renderers[scale] = renderer
        return renderer

    def grab(self, tick: int) -> tuple[EyeFrame, EyeFrame]:
        if not self._opened:
            raise UnavailableError("the sim cameras are not open", reason="SOURCE_CLOSED")
        q = np.asarray(self._joints(), dtype=float)
        state_time_ns = time.time_ns()
        if q.shape != self._ids.qpos.shape or not np.isfinite(q).all():
            raise UnavailableError(f"the world sent joint positions that cannot be rendered: {q!r}",
                                   reason="BAD_JOINT_STATE")
        self._data.qpos[self._ids.qpos] = q
        mujoco.mj_kinematics(self._model, self._data)
        mujoco.mj_camlight(self._model, self._data)
        scale = self._scaler.scale
        renderer = self._renderer(scale)
        started = time.perf_counter()
        frames = []
        for camera in (self._ids.left_camera, self._ids.right_camera):
            renderer.update_scene(self._data, camera=camera)
            frames.append(EyeFrame(tick, renderer.render(), state_time_ns, scale))
        render_s = time.perf_counter() - started
        if self._scaler.observe(render_s, time.monotonic()) != scale:
            log.info("rendering at %g of %dx%d from the next pair: a pair took %.1f ms at %g, "
                     "its frame interval is %.1f ms", self._scaler.scale,
                     self.geometry.width_px, self.geometry.height_px, render_s * 1e3, scale,
                     1e3 / self.geometry.rate_hz)
        return frames[0], frames[1]

    def close(self) -> None:
        renderers, self._renderers = self._renderers, {}
        self._opened = False
        for renderer in renderers.values():
            renderer.close()


class WorldJoints:
    """Joint positions of the simulated arm, read from the world process's shared memory.

    Attaches on first use and again after the world restarts; UnavailableError (naming what to do)
    while no world is running. Read-only use of SharedMemoryArmLink: it never commands.
    """

    def __init__(self, shm_name: str | None = None):
        self._shm_name = shm_name
        self._lock = threading.Lock()
        self._link: SharedMemoryArmLink | None = None

    def __call__(self) -> np.ndarray:
        with self._lock:
            if self._link is None:
                self._link = SharedMemoryArmLink(self._shm_name)  # UnavailableError: no world
            try:
                return self._link.read_arm().joint_positions_rad
            except UnavailableError:
                self._link.close()
                self._link: SharedMemoryArmLink | None = None
                raise

    def close(self) -> None:
        with self._lock:
            link, self._link = self._link, None
        if link is not None:
            link.close()
