"""When to restart a child that ended on its own: capped exponential back-off, and a limit.

As systemd's `Restart=on-failure` with `StartLimitBurst`, or an Erlang/OTP supervisor's
intensity and period: a child is restarted after a back-off that doubles from `first_delay_s`
up to `max_delay_s`; one that fails `max_failures` times within `window_s` is given up on. A
failure older than the window is forgotten, and so is the back-off once the child has run for a
whole window. Time comes from the caller (monotonic seconds), so tests need no clock.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass


@dataclass(frozen=True)
class RestartPolicy:
    first_delay_s: float = 0.1
    max_delay_s: float = 5.0
    max_failures: int = 5
    window_s: float = 60.0


class RestartTracker:
    """One child's recent failures under a policy."""

    def __init__(self, policy: RestartPolicy = RestartPolicy()):
        self.policy = policy
        self._failures: deque[float] = deque()
        self.restarts = 0

    def failed(self, now: float) -> float | None:
        """Record a failure at `now`; the delay before restarting, or None to give up."""
        self._failures.append(now)
        while self._failures and self._failures[0] <= now - self.policy.window_s:
            self._failures.popleft()
        count = len(self._failures)
        if count >= self.policy.max_failures:
            return None
        return min(self.policy.first_delay_s * 2 ** (count - 1), self.policy.max_delay_s)

    def describe_limit(self) -> str:
        return (f"{self.policy.max_failures} failures within {self.policy.window_s:.0f} s")
