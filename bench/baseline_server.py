"""python -m bench.baseline_server --transport zmq|tcp|zmq-teleop: the baselines' slave side.

The same domain code as the services (ProxyRobotCore driving the world's shared memory,
ForceSensorCore sampling it at 1 kHz with per-subscriber decimation) and the same protobuf
payloads (MoveJointsIncrementalRequest/Response, StreamWrenchResponse), behind another
transport instead of gRPC, so that a project/baseline ratio isolates the transport:

- zmq: commands over REQ/REP, the wrench stream over PUB/SUB (an XPUB socket, so the server
  sees a subscription to topic ``d<N>|`` and opens a sensor subscription with decimation N);
- tcp: a plain socket with struct framing (framing.py): the papers' "custom protocol".

It connects and initializes the arm and starts the sensor on start-up; the bench disconnects
the ProxyRobot service first, because the world's command record has one writer at a time.
It prints ``TELEROBOT_READY baseline_command host:port`` and ``... baseline_force host:port``
and runs until SIGTERM/SIGINT (or until its parent, TELEROBOT_PARENT_PID, is gone).

- zmq-teleop: the Teleoperate stream's baseline (teleop_1000_zmq). The DecisionServer's own
  domain code, built as its __main__ builds it: a DecisionCore over a GrpcSlave to the
  station's ProxyRobot and ForceSensor services (which stay up), behind a ROUTER socket
  instead of grpcio. A DEALER sends TeleoperateRequest bytes (init, then commands, then an
  empty frame for the half-close); each gets [K, TeleoperateResponse bytes] (ready, then one
  ack per command), [E, why] (the session is over), or [X] for the half-close. Commands that
  arrived together are one batch for the servicer's own code (OperatorSessions), as on the gRPC
  stream. An init without a lease takes one (the bench has no other channel).
  It prints ``TELEROBOT_READY baseline_teleop host:port``.
"""

from __future__ import annotations

import argparse
import logging
import os
import signal
import socket
import sys
import tempfile
import threading
from pathlib import Path

from bench import framing
from services.decision_server.arbitration import ControlMode
from services.decision_server.backends import GrpcSlave
from services.decision_server.core import DecisionCore
from services.decision_server.recordings import RecordingStore
from services.decision_server.servicer import _END_OF_SESSION, DecisionServerServicer
from services.decision_server.sessions import OperatorSession
from services.force_sensor.core import ForceSensorCore
from services.force_sensor.servicer import reading_to_proto
from services.force_sensor.subscribers import StreamOptions
from services.proxy_robot.core import ProxyRobotCore
from services.runtime.process import GIL_SWITCH_INTERVAL_S, watch_parent
from services.world.shm_link import SharedMemoryArmLink, SharedMemoryWrenchLink
from telerobot.v1 import decision_server_pb2 as dpb
from telerobot.v1 import force_sensor_pb2, proxy_robot_pb2, types_pb2
from wire import convert
from wire.errors import InvalidArgumentError, TelerobotError
from wire.processes import say_ready

log = logging.getLogger("baseline")
POLL_S = 0.1  # how often idle loops look at the stop flag
SUBSCRIPTION_WAIT_S = 0.01
TELEOP_LEASE_S = 60.0  # every command renews it
TELEOP_END = b"X"
_MAPPINGS = {types_pb2.REFERENCE_FRAME_BASE: "BASE", types_pb2.REFERENCE_FRAME_TOOL: "TOOL"}


class Cores:
    """The arm proxy and the wrist sensor, exactly as the services run them."""

    def __init__(self, shm_name: str):
        self.robot = ProxyRobotCore(lambda: SharedMemoryArmLink(shm_name))
        self.sensor = ForceSensorCore(lambda: SharedMemoryWrenchLink(shm_name),
                                      lambda: SharedMemoryArmLink(shm_name))

    def start(self) -> None:
        self.robot.connect()
        self.robot.initialize()
        self.sensor.start_reading()

    def move(self, raw: bytes) -> bytes:
        """One MoveJointsIncremental, request bytes to reply bytes (K + response or E + why)."""
        try:
            request = proxy_robot_pb2.MoveJointsIncrementalRequest.FromString(raw)
            target, tool = self.robot.move_joints(request.delta_joint_positions_rad)
        except TelerobotError as error:
            return framing.REPLY_ERROR + error.message.encode()
        response = proxy_robot_pb2.MoveJointsIncrementalResponse(
            target_joint_positions_rad=target.tolist(),
            target_tool_pose=convert.pose_to_proto(tool))
        return framing.REPLY_OK + response.SerializeToString()

    def subscribe(self, decimation: int):
        return self.sensor.subscribe(StreamOptions(decimation=max(1, decimation)))

    def close(self) -> None:
        self.sensor.close()
        self.robot.close()


def wrench_payload(batch, dropped: int) -> bytes:
    """The bytes gRPC's StreamWrench would carry for this batch."""
    return force_sensor_pb2.StreamWrenchResponse(
        samples=[reading_to_proto(r) for r in batch], dropped_count=dropped).SerializeToString()


# -- zmq --------------------------------------------------------------------------------------


def serve_zmq(cores: Cores, stop: threading.Event) -> list[threading.Thread]:
    import zmq

    context = zmq.Context.instance()
    rep = context.socket(zmq.REP)
    rep.setsockopt(zmq.LINGER, 0)
    command_port = rep.bind_to_random_port("tcp://127.0.0.1")
    xpub = context.socket(zmq.XPUB)
    xpub.setsockopt(zmq.LINGER, 0)
    force_port = xpub.bind_to_random_port("tcp://127.0.0.1")

    def commands():
        while not stop.is_set():
            if rep.poll(int(POLL_S * 1000)):
                rep.send(cores.move(rep.recv()))
        rep.close()

    def force():
        subscription, topic = None, b""
        while not stop.is_set():
            while xpub.poll(0):
                event = xpub.recv()
                if event[:1] == b"\x01":  # subscribe to b"d<N>|"
                    if subscription is not None:
                        subscription.close()
                    topic = event[1:]
                    subscription = cores.subscribe(int(topic[1:].split(b"|")[0]))
                elif event[:1] == b"\x00" and subscription is not None:
                    subscription.close()
                    subscription = None
            if subscription is None:
                stop.wait(SUBSCRIPTION_WAIT_S)
                continue
            batch = subscription.get(SUBSCRIPTION_WAIT_S)
            if batch:
                xpub.send_multipart([topic, wrench_payload(batch, subscription.dropped)])
        if subscription is not None:
            subscription.close()
        xpub.close()

    threads = [threading.Thread(target=commands, name="zmq-commands", daemon=True),
               threading.Thread(target=force, name="zmq-force", daemon=True)]
    say_ready("baseline_command", f"127.0.0.1:{command_port}")
    say_ready("baseline_force", f"127.0.0.1:{force_port}")
    return threads


# -- tcp --------------------------------------------------------------------------------------


def serve_tcp(cores: Cores, stop: threading.Event) -> list[threading.Thread]:
    listener = socket.create_server(("127.0.0.1", 0))
    listener.settimeout(POLL_S)
    port = listener.getsockname()[1]

    def connection(sock: socket.socket):
        sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        sock.settimeout(POLL_S)
        try:
            mode = framing.recv_exact(sock, 1)
            if mode == framing.MODE_COMMANDS:
                while not stop.is_set():
                    try:
                        raw = framing.recv_frame(sock)
                    except TimeoutError:
                        continue
                    framing.send_frame(sock, cores.move(raw))
            elif mode == framing.MODE_FORCE:
                (decimation,) = framing.DECIMATION.unpack(
                    framing.recv_exact(sock, framing.DECIMATION.size))
                with cores.subscribe(decimation) as subscription:
                    while not stop.is_set():
                        batch = subscription.get(POLL_S)
                        if batch:
                            framing.send_frame(sock, wrench_payload(batch,
                                                                    subscription.dropped))
        except (ConnectionError, TimeoutError, OSError):
            pass  # the client left
        finally:
            sock.close()

    def accept():
        while not stop.is_set():
            try:
                sock, _ = listener.accept()
            except TimeoutError:
                continue
            threading.Thread(target=connection, args=(sock,), name="tcp-conn",
                             daemon=True).start()
        listener.close()

    say_ready("baseline_command", f"127.0.0.1:{port}")
    say_ready("baseline_force", f"127.0.0.1:{port}")
    return [threading.Thread(target=accept, name="tcp-accept", daemon=True)]


# -- zmq-teleop ---------------------------------------------------------------------------------


class OperatorSessions:
    """The Teleoperate sessions of the DEALERs connected, by their zmq identity, served by the
    DecisionServer servicer's own per-message and per-batch code (`_received`: a command
    checked, converted and stamped; `_serve_batch`: the commands that arrived together go to
    the session together, which may merge them into one move, and come back as acks built as
    the gRPC stream's are). Private methods, used on purpose: the baseline must not drift from
    what the service does; only the transport differs."""

    def __init__(self, core: DecisionCore):
        self.core = core
        self.servicer = DecisionServerServicer(core)
        self._sessions: dict[bytes, tuple[OperatorSession, str | None, bool]] = {}  # grouped acks

    def handle(self, frames: list[tuple[bytes, bytes]]) -> list[tuple[bytes, list[bytes]]]:
        """Frames (identity, payload) that arrived together, in order: the replies, in order.
        A peer's consecutive commands form one batch, as the gRPC handler's inbox takes them."""
        replies: list[tuple[bytes, list[bytes]]] = []
        batch: list = []
        batch_of: bytes | None = None
        for identity, raw in [*frames, (None, None)]:
            request = None
            if raw:
                request = dpb.TeleoperateRequest.FromString(raw)
            if (request is not None and identity == batch_of
                    and request.WhichOneof("message") in ("command", "heartbeat")):
                batch.append(request)
                continue
            if batch:
                replies += self._serve(batch_of, batch)
                batch, batch_of = [], None
            if identity is None:
                break
            if raw == b"":
                self.end(identity, "the stream ended")
                replies.append((identity, [TELEOP_END, b""]))
            elif request.WhichOneof("message") == "init":
                replies.append((identity, self._reply(identity, self._open, request.init)))
            else:
                batch, batch_of = [request], identity
        return replies

    def _serve(self, identity: bytes, requests: list) -> list[tuple[bytes, list[bytes]]]:
        def acks() -> list[bytes]:
            entry = self._sessions.get(identity)
            if entry is None:
                raise InvalidArgumentError("a Teleoperate stream starts with an init",
                                           reason="NO_INIT")
            session, _, grouped = entry
            received = [self.servicer._received(request) for request in requests]
            return [answer.SerializeToString()
                    for answer in self.servicer._answers(session, session.stream, received,
                                                         grouped)
                    if answer is not _END_OF_SESSION]

        try:
            return [(identity, [framing.REPLY_OK, ack]) for ack in acks()]
        except TelerobotError as error:
            self.end(identity, f"the stream failed: {error.message}")
            return [(identity, [framing.REPLY_ERROR, error.message.encode()])]

    def _reply(self, identity: bytes, action, *args) -> list[bytes]:
        try:
            return [framing.REPLY_OK, action(identity, *args).SerializeToString()]
        except TelerobotError as error:
            self.end(identity, f"the stream failed: {error.message}")
            return [framing.REPLY_ERROR, error.message.encode()]

    def _open(self, identity: bytes, init) -> dpb.TeleoperateResponse:
        self.end(identity, "a new init on the same stream")
        own_lease = None
        lease_id = init.lease_id
        if not lease_id:
            own_lease = lease_id = self.core.locks.acquire(
                init.operator_id or "bench", ControlMode.EXCLUSIVE, wait=True,
                wait_timeout_s=5.0, lease_s=TELEOP_LEASE_S).lease_id
        try:
            session = self.core.open_session(init.operator_id, lease_id,
                                             _MAPPINGS.get(init.mapping),
                                             convert.seconds(init.watchdog_timeout))
        except TelerobotError:
            if own_lease:
                self.core.locks.release(own_lease)
            raise
        self._sessions[identity] = (session, own_lease, init.grouped_acks)
        mapping = session.mapping or self.core.assistance.mapping
        return dpb.TeleoperateResponse(ready=dpb.TeleoperateReady(
            session_id=session.session_id,
            mapping=types_pb2.ReferenceFrame.Value(f"REFERENCE_FRAME_{mapping}"),
            watchdog_timeout=convert.duration(session.watchdog_s)))

    def end(self, identity: bytes, reason: str) -> None:
        entry = self._sessions.pop(identity, None)
        if entry is None:
            return
        session, own_lease, _ = entry
        session.close(reason)
        if own_lease:
            try:
                self.core.locks.release(own_lease)
            except TelerobotError:
                pass  # it lapsed: nothing to give back

    def close(self) -> None:
        for identity in list(self._sessions):
            self.end(identity, "the server is stopping")


def serve_teleop_zmq(core: DecisionCore, stop: threading.Event) -> list[threading.Thread]:
    import zmq

    context = zmq.Context.instance()
    router = context.socket(zmq.ROUTER)
    router.setsockopt(zmq.LINGER, 0)
    port = router.bind_to_random_port("tcp://127.0.0.1")
    sessions = OperatorSessions(core)

    def teleoperate():
        # One thread: everything that arrived since the last look is one batch (the gRPC
        # handler's inbox does the same on a thread of its own), then its acks are queued to
        # zmq's I/O thread, which never makes this one wait.
        while not stop.is_set():
            if not router.poll(int(POLL_S * 1000)):
                continue
            frames = []
            while True:
                try:
                    identity, raw = router.recv_multipart(zmq.NOBLOCK)
                except zmq.Again:
                    break
                frames.append((identity, raw))
            for identity, reply in sessions.handle(frames):
                router.send_multipart([identity, *reply])
        sessions.close()
        router.close()

    say_ready("baseline_teleop", f"127.0.0.1:{port}")
    return [threading.Thread(target=teleoperate, name="zmq-teleoperate", daemon=True)]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.baseline_server",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--transport", choices=["zmq", "tcp", "zmq-teleop"], required=True)
    parser.add_argument("--shm-name", help="the world's segment (zmq, tcp)")
    parser.add_argument("--proxy-robot-address", help="the station's ProxyRobot (zmq-teleop)")
    parser.add_argument("--force-sensor-address", help="the station's ForceSensor (zmq-teleop)")
    args = parser.parse_args(argv)
    logging.basicConfig(level=os.environ.get("TELEROBOT_LOG_LEVEL", "WARNING"),
                        stream=sys.stderr,
                        format="%(asctime)s baseline[%(process)d] %(levelname)s %(message)s")
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    signal.signal(signal.SIGINT, lambda *_: stop.set())
    watch_parent(stop.set, stop)
    sys.setswitchinterval(GIL_SWITCH_INTERVAL_S)  # as every service process sets it
    if args.transport == "zmq-teleop":
        return _serve_teleop(args, stop)

    cores = Cores(args.shm_name)
    try:
        cores.start()
        serve = serve_zmq if args.transport == "zmq" else serve_tcp
        _run_until(serve(cores, stop), stop)
    finally:
        cores.close()
    return 0


def _run_until(threads: list[threading.Thread], stop: threading.Event) -> None:
    """Start the serving threads, and join them once `stop` is set."""
    for thread in threads:
        thread.start()
    stop.wait()
    for thread in threads:
        thread.join(2.0)


def _serve_teleop(args: argparse.Namespace, stop: threading.Event) -> int:
    slave = GrpcSlave(args.proxy_robot_address, args.force_sensor_address)
    with tempfile.TemporaryDirectory(prefix="baseline_recordings_") as recordings:
        core = DecisionCore(slave, RecordingStore(Path(recordings)))
        try:
            _run_until(serve_teleop_zmq(core, stop), stop)
        finally:
            core.close()
            slave.close()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
