"""python -m bench.baseline_server --transport zmq|tcp: the baselines' slave side.

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
"""

from __future__ import annotations

import argparse
import logging
import os
import signal
import socket
import sys
import threading

from bench import framing
from services.common import convert
from services.force_sensor.core import ForceSensorCore
from services.force_sensor.servicer import reading_to_proto
from services.force_sensor.subscribers import StreamOptions
from services.proxy_robot.core import ProxyRobotCore
from services.runtime.errors import TelerobotError
from services.runtime.process import ready_line, watch_parent
from services.world.shm_link import SharedMemoryArmLink, SharedMemoryWrenchLink
from telerobot.v1 import force_sensor_pb2, proxy_robot_pb2

log = logging.getLogger("baseline")
POLL_S = 0.1  # how often idle loops look at the stop flag
SUBSCRIPTION_WAIT_S = 0.01


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
    print(ready_line("baseline_command", f"127.0.0.1:{command_port}"), flush=True)
    print(ready_line("baseline_force", f"127.0.0.1:{force_port}"), flush=True)
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

    print(ready_line("baseline_command", f"127.0.0.1:{port}"), flush=True)
    print(ready_line("baseline_force", f"127.0.0.1:{port}"), flush=True)
    return [threading.Thread(target=accept, name="tcp-accept", daemon=True)]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.baseline_server",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--transport", choices=["zmq", "tcp"], required=True)
    parser.add_argument("--shm-name", required=True)
    args = parser.parse_args(argv)
    logging.basicConfig(level=os.environ.get("TELEROBOT_LOG_LEVEL", "WARNING"),
                        stream=sys.stderr,
                        format="%(asctime)s baseline[%(process)d] %(levelname)s %(message)s")
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    signal.signal(signal.SIGINT, lambda *_: stop.set())
    watch_parent(stop.set, stop)

    cores = Cores(args.shm_name)
    try:
        cores.start()
        serve = serve_zmq if args.transport == "zmq" else serve_tcp
        threads = serve(cores, stop)
        for thread in threads:
            thread.start()
        stop.wait()
        for thread in threads:
            thread.join(2.0)
    finally:
        cores.close()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
