"""DecisionServer clients: the operator's one address, with the control lease and Teleoperate.

``DecisionClient`` (blocking) and ``AsyncDecisionClient`` (asyncio) have the same methods.

The lease: ``acquire_control(...)`` returns a `Lease` and keeps it; from then on every call of
this client and of its facades (``client.robot``, ``client.sensor``, ``client.camera``, the
ProxyRobot, ForceSensor and StereoCamera services on the same port) carries its id in the
``telerobot-lease-id`` metadata, which is what commanding calls need. ``release_control()``
drops it; closing the client releases a lease it still holds (``release_on_close``). The lease
is not renewed in the background: every authorized call renews it, and an operator who only
watches calls ``renew_control()`` within the lease (10 s by default). A lease that lapsed gets
NOT_FOUND on renew and FAILED_PRECONDITION on commands: acquire again (explicitly).

Teleoperate: ``client.teleoperate(...)`` returns a session (``teleoperate.py``): commands,
heartbeats and their acks, and a session that reconnects and resumes across a broken link.

Returns: `Lease`, `Recording`, `Cobegin`, `ActionRun`, `Ack`, `Dependency` (``values.py``);
the proto ``AssistanceConfig`` and ``ControlState`` (nested configuration records, clearest as
protos), and proto ``StreamEventsResponse`` events (their oneof says which event).
"""

from __future__ import annotations

import dataclasses
import logging
import time
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import grpc

from clients.python.base import DEFAULT_TIMEOUT_S, AsyncClient, SyncClient
from clients.python.force_sensor import AsyncForceSensorClient, ForceSensorClient
from clients.python.proxy_robot import (
    AsyncProxyRobotClient,
    ProxyRobotClient,
    cartesian_request,
    joints_request,
)
from clients.python.stereo_camera import AsyncStereoCameraClient, StereoCameraClient
from clients.python.teleoperate import AsyncTeleopSession, TeleopSession, teleoperate_init
from clients.python.values import (
    Ack,
    ActionRun,
    BusyWork,
    CartesianIncrement,
    Cobegin,
    ControlMode,
    Dependency,
    JointIncrement,
    Lane,
    Lease,
    Recording,
    RobotStatus,
    enum_value,
    time_ns,
)
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import decision_server_pb2_grpc
from wire import convert
from wire.errors import TelerobotError
from wire.tls import ChannelSecurity

if TYPE_CHECKING:  # the master's side of TDPA; the client only reads its ledger
    from domain.passivity import MasterPassivity

log = logging.getLogger(__name__)



def _action_request(action, cobegin_id: str, action_id: str) -> pb.RunActionRequest:
    request = pb.RunActionRequest(cobegin_id=cobegin_id, action_id=action_id)
    if isinstance(action, BusyWork):
        request.busy_work.duration.CopyFrom(convert.duration(action.duration_s))
    elif isinstance(action, JointIncrement):
        request.move_joints.CopyFrom(joints_request(action.delta))
    elif isinstance(action, CartesianIncrement):
        request.move_cartesian.CopyFrom(cartesian_request(
            action.delta_position, action.delta_rotation, action.frame))
    else:
        raise TypeError(f"action must be BusyWork, JointIncrement or CartesianIncrement, "
                        f"not {type(action).__name__}")
    return request


# -- the clients --------------------------------------------------------------------------------

class _DecisionMethods:
    """The DecisionServer calls; on the async client each returns an awaitable of the same
    value."""

    SERVICE = "telerobot.v1.DecisionServer"
    ADDRESS_NAME = "decision_server"
    CERTIFICATE_SERVICE = "decision_server"  # only a DecisionServer serves this contract
    STUB = decision_server_pb2_grpc.DecisionServerStub

    def _init_decision(self, release_on_close: bool) -> None:
        self.release_on_close = release_on_close
        self._held: Lease | None = None
        self._facades: dict[str, Any] = {}

    @property
    def lease(self) -> Lease | None:
        """The lease this client holds and sends, or None."""
        return self._held

    def _held_lease_id(self) -> str | None:
        return self._held.lease_id if self._held else None

    # -- control ---------------------------------------------------------------------------------
    def acquire_control(self, operator_id: str, mode: int = ControlMode.EXCLUSIVE, *,
                        group: str = "", group_secret: str = "", wait: bool = False,
                        wait_timeout_s: float = 0.0,
                        lease_duration_s: float = 0.0, timeout: float | None = None,
                        lane: str | None = None) -> Lease:
        """Ask for the control lock; keep and return the `Lease`. With ``wait=True`` the call
        queues fairly for up to `wait_timeout_s` (0: until the call's `timeout`). Joining a
        COLLABORATIVE group that holds control takes its `group_secret` (a member's
        `Lease.group_secret`)."""
        request = pb.AcquireControlRequest(operator_id=operator_id, mode=int(mode), group=group,
                                           group_secret=group_secret, wait=wait)
        if wait_timeout_s:
            request.wait_timeout.CopyFrom(convert.duration(wait_timeout_s))
        if lease_duration_s:
            request.lease_duration.CopyFrom(convert.duration(lease_duration_s))

        def keep(response: pb.AcquireControlResponse) -> Lease:
            holder = response.operator_id or operator_id  # with TLS: the server's identity
            self._held = Lease(response.lease_id, holder, enum_value(ControlMode, mode),
                               group, time_ns(response.expire_time), response.state,
                               response.group_secret)
            return self._held

        return self._unary("AcquireControl", request, keep, timeout, lane)

    def renew_control(self, *, timeout: float | None = None, lane: str | None = None) -> int:
        """Extend the held lease; returns its new expiry (ns). NOT_FOUND once it lapsed."""
        held = self._require_lease()

        def keep(response: pb.RenewControlResponse) -> int:
            expire = time_ns(response.expire_time)
            if self._held is not None and self._held.lease_id == held.lease_id:
                self._held = dataclasses.replace(self._held, expire_time_ns=expire)
            return expire

        return self._unary("RenewControl", pb.RenewControlRequest(lease_id=held.lease_id), keep,
                           timeout, lane)

    def release_control(self, *, timeout: float | None = None, lane: str | None = None
                        ) -> pb.ControlState:
        """Give the held lease up (the arm holds); returns who holds control now."""
        held = self._require_lease()

        def forget(response: pb.ReleaseControlResponse) -> pb.ControlState:
            if self._held is not None and self._held.lease_id == held.lease_id:
                self._held = None
            return response.state

        return self._unary("ReleaseControl", pb.ReleaseControlRequest(lease_id=held.lease_id),
                           forget, timeout, lane)

    def _require_lease(self) -> Lease:
        if self._held is None:
            raise RuntimeError("no lease held: call acquire_control() first")
        return self._held

    def get_control_state(self, *, timeout: float | None = None, lane: str | None = None
                          ) -> pb.ControlState:
        return self._unary("GetControlState", pb.GetControlStateRequest(), lambda r: r.state,
                           timeout, lane)

    # -- assistance ------------------------------------------------------------------------------
    def get_assistance(self, *, timeout: float | None = None, lane: str | None = None
                       ) -> pb.AssistanceConfig:
        return self._unary("GetAssistance", pb.GetAssistanceRequest(), lambda r: r.assistance,
                           timeout, lane)

    def set_assistance(self, assistance: pb.AssistanceConfig, *, timeout: float | None = None,
                       lane: str | None = None) -> pb.AssistanceConfig:
        """Replace the whole assistance configuration; returns the one in force."""
        return self._unary("SetAssistance", pb.SetAssistanceRequest(assistance=assistance),
                           lambda r: r.assistance, timeout, lane)

    def set_indexing(self, engaged: bool, *, timeout: float | None = None,
                     lane: str | None = None) -> bool:
        """Engage or release the server-side clutch; returns whether it is engaged."""
        return self._unary("SetIndexing", pb.SetIndexingRequest(engaged=engaged),
                           lambda r: r.engaged, timeout, lane)

    # -- record and replay -----------------------------------------------------------------------
    def start_recording(self, name: str, *, format: int = pb.RECORDING_FORMAT_JSONL,
                        task: str = "", timeout: float | None = None,
                        lane: str | None = None) -> Recording:
        """Record the applied commands under `name` (MCAP: with the arm's state, wrench and
        the stereo video); a `task` makes it an episode (MCAP)."""
        return self._unary("StartRecording", pb.StartRecordingRequest(
            name=name, format=format, task=task),
            lambda r: Recording.from_proto(r.recording), timeout, lane)

    def stop_recording(self, *, outcome: int = pb.EPISODE_OUTCOME_UNSPECIFIED,
                       timeout: float | None = None, lane: str | None = None) -> Recording:
        """Save the recording; `outcome` (an EpisodeOutcome) says how an episode went."""
        return self._unary("StopRecording", pb.StopRecordingRequest(outcome=outcome),
                           lambda r: Recording.from_proto(r.recording), timeout, lane)

    def start_episode(self, task: str, name: str | None = None, *,
                      timeout: float | None = None, lane: str | None = None) -> Recording:
        """Start a demonstration episode of `task` (an MCAP recording; named after the time
        unless `name`). Needs the control lock, as any recording."""
        name = name or time.strftime("episode-%Y%m%d-%H%M%S", time.gmtime()) + \
            f"-{time.time_ns() // 1_000_000 % 1000:03d}"
        return self.start_recording(name, format=pb.RECORDING_FORMAT_MCAP, task=task,
                                    timeout=timeout, lane=lane)

    def end_episode(self, outcome: int = pb.EPISODE_OUTCOME_SUCCEEDED, *,
                    timeout: float | None = None, lane: str | None = None) -> Recording:
        """End the episode: saved (fsynced) with how it went (SUCCEEDED, FAILED, DISCARDED)."""
        return self.stop_recording(outcome=outcome, timeout=timeout, lane=lane)

    def list_recordings(self, *, timeout: float | None = None, lane: str | None = None
                        ) -> list[Recording]:
        return self._unary("ListRecordings", pb.ListRecordingsRequest(),
                           lambda r: [Recording.from_proto(x) for x in r.recordings],
                           timeout, lane)

    def delete_recording(self, name: str, *, timeout: float | None = None,
                         lane: str | None = None) -> None:
        return self._unary("DeleteRecording", pb.DeleteRecordingRequest(name=name),
                           lambda r: None, timeout, lane)

    def start_replay(self, name: str, speed: float = 1.0, *,
                     increments: Sequence[pb.RecordedIncrement] = (),
                     timeout: float | None = None, lane: str | None = None) -> Recording:
        """Replay the stored recording `name`, or `increments` (RecordedIncrements, each at its
        offset; `name` then labels the replay's events)."""
        return self._unary("StartReplay", pb.StartReplayRequest(
            name=name, speed=speed, increments=increments),
            lambda r: Recording.from_proto(r.recording), timeout, lane)

    def stop_replay(self, *, timeout: float | None = None, lane: str | None = None) -> int:
        """Interrupt the replay; returns the number of commands replayed."""
        return self._unary("StopReplay", pb.StopReplayRequest(), lambda r: r.commands_replayed,
                           timeout, lane)

    # -- cobegin ---------------------------------------------------------------------------------
    def begin_cobegin(self, action_count: int, barrier_timeout_s: float = 0.0, *,
                      timeout: float | None = None, lane: str | None = None) -> Cobegin:
        request = pb.BeginCobeginRequest(action_count=action_count)
        if barrier_timeout_s:
            request.barrier_timeout.CopyFrom(convert.duration(barrier_timeout_s))
        return self._unary("BeginCobegin", request,
                           lambda r: Cobegin(r.cobegin_id, time_ns(r.deadline_time)),
                           timeout, lane)

    def run_action(self, action: BusyWork | JointIncrement | CartesianIncrement, *,
                   cobegin_id: str = "", action_id: str = "", timeout: float | None = None,
                   lane: str | None = None) -> ActionRun:
        """Run one action on `lane`, at once or at its cobegin's barrier; returns when it
        ended."""
        return self._unary("RunAction", _action_request(action, cobegin_id, action_id),
                           lambda r: ActionRun(r.action_id, enum_value(Lane, r.lane),
                                               time_ns(r.arrive_time), time_ns(r.start_time),
                                               time_ns(r.end_time)), timeout, lane)

    # -- dependencies ----------------------------------------------------------------------------
    def get_dependencies(self, *, timeout: float | None = None, lane: str | None = None
                         ) -> list[Dependency]:
        """How each service the DecisionServer depends on is (proxy_robot, force_sensor,
        stereo_camera, emergency_stop): SERVING, NOT_SERVING or RESTARTING, and why. Changes
        also come as ``dependency_changed`` events (`Dependency.from_proto` reads them)."""
        return self._unary("GetDependencies", pb.GetDependenciesRequest(),
                           lambda r: [Dependency.from_proto(d) for d in r.dependencies],
                           timeout, lane)

    # -- events ----------------------------------------------------------------------------------
    def stream_events(self, include_data_received: bool = False, *,
                      timeout: float | None = None, lane: str | None = None):
        """Proto ``StreamEventsResponse`` events until cancelled."""
        return self._server_stream("StreamEvents", pb.StreamEventsRequest(
            include_data_received=include_data_received), lambda r: r, timeout, lane)

    # -- the inherited services on the same port -------------------------------------------------
    def _facade(self, name: str, cls, own_channel: bool = False):
        if name not in self._facades:
            target = self.address if own_channel and self.address else self.channel
            self._facades[name] = cls(target, lease=self._held_lease_id, lane=self.lane,
                                      default_timeout=self.default_timeout,
                                      security=self.security)
        return self._facades[name]

    def emergency_stop(self, reason: str = "", *, timeout: float | None = None,
                       lane: str | None = None) -> RobotStatus:
        """ProxyRobot.EmergencyStop on this port: needs no lock; also stops teleoperation,
        replay and force control."""
        return self.robot.emergency_stop(reason, timeout=timeout, lane=lane)

    def reset(self, *, timeout: float | None = None, lane: str | None = None) -> RobotStatus:
        """ProxyRobot.Reset on this port (needs the lock)."""
        return self.robot.reset(timeout=timeout, lane=lane)


class DecisionClient(_DecisionMethods, SyncClient):
    """Blocking DecisionServer client (and, through ``robot``, ``sensor`` and ``camera``, the
    services forwarded on its port). A context manager: leaving it releases a held lease (if
    ``release_on_close``) and closes the channel."""

    def __init__(self, target: str | grpc.Channel | None = None, *, lane: str | None = None,
                 default_timeout: float | None = DEFAULT_TIMEOUT_S,
                 options: Sequence[tuple[str, Any]] = (), release_on_close: bool = True,
                 security: ChannelSecurity | None = None):
        self._init_decision(release_on_close)
        super().__init__(target, lease=self._held_lease_id, lane=lane,
                         default_timeout=default_timeout, options=options, security=security)

    @property
    def robot(self) -> ProxyRobotClient:
        """ProxyRobot on this port, on this channel, with this client's lease."""
        return self._facade("robot", ProxyRobotClient)

    @property
    def sensor(self) -> ForceSensorClient:
        """ForceSensor on this port, on this channel, with this client's lease."""
        return self._facade("sensor", ForceSensorClient)

    @property
    def camera(self) -> StereoCameraClient:
        """StereoCamera on this port, on its own low-latency channel when this client opened
        its channel from an address."""
        return self._facade("camera", StereoCameraClient, own_channel=True)

    def teleoperate(self, operator_id: str | None = None, mapping: int | None = None, *,
                    watchdog_timeout_s: float | None = None, timeout: float | None = None,
                    on_ack: Callable[[Ack], Any] | None = None, resume: bool = True,
                    on_link: Callable[[str, str], Any] | None = None,
                    passivity: MasterPassivity | None = None,
                    max_command_age_s: float | None = None) -> TeleopSession:
        """Open a Teleoperate session with the held lease (operator: the lease's, unless given;
        mapping: BASE or TOOL, None keeps the assistance configuration's; watchdog: None is the
        server's 100 ms). Waits up to `timeout` for the Ready; FAILED_PRECONDITION without the
        lock or when the arm is not READY. A broken link is resumed (see teleoperate.py) unless
        `resume` is False; `on_link(state, detail)` hears of it. With `passivity` (TDPA's master
        port, the one the master arm displays its force through) the session asks the server
        for TDPA and carries the two ports' energies. `max_command_age_s`: how long a command
        may wait in the server and still move the arm on its own (None: the server's 50 ms)."""
        self._check_open()
        init = teleoperate_init(operator_id or (self._held.operator_id if self._held else ""),
                     self._held_lease_id() or "", mapping, watchdog_timeout_s,
                     passivity=passivity is not None, max_command_age_s=max_command_age_s)
        return TeleopSession(self._stub, init, self._metadata(None),
                             ready_timeout=self._timeout(timeout),
                             default_timeout=self.default_timeout, on_ack=on_ack,
                             resume=resume, on_link=on_link, passivity=passivity)

    def close(self) -> None:
        if self._closed:
            return
        if self.release_on_close and self._held is not None:
            try:
                self.release_control(timeout=1.0)
            except TelerobotError as error:
                log.info("could not release the lease on close: %s", error)
        for facade in self._facades.values():
            facade.close()
        super().close()


class AsyncDecisionClient(_DecisionMethods, AsyncClient):
    """asyncio DecisionServer client: the same methods, awaited; ``async with`` releases a
    held lease (if ``release_on_close``) and closes the channel."""

    def __init__(self, target: str | grpc.aio.Channel | None = None, *,
                 lane: str | None = None, default_timeout: float | None = DEFAULT_TIMEOUT_S,
                 options: Sequence[tuple[str, Any]] = (), release_on_close: bool = True,
                 security: ChannelSecurity | None = None):
        self._init_decision(release_on_close)
        super().__init__(target, lease=self._held_lease_id, lane=lane,
                         default_timeout=default_timeout, options=options, security=security)

    @property
    def robot(self) -> AsyncProxyRobotClient:
        return self._facade("robot", AsyncProxyRobotClient)

    @property
    def sensor(self) -> AsyncForceSensorClient:
        return self._facade("sensor", AsyncForceSensorClient)

    @property
    def camera(self) -> AsyncStereoCameraClient:
        return self._facade("camera", AsyncStereoCameraClient, own_channel=True)

    async def teleoperate(self, operator_id: str | None = None, mapping: int | None = None, *,
                          watchdog_timeout_s: float | None = None,
                          timeout: float | None = None,
                          on_ack: Callable[[Ack], Any] | None = None,
                          max_command_age_s: float | None = None) -> AsyncTeleopSession:
        """As `DecisionClient.teleoperate`, awaited."""
        self._check_open()
        init = teleoperate_init(operator_id or (self._held.operator_id if self._held else ""),
                     self._held_lease_id() or "", mapping, watchdog_timeout_s,
                     max_command_age_s=max_command_age_s)
        return await AsyncTeleopSession.open(self._stub, init, self._metadata(None),
                                             ready_timeout=self._timeout(timeout),
                                             default_timeout=self.default_timeout,
                                             on_ack=on_ack)

    async def close(self) -> None:
        if self._closed:
            return
        if self.release_on_close and self._held is not None:
            try:
                await self.release_control(timeout=1.0)
            except TelerobotError as error:
                log.info("could not release the lease on close: %s", error)
        for facade in self._facades.values():
            await facade.close()
        await super().close()
