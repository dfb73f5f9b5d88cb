"""Layout of the world's shared-memory segment, and creating / attaching it safely.

One POSIX shared-memory segment per world, named by TELEROBOT_WORLD_SHM (default
"telerobot_world", i.e. /dev/shm/telerobot_world on Linux). Each part starts on its own 64-byte
cache line, so the world's writes and the driver's writes never share a line:

    header   written once by the world at creation, except `status` and `heartbeat_ns`
    state    seqlock record, written by the world every servo step (arm sample + wrench + loop)
    command  seqlock record, written by the driver (target and its segment's duration,
             hold, release)
    emergency one aligned word, written by any emergency-stop device (see below)

Commands are numbered: every command a driver issues takes the next `command_sequence`, and the
record keeps the number of the latest target, hold and release. The world applies new ones in
number order, so a hold and a release issued within one servo period are neither lost nor
reordered (edge-triggered), and repeating one is harmless (holding twice is holding).

The emergency word is the stop button wired past the driver: a second process (the emergency-stop
service) writes the time of its request there, and the world latches a hold whenever the word
changes, after that step's driver commands, so a release in the same step cannot undo it. One
aligned 8-byte store needs no seqlock, and there may be several writers.
"""

from __future__ import annotations

import os
from multiprocessing import resource_tracker, shared_memory

import numpy as np

from domain.robot_model.description import MAX_JOINTS
from services.world.seqlock import SeqlockRecord

SHM_NAME_ENV = "TELEROBOT_WORLD_SHM"
DEFAULT_SHM_NAME = "telerobot_world"

MAGIC = 0x5445_4C45_5752_4C44  # "TELEWRLD": set last at creation, so a half-made segment is seen
LAYOUT_VERSION = 5
CACHE_LINE = 64
FAULT_BYTES = 240  # UTF-8, truncated
ARM_NAME_BYTES = 32  # ASCII

STATUS_STARTING = 0
STATUS_RUNNING = 1
STATUS_CLOSED = 2

HEADER_DTYPE = np.dtype([
    ("magic", "u8"),
    ("layout_version", "u8"),
    ("world_pid", "i8"),
    ("status", "u8"),  # STATUS_*
    ("heartbeat_ns", "i8"),  # time.monotonic_ns() of the latest step (one aligned 8-byte word)
    ("period_ns", "i8"),  # servo period
    ("arm", f"S{ARM_NAME_BYTES}"),  # the arm's name (its description file)
    ("joint_count", "u8"),  # the arm's joints: the first joint_count slots of every array
    ("joint_lower", "f8", (MAX_JOINTS,)),  # rad
    ("joint_upper", "f8", (MAX_JOINTS,)),  # rad
], align=True)

STATE_DTYPE = np.dtype([
    ("heartbeat_ns", "i8"),  # time.monotonic_ns() of this step
    ("arm_sequence", "u8"),
    ("arm_time_ns", "i8"),  # time.time_ns()
    ("q", "f8", (MAX_JOINTS,)),  # rad
    ("qd", "f8", (MAX_JOINTS,)),  # rad/s
    ("target", "f8", (MAX_JOINTS,)),  # rad
    ("hold_latched", "u8"),
    # arm_time_ns of the step the hold latched at (0: not latched): what an e-stop took, even
    # for a reader that did not see that step
    ("hold_latched_ns", "i8"),
    ("fault", f"S{FAULT_BYTES}"),
    ("wrench_sequence", "u8"),
    ("wrench_time_ns", "i8"),
    ("force", "f8", (3,)),  # N
    ("torque", "f8", (3,)),  # N*m
    ("applied_command", "u8"),  # highest command_sequence the world has applied
    ("loop_steps", "u8"),
    ("loop_overruns", "u8"),
    ("loop_dropped_steps", "u8"),
    ("loop_worst_lateness_ns", "i8"),
    ("loop_worst_step_ns", "i8"),
], align=True)

COMMAND_DTYPE = np.dtype([
    ("command_sequence", "u8"),  # number of the latest command of any kind
    ("target_command", "u8"),  # number of the latest target (0: none yet)
    ("target", "f8", (MAX_JOINTS,)),  # rad
    ("target_duration_s", "f8"),  # the straight segment to reach it over (0: at once)
    ("hold_command", "u8"),  # number of the latest hold (0: none yet)
    ("release_command", "u8"),  # number of the latest release (0: none yet)
    ("driver_pid", "i8"),
], align=True)


EMERGENCY_DTYPE = np.dtype([
    ("stop_request_ns", "i8"),  # time.time_ns() of the latest emergency stop request (0: none)
], align=True)


def _aligned(size: int) -> int:
    return -(-size // CACHE_LINE) * CACHE_LINE


HEADER_OFFSET = 0
STATE_OFFSET = _aligned(HEADER_DTYPE.itemsize)
COMMAND_OFFSET = STATE_OFFSET + _aligned(SeqlockRecord.size(STATE_DTYPE))
EMERGENCY_OFFSET = COMMAND_OFFSET + _aligned(SeqlockRecord.size(COMMAND_DTYPE))
SEGMENT_SIZE = EMERGENCY_OFFSET + _aligned(EMERGENCY_DTYPE.itemsize)


def segment_name(name: str | None = None) -> str:
    """The segment name: ``name``, else $TELEROBOT_WORLD_SHM, else "telerobot_world"."""
    return name or os.environ.get(SHM_NAME_ENV) or DEFAULT_SHM_NAME


def add_shm_name_argument(parser, what: str) -> None:
    """The --shm-name flag every process on the link takes: `what` the segment is to it, and
    the default segment_name() gives (env TELEROBOT_WORLD_SHM, else the default name)."""
    parser.add_argument("--shm-name", default=segment_name(), help=f"{what} (env {SHM_NAME_ENV})")


class WorldSegment:
    """Numpy views of one attached (or created) segment."""

    def __init__(self, shm: shared_memory.SharedMemory):
        self.shm = shm
        self.name = shm.name
        self.header = np.ndarray((1,), HEADER_DTYPE, shm.buf, HEADER_OFFSET)
        self.state = SeqlockRecord(shm.buf, STATE_OFFSET, STATE_DTYPE)
        self.command = SeqlockRecord(shm.buf, COMMAND_OFFSET, COMMAND_DTYPE)
        self.emergency = np.ndarray((1,), EMERGENCY_DTYPE, shm.buf, EMERGENCY_OFFSET)

    @property
    def status(self) -> int:
        return int(self.header["status"][0])

    @property
    def heartbeat_ns(self) -> int:
        return int(self.header["heartbeat_ns"][0])

    @property
    def world_pid(self) -> int:
        return int(self.header["world_pid"][0])

    @property
    def arm(self) -> str:
        """The name of the arm the world simulates."""
        return bytes(self.header["arm"][0]).decode("ascii", "replace")

    @property
    def joint_count(self) -> int:
        return int(self.header["joint_count"][0])

    def layout_problem(self) -> str:
        """Why this segment is not a usable world segment ("" when it is)."""
        if self.shm.size < SEGMENT_SIZE:
            return f"it is {self.shm.size} bytes, a world segment is {SEGMENT_SIZE}"
        if int(self.header["magic"][0]) != MAGIC:
            return "it is not (yet) a world segment: the world may still be starting"
        version = int(self.header["layout_version"][0])
        if version != LAYOUT_VERSION:
            return (f"its layout is version {version}, this code speaks {LAYOUT_VERSION}: "
                    "run the world and the driver from the same checkout")
        return ""

    def release(self) -> None:
        """Drop the views into the buffer (needed before the mapping can be closed)."""
        del self.header, self.emergency
        self.state.release()
        self.command.release()

    def close(self) -> None:
        """Drop the views and unmap (the segment itself stays unless unlinked)."""
        self.release()
        self.shm.close()


# Segments this process created (and whose unlinking its resource tracker rightly owns).
_created_here: set[str] = set()


def create_segment(name: str) -> shared_memory.SharedMemory:
    """Create a world-sized segment (FileExistsError if the name is taken). This process's
    resource tracker removes it if the process dies without unlink_segment()."""
    shm = shared_memory.SharedMemory(name=name, create=True, size=SEGMENT_SIZE)
    _created_here.add(shm.name)
    return shm


def unlink_segment(shm: shared_memory.SharedMemory) -> None:
    """Remove a segment this process created or adopted with adopt_for_unlink()."""
    shm.unlink()
    _created_here.discard(shm.name)


def adopt_for_unlink(shm: shared_memory.SharedMemory) -> None:
    """Make an attached segment this process's to unlink (a stale one being replaced)."""
    if shm.name not in _created_here:
        resource_tracker.register(shm._name, "shared_memory")  # _name: the posix name


def attach_untracked(name: str) -> shared_memory.SharedMemory:
    """Attach to an existing segment without letting this process's resource_tracker adopt it.

    Before Python 3.13, attaching registers the segment with the resource tracker, which unlinks
    it when this process exits, destroying the world's segment under it (cpython issue 82300).
    FileNotFoundError when there is no such segment.
    """
    try:
        return shared_memory.SharedMemory(name=name, track=False)  # Python >= 3.13
    except TypeError:
        shm = shared_memory.SharedMemory(name=name)
        if shm.name not in _created_here:  # (in the creator, the registration is its own)
            resource_tracker.unregister(shm._name, "shared_memory")  # _name: the posix name
        return shm


def pid_alive(pid: int) -> bool:
    """Whether a process with this pid exists (it may belong to another user)."""
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True
