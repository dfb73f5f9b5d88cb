"""ProxyRobot over gRPC: reads requests, calls ProxyRobotCore, converts answers and errors."""

from __future__ import annotations

import time

import pinocchio as pin

from services.common import se3
from services.common.fanout import Fanout, Subscription
from services.proxy_robot.core import ProxyRobotCore
from services.proxy_robot.status import (
    Moved,
    RobotErrorRaised,
    RobotSnapshot,
    RobotStatus,
    StatusChanged,
)
from services.runtime.validation import check_request
from telerobot.v1 import proxy_robot_pb2 as pb
from telerobot.v1 import proxy_robot_pb2_grpc, types_pb2
from wire import convert
from wire.errors import FailedPreconditionError, InvalidArgumentError, UnavailableError
from wire.local_call import Handler, method_path

_FRAMES = {
    types_pb2.REFERENCE_FRAME_BASE: "BASE",
    types_pb2.REFERENCE_FRAME_WRIST: "WRIST",
    types_pb2.REFERENCE_FRAME_TOOL: "TOOL",
}
_EVENT_KINDS = {
    pb.ROBOT_EVENT_KIND_DATA_RECEIVED: "data_received",
    pb.ROBOT_EVENT_KIND_ERROR: "error",
    pb.ROBOT_EVENT_KIND_MOVED: "moved",
    pb.ROBOT_EVENT_KIND_STATUS_CHANGED: "status_changed",
}
DEFAULT_DATA_RECEIVED_PERIOD_S = 0.1
# How long a stream waits for news before it checks whether its client is still there.
STREAM_POLL_S = 0.1
STATE_QUEUE = 8  # state samples: only the newest matter to a slow reader


class PeriodicSubscription(Subscription[RobotSnapshot]):
    """State samples at most one per `period_ns` of sample time. Filtering here, in the
    publisher's thread, spares a slower subscriber the wake-ups for samples it would drop (when
    the monitor published every 2 ms, those were a third of ProxyRobot's GIL time in a profile
    under Teleoperate)."""

    def __init__(self, fanout: Fanout[RobotSnapshot], capacity: int, period_ns: int):
        super().__init__(fanout, capacity)
        self._period_ns = period_ns
        self._next_due_ns = 0

    def offer(self, item: RobotSnapshot) -> None:
        if item.sample_time_ns < self._next_due_ns:
            return
        self._next_due_ns = item.sample_time_ns + self._period_ns
        super().offer(item)


def status_to_proto(status: RobotStatus) -> int:
    return types_pb2.RobotStatus.Value(f"ROBOT_STATUS_{status.name}")


def snapshot_to_proto(snapshot: RobotSnapshot) -> types_pb2.RobotState:
    return types_pb2.RobotState(
        sequence=snapshot.sequence,
        sample_time=convert.timestamp(snapshot.sample_time_ns),
        status=status_to_proto(snapshot.status),
        joint_positions_rad=snapshot.joint_positions_rad.tolist(),
        joint_velocities_rad_per_s=snapshot.joint_velocities_rad_per_s.tolist(),
        flange_pose=convert.pose_to_proto(snapshot.flange_pose),
        tool_pose=convert.pose_to_proto(snapshot.tool_pose),
    )


def event_to_proto(event) -> pb.StreamRobotEventsResponse:
    message = pb.StreamRobotEventsResponse(sequence=event.sequence,
                                           event_time=convert.timestamp(event.time_ns))
    payload = event.payload
    if isinstance(payload, StatusChanged):
        message.status_changed.CopyFrom(pb.StatusChangedEvent(
            previous_status=status_to_proto(payload.previous),
            status=status_to_proto(payload.status), reason=payload.reason))
    elif isinstance(payload, Moved):
        message.moved.CopyFrom(pb.MovedEvent(
            joint_positions_rad=payload.joint_positions_rad.tolist(),
            tool_pose=convert.pose_to_proto(payload.tool_pose)))
    elif isinstance(payload, RobotErrorRaised):
        message.error.CopyFrom(pb.RobotErrorEvent(reason=payload.reason,
                                                  message=payload.message))
    return message


def frame_from_proto(frame: int) -> str:
    if frame not in _FRAMES:
        raise InvalidArgumentError("set frame to REFERENCE_FRAME_BASE, REFERENCE_FRAME_WRIST or "
                                   "REFERENCE_FRAME_TOOL", reason="BAD_FRAME")
    return _FRAMES[frame]


class ProxyRobotServicer(proxy_robot_pb2_grpc.ProxyRobotServicer):
    """The ProxyRobot contract on top of a ProxyRobotCore."""

    def __init__(self, core: ProxyRobotCore):
        self._core = core

    def Connect(self, request, context):
        return pb.ConnectResponse(status=status_to_proto(self._core.connect()))

    def Initialize(self, request, context):
        return pb.InitializeResponse(status=status_to_proto(self._core.initialize()))

    def Disconnect(self, request, context):
        return pb.DisconnectResponse(status=status_to_proto(self._core.disconnect()))

    def GetStatus(self, request, context):
        status, reason, change_time_ns = self._core.status
        return pb.GetStatusResponse(status=status_to_proto(status), reason=reason,
                                    change_time=convert.timestamp(change_time_ns))

    def GetState(self, request, context):
        return pb.GetStateResponse(state=snapshot_to_proto(self._core.snapshot()))

    def GetArmInfo(self, request, context):
        arm = self._core.arm
        return pb.GetArmInfoResponse(
            name=arm.name, joint_names=arm.joint_names,
            joint_lower_limits_rad=arm.lower, joint_upper_limits_rad=arm.upper,
            joint_velocity_limits_rad_per_s=arm.max_velocity,
            joint_torque_limits_nm=arm.max_torque, home_joint_positions_rad=arm.home_q,
            default_flange_to_tool=convert.pose_to_proto(pin.SE3(arm.flange_T_tool)))

    def GetToolFrame(self, request, context):
        return pb.GetToolFrameResponse(flange_to_tool=convert.pose_to_proto(self._core.tool_frame))

    def SetToolFrame(self, request, context):
        pose = se3.pose_from_proto(request.flange_to_tool, "flange_to_tool")
        return pb.SetToolFrameResponse(
            flange_to_tool=convert.pose_to_proto(self._core.set_tool_frame(pose)))

    def MoveJointsIncremental(self, request, context):
        target, tool = self._core.move_joints(request.delta_joint_positions_rad)
        return pb.MoveJointsIncrementalResponse(target_joint_positions_rad=target.tolist(),
                                                target_tool_pose=convert.pose_to_proto(tool))

    def MoveCartesianIncremental(self, request, context):
        frame = frame_from_proto(request.frame)
        delta_x = convert.vector3_from_proto(request.delta_position_m, "delta_position_m")
        delta_m = convert.rotation_from_proto(request.delta_rotation, "delta_rotation")
        target, tool, fraction = self._core.move_cartesian(delta_x, delta_m, frame)
        return pb.MoveCartesianIncrementalResponse(
            target_joint_positions_rad=target.tolist(),
            target_tool_pose=convert.pose_to_proto(tool), applied_fraction=fraction)

    def Hold(self, request, context):
        target, tool, cut = self._core.hold()
        return pb.HoldResponse(target_joint_positions_rad=target.tolist(),
                               target_tool_pose=convert.pose_to_proto(tool),
                               cut_target_tool_pose=convert.pose_to_proto(cut))

    def StreamState(self, request, context):
        period_s = convert.seconds(request.period)
        if period_s < 0:
            raise InvalidArgumentError("period must not be negative", reason="BAD_PERIOD")
        self._core.snapshot()  # FailedPreconditionError when not connected
        subscription = PeriodicSubscription(self._core.states, STATE_QUEUE, int(period_s * 1e9))
        with self._core.states.attach(subscription) as states:
            while context.is_active():
                snapshot = states.get(STREAM_POLL_S)
                if snapshot is None:
                    if self._core.status[0] == RobotStatus.NOT_CONNECTED:
                        raise UnavailableError(
                            "the hardware link dropped: Connect, then resubscribe")
                    continue
                yield pb.StreamStateResponse(state=snapshot_to_proto(snapshot))

    def StreamRobotEvents(self, request, context):
        kinds = {_EVENT_KINDS[k] for k in request.kinds if k in _EVENT_KINDS} or set(
            _EVENT_KINDS.values())
        data_period_s = convert.seconds(request.data_received_period)
        if data_period_s < 0:
            raise InvalidArgumentError("data_received_period must not be negative",
                                       reason="BAD_PERIOD")
        data_period_s = data_period_s or DEFAULT_DATA_RECEIVED_PERIOD_S
        next_data = time.monotonic()
        with self._core.events.subscribe(256) as events:
            while context.is_active():
                wait = STREAM_POLL_S
                if "data_received" in kinds:
                    wait = min(wait, max(0.0, next_data - time.monotonic()))
                event = events.get(wait)
                if event is not None:
                    message = event_to_proto(event)
                    if message.WhichOneof("event") in kinds:
                        yield message
                if "data_received" in kinds and time.monotonic() >= next_data:
                    next_data = time.monotonic() + data_period_s
                    message = self._data_received()
                    if message is not None:
                        yield message

    def _data_received(self) -> pb.StreamRobotEventsResponse | None:
        try:
            snapshot = self._core.snapshot()
        except FailedPreconditionError:
            return None  # not connected: no data arrives
        return pb.StreamRobotEventsResponse(
            event_time=convert.timestamp(time.time_ns()),
            data_received=pb.DataReceivedEvent(state=snapshot_to_proto(snapshot)))

    def EmergencyStop(self, request, context):
        status, stop_time_ns = self._core.emergency_stop(request.reason)
        return pb.EmergencyStopResponse(status=status_to_proto(status),
                                        stop_time=convert.timestamp(stop_time_ns))

    def Reset(self, request, context):
        return pb.ResetResponse(status=status_to_proto(self._core.reset()))


# The calls the DecisionServer makes for every command, which it makes on the local socket
# when it runs on this host (wire/local_call.py).
LOCAL_MOVES = ("MoveCartesianIncremental", "MoveJointsIncremental")


def local_moves(servicer: ProxyRobotServicer) -> dict[str, Handler]:
    """LOCAL_MOVES for a LocalCallServer: the servicer's own handlers, behind the request
    checks a gRPC call gets (services/runtime/validation.py)."""
    service = pb.DESCRIPTOR.services_by_name["ProxyRobot"]

    def checked(handler):
        def handle(request):
            check_request(request)
            return handler(request, None)
        return handle

    return {method_path(service, name): (getattr(pb, f"{name}Request"),
                                         checked(getattr(servicer, name)))
            for name in LOCAL_MOVES}
