"""An arm as its description file declares it, and which arm this station drives.

Everything the station needs to know of an arm comes from its ``arm.xml``: the joints in chain
order, their limits, velocity bounds (a ``max_joint_velocity`` custom numeric, since MJCF has no
velocity limit) and torque bounds (each joint's motor ``ctrlrange``), the flange, tool and wrist
sensor sites, and the ``home`` keyframe. A file that lacks one of them, or gives a bad limit, is
refused when it is read, with the element named, so a station never starts on a broken arm.

The arm is chosen once per station: ``$TELEROBOT_ARM`` (``make serve ARM=…`` and every service's
``--arm`` set it), ``puma560`` when unset. Child processes inherit it.
"""

from __future__ import annotations

import functools
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from domain.robot_model import names as n
from domain.robot_model.model_files import (
    ARM_FILE,
    ARMS_DIR,
    DEFAULT_ARM,
    arm_xml_path,
    scene_xml_path,
)

ARM_ENV = "TELEROBOT_ARM"
MAX_JOINTS = 8  # the most any arm file may declare (the world's shared memory has room for this)


class ArmDescriptionError(ValueError):
    """A description file that the station cannot drive an arm from; the message names why."""


class UnknownArmError(ValueError):
    """An arm name with no description file; the message lists the arms there are."""


@dataclass(frozen=True)
class ArmDescription:
    """One arm: names, bounds and poses, all in the file's joint order (rad, rad/s, N*m)."""

    name: str
    arm_xml: Path
    scene_xml: Path
    joint_names: tuple[str, ...]
    actuator_names: tuple[str, ...]
    lower: np.ndarray
    upper: np.ndarray
    max_velocity: np.ndarray
    max_torque: np.ndarray
    home_q: np.ndarray
    flange_T_tool: np.ndarray  # 4x4, the tool_point site in the flange site's frame

    @property
    def joint_count(self) -> int:
        return len(self.joint_names)


def available_arms() -> tuple[str, ...]:
    """Every arm with a description file, by name."""
    return tuple(sorted(d.name for d in ARMS_DIR.iterdir() if (d / ARM_FILE).is_file()))


def selected_arm_name() -> str:
    """The arm this process drives: ``$TELEROBOT_ARM``, else the default."""
    return os.environ.get(ARM_ENV) or DEFAULT_ARM


def select_arm(name: str, read: bool = True) -> None:
    """Make ``name`` this process's arm (and its children's); UnknownArmError, or with `read`
    ArmDescriptionError for a broken file, before anything is changed. Without `read` only the
    name is checked (a process that never loads the arm's model)."""
    _known(name)
    if read:
        arm_description(name)
    os.environ[ARM_ENV] = name


@functools.cache
def arm_description(name: str | None = None) -> ArmDescription:
    """The description of arm ``name`` (default: the selected arm), read once per process."""
    name = _known(name or selected_arm_name())
    return read_description(name, arm_xml_path(name), scene_xml_path(name))


def _known(name: str) -> str:
    arms = available_arms()
    if name not in arms:
        raise UnknownArmError(f"unknown arm {name!r}: the arms are {', '.join(arms)}")
    return name


def read_description(name: str, arm_xml: Path, scene_xml: Path) -> ArmDescription:
    """Read and check one arm file; ArmDescriptionError names the file and the element."""
    import mujoco  # here: naming an arm (the emergency-stop band) needs no MuJoCo

    try:
        model = mujoco.MjModel.from_xml_path(str(arm_xml))
    except ValueError as error:
        raise ArmDescriptionError(f"{arm_xml}: MuJoCo cannot read it: {error}") from error

    def fail(problem: str) -> ArmDescriptionError:
        return ArmDescriptionError(f"{arm_xml}: {problem}")

    def named(kind: mujoco.mjtObj, index: int) -> str:
        return mujoco.mj_id2name(model, kind, index) or f"#{index}"

    joints = range(model.njnt)
    joint_names = tuple(named(mujoco.mjtObj.mjOBJ_JOINT, j) for j in joints)
    if not 1 <= model.njnt <= MAX_JOINTS:
        raise fail(f"an arm has 1 to {MAX_JOINTS} joints, this file has {model.njnt}")
    for j, joint in zip(joints, joint_names, strict=True):
        if model.jnt_type[j] != mujoco.mjtJoint.mjJNT_HINGE:
            raise fail(f"joint {joint!r} is not a hinge: every arm joint is revolute")
        lower, upper = model.jnt_range[j]
        if not model.jnt_limited[j] or not lower < upper:
            raise fail(f"joint {joint!r} has no limits (range {lower:g} {upper:g}): give it a "
                       "range with lower < upper")

    motors = {}
    for a in range(model.nu):
        if model.actuator_trntype[a] == mujoco.mjtTrn.mjTRN_JOINT:
            motors[int(model.actuator_trnid[a, 0])] = a
    actuators, torque = [], []
    for j, joint in zip(joints, joint_names, strict=True):
        if j not in motors:
            raise fail(f"joint {joint!r} has no motor: add an <actuator><motor joint=...>")
        a = motors[j]
        low, high = model.actuator_ctrlrange[a]
        if not model.actuator_ctrllimited[a] or not (high > 0 and low == -high):
            raise fail(f"motor {named(mujoco.mjtObj.mjOBJ_ACTUATOR, a)!r} needs a symmetric "
                       f"ctrlrange -T T with T > 0 (N*m), has {low:g} {high:g}")
        actuators.append(named(mujoco.mjtObj.mjOBJ_ACTUATOR, a))
        torque.append(high)

    for kind, element in ((mujoco.mjtObj.mjOBJ_SITE, n.FLANGE_SITE),
                          (mujoco.mjtObj.mjOBJ_SITE, n.FT_SITE),
                          (mujoco.mjtObj.mjOBJ_SITE, n.TOOL_SITE),
                          (mujoco.mjtObj.mjOBJ_SENSOR, n.FORCE_SENSOR),
                          (mujoco.mjtObj.mjOBJ_SENSOR, n.TORQUE_SENSOR),
                          (mujoco.mjtObj.mjOBJ_KEY, n.HOME_KEY),
                          (mujoco.mjtObj.mjOBJ_NUMERIC, n.MAX_VELOCITY_NUMERIC)):
        if mujoco.mj_name2id(model, kind, element) < 0:
            what = kind.name.removeprefix("mjOBJ_").lower()
            raise fail(f"it has no {what} named {element!r}")

    numeric = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_NUMERIC, n.MAX_VELOCITY_NUMERIC)
    start, size = model.numeric_adr[numeric], model.numeric_size[numeric]
    velocity = model.numeric_data[start:start + size].copy()
    if size != model.njnt or not (velocity > 0).all():
        raise fail(f"numeric {n.MAX_VELOCITY_NUMERIC!r} needs {model.njnt} positive values "
                   f"(rad/s, one per joint), has {velocity.tolist()}")

    flange, tool = (mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, site)
                    for site in (n.FLANGE_SITE, n.TOOL_SITE))
    if (model.body_weldid[model.site_bodyid[tool]]
            != model.body_weldid[model.site_bodyid[flange]]):
        raise fail(f"site {n.TOOL_SITE!r} is not rigid with site {n.FLANGE_SITE!r}: the tool "
                   "mounts on the last link, with no joint between them")

    lower, upper = model.jnt_range[:, 0].copy(), model.jnt_range[:, 1].copy()
    home = model.key_qpos[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, n.HOME_KEY)].copy()
    for joint, value, low, high in zip(joint_names, home, lower, upper, strict=True):
        if not low <= value <= high:
            raise fail(f"keyframe {n.HOME_KEY!r} puts joint {joint!r} at {value:g} rad, outside "
                       f"its range {low:g} {high:g}")

    return ArmDescription(
        name=name, arm_xml=arm_xml, scene_xml=scene_xml, joint_names=joint_names,
        actuator_names=tuple(actuators), lower=lower, upper=upper, max_velocity=velocity,
        max_torque=np.array(torque), home_q=home,
        flange_T_tool=_flange_T_tool(model, home))


def _flange_T_tool(model, home: np.ndarray) -> np.ndarray:
    """The tool_point site in the flange site's frame (4x4), from a compiled arm model."""
    import mujoco

    data = mujoco.MjData(model)
    data.qpos[:] = home
    mujoco.mj_kinematics(model, data)

    def pose(site: str) -> np.ndarray:
        index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, site)
        transform = np.eye(4)
        transform[:3, :3] = data.site_xmat[index].reshape(3, 3)
        transform[:3, 3] = data.site_xpos[index]
        return transform

    return np.linalg.inv(pose(n.FLANGE_SITE)) @ pose(n.TOOL_SITE)
