"""The Net F/T RDT driver against an RDT responder on loopback that streams real-format
packets, and can lose, reorder, corrupt or stop them."""

from __future__ import annotations

import socket
import struct
import threading
import time

import numpy as np
import pytest

from services.force_sensor.rdt import (
    CMD_START_STREAMING,
    CMD_STOP_STREAMING,
    RDT_HEADER,
    RECORD,
    REQUEST,
    RdtWrenchLink,
)
from tests.conftest import wait_for
from tests.processes import start_service
from wire.errors import UnavailableError

COUNTS = 1_000_000


class RdtResponder:
    """A stand-in Net F/T: answers the start command by streaming records at ~1 kHz."""

    def __init__(self, drop_every: int = 0, swap_every: int = 0, status: int = 0):
        self.socket = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.socket.bind(("127.0.0.1", 0))
        self.socket.settimeout(0.05)
        self.port = self.socket.getsockname()[1]
        self.drop_every, self.swap_every, self.status = drop_every, swap_every, status
        self.silent = threading.Event()
        self.commands: list[int] = []
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._serve, daemon=True)
        self._thread.start()

    def record(self, sequence: int) -> bytes:
        force = [int(1.5 * COUNTS), int(-2.0 * COUNTS), int(10.25 * COUNTS)]
        torque = [int(0.1 * COUNTS), int(0.0 * COUNTS), int(-0.05 * COUNTS)]
        return RECORD.pack(sequence, sequence * 2, self.status, *force, *torque)

    def _serve(self):
        client, sequence, held = None, 0, None
        while not self._stop.is_set():
            try:
                packet, client_address = self.socket.recvfrom(64)
                header, command, _count = REQUEST.unpack(packet)
                assert header == RDT_HEADER
                self.commands.append(command)
                client = client_address if command == CMD_START_STREAMING else None
            except TimeoutError:
                pass
            while client and not self.silent.is_set() and not self._stop.is_set():
                sequence += 1
                out = self.record(sequence)
                if self.drop_every and sequence % self.drop_every == 0:
                    out = None
                elif self.swap_every and sequence % self.swap_every == 0:
                    held, out = out, None  # send it after the next one
                if out:
                    self.socket.sendto(out, client)
                    if held:
                        self.socket.sendto(held, client)
                        held = None
                self._stop.wait(0.001)  # the sensor's sample period
                try:  # a stop command ends the stream
                    packet, _ = self.socket.recvfrom(64)
                    self.commands.append(REQUEST.unpack(packet)[1])
                    if self.commands[-1] == CMD_STOP_STREAMING:
                        client = None
                except (TimeoutError, BlockingIOError):
                    pass
                self.socket.settimeout(0)
            self.socket.settimeout(0.05)

    def close(self):
        self._stop.set()
        self._thread.join(2)
        self.socket.close()


@pytest.fixture
def responder_factory():
    made: list[RdtResponder] = []

    def make(**options) -> RdtResponder:
        made.append(RdtResponder(**options))
        return made[-1]

    yield make
    for responder in made:
        responder.close()


def test_parses_real_format_records_into_newtons(responder_factory):
    responder = responder_factory()
    link = RdtWrenchLink("127.0.0.1", responder.port)  # returns once a record arrived
    try:
        sample = link.read_wrench()
        np.testing.assert_allclose(sample.force_n, [1.5, -2.0, 10.25])
        np.testing.assert_allclose(sample.torque_nm, [0.1, 0.0, -0.05])
        assert sample.sequence > 0
    finally:
        link.close()
    assert responder.commands[0] == CMD_START_STREAMING
    # The responder reads the stop command on its own thread.
    wait_for(lambda: responder.commands[-1] == CMD_STOP_STREAMING, timeout_s=1.0,
             what="the stop command")


def test_counts_lost_and_drops_reordered_packets(responder_factory):
    responder = responder_factory(drop_every=10, swap_every=7)
    link = RdtWrenchLink("127.0.0.1", responder.port)
    try:
        sequences = []

        def lost_and_reordered_seen() -> bool:
            sequences.append(link.read_wrench().sequence)
            return link.stats.lost > 5 and link.stats.reordered > 5

        wait_for(lost_and_reordered_seen, what="more than 5 lost and 5 reordered packets")
        assert sequences == sorted(sequences)  # never goes back in time
    finally:
        link.close()


def test_a_silent_sensor_is_unavailable_quickly_and_nothing_hangs(responder_factory):
    responder = responder_factory()
    link = RdtWrenchLink("127.0.0.1", responder.port, stale_after_s=0.05)
    try:
        link.read_wrench()
        responder.silent.set()

        def silence_reported() -> tuple[UnavailableError, float] | None:
            started = time.monotonic()
            try:
                link.read_wrench()
            except UnavailableError as error:
                return error, time.monotonic() - started
            return None

        error, took = wait_for(silence_reported, timeout_s=2.0, what="the silence reported")
        assert "has sent nothing for" in str(error)
        assert took < 0.5  # no waiting on the socket (loose: shared CPUs)
    finally:
        link.close()


def test_no_sensor_at_all_fails_at_open():
    # A port of our own that never answers: a Net F/T that is off (the link treats an ICMP
    # "port unreachable" from an address with nothing bound the same way).
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as mute:
        mute.bind(("127.0.0.1", 0))
        port = mute.getsockname()[1]
        started = time.monotonic()
        with pytest.raises(UnavailableError,
                           match=f"no RDT data from the Net F/T at 127.0.0.1:{port}"):
            RdtWrenchLink("127.0.0.1", port, connect_timeout_s=0.3)
        assert time.monotonic() - started < 1.0


def test_a_sensor_reporting_an_error_status_is_unavailable(responder_factory):
    responder = responder_factory(status=0x8000_0001)
    link = RdtWrenchLink("127.0.0.1", responder.port)
    try:
        with pytest.raises(UnavailableError, match="status 0x80000001"):
            link.read_wrench()
    finally:
        link.close()


def test_malformed_packets_are_counted_and_ignored(responder_factory):
    responder = responder_factory()
    link = RdtWrenchLink("127.0.0.1", responder.port)
    try:
        link._accept(b"\x00" * 10)  # noqa: SLF001 - a truncated datagram
        link._accept(struct.pack("!I", 5))  # noqa: SLF001
        assert link.stats.malformed == 2
        assert link.read_wrench().force_n[2] == pytest.approx(10.25)
    finally:
        link.close()


@pytest.mark.e2e
def test_the_service_process_reads_a_net_ft_when_configured(responder_factory, world):
    import grpc

    from telerobot.v1 import force_sensor_pb2 as pb
    from telerobot.v1 import force_sensor_pb2_grpc
    responder = responder_factory()
    process = start_service("force_sensor", "--sensor", "rdt",
                            "--rdt-address", f"127.0.0.1:{responder.port}",
                            env={"TELEROBOT_WORLD_SHM": world.shm_name})
    try:
        with grpc.insecure_channel(process.address) as channel:
            sensor = force_sensor_pb2_grpc.ForceSensorStub(channel)
            sensor.StartReading(pb.StartReadingRequest(), timeout=5)
            sample = sensor.GetWrench(pb.GetWrenchRequest(), timeout=5).sample
        # The tool's weight is removed and the result is in tool axes about the tool point:
        # compare with the same conversion of the responder's numbers at the arm's pose.
        from domain.robot_model import puma560
        from domain.robot_model.kinematics import ArmKinematics
        from domain.wrench_model import contact_wrench, default_payload
        from services.world.shm_link import SharedMemoryArmLink

        arm = SharedMemoryArmLink(world.shm_name)
        q = arm.read_arm().joint_positions_rad
        arm.close()
        kinematics = ArmKinematics()
        sensor_pose = kinematics.frame_pose(q, puma560.FT_SITE)
        expected = contact_wrench(np.array([1.5, -2.0, 10.25]), np.array([0.1, 0.0, -0.05]),
                                  sensor_pose.rotation,
                                  sensor_pose.actInv(kinematics.tool_pose(q)), default_payload())
        got = sample.wrench
        np.testing.assert_allclose([got.force_n.x, got.force_n.y, got.force_n.z],
                                   expected.force_n, atol=1e-3)
        np.testing.assert_allclose([got.torque_nm.x, got.torque_nm.y, got.torque_nm.z],
                                   expected.torque_nm, atol=1e-3)
    finally:
        process.stop()
