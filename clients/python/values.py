"""Plain values the clients return, and enums mirroring the proto enums.

Units are the contracts' units: metres, radians, newtons, newton-metres, seconds; timestamps are
integers in nanoseconds since the Unix epoch (``*_time_ns``), the server's clock. Poses are
`Pose` (``wire.pose``: the child frame in the parent frame, with a ``pin.SE3``'s ``rotation``,
``translation`` and ``homogeneous``), vectors ``numpy`` float arrays.

The enums are built from the generated proto enums, without their prefix, so they never drift:
``RobotStatus.READY == types_pb2.ROBOT_STATUS_READY``. They are ``IntEnum``s: a proto field
accepts them as they are.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field

import numpy as np

from telerobot.v1 import decision_server_pb2 as ds_pb
from telerobot.v1 import force_sensor_pb2 as fs_pb
from telerobot.v1 import options_pb2, types_pb2
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from wire.convert import pose_value, seconds, time_ns, vector3_value
from wire.pose import Pose


def _proto_enum(name: str, proto_enum, prefix: str) -> type[enum.IntEnum]:
    return enum.IntEnum(name, {key.removeprefix(prefix): value
                               for key, value in proto_enum.items()})


RobotStatus = _proto_enum("RobotStatus", types_pb2.RobotStatus, "ROBOT_STATUS_")
ReferenceFrame = _proto_enum("ReferenceFrame", types_pb2.ReferenceFrame, "REFERENCE_FRAME_")
ControlMode = _proto_enum("ControlMode", ds_pb.ControlMode, "CONTROL_MODE_")
CommandOutcome = _proto_enum("CommandOutcome", ds_pb.CommandOutcome, "COMMAND_OUTCOME_")
ReplayState = _proto_enum("ReplayState", ds_pb.ReplayState, "REPLAY_STATE_")
DependencyState = _proto_enum("DependencyState", ds_pb.DependencyState, "DEPENDENCY_STATE_")
ImageEncoding = _proto_enum("ImageEncoding", sc_pb.ImageEncoding, "IMAGE_ENCODING_")
TransferMode = _proto_enum("TransferMode", sc_pb.TransferMode, "TRANSFER_MODE_")
SensorThreadPriority = _proto_enum("SensorThreadPriority", fs_pb.SensorThreadPriority,
                                   "SENSOR_THREAD_PRIORITY_")
Lane = _proto_enum("Lane", options_pb2.Lane, "LANE_")


def enum_value(cls, value: int):
    """``cls(value)``, or the plain int for a value this build's protos do not know."""
    try:
        return cls(value)
    except ValueError:
        return int(value)


# -- ProxyRobot -------------------------------------------------------------------------------

@dataclass(frozen=True)
class StatusInfo:
    """ProxyRobot.GetStatus: the status, why it was entered, and when."""

    status: RobotStatus
    reason: str
    change_time_ns: int


@dataclass(frozen=True)
class ArmInfo:
    """What arm this is (ProxyRobot.GetArmInfo): every joint array in joint_names' order."""

    name: str
    joint_names: tuple[str, ...]
    lower_limits: np.ndarray  # rad
    upper_limits: np.ndarray  # rad
    velocity_limits: np.ndarray  # rad/s
    torque_limits: np.ndarray  # N*m
    home: np.ndarray  # rad
    default_flange_to_tool: Pose

    @property
    def joint_count(self) -> int:
        return len(self.joint_names)

    @classmethod
    def from_proto(cls, info) -> ArmInfo:
        def joints(values) -> np.ndarray:
            return np.asarray(values, dtype=float)

        return cls(info.name, tuple(info.joint_names), joints(info.joint_lower_limits_rad),
                   joints(info.joint_upper_limits_rad),
                   joints(info.joint_velocity_limits_rad_per_s),
                   joints(info.joint_torque_limits_nm), joints(info.home_joint_positions_rad),
                   pose_value(info.default_flange_to_tool))


@dataclass(frozen=True)
class RobotState:
    """One state sample of the arm (ProxyRobot.GetState / StreamState)."""

    sequence: int
    sample_time_ns: int
    status: RobotStatus
    joint_positions: np.ndarray  # rad, one per joint
    joint_velocities: np.ndarray  # rad/s, one per joint
    flange_pose: Pose  # in the base frame
    tool_pose: Pose  # in the base frame

    @classmethod
    def from_proto(cls, state: types_pb2.RobotState) -> RobotState:
        return cls(state.sequence, time_ns(state.sample_time),
                   enum_value(RobotStatus, state.status),
                   np.asarray(state.joint_positions_rad, dtype=float),
                   np.asarray(state.joint_velocities_rad_per_s, dtype=float),
                   pose_value(state.flange_pose), pose_value(state.tool_pose))


@dataclass(frozen=True)
class MoveResult:
    """The target a move was accepted with (MoveJointsIncremental, MoveCartesianIncremental).

    ``applied_fraction`` is 1 for joint moves; below 1 when a Cartesian step was reduced near a
    singularity."""

    target_joint_positions: np.ndarray  # rad, one per joint
    target_tool_pose: Pose
    applied_fraction: float = 1.0


# -- ForceSensor ------------------------------------------------------------------------------

@dataclass(frozen=True)
class WrenchSample:
    """One sensor sample: the wrench the environment applies to the tool, in tool axes, about
    the tool point, with the tool's weight and the tare bias removed."""

    sequence: int
    sample_time_ns: int
    force: np.ndarray  # N, (3,)
    torque: np.ndarray  # N*m, (3,)

    @classmethod
    def from_proto(cls, sample: fs_pb.WrenchSample) -> WrenchSample:
        return cls(sample.sequence, time_ns(sample.sample_time),
                   vector3_value(sample.wrench.force_n), vector3_value(sample.wrench.torque_nm))

    @property
    def wrench(self) -> np.ndarray:
        """[force; torque], (6,)."""
        return np.concatenate([self.force, self.torque])


@dataclass(frozen=True)
class WrenchBatch:
    """One StreamWrench message: samples oldest first, and batches dropped so far."""

    samples: list[WrenchSample]
    dropped_count: int


@dataclass(frozen=True)
class TareResult:
    bias_force: np.ndarray  # N, (3,), now subtracted from every sample
    bias_torque: np.ndarray  # N*m, (3,)
    sample_count: int


@dataclass(frozen=True)
class SensorConfig:
    """The sensor's configuration (SensorConfig)."""

    period_s: float
    threshold_force_n: float
    threshold_torque_nm: float
    thread_priority: SensorThreadPriority
    reading: bool
    flange_to_tool: Pose

    @classmethod
    def from_proto(cls, config: fs_pb.SensorConfig) -> SensorConfig:
        return cls(seconds(config.period), config.threshold_force_n, config.threshold_torque_nm,
                   enum_value(SensorThreadPriority, config.thread_priority), config.reading,
                   pose_value(config.flange_to_tool))


# -- StereoCamera -----------------------------------------------------------------------------

@dataclass(frozen=True)
class StereoFrame:
    """One synchronized pair with the stream header that describes it.

    ``left``/``right`` are decoded RGB8 arrays (height, width, 3), or None when the client was
    asked not to decode; ``pair`` keeps the encoded bytes and timing; ``received_ns`` is when
    the client read it (wall clock, ns)."""

    header: sc_pb.StereoHeader
    pair: sc_pb.StereoPair
    left: np.ndarray | None
    right: np.ndarray | None
    received_ns: int = 0

    @property
    def sequence(self) -> int:
        return self.pair.sequence


# -- DecisionServer ---------------------------------------------------------------------------

@dataclass(frozen=True)
class Lease:
    """A granted control lock. ``lease_id`` goes in the ``telerobot-lease-id`` metadata."""

    lease_id: str
    operator_id: str
    mode: ControlMode
    group: str
    expire_time_ns: int
    state: ds_pb.ControlState = field(repr=False)
    group_secret: str = field(default="", repr=False)  # COLLABORATIVE: what lets others join


@dataclass(frozen=True)
class Recording:
    name: str
    create_time_ns: int
    duration_s: float
    command_count: int
    task: str = ""  # an episode's
    outcome: str = ""  # an episode's: SUCCEEDED, FAILED, DISCARDED or UNSPECIFIED
    video_frames: int = 0
    error: str = ""  # why it cannot be replayed, when it cannot

    @classmethod
    def from_proto(cls, recording: ds_pb.Recording) -> Recording:
        outcome = ds_pb.EpisodeOutcome.Name(recording.outcome).removeprefix("EPISODE_OUTCOME_")
        return cls(recording.name, time_ns(recording.create_time), seconds(recording.duration),
                   recording.command_count, recording.task,
                   outcome if recording.task else "", recording.video_frames, recording.error)


@dataclass(frozen=True)
class Dependency:
    """One service the DecisionServer depends on (GetDependencies, and the dependency_changed
    event): proxy_robot, force_sensor, stereo_camera or emergency_stop."""

    name: str
    state: DependencyState  # SERVING, NOT_SERVING or RESTARTING
    reason: str  # why not serving, for people; empty while serving
    change_time_ns: int  # when it entered this state (the server's clock)
    restarts: int  # how often the station's launcher restarted it

    @classmethod
    def from_proto(cls, dependency: ds_pb.Dependency) -> Dependency:
        return cls(dependency.name, enum_value(DependencyState, dependency.state),
                   dependency.reason, time_ns(dependency.change_time), dependency.restarts)

    @property
    def serving(self) -> bool:
        return self.state == DependencyState.SERVING


@dataclass(frozen=True)
class Cobegin:
    cobegin_id: str
    deadline_time_ns: int


@dataclass(frozen=True)
class ActionRun:
    """RunAction's answer: the lane the action ran on and when."""

    action_id: str
    lane: Lane
    arrive_time_ns: int
    start_time_ns: int
    end_time_ns: int


@dataclass(frozen=True)
class BusyWork:
    """RunAction: occupy the server's simulated processor for `duration_s`."""

    duration_s: float


@dataclass(frozen=True)
class JointIncrement:
    """RunAction: a joint increment, as ProxyRobot.MoveJointsIncremental."""

    delta: tuple[float, ...] | np.ndarray


@dataclass(frozen=True)
class CartesianIncrement:
    """RunAction: a Cartesian increment, as ProxyRobot.MoveCartesianIncremental."""

    delta_position: tuple[float, float, float] | np.ndarray
    delta_rotation: np.ndarray | None = None
    frame: int = ReferenceFrame.BASE


@dataclass(frozen=True)
class Ack:
    """One Teleoperate ack (CommandAck), with the client's receive time.

    ``tool_pose`` is the slave's measured tool pose (base frame), ``force``/``torque`` the
    wrench at the tool in tool axes; None when the server had none to send."""

    sequence: int  # the command's sequence; 0 for a heartbeat
    outcome: CommandOutcome
    detail: str
    command_send_time_ns: int  # the client's clock, echoed
    receive_time_ns: int  # the server's clock
    apply_time_ns: int  # the server's clock
    received_time_ns: int  # the client's clock, when the ack arrived
    tool_pose: Pose | None
    force: np.ndarray | None
    torque: np.ndarray | None
    status: RobotStatus
    message: ds_pb.CommandAck = field(repr=False)

    @classmethod
    def from_proto(cls, ack: ds_pb.CommandAck, received_time_ns: int) -> Ack:
        has_wrench = ack.HasField("tool_wrench")
        return cls(ack.sequence, enum_value(CommandOutcome, ack.outcome), ack.detail,
                   time_ns(ack.command_send_time), time_ns(ack.receive_time),
                   time_ns(ack.apply_time), received_time_ns,
                   pose_value(ack.tool_pose) if ack.HasField("tool_pose") else None,
                   vector3_value(ack.tool_wrench.force_n) if has_wrench else None,
                   vector3_value(ack.tool_wrench.torque_nm) if has_wrench else None,
                   enum_value(RobotStatus, ack.status), ack)

    @property
    def round_trip_s(self) -> float:
        """From sending the command to receiving its ack, on the client's clock."""
        return (self.received_time_ns - self.command_send_time_ns) * 1e-9

    @property
    def applied(self) -> bool:
        """True when the increment moved the slave (APPLIED, MODIFIED, or MERGED_LATE: with
        the fresh command after it)."""
        return self.outcome in (CommandOutcome.APPLIED, CommandOutcome.MODIFIED,
                                CommandOutcome.MERGED_LATE)

    @property
    def clock_offset_s(self) -> float | None:
        """The server's estimate of its clock minus this client's, or None before it has one
        (it needs an AckReceipt, which the session sends with the next message)."""
        if not self.message.HasField("clock_offset"):
            return None
        return self.message.clock_offset.ToNanoseconds() * 1e-9

    @property
    def clock_offset_error_s(self) -> float | None:
        """How far `clock_offset_s` can be off."""
        if not self.message.HasField("clock_offset"):
            return None
        return self.message.clock_offset_error.ToNanoseconds() * 1e-9

    @property
    def sent_to_applied_s(self) -> float | None:
        """From sending the command to the server applying it, on the server's clock (the send
        time moved by `clock_offset_s`), so it holds across hosts; None without an offset."""
        offset = self.clock_offset_s
        if offset is None or not self.command_send_time_ns:
            return None
        return (self.apply_time_ns - self.command_send_time_ns) * 1e-9 - offset
