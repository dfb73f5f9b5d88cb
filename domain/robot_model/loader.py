"""Load an arm's models and resolve MuJoCo ids by name.

MuJoCo loads the arm's ``scene.xml`` (arm + work cell); Pinocchio loads its ``arm.xml`` (the arm
alone, which ``scene.xml`` includes), so the two models share every kinematic and inertial number.
Every function defaults to the station's selected arm (``description.py``).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np
import pinocchio as pin

from domain.robot_model import names as n
from domain.robot_model import workspace as ws
from domain.robot_model.description import ArmDescription, arm_description


def load_mujoco_model(path: Path | str | None = None) -> mujoco.MjModel:
    """Compile a MuJoCo model: ``path``, else the selected arm's work cell (``scene.xml``)."""
    return mujoco.MjModel.from_xml_path(str(path or arm_description().scene_xml))


def load_pinocchio_model(arm: ArmDescription | None = None) -> pin.Model:
    """Build the Pinocchio model of an arm (default: the selected one) from its ``arm.xml``.

    The MJCF parser takes limits, armature and damping from the joints but ignores the motors and
    custom data, so the torque bounds (the motors' ctrlrange) and velocity bounds are filled in
    here from the same file's description.
    """
    arm = arm or arm_description()
    model = pin.buildModelFromMJCF(str(arm.arm_xml))
    model.effortLimit = arm.max_torque.copy()
    model.velocityLimit = arm.max_velocity.copy()
    return model


def _id(model: mujoco.MjModel, kind: mujoco.mjtObj, name: str) -> int:
    index = mujoco.mj_name2id(model, kind, name)
    if index < 0:
        raise KeyError(
            f"MuJoCo model has no {kind.name.removeprefix('mjOBJ_').lower()} named {name!r}"
        )
    return index


def _sensor_slice(model: mujoco.MjModel, name: str) -> slice:
    sensor = _id(model, mujoco.mjtObj.mjOBJ_SENSOR, name)
    start = int(model.sensor_adr[sensor])
    return slice(start, start + int(model.sensor_dim[sensor]))


@dataclass(frozen=True)
class MujocoIds:
    """Indices into a compiled work-cell model, resolved by name (arrays in the arm's joint
    order)."""

    joints: np.ndarray  # joint ids
    qpos: np.ndarray  # addresses in data.qpos
    dofs: np.ndarray  # addresses in data.qvel / qfrc_* / qacc
    actuators: np.ndarray  # indices in data.ctrl
    flange_site: int
    ft_site: int
    tool_site: int
    hole_entry_site: int
    hole_bottom_site: int
    wrist_force: slice  # N, in the wrist_ft site frame, within data.sensordata
    wrist_torque: slice  # N*m, in the wrist_ft site frame, within data.sensordata
    left_camera: int
    right_camera: int
    home_key: int


def mujoco_ids(model: mujoco.MjModel, arm: ArmDescription | None = None) -> MujocoIds:
    """Resolve every joint, actuator, site, sensor, camera and keyframe the world uses, for
    ``arm`` (default: the selected one).

    Raises ``KeyError`` naming the first missing element (e.g. when given the bare arm model).
    """
    arm = arm or arm_description()
    obj = mujoco.mjtObj
    joints = np.array([_id(model, obj.mjOBJ_JOINT, name) for name in arm.joint_names])
    return MujocoIds(
        joints=joints,
        qpos=model.jnt_qposadr[joints].copy(),
        dofs=model.jnt_dofadr[joints].copy(),
        actuators=np.array([_id(model, obj.mjOBJ_ACTUATOR, name) for name in arm.actuator_names]),
        flange_site=_id(model, obj.mjOBJ_SITE, n.FLANGE_SITE),
        ft_site=_id(model, obj.mjOBJ_SITE, n.FT_SITE),
        tool_site=_id(model, obj.mjOBJ_SITE, n.TOOL_SITE),
        hole_entry_site=_id(model, obj.mjOBJ_SITE, ws.HOLE_ENTRY_SITE),
        hole_bottom_site=_id(model, obj.mjOBJ_SITE, ws.HOLE_BOTTOM_SITE),
        wrist_force=_sensor_slice(model, n.FORCE_SENSOR),
        wrist_torque=_sensor_slice(model, n.TORQUE_SENSOR),
        left_camera=_id(model, obj.mjOBJ_CAMERA, ws.LEFT_CAMERA),
        right_camera=_id(model, obj.mjOBJ_CAMERA, ws.RIGHT_CAMERA),
        home_key=_id(model, obj.mjOBJ_KEY, n.HOME_KEY),
    )
