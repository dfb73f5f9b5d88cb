"""ProxyRobot clients: the slave arm's status machine, tool frame, moves, e-stop and streams.

Use `ProxyRobotClient` on ProxyRobot's own port (50052), or on the DecisionServer's (50051)
with a lease: ``DecisionClient.robot`` is one already sharing its channel and lease. On the
emergency-stop band's port (50055) only `emergency_stop` works: the stop no load can delay.

Returns: `StatusInfo`, `RobotState`, `MoveResult` (``values.py``), `RobotStatus` for the
life-cycle calls, `Pose` for tool frames (``set_tool_frame`` also takes a ``pin.SE3``), joint
arrays as ``numpy``. Event streams give the
proto ``StreamRobotEventsResponse`` (its oneof says which event), state streams `RobotState`.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np

from clients.python.base import AsyncClient, SyncClient
from clients.python.values import (
    ArmInfo,
    MoveResult,
    ReferenceFrame,
    RobotState,
    RobotStatus,
    StatusInfo,
    enum_value,
)
from telerobot.v1 import proxy_robot_pb2 as pb
from telerobot.v1 import proxy_robot_pb2_grpc
from wire import convert
from wire.convert import pose_value, time_ns
from wire.pose import Pose


def _status(response) -> RobotStatus:
    return enum_value(RobotStatus, response.status)


def cartesian_request(delta_position, delta_rotation=None,
                      frame: int = ReferenceFrame.BASE) -> pb.MoveCartesianIncrementalRequest:
    """The request for a Cartesian increment (ΔX in metres, ΔM a 3x3 rotation or None)."""
    request = pb.MoveCartesianIncrementalRequest(
        delta_position_m=convert.vector3_to_proto(delta_position), frame=int(frame))
    if delta_rotation is not None:
        request.delta_rotation.CopyFrom(convert.rotation_to_proto(delta_rotation))
    return request


def joints_request(delta) -> pb.MoveJointsIncrementalRequest:
    return pb.MoveJointsIncrementalRequest(
        delta_joint_positions_rad=np.asarray(delta, dtype=float).tolist())


class _ProxyRobotMethods:
    """The ProxyRobot calls; on the async client each returns an awaitable of the same value."""

    SERVICE = "telerobot.v1.ProxyRobot"
    ADDRESS_NAME = "proxy_robot"
    STUB = proxy_robot_pb2_grpc.ProxyRobotStub

    def connect(self, *, timeout: float | None = None, lane: str | None = None) -> RobotStatus:
        """Open the hardware link: NOT_CONNECTED -> CONNECTED. Returns the status after."""
        return self._unary("Connect", pb.ConnectRequest(), _status, timeout, lane)

    def initialize(self, *, timeout: float | None = None, lane: str | None = None
                   ) -> RobotStatus:
        """CONNECTED -> READY (the arm holds where it is). Returns the status after."""
        return self._unary("Initialize", pb.InitializeRequest(), _status, timeout, lane)

    def disconnect(self, *, timeout: float | None = None, lane: str | None = None
                   ) -> RobotStatus:
        """Hold the arm and close the hardware link. Returns NOT_CONNECTED."""
        return self._unary("Disconnect", pb.DisconnectRequest(), _status, timeout, lane)

    def get_status(self, *, timeout: float | None = None, lane: str | None = None
                   ) -> StatusInfo:
        return self._unary("GetStatus", pb.GetStatusRequest(),
                           lambda r: StatusInfo(enum_value(RobotStatus, r.status), r.reason,
                                                time_ns(r.change_time)), timeout, lane)

    def get_state(self, *, timeout: float | None = None, lane: str | None = None
                  ) -> RobotState:
        """Latest joints, flange pose and tool pose."""
        return self._unary("GetState", pb.GetStateRequest(),
                           lambda r: RobotState.from_proto(r.state), timeout, lane)

    def get_arm_info(self, *, timeout: float | None = None, lane: str | None = None
                     ) -> ArmInfo:
        """What arm this is: name, joints, limits, home pose and default tool frame."""
        return self._unary("GetArmInfo", pb.GetArmInfoRequest(), ArmInfo.from_proto, timeout,
                           lane)

    def get_tool_frame(self, *, timeout: float | None = None, lane: str | None = None
                       ) -> Pose:
        """The tool frame in the flange frame (T_t, M_e^t)."""
        return self._unary("GetToolFrame", pb.GetToolFrameRequest(),
                           lambda r: pose_value(r.flange_to_tool), timeout, lane)

    def set_tool_frame(self, flange_to_tool: Pose, *, timeout: float | None = None,
                       lane: str | None = None) -> Pose:
        """Set the tool frame (in the flange frame: a `Pose`, a ``pin.SE3`` or anything with
        ``rotation`` and ``translation``); returns the one now in force."""
        return self._unary("SetToolFrame", pb.SetToolFrameRequest(
            flange_to_tool=convert.pose_to_proto(flange_to_tool)),
            lambda r: pose_value(r.flange_to_tool), timeout, lane)

    def move_joints(self, delta: Sequence[float] | np.ndarray, *, timeout: float | None = None,
                    lane: str | None = None) -> MoveResult:
        """Add a joint increment (six values, rad) to the current target. Sent once: on an error
        nothing moved, and the client does not resend it."""
        return self._unary("MoveJointsIncremental", joints_request(delta),
                           lambda r: MoveResult(np.asarray(r.target_joint_positions_rad),
                                                pose_value(r.target_tool_pose)), timeout, lane)

    def move_cartesian(self, delta_position: Sequence[float] | np.ndarray,
                       delta_rotation: np.ndarray | None = None,
                       frame: int = ReferenceFrame.BASE, *, timeout: float | None = None,
                       lane: str | None = None) -> MoveResult:
        """Move the tool by (ΔX, ΔM) in `frame` (BASE, WRIST or TOOL; eq. 1). Sent once."""
        return self._unary("MoveCartesianIncremental",
                           cartesian_request(delta_position, delta_rotation, frame),
                           lambda r: MoveResult(np.asarray(r.target_joint_positions_rad),
                                                pose_value(r.target_tool_pose), r.applied_fraction),
                           timeout, lane)

    def hold(self, reason: str = "", *, timeout: float | None = None, lane: str | None = None
             ) -> np.ndarray:
        """Controlled stop without a latch; returns the joint target it stops at."""
        return self._unary("Hold", pb.HoldRequest(reason=reason),
                           lambda r: np.asarray(r.target_joint_positions_rad), timeout, lane)

    def emergency_stop(self, reason: str = "", *, timeout: float | None = None,
                       lane: str | None = None) -> RobotStatus:
        """Latch an emergency stop (no lock needed). Returns ESTOPPED."""
        return self._unary("EmergencyStop", pb.EmergencyStopRequest(reason=reason), _status,
                           timeout, lane)

    def reset(self, *, timeout: float | None = None, lane: str | None = None) -> RobotStatus:
        """Clear an e-stop or fault latch; the arm stays where it is. Returns READY or
        CONNECTED."""
        return self._unary("Reset", pb.ResetRequest(), _status, timeout, lane)

    def stream_state(self, period_s: float = 0.0, *, timeout: float | None = None,
                     lane: str | None = None):
        """`RobotState` samples every `period_s` (0: every sample) until cancelled."""
        return self._server_stream("StreamState", pb.StreamStateRequest(
            period=convert.duration(period_s)), lambda r: RobotState.from_proto(r.state),
            timeout, lane)

    def stream_events(self, kinds: Iterable[int] = (), data_received_period_s: float = 0.0, *,
                      timeout: float | None = None, lane: str | None = None):
        """Proto ``StreamRobotEventsResponse`` events (of `kinds`, proto RobotEventKind
        values; empty: all) until cancelled."""
        return self._server_stream("StreamRobotEvents", pb.StreamRobotEventsRequest(
            kinds=list(kinds), data_received_period=convert.duration(data_received_period_s)),
            lambda r: r, timeout, lane)


class ProxyRobotClient(_ProxyRobotMethods, SyncClient):
    """Blocking ProxyRobot client. ``with ProxyRobotClient("127.0.0.1:50052") as robot: ...``"""


class AsyncProxyRobotClient(_ProxyRobotMethods, AsyncClient):
    """asyncio ProxyRobot client: the same methods, awaited; streams are ``async for``."""
