"""Load the generated PUMA 560 models and resolve MuJoCo ids by name.

MuJoCo loads ``scene.xml`` (arm + work cell); Pinocchio loads ``puma560.xml`` (the arm alone,
which ``scene.xml`` includes). Both files come from ``mjcf.py``, so the two models share every
kinematic and inertial number.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np
import pinocchio as pin

from domain.robot_model import puma560 as p
from domain.robot_model import workspace as ws
from domain.robot_model.model_files import ROBOT_XML_PATH, SCENE_XML_PATH


def load_mujoco_model(path: Path | str = SCENE_XML_PATH) -> mujoco.MjModel:
    """Compile the MuJoCo work-cell model (defaults to the committed ``scene.xml``)."""
    return mujoco.MjModel.from_xml_path(str(path))


def load_pinocchio_model(path: Path | str = ROBOT_XML_PATH) -> pin.Model:
    """Build the Pinocchio model of the arm from the committed ``puma560.xml``.

    The MJCF parser takes limits, armature and damping from the joints but ignores the motor
    actuators, so the joint torque limits (N*m, the motors' ctrlrange) are filled in here from
    the same parameter module.
    """
    model = pin.buildModelFromMJCF(str(path))
    model.effortLimit = p.MAX_TORQUE.copy()
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
    """Indices into a compiled work-cell model, resolved by name (arrays in joint order 1..6)."""

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


def mujoco_ids(model: mujoco.MjModel) -> MujocoIds:
    """Resolve every joint, actuator, site, sensor, camera and keyframe the world uses.

    Raises ``KeyError`` naming the first missing element (e.g. when given the bare arm model).
    """
    obj = mujoco.mjtObj
    joints = np.array([_id(model, obj.mjOBJ_JOINT, name) for name in p.JOINT_NAMES])
    return MujocoIds(
        joints=joints,
        qpos=model.jnt_qposadr[joints].copy(),
        dofs=model.jnt_dofadr[joints].copy(),
        actuators=np.array([_id(model, obj.mjOBJ_ACTUATOR, name) for name in p.ACTUATOR_NAMES]),
        flange_site=_id(model, obj.mjOBJ_SITE, p.FLANGE_SITE),
        ft_site=_id(model, obj.mjOBJ_SITE, p.FT_SITE),
        tool_site=_id(model, obj.mjOBJ_SITE, p.TOOL_SITE),
        hole_entry_site=_id(model, obj.mjOBJ_SITE, ws.HOLE_ENTRY_SITE),
        hole_bottom_site=_id(model, obj.mjOBJ_SITE, ws.HOLE_BOTTOM_SITE),
        wrist_force=_sensor_slice(model, p.FORCE_SENSOR),
        wrist_torque=_sensor_slice(model, p.TORQUE_SENSOR),
        left_camera=_id(model, obj.mjOBJ_CAMERA, ws.LEFT_CAMERA),
        right_camera=_id(model, obj.mjOBJ_CAMERA, ws.RIGHT_CAMERA),
        home_key=_id(model, obj.mjOBJ_KEY, p.HOME_KEY),
    )
