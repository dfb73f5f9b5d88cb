"""The DecisionServer's contracts over gRPC: DecisionServer itself, and the ProxyRobot,
ForceSensor and StereoCamera services it forwards (IDecisionServer inherits IProxyRobot and
IForceSensor). Reads requests, calls DecisionCore, converts answers and errors."""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable, Iterator

import grpc
import numpy as np

from domain.geometry import finite_vector
from domain.robot_model.description import arm_description
from services.common import se3
from services.common.fanout import Subscription
from services.common.inbox import Inbox, Producer
from services.decision_server import assistance as assist
from services.decision_server import recording_mcap
from services.decision_server.arbitration import DEFAULT_LEASE_S, ControlMode, ControlView, Lease
from services.decision_server.backends import forwarding_servicer, status_name
from services.decision_server.cobegin import MAX_BUSY_WORK_S
from services.decision_server.core import (
    AssistanceChanged,
    ControlChanged,
    DecisionCore,
    RecordingFailed,
    ReplayProgress,
    RobotEventForwarded,
)
from services.decision_server.dependencies import Dependency, DependencyChanged, DependencyWatch
from services.decision_server.recordings import RecordedCommand
from services.decision_server.sessions import (
    CommandResult,
    MasterIncrement,
    OperatorSession,
    SessionChanged,
    WatchdogHold,
)
from services.proxy_robot.servicer import frame_from_proto
from services.runtime.clock import Clock
from services.runtime.lanes import Lane, current_lane
from services.runtime.rpc import LANE_TO_PROTO
from telerobot.v1 import (
    decision_server_pb2 as pb,
)
from telerobot.v1 import (
    decision_server_pb2_grpc,
    force_sensor_pb2,
    force_sensor_pb2_grpc,
    proxy_robot_pb2,
    proxy_robot_pb2_grpc,
    stereo_camera_pb2,
    stereo_camera_pb2_grpc,
    types_pb2,
)
from wire import convert
from wire.errors import AbortedError, InvalidArgumentError, TelerobotError
from wire.metadata import LEASE_METADATA_KEY

STREAM_POLL_S = 0.1
# A Teleoperate stream takes one of the server's capped stream slots from its first byte: its
# init must come within this, or the stream is cancelled and the slot freed.
INIT_TIMEOUT_S = 10.0
MAX_COMMANDS_PER_MESSAGE = 1000  # TeleoperateRequest.commands: a second's worth at 1 kHz
# Calls through the facades that command the arm or the sensor need the control lock.
PROXY_COMMANDS = {"Connect", "Initialize", "Disconnect", "SetToolFrame", "MoveJointsIncremental",
                  "MoveCartesianIncremental", "Hold", "Reset"}
# Forwarded calls whose answer says the arm's new status, which the core notes.
STATUS_ANSWERS = {"Connect", "Initialize", "Disconnect"}
SENSOR_COMMANDS = {"StartReading", "StopReading", "Tare", "SetSensorConfig"}
_OUTCOMES = {name: pb.CommandOutcome.Value(f"COMMAND_OUTCOME_{name}")
             for name in ("APPLIED", "MODIFIED", "MERGED_LATE", "INDEXED", "REJECTED",
                          "HEARTBEAT", "DUPLICATE")}


_END_OF_SESSION = object()  # from _serve_batch: the operator sent `end`


def lease_id(context: grpc.ServicerContext) -> str | None:
    for key, value in context.invocation_metadata():
        if key == LEASE_METADATA_KEY:
            return value
    return None


# -- conversions ------------------------------------------------------------------------------

def _mode(mode: ControlMode | None) -> int:
    return pb.ControlMode.Value(f"CONTROL_MODE_{mode.name}") if mode else 0


def _holder(lease: Lease, clock: Clock) -> pb.ControlHolder:
    """A lease, its deadline (on the clock's monotonic scale) as a wall-clock time."""
    expires_ns = clock.time_ns() + int((lease.expires_at - clock.monotonic()) * 1e9)
    return pb.ControlHolder(operator_id=lease.operator_id, mode=_mode(lease.mode),
                            group=lease.group, expire_time=convert.timestamp(expires_ns))


def control_state(view: ControlView, clock: Clock) -> pb.ControlState:
    now_ns, now = clock.time_ns(), clock.monotonic()
    return pb.ControlState(
        mode=_mode(view.mode), holders=[_holder(h, clock) for h in view.holders],
        waiters=[pb.ControlHolder(operator_id=o, mode=_mode(m), group=g,
                                  expire_time=convert.timestamp(now_ns + int((d - now) * 1e9)))
                 for o, m, g, d in view.waiters])


def _axes(selection: pb.AxisSelection) -> np.ndarray:
    return np.array([selection.x, selection.y, selection.z, selection.rx, selection.ry,
                     selection.rz], dtype=bool)


def assistance_from_proto(config: pb.AssistanceConfig) -> assist.Assistance:
    mapping = "TOOL" if config.mapping == types_pb2.REFERENCE_FRAME_TOOL else "BASE"
    if config.mapping == types_pb2.REFERENCE_FRAME_WRIST:
        raise InvalidArgumentError("mapping is BASE (world) or TOOL", reason="BAD_MAPPING")
    floating = None
    if config.floating_tool_frame.enabled:
        floating = convert.vector3_from_proto(config.floating_tool_frame.point_m, "point_m")
    constraint = None
    if config.constraint.type:
        kind = assist.ConstraintType[pb.ConstraintType.Name(config.constraint.type)
                                     .removeprefix("CONSTRAINT_TYPE_")]
        frame = "TOOL" if config.constraint.frame == types_pb2.REFERENCE_FRAME_TOOL else "BASE"
        axis = convert.vector3_from_proto(config.constraint.axis, "constraint.axis")
        constraint = assist.Constraint(kind, axis, frame)
    force = None
    if config.force_control.enabled:
        control = config.force_control
        wrench = control.desired_wrench
        force = assist.ForceControl(
            _axes(control.axes), convert.vector3_from_proto(wrench.force_n, "force_n"),
            convert.vector3_from_proto(wrench.torque_nm, "torque_nm"),
            control.translation_gain_m_per_n_s, control.rotation_gain_rad_per_nm_s)
    return assist.Assistance(mapping, floating, constraint, force,
                             config.scaling.translation_scale or 1.0,
                             config.scaling.rotation_scale or 1.0)


def assistance_to_proto(value: assist.Assistance) -> pb.AssistanceConfig:
    config = pb.AssistanceConfig(
        mapping=types_pb2.REFERENCE_FRAME_TOOL if value.mapping == "TOOL"
        else types_pb2.REFERENCE_FRAME_BASE,
        scaling=pb.Scaling(translation_scale=value.translation_scale,
                           rotation_scale=value.rotation_scale))
    if value.floating_point_m is not None:
        config.floating_tool_frame.enabled = True
        config.floating_tool_frame.point_m.CopyFrom(convert.vector3_to_proto(value.floating_point_m))
    if value.constraint is not None:
        config.constraint.type = pb.ConstraintType.Value(
            f"CONSTRAINT_TYPE_{value.constraint.type.name}")
        config.constraint.axis.CopyFrom(convert.vector3_to_proto(value.constraint.axis))
        config.constraint.frame = (types_pb2.REFERENCE_FRAME_TOOL if value.constraint.frame ==
                                   "TOOL" else types_pb2.REFERENCE_FRAME_BASE)
    if value.force_control is not None:
        control = value.force_control
        x, y, z, rx, ry, rz = (bool(a) for a in control.axes)
        config.force_control.CopyFrom(pb.ForceControl(
            enabled=True, axes=pb.AxisSelection(x=x, y=y, z=z, rx=rx, ry=ry, rz=rz),
            desired_wrench=convert.wrench_to_proto(control.desired_force_n,
                                                   control.desired_torque_nm),
            translation_gain_m_per_n_s=control.translation_gain_m_per_n_s,
            rotation_gain_rad_per_nm_s=control.rotation_gain_rad_per_nm_s))
    return config


def recording_to_proto(info) -> pb.Recording:
    duration = convert.duration(info.duration_s)
    return pb.Recording(name=info.name, create_time=convert.timestamp(info.create_time_ns),
                        duration=duration, command_count=info.command_count,
                        format=pb.RecordingFormat.Value(f"RECORDING_FORMAT_{info.format}"),
                        error=info.error, task=info.task,
                        outcome=pb.EpisodeOutcome.Value(
                            f"EPISODE_OUTCOME_{info.outcome or 'UNSPECIFIED'}"),
                        video_frames=info.video_frames)


MAX_INLINE_INCREMENTS = 100_000


def inline_increments(messages) -> list[RecordedCommand]:
    """A StartReplay's own increments as RecordedCommands; InvalidArgumentError naming the
    first that is not a finite Cartesian increment at an offset that does not go back."""
    if len(messages) > MAX_INLINE_INCREMENTS:
        raise InvalidArgumentError(f"at most {MAX_INLINE_INCREMENTS} increments in a replay, "
                                   f"not {len(messages)}", reason="TOO_MANY_INCREMENTS")
    commands, last = [], 0.0
    for index, message in enumerate(messages):
        try:
            if message.delta_joints_rad:
                raise ValueError("a joint increment: only Cartesian ones replay from a request")
            command = recording_mcap.increment_from_proto(message, RecordedCommand)
            values = np.concatenate([command.delta_position_m, command.delta_rotation.ravel(),
                                     [command.offset_s]])
            if not np.isfinite(values).all():
                raise ValueError("a value that is not finite")
            if command.offset_s < last:
                raise ValueError(f"its offset {command.offset_s:.3f} s goes back")
            if not np.allclose(command.delta_rotation @ command.delta_rotation.T, np.eye(3),
                               atol=1e-6) or np.linalg.det(command.delta_rotation) < 0:
                raise ValueError("a delta_rotation that is not a rotation")
        except ValueError as error:
            raise InvalidArgumentError(f"increment {index}: {error}",
                                       reason="BAD_INCREMENT") from None
        last = command.offset_s
        commands.append(command)
    return commands


def episode_outcome(value: int) -> str:
    """SUCCEEDED, FAILED, DISCARDED or UNSPECIFIED, from a request; InvalidArgumentError for a
    value the contract does not have."""
    try:
        return pb.EpisodeOutcome.Name(value).removeprefix("EPISODE_OUTCOME_")
    except ValueError:
        raise InvalidArgumentError(f"unknown episode outcome {value}: use EPISODE_OUTCOME_"
                                   "SUCCEEDED, _FAILED, _DISCARDED or _UNSPECIFIED",
                                   reason="BAD_OUTCOME") from None


def recording_format(value: int) -> str:
    """JSONL or MCAP, from a request (UNSPECIFIED: JSONL)."""
    if value == pb.RECORDING_FORMAT_UNSPECIFIED:
        return "JSONL"
    if value not in pb.RecordingFormat.values():
        raise InvalidArgumentError(f"unknown recording format {value}", reason="BAD_FORMAT")
    return pb.RecordingFormat.Name(value).removeprefix("RECORDING_FORMAT_")


def _is_state_sample(event) -> bool:
    payload = event.payload
    return (isinstance(payload, RobotEventForwarded)
            and payload.message.WhichOneof("event") == "data_received")


_ROUTINE_STATUSES = frozenset({types_pb2.ROBOT_STATUS_READY, types_pb2.ROBOT_STATUS_MOVING})


def _sampled_by_recording(event) -> bool:
    """ProxyRobot's events that an MCAP recording's own 100 Hz state samples already hold:
    state samples, arrivals (moved) and the READY <-> MOVING changes each command brings
    (about 290 a second at 1 kHz). Errors and every other status change are kept."""
    payload = event.payload
    if not isinstance(payload, RobotEventForwarded):
        return False
    message = payload.message
    kind = message.WhichOneof("event")
    if kind == "status_changed":
        change = message.status_changed
        return {change.previous_status, change.status} <= _ROUTINE_STATUSES
    return kind in ("data_received", "moved")


def _dependency_state(state: str) -> int:
    return pb.DependencyState.Value(f"DEPENDENCY_STATE_{state}")


def dependency_to_proto(dependency: Dependency) -> pb.Dependency:
    return pb.Dependency(name=dependency.name, state=_dependency_state(dependency.state),
                         reason=dependency.reason,
                         change_time=convert.timestamp(dependency.change_time_ns),
                         restarts=dependency.restarts)


def event_to_proto(event, clock: Clock) -> pb.StreamEventsResponse:
    message = pb.StreamEventsResponse(sequence=event.sequence,
                                      event_time=convert.timestamp(event.time_ns))
    payload = event.payload
    if isinstance(payload, RobotEventForwarded):
        message.robot.CopyFrom(payload.message)
    elif isinstance(payload, ControlChanged):
        message.control_changed.CopyFrom(pb.ControlChangedEvent(
            state=control_state(payload.view, clock), reason=payload.reason))
    elif isinstance(payload, WatchdogHold):
        message.watchdog_hold.CopyFrom(pb.WatchdogHoldEvent(
            session_id=payload.session_id, reason=payload.reason,
            silence=convert.duration(payload.silence_s)))
    elif isinstance(payload, AssistanceChanged):
        message.assistance_changed.CopyFrom(pb.AssistanceChangedEvent(
            assistance=assistance_to_proto(payload.assistance), operator_id=payload.operator_id))
    elif isinstance(payload, ReplayProgress):
        message.replay_progress.CopyFrom(pb.ReplayProgressEvent(
            name=payload.name, commands_replayed=payload.replayed, command_count=payload.total,
            state=pb.ReplayState.Value(f"REPLAY_STATE_{payload.state}"), detail=payload.detail))
    elif isinstance(payload, SessionChanged):
        counts = payload.counts
        message.teleop_session.CopyFrom(pb.TeleopSessionEvent(
            session_id=payload.session_id, operator_id=payload.operator_id,
            state=pb.TeleopSessionState.Value(f"TELEOP_SESSION_STATE_{payload.state}"),
            reason=payload.reason, commands_processed=counts.processed,
            commands_applied=counts.applied, resends_answered=counts.resends,
            last_sequence=counts.last_sequence))
    elif isinstance(payload, RecordingFailed):
        message.recording_failed.CopyFrom(pb.RecordingFailedEvent(name=payload.name,
                                                                  reason=payload.reason))
    elif isinstance(payload, DependencyChanged):
        message.dependency_changed.CopyFrom(pb.DependencyChangedEvent(
            dependency=dependency_to_proto(payload.dependency),
            previous_state=_dependency_state(payload.previous_state)))
    return message


# -- DecisionServer ---------------------------------------------------------------------------

class _WithoutStateSamples(Subscription):
    """Every event but ProxyRobot's forwarded state samples (data_received)."""

    def offer(self, item) -> None:
        if not _is_state_sample(item):
            super().offer(item)


class _LastConverted:
    """`convert(sample)`, computed once for the last sample seen (by identity). The (sample,
    message) pair is swapped in whole, so concurrent streams always read a consistent one."""

    def __init__(self, convert: Callable):
        self._convert = convert
        self._last: tuple[object, object] = (None, None)

    def __call__(self, sample):
        seen, message = self._last
        if seen is not sample:
            message = self._convert(sample)
            self._last = (sample, message)
        return message


class DecisionServerServicer(decision_server_pb2_grpc.DecisionServerServicer):
    def __init__(self, core: DecisionCore, dependencies: DependencyWatch | None = None):
        """`dependencies`: the watch whose changes reach the core's events (the process's,
        polling on its thread); None makes one here that looks only when GetDependencies asks."""
        self._core = core
        if dependencies is None:
            dependencies = DependencyWatch(core.slave.health, core.clock)
            dependencies.subscribe(core.emit)
        self._dependencies = dependencies
        # MCAP recordings hold the events as StreamEventsResponse, without those of ProxyRobot
        # the recording's own state samples hold.
        core.recordings.event_to_message = lambda event: (
            None if _sampled_by_recording(event) else event_to_proto(event, core.clock))
        # The state and the wrench change at 100 Hz, acks go out at up to 1 kHz: each sample
        # is converted once, for every ack that carries it.
        self._pose_of = _LastConverted(lambda state: convert.pose_to_proto(state.tool_pose))
        self._wrench_of = _LastConverted(
            lambda wrench: convert.wrench_to_proto(wrench.force_n, wrench.torque_nm))
        # Told each command's age (receive minus send time, in seconds): the process's metrics.
        self.on_command_age: Callable[[float], None] | None = None

    def _ack(self, sequence: int, send_time_ns: int, result: CommandResult,
             session: OperatorSession | None = None) -> pb.TeleoperateResponse:
        ack = pb.CommandAck(sequence=sequence,
                            command_send_time=convert.timestamp(send_time_ns)
                            if send_time_ns else None,
                            receive_time=convert.timestamp(result.receive_time_ns),
                            apply_time=convert.timestamp(result.apply_time_ns),
                            outcome=_OUTCOMES[result.outcome], detail=result.detail)
        if session is not None:
            clock = session.clock_offset
            clock.answered(sequence, send_time_ns, result.receive_time_ns, result.apply_time_ns)
            estimate = clock.estimate()
            if estimate is not None:
                ack.clock_offset.FromNanoseconds(estimate.offset_ns)
                ack.clock_offset_error.FromNanoseconds(estimate.error_ns)
        passivity = session.passivity if session is not None else None
        if passivity is not None:  # the slave port's energy, for the master's controller
            ack.slave_energy.CopyFrom(pb.PortEnergy(
                energy_in_j=passivity.ledger.energy_in_j,
                energy_out_j=passivity.ledger.energy_out_j,
                dissipated_j=passivity.dissipated_j,
                sample_time=convert.timestamp(self._core.clock.time_ns())))
            ack.passivity_drift_m.CopyFrom(convert.vector3_to_proto(passivity.drift_m))
        try:
            state = self._core.robot_state()
            ack.tool_pose.CopyFrom(self._pose_of(state))
            ack.status = _status(state.status)
        except TelerobotError:
            pass  # the ack still says what happened to the command
        wrench = self._core.wrench()
        if wrench is not None:
            ack.tool_wrench.CopyFrom(self._wrench_of(wrench))
        self._core.recordings.note_ack(ack)  # an MCAP recording keeps it (queued only)
        return pb.TeleoperateResponse(ack=ack)

    def Teleoperate(self, request_iterator, context):
        first = _first_message(request_iterator, context, INIT_TIMEOUT_S)
        if first is None or first.WhichOneof("message") != "init":
            raise InvalidArgumentError("the first Teleoperate message must be an init",
                                       reason="NO_INIT")
        session, stream = self._session_for(first.init)
        # Only the operator's `end` ends the session; a stream that ends without one (a cut, a
        # lost connection, a half-close alone: gRPC may report a dead connection as a clean
        # end) leaves it to be resumed, the arm held (services.decision_server.sessions).
        reason, resumable = "the stream broke", True
        ended = threading.Event()
        try:
            yield pb.TeleoperateResponse(ready=pb.TeleoperateReady(
                session_id=session.session_id,
                mapping=types_pb2.ReferenceFrame.Value(
                    f"REFERENCE_FRAME_{session.mapping or self._core.assistance.mapping}"),
                watchdog_timeout=convert.duration(session.watchdog_s),
                assistance=assistance_to_proto(self._core.assistance),
                resumed=stream > 1, last_sequence=session.last_sequence,
                resume_window=convert.duration(session.resume_window_s),
                passivity=pb.PASSIVITY_TDPA if session.passivity else pb.PASSIVITY_OFF,
                max_command_age=convert.duration(session.max_command_age_s)))
            # Three threads (services/common/inbox.py): the inbox reads, the producer moves the
            # arm, this one writes the acks; the arm never waits for an ack to be written.
            inbox = Inbox(request_iterator, self._received, name=f"teleop-in-{session.session_id}")
            # (None, []): no message; the batch it ends is decided, late commands with it.
            session.wake_server = lambda: inbox.put((None, []))

            grouped = first.init.grouped_acks

            def serve(emit) -> None:
                while batch := inbox.take():
                    for answer in self._answers(session, stream, batch, grouped):
                        if answer is _END_OF_SESSION:
                            ended.set()
                            return
                        emit(answer)

            try:
                yield from Producer(serve, name=f"teleop-{session.session_id}")
            finally:
                inbox.close()  # (a move in flight lands before the session holds the arm)
            reason = "the operator ended the session" if ended.is_set() else "the stream ended"
            resumable = not ended.is_set()
        except TelerobotError as error:
            reason, resumable = error.message, error.reason == "STREAM_BROKEN"
            if error.reason == "NO_CONTROL":
                raise AbortedError(f"control was lost mid-stream: {error.message}",
                                   reason="CONTROL_LOST") from None
            raise
        finally:
            session.end(stream, reason, resumable)

    def _session_for(self, init: pb.TeleoperateInit) -> tuple[OperatorSession, int]:
        """The session an Init opens or resumes, and the stream's number in it."""
        if init.resume_session_id:
            return self._core.resume_session(init.resume_session_id, init.lease_id)
        mapping = None
        if init.mapping:
            mapping = frame_from_proto(init.mapping)
            if mapping == "WRIST":
                raise InvalidArgumentError("mapping is BASE (world) or TOOL", reason="BAD_MAPPING")
        session = self._core.open_session(init.operator_id, init.lease_id, mapping,
                                          convert.seconds(init.watchdog_timeout),
                                          passivity=init.passivity == pb.PASSIVITY_TDPA,
                                          max_command_age_s=convert.seconds(
                                              init.max_command_age))
        return session, session.stream

    def _received(self, request: pb.TeleoperateRequest
                  ) -> tuple[pb.TeleoperateRequest, list[MasterIncrement]]:
        """A Teleoperate message as it arrives (on the inbox's thread), with its commands (none
        for a heartbeat or an end), each checked, converted and stamped with its receive time
        then."""
        kind = request.WhichOneof("message")
        if kind == "heartbeat":
            _master_energy_in(request.heartbeat)  # checked as it arrives, like a command
        if kind in ("heartbeat", "end"):
            return request, []
        if kind == "command":
            commands = [request.command]
        elif kind == "commands":
            commands = request.commands.commands
            if not 1 <= len(commands) <= MAX_COMMANDS_PER_MESSAGE:
                raise InvalidArgumentError(
                    f"commands carries 1 to {MAX_COMMANDS_PER_MESSAGE} commands, not "
                    f"{len(commands)}", reason="BAD_COMMANDS")
        else:
            raise InvalidArgumentError("only commands, heartbeats and an end may follow the init",
                                       reason="BAD_MESSAGE")
        received_ns = self._core.clock.time_ns()
        return request, [self._increment(command, received_ns) for command in commands]

    def _increment(self, command: pb.MasterCommand, received_ns: int) -> MasterIncrement:
        if command.sequence < 0:
            raise InvalidArgumentError("sequence must be ≥ 0", reason="BAD_SEQUENCE")
        on_command_age = self.on_command_age
        if on_command_age is not None and command.HasField("send_time"):
            on_command_age((received_ns - convert.time_ns(command.send_time)) / 1e9)
        return MasterIncrement(
            convert.vector3_from_proto(command.delta_position_m, "delta_position_m"),
            convert.rotation_from_proto(command.delta_rotation, "delta_rotation"),
            command.clutch_engaged, received_ns, command.sequence,
            _master_energy_in(command), convert.time_ns(command.send_time))

    def _answers(self, session: OperatorSession, stream: int, batch, grouped: bool
                 ) -> Iterator[pb.TeleoperateResponse]:
        """What messages that arrived together are answered with, in order: an ack each, or
        (`grouped`, TeleoperateInit.grouped_acks) all their acks in one message; then
        _END_OF_SESSION if they held the operator's end."""
        if not grouped:
            yield from self._serve_batch(session, stream, batch)
            return
        acks, ended = [], False
        try:
            for answer in self._serve_batch(session, stream, batch):
                if answer is _END_OF_SESSION:
                    ended = True
                    break
                acks.append(answer.ack)
        except TelerobotError:
            if acks:  # what was done before the error is still answered
                yield pb.TeleoperateResponse(acks=pb.CommandAcks(acks=acks))
            raise
        if acks:
            yield pb.TeleoperateResponse(acks=pb.CommandAcks(acks=acks))
        if ended:
            yield _END_OF_SESSION

    def _serve_batch(self, session: OperatorSession, stream: int, batch
                     ) -> Iterator[pb.TeleoperateResponse]:
        """Acks, in order, for messages that arrived together: the commands between heartbeats
        go to the session together (it may merge them into one move)."""
        increments: list[MasterIncrement] = []
        for request, commands in [*batch, (None, [])]:
            for receipt in _ack_receipts(request):
                if receipt.sequence > 0:
                    session.clock_offset.receipt(receipt.sequence,
                                                 convert.time_ns(receipt.receive_time))
            if commands:
                increments += commands
                continue
            # (A late command's ack comes with that of the fresh command it joins.)
            for command, result in session.decide(increments, stream):
                yield self._ack(command.sequence, command.send_time_ns, result, session)
            increments = []
            if request is not None and request.WhichOneof("message") == "end":
                for command, result in session.ending(stream):
                    yield self._ack(command.sequence, command.send_time_ns, result, session)
                yield _END_OF_SESSION  # what came after it is ignored
                return
            if request is not None:
                heartbeat = request.heartbeat
                yield self._ack(0, convert.time_ns(heartbeat.send_time),
                                session.heartbeat(stream, _master_energy_in(heartbeat)), session)

    def _control_state(self) -> pb.ControlState:
        return control_state(self._core.locks.view(), self._core.clock)

    def GetAssistance(self, request, context):
        return pb.GetAssistanceResponse(assistance=assistance_to_proto(self._core.assistance))

    def SetAssistance(self, request, context):
        value = self._core.set_assistance(lease_id(context),
                                          assistance_from_proto(request.assistance))
        return pb.SetAssistanceResponse(assistance=assistance_to_proto(value))

    def SetIndexing(self, request, context):
        return pb.SetIndexingResponse(
            engaged=self._core.set_indexing(lease_id(context), request.engaged))

    def AcquireControl(self, request, context):
        if not request.mode:
            raise InvalidArgumentError("mode must be CONTROL_MODE_EXCLUSIVE or "
                                       "CONTROL_MODE_COLLABORATIVE", reason="BAD_MODE")
        mode = ControlMode[pb.ControlMode.Name(request.mode).removeprefix("CONTROL_MODE_")]
        wait_s = convert.seconds(request.wait_timeout) or context.time_remaining()
        lease = self._core.locks.acquire(
            request.operator_id, mode, request.group, request.wait, wait_s,
            convert.seconds(request.lease_duration) or DEFAULT_LEASE_S,
            on_caller_gone=context.add_callback,  # a cancelled wait leaves the queue
            group_secret=request.group_secret)
        return pb.AcquireControlResponse(lease_id=lease.lease_id, operator_id=lease.operator_id,
                                         expire_time=_holder(lease, self._core.clock).expire_time,
                                         state=self._control_state(),
                                         group_secret=lease.group_secret)

    def RenewControl(self, request, context):
        return pb.RenewControlResponse(
            expire_time=_holder(self._core.locks.renew(request.lease_id),
                                 self._core.clock).expire_time)

    def ReleaseControl(self, request, context):
        self._core.locks.release(request.lease_id)
        return pb.ReleaseControlResponse(state=self._control_state())

    def GetControlState(self, request, context):
        return pb.GetControlStateResponse(state=self._control_state())

    def StartRecording(self, request, context):
        info = self._core.start_recording(lease_id(context), request.name,
                                          recording_format(request.format), request.task)
        return pb.StartRecordingResponse(recording=recording_to_proto(info))

    def StopRecording(self, request, context):
        return pb.StopRecordingResponse(recording=recording_to_proto(
            self._core.stop_recording(lease_id(context), episode_outcome(request.outcome))))

    def ListRecordings(self, request, context):
        return pb.ListRecordingsResponse(
            recordings=[recording_to_proto(i) for i in self._core.recordings.list()])

    def DeleteRecording(self, request, context):
        self._core.recordings.delete(request.name)
        return pb.DeleteRecordingResponse()

    def StartReplay(self, request, context):
        commands = inline_increments(request.increments) if request.increments else None
        info = self._core.start_replay(lease_id(context), request.name, request.speed,
                                       commands)
        return pb.StartReplayResponse(recording=recording_to_proto(info))

    def StopReplay(self, request, context):
        return pb.StopReplayResponse(commands_replayed=self._core.stop_replay(lease_id(context)))

    def BeginCobegin(self, request, context):
        cobegin_id, timeout_s = self._core.barriers.open(
            request.action_count, convert.seconds(request.barrier_timeout))
        return pb.BeginCobeginResponse(
            cobegin_id=cobegin_id,
            deadline_time=convert.timestamp(time.time_ns() + int(timeout_s * 1e9)))

    def RunAction(self, request, context):
        arrive = time.time_ns()
        lane = current_lane() or Lane.MEDIUM
        kind = request.WhichOneof("action")
        if kind is None:
            raise InvalidArgumentError("set one action: busy_work, move_joints or move_cartesian",
                                       reason="NO_ACTION")
        # The action checked first, then the lease (every action needs it, busy work too: it
        # holds a lane thread and the processor), before waiting at a barrier.
        move = _move_from_proto(self._core, lease_id(context), kind, getattr(request, kind))
        busy_s = _busy_work_s(request.busy_work) if kind == "busy_work" else 0.0
        self._core.locks.require(lease_id(context))
        if request.cobegin_id:
            self._core.barriers.arrive_and_wait(request.cobegin_id)
        if kind == "busy_work":
            start, end = self._core.processor.run(int(lane), busy_s,
                                                  cancelled=lambda: not context.is_active())
        else:
            start = time.time_ns()
            move()
            end = time.time_ns()
        return pb.RunActionResponse(action_id=request.action_id, lane=LANE_TO_PROTO[lane],
                                    arrive_time=convert.timestamp(arrive),
                                    start_time=convert.timestamp(start),
                                    end_time=convert.timestamp(end))

    def GetDependencies(self, request, context):
        # A fresh look (cheap: cached health answers and a small file), so the answer is
        # current even between the watch's polls; a change seen here is raised as an event.
        return pb.GetDependenciesResponse(
            dependencies=[dependency_to_proto(d) for d in self._dependencies.poll()])

    def StreamEvents(self, request, context):
        # Unwanted state samples are left out as they are published, not as they are read:
        # queued, their flood would crowd out (and a slow reader would drop) the rare events.
        subscription = (Subscription(self._core.events, 256) if request.include_data_received
                        else _WithoutStateSamples(self._core.events, 256))
        with self._core.events.attach(subscription) as events:
            while context.is_active():
                event = events.get(STREAM_POLL_S)
                if event is not None:
                    yield event_to_proto(event, self._core.clock)


# -- the inherited services, forwarded --------------------------------------------------------

def _move_from_proto(core: DecisionCore, lease: str | None, kind: str, action):
    """RunAction's move, checked and converted now, to run through the core later."""
    if kind == "move_joints":
        deltas = finite_vector(action.delta_joint_positions_rad, arm_description().joint_count,
                               "delta_joint_positions_rad")
        return lambda: core.move_joints(lease, deltas)
    if kind == "move_cartesian":
        delta_x = convert.vector3_from_proto(action.delta_position_m, "delta_position_m")
        delta_m = convert.rotation_from_proto(action.delta_rotation, "delta_rotation")
        frame = frame_from_proto(action.frame)
        return lambda: core.move_cartesian(lease, delta_x, delta_m, frame)
    return None


def _ack_receipts(request: pb.TeleoperateRequest | None) -> list[pb.AckReceipt]:
    """The ack receipts a Teleoperate message carries: its command's or heartbeat's, or each
    of its commands'."""
    kind = request.WhichOneof("message") if request is not None else None
    if kind in ("command", "heartbeat"):
        return [getattr(request, kind).ack_receipt]
    if kind == "commands":
        return [command.ack_receipt for command in request.commands.commands]
    return []


def _busy_work_s(action: pb.BusyWorkAction) -> float:
    """RunAction's busy work, its duration checked now (before the lease and the barrier)."""
    seconds = convert.seconds(action.duration)
    if not 0 <= seconds <= MAX_BUSY_WORK_S:
        raise InvalidArgumentError(f"busy_work.duration must be 0..{MAX_BUSY_WORK_S:.0f} s",
                                   reason="BAD_DURATION")
    return seconds


def _status(name: str) -> int:
    return types_pb2.RobotStatus.Value(f"ROBOT_STATUS_{name}")


def _master_energy_in(message: pb.MasterCommand | pb.Heartbeat) -> float | None:
    """The master port's E_in a command or heartbeat carries (J), or None without one."""
    if not message.HasField("master_energy"):
        return None
    energy = message.master_energy
    values = (energy.energy_in_j, energy.energy_out_j, energy.dissipated_j)
    if not all(math.isfinite(v) and v >= 0.0 for v in values):
        raise InvalidArgumentError("master_energy must hold finite energies ≥ 0 J",
                                   reason="BAD_ENERGY")
    return energy.energy_in_j


def make_facades(core: DecisionCore, robot_stub, sensor_stub, stereo_stub) -> list[tuple]:
    """(grpc module, service name, servicer) for ProxyRobot, ForceSensor and StereoCamera:
    each forwarded to its stub with the lock in front of commands, and the calls that change
    what the DecisionServer supervises (stop, reset, tool frame) through the core."""

    def guard_commands(commands: set[str]):
        def guard(method: str, context) -> None:
            if method in commands:
                core.locks.require(lease_id(context))
        return guard

    class RobotOverrides:
        def EmergencyStop(self, request, context):
            status = core.emergency_stop(request.reason or "emergency stop")
            return proxy_robot_pb2.EmergencyStopResponse(
                status=_status(status), stop_time=convert.timestamp(time.time_ns()))

        def Reset(self, request, context):
            return proxy_robot_pb2.ResetResponse(status=_status(core.reset(lease_id(context))))

        def SetToolFrame(self, request, context):
            flange_to_tool = se3.pose_from_proto(request.flange_to_tool, "flange_to_tool")
            return proxy_robot_pb2.SetToolFrameResponse(flange_to_tool=convert.pose_to_proto(
                core.set_tool_frame(lease_id(context), flange_to_tool)))

    def note_status(method: str, reply) -> None:
        if method in STATUS_ANSWERS:
            core.note_status(status_name(reply.status), method.lower())

    robot = forwarding_servicer(
        proxy_robot_pb2_grpc.ProxyRobotServicer, robot_stub,
        proxy_robot_pb2.DESCRIPTOR.services_by_name["ProxyRobot"],
        guard_commands(PROXY_COMMANDS), RobotOverrides, answered=note_status)
    sensor = forwarding_servicer(
        force_sensor_pb2_grpc.ForceSensorServicer, sensor_stub,
        force_sensor_pb2.DESCRIPTOR.services_by_name["ForceSensor"],
        guard_commands(SENSOR_COMMANDS))
    stereo = forwarding_servicer(
        stereo_camera_pb2_grpc.StereoCameraServicer, stereo_stub,
        stereo_camera_pb2.DESCRIPTOR.services_by_name["StereoCamera"], lambda m, c: None)
    return [(proxy_robot_pb2_grpc, "ProxyRobot", robot()),
            (force_sensor_pb2_grpc, "ForceSensor", sensor()),
            (stereo_camera_pb2_grpc, "StereoCamera", stereo())]


def _first_message(request_iterator, context: grpc.ServicerContext, timeout_s: float):
    """The stream's first message, or None; a client that sends none within `timeout_s` has its
    call cancelled (a blocked read ends only so)."""
    timer = threading.Timer(timeout_s, context.cancel)
    timer.daemon = True
    timer.start()
    try:
        return next(request_iterator, None)
    finally:
        timer.cancel()
