"""Shared, read-only models for the robot_model tests (compiled once per session)."""

from __future__ import annotations

import mujoco
import pytest

from domain.robot_model.kinematics import ArmKinematics
from domain.robot_model.loader import MujocoIds, load_mujoco_model, mujoco_ids


@pytest.fixture(scope="session")
def mj_model() -> mujoco.MjModel:
    return load_mujoco_model()


@pytest.fixture(scope="session")
def ids(mj_model: mujoco.MjModel) -> MujocoIds:
    return mujoco_ids(mj_model)


@pytest.fixture
def mj_data(mj_model: mujoco.MjModel) -> mujoco.MjData:
    return mujoco.MjData(mj_model)


@pytest.fixture
def kin() -> ArmKinematics:
    return ArmKinematics()
