"""A driver for ATI's Net F/T sensors over RDT (Raw Data Transfer, UDP port 49152).

It asks the sensor to stream (command 0x0002, endless) and keeps the newest record. Packets come
in network byte order:

    request  (8 bytes):  uint16 header 0x1234, uint16 command, uint32 sample count (0 = endless)
    record  (36 bytes):  uint32 rdt_sequence, uint32 ft_sequence, uint32 status,
                         int32 Fx, Fy, Fz, Tx, Ty, Tz   (counts; divide by counts per unit)

UDP may lose or reorder packets: a record older than the newest one is dropped (counted as
reordered) and a gap in rdt_sequence is counted as lost. A sensor that stops sending makes
read_wrench() raise UnavailableError after `stale_after_s` instead of handing out an old reading,
and nothing here blocks longer than that. Implements services.world.link.WrenchLink.
"""

from __future__ import annotations

import logging
import socket
import struct
import threading
import time
from dataclasses import dataclass

import numpy as np

from services.world.link import RawWrench
from wire.errors import UnavailableError

log = logging.getLogger(__name__)

RDT_PORT = 49152
RDT_HEADER = 0x1234
CMD_STOP_STREAMING = 0x0000
CMD_START_STREAMING = 0x0002
REQUEST = struct.Struct("!HHI")
RECORD = struct.Struct("!III6i")
STATUS_ERROR_BIT = 0x8000_0000  # set by the sensor whenever a status bit reports a problem
DEFAULT_COUNTS_PER_UNIT = 1_000_000  # the Net F/T default; read the sensor's calibration page
RECEIVE_POLL_S = 0.05


def request_packet(command: int, sample_count: int = 0) -> bytes:
    return REQUEST.pack(RDT_HEADER, command, sample_count)


@dataclass(frozen=True)
class RdtRecord:
    rdt_sequence: int
    ft_sequence: int
    status: int
    counts: tuple[int, int, int, int, int, int]

    @classmethod
    def parse(cls, packet: bytes) -> RdtRecord:
        """ValueError for a packet of the wrong size."""
        if len(packet) != RECORD.size:
            raise ValueError(f"RDT record is {RECORD.size} bytes, got {len(packet)}")
        rdt_sequence, ft_sequence, status, *counts = RECORD.unpack(packet)
        return cls(rdt_sequence, ft_sequence, status, tuple(counts))


@dataclass
class RdtStats:
    received: int = 0
    lost: int = 0
    reordered: int = 0
    malformed: int = 0


def _newer(sequence: int, last: int) -> int:
    """How far `sequence` is ahead of `last` in uint32 wrap-around arithmetic (<= 0: not newer)."""
    ahead = (sequence - last) % (1 << 32)
    return ahead if ahead < (1 << 31) else ahead - (1 << 32)


class RdtWrenchLink:
    """The newest reading of a Net F/T sensor, streamed over RDT."""

    def __init__(self, host: str, port: int = RDT_PORT,
                 counts_per_force: float = DEFAULT_COUNTS_PER_UNIT,
                 counts_per_torque: float = DEFAULT_COUNTS_PER_UNIT,
                 stale_after_s: float = 0.1, connect_timeout_s: float = 1.0):
        self.address = f"{host}:{port}"
        self._scale = np.array([1.0 / counts_per_force] * 3 + [1.0 / counts_per_torque] * 3)
        self._stale_after_ns = int(stale_after_s * 1e9)
        self._socket = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self._socket.settimeout(RECEIVE_POLL_S)
        self._socket.connect((host, port))
        self._lock = threading.Lock()
        self._latest: RawWrench | None = None
        self._status = 0
        self._last_receive_ns = 0
        self._last_sequence: int | None = None
        self.stats = RdtStats()
        self._closed = threading.Event()
        self._first = threading.Event()
        self._socket.send(request_packet(CMD_START_STREAMING))
        self._thread = threading.Thread(target=self._receive, name="rdt-receiver", daemon=True)
        self._thread.start()
        if not self._first.wait(connect_timeout_s):
            self.close()
            raise UnavailableError(f"no RDT data from the Net F/T at {self.address} within "
                                   f"{connect_timeout_s:.1f} s: check its address and power",
                                   reason="SENSOR_SILENT")

    def read_wrench(self) -> RawWrench:
        if self._closed.is_set():
            raise UnavailableError("the RDT link is closed: open a new one", reason="LINK_CLOSED")
        with self._lock:
            latest, status, last_ns = self._latest, self._status, self._last_receive_ns
        silent_ns = time.monotonic_ns() - last_ns
        if silent_ns > self._stale_after_ns:
            raise UnavailableError(f"the Net F/T at {self.address} has sent nothing for "
                                   f"{silent_ns / 1e6:.0f} ms", reason="SENSOR_SILENT")
        if status & STATUS_ERROR_BIT:
            raise UnavailableError(f"the Net F/T at {self.address} reports status 0x{status:08x}; "
                                   "see its status page", reason="SENSOR_FAULT")
        return latest

    def close(self) -> None:
        if self._closed.is_set():
            return
        self._closed.set()
        try:
            self._socket.send(request_packet(CMD_STOP_STREAMING))
        except OSError:
            pass  # the sensor is gone; nothing to stop
        self._thread.join(1.0)
        self._socket.close()

    def _receive(self) -> None:
        while not self._closed.is_set():
            try:
                packet = self._socket.recv(RECORD.size + 1)
            except OSError:  # the poll timed out, or ICMP "port unreachable": try again
                continue
            self._accept(packet)

    def _accept(self, packet: bytes) -> None:
        try:
            record = RdtRecord.parse(packet)
        except ValueError:
            self.stats.malformed += 1
            return
        now_ns = time.monotonic_ns()
        with self._lock:
            if self._last_sequence is not None:
                ahead = _newer(record.rdt_sequence, self._last_sequence)
                if ahead <= 0:
                    self.stats.reordered += 1
                    return
                self.stats.lost += ahead - 1
            self._last_sequence = record.rdt_sequence
            values = np.array(record.counts, dtype=float) * self._scale
            self._latest = RawWrench(record.rdt_sequence, time.time_ns(), values[:3], values[3:])
            self._status = record.status
            self._last_receive_ns = now_ns
            self.stats.received += 1
        self._first.set()
