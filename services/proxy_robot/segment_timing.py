"""How long the servo should take to reach each new joint target: the segment's duration the
driver sends with it (ArmLink.write_target); the servo spreads the target over its own periods
(services.world.trajectory.SegmentedGoal).

Master commands arrive at 50 Hz or so; handing each target to the servo at once would make the
arm accelerate and brake between commands. Instead each target becomes a straight joint-space
segment from the servo's setpoint, lasting one command interval. The interval is a running
average of the gaps between commands (at most MAX_SEGMENT_S): over a network the gaps jitter,
and following each one would turn the jitter into velocity steps, which a stiff servo in contact
turns into force spikes. Commands at the servo rate pass straight through (duration 0).

A command after a pause (no command for MAX_SEGMENT_S or more) belongs to no stream: there is
no interval to spread it over, so it takes only as long as its largest joint motion needs at
LONE_COMMAND_SPEED_RAD_PER_S (at least one servo period), and the running average starts
again. Spreading it over MAX_SEGMENT_S instead made a lone command reach the servo's target
50 ms late, which was most of the closed loop's time (the bench's `closed_loop`).

The servo, not this process, writes the intermediate setpoints: a Python thread doing it at
1 kHz took a third of ProxyRobot's GIL time under a 1 kHz command stream, and its scheduling
hiccups under load became setpoint jumps.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

SERVO_PERIOD_S = 0.001  # the servo rate: a segment this short or shorter is no segment
MAX_SEGMENT_S = 0.05  # a segment never lasts longer: slower senders see 50 ms of smoothing
INTERVAL_SMOOTHING = 0.1  # weight of the newest gap in the running average
# The fastest joint speed a lone command's segment asks for; the PUMA 560's joints reach about
# 2-4 rad/s, so this leaves the servo margin.
LONE_COMMAND_SPEED_RAD_PER_S = 1.0


class SegmentTiming:
    """The duration of each new target's segment, from when the targets come. Thread-safe."""

    def __init__(self, monotonic_ns: Callable[[], int] = time.monotonic_ns):
        self._monotonic_ns = monotonic_ns
        self._lock = threading.Lock()
        self._last_command_s: float | None = None  # None: the next command is a lone one
        self._interval_s = MAX_SEGMENT_S

    def duration_s(self, largest_joint_motion_rad: float) -> float:
        """The segment for a target `largest_joint_motion_rad` away from the previous one
        (rad): the running average of the gaps between commands, or, after a pause, as fast as
        LONE_COMMAND_SPEED_RAD_PER_S allows; 0 (at once) when that is a servo period or less."""
        now = self._monotonic_ns() * 1e-9
        with self._lock:
            last, self._last_command_s = self._last_command_s, now
            if last is None or now - last >= MAX_SEGMENT_S:
                self._interval_s = MAX_SEGMENT_S  # the next stream starts smoothing afresh
                duration = min(MAX_SEGMENT_S,
                               abs(largest_joint_motion_rad) / LONE_COMMAND_SPEED_RAD_PER_S)
            else:
                self._interval_s += INTERVAL_SMOOTHING * (max(now - last, 0.0) - self._interval_s)
                duration = self._interval_s
        return duration if duration > SERVO_PERIOD_S else 0.0
