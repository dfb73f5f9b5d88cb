"""Typed Python clients for the telerobot services (see README.md in this folder).

One module per service plus the shared base:

* ``proxy_robot``    -- `ProxyRobotClient`, `AsyncProxyRobotClient`
* ``force_sensor``   -- `ForceSensorClient`, `AsyncForceSensorClient`
* ``stereo_camera``  -- `StereoCameraClient`, `AsyncStereoCameraClient`
* ``decision_server``-- `DecisionClient`, `AsyncDecisionClient` (the lease and the rest)
* ``teleoperate``    -- `TeleopSession` (resumes across a broken link), `AsyncTeleopSession`,
  `LinkInterruptedError`
* ``base``           -- channels, metadata (lease, lane), timeouts, streams
* ``errors``         -- `TelerobotError` and one subclass per status code
* ``values``         -- the dataclasses and enums the calls return; poses are `Pose`

The package needs only grpcio, protobuf, numpy, the generated ``telerobot.v1`` code and
``wire`` (the contracts' Python side); OpenCV only to decode JPEG or PNG stereo frames.
"""

from clients.python.base import DEFAULT_TIMEOUT_S, LANE_METADATA_KEY, LEASE_METADATA_KEY
from clients.python.decision_server import AsyncDecisionClient, DecisionClient
from clients.python.force_sensor import AsyncForceSensorClient, ForceSensorClient
from clients.python.proxy_robot import AsyncProxyRobotClient, ProxyRobotClient
from clients.python.stereo_camera import AsyncStereoCameraClient, StereoCameraClient
from clients.python.teleoperate import AsyncTeleopSession, LinkInterruptedError, TeleopSession
from clients.python.values import (
    Ack,
    ActionRun,
    ArmInfo,
    BusyWork,
    CartesianIncrement,
    Cobegin,
    CommandOutcome,
    ControlMode,
    Dependency,
    DependencyState,
    ImageEncoding,
    JointIncrement,
    Lane,
    Lease,
    MoveResult,
    Recording,
    ReferenceFrame,
    ReplayState,
    RobotState,
    RobotStatus,
    SensorConfig,
    SensorThreadPriority,
    StatusInfo,
    StereoFrame,
    TareResult,
    TransferMode,
    WrenchBatch,
    WrenchSample,
)
from wire.errors import (
    AbortedError,
    AlreadyExistsError,
    DeadlineExceededError,
    FailedPreconditionError,
    InternalError,
    InvalidArgumentError,
    NotFoundError,
    OutOfRangeError,
    PermissionDeniedError,
    ResourceExhaustedError,
    RpcCancelledError,
    TelerobotError,
    UnauthenticatedError,
    UnavailableError,
    UnimplementedError,
)
from wire.pose import Pose

__all__ = [
    "DEFAULT_TIMEOUT_S", "LANE_METADATA_KEY", "LEASE_METADATA_KEY",
    "AsyncDecisionClient", "AsyncForceSensorClient", "AsyncProxyRobotClient",
    "AsyncStereoCameraClient", "AsyncTeleopSession", "DecisionClient", "ForceSensorClient",
    "LinkInterruptedError", "ProxyRobotClient", "StereoCameraClient", "TeleopSession",
    "AbortedError", "AlreadyExistsError", "DeadlineExceededError", "FailedPreconditionError",
    "InternalError", "InvalidArgumentError", "NotFoundError", "OutOfRangeError",
    "PermissionDeniedError", "ResourceExhaustedError", "RpcCancelledError", "TelerobotError",
    "UnauthenticatedError",
    "UnavailableError", "UnimplementedError",
    "Ack", "ActionRun", "ArmInfo", "BusyWork", "CartesianIncrement", "Cobegin", "CommandOutcome",
    "ControlMode", "Dependency", "DependencyState", "ImageEncoding", "JointIncrement", "Lane",
    "Lease", "MoveResult", "Pose",
    "Recording", "ReferenceFrame", "ReplayState", "RobotState", "RobotStatus", "SensorConfig",
    "SensorThreadPriority", "StatusInfo", "StereoFrame", "TareResult", "TransferMode",
    "WrenchBatch", "WrenchSample",
]
