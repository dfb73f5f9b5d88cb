"""The link model: when each chunk of one direction's byte stream comes out of the link.

Pure: times are arguments (seconds on any one clock) and randomness is a seeded
random.Random, so a test checks a schedule exactly without sleeping and a seed repeats it.
The proxy (proxy.py) feeds it the times at which it read each chunk and writes each chunk out
at the time it returns.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass


@dataclass(frozen=True)
class LinkProfile:
    """One direction of the link."""

    delay_s: float = 0.0  # one way, after the chunk is serialized onto the line
    jitter_s: float = 0.0  # each chunk's delay is delay_s ± jitter_s (uniform, never below 0)
    bandwidth_bps: float = 0.0  # bits per second; 0: unlimited
    # TCP turns a lost segment into a stall: the receiver gets nothing past the hole until the
    # sender resends it. Per chunk, with this probability, the chunk comes stall_s late and
    # holds every chunk behind it.
    stall_probability: float = 0.0
    stall_s: float = 0.0
    seed: int = 0

    def __post_init__(self) -> None:
        for name in ("delay_s", "jitter_s", "bandwidth_bps", "stall_s"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0):
                raise ValueError(f"{name} must be a finite number >= 0, not {value}")
        if not 0.0 <= self.stall_probability <= 1.0:
            raise ValueError(f"stall_probability must be in [0, 1], not {self.stall_probability}")

    def describe(self) -> str:
        """What this direction does, for people: "delay 50 ms ± 5 ms, 1 Mbit/s, …"."""
        parts = [f"delay {self.delay_s * 1e3:g} ms"]
        if self.jitter_s:
            parts[0] += f" ± {self.jitter_s * 1e3:g} ms"
        parts.append(f"{self.bandwidth_bps / 1e6:g} Mbit/s" if self.bandwidth_bps
                     else "unlimited bandwidth")
        if self.stall_probability and self.stall_s:
            parts.append(f"stalls of {self.stall_s * 1e3:g} ms "
                         f"with probability {self.stall_probability:g} per chunk")
        parts.append(f"seed {self.seed}")
        return ", ".join(parts)


class LinkSchedule:
    """Release times for the chunks of one direction, in the order they arrive.

    A chunk is serialized onto the line when it arrives and the line is free (bandwidth),
    then travels delay ± jitter, plus a stall if it was "lost". It is never released before
    the previous chunk: TCP delivers bytes in order, so jitter and stalls delay, never reorder.
    """

    def __init__(self, profile: LinkProfile, rng: random.Random | None = None):
        self.profile = profile
        self._rng = rng if rng is not None else random.Random(profile.seed)
        self._line_free_s = -math.inf  # when the line has serialized everything so far
        self._last_release_s = -math.inf
        self.stalls = 0

    def release_time(self, arrival_s: float, size_bytes: int) -> float:
        """When the chunk of `size_bytes` that arrived at `arrival_s` leaves the link."""
        profile = self.profile
        start_s = max(arrival_s, self._line_free_s)
        sent_s = start_s
        if profile.bandwidth_bps:
            sent_s += size_bytes * 8 / profile.bandwidth_bps
        self._line_free_s = sent_s
        # Both draws every chunk, whatever the settings: a seed then places the same stalls
        # with or without jitter, and the same jitter with or without stalls.
        jitter_draw = self._rng.uniform(-1.0, 1.0)
        stall_draw = self._rng.random()
        travel_s = max(0.0, profile.delay_s + profile.jitter_s * jitter_draw)
        if stall_draw < profile.stall_probability:
            travel_s += profile.stall_s
            self.stalls += 1
        release_s = max(sent_s + travel_s, self._last_release_s)
        self._last_release_s = release_s
        return release_s

    def hold(self, until_s: float) -> None:
        """A cut until `until_s`: nothing is released before then, and a chunk arriving
        meanwhile is only serialized onto the line once it is back."""
        self._line_free_s = max(self._line_free_s, until_s)
        self._last_release_s = max(self._last_release_s, until_s)
