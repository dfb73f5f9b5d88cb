"""RenderScaler: the sim cameras keep their frame rate by rendering fewer pixels when short of CPU.

A software renderer (Mesa's llvmpipe, no GPU) costs about 33 ms of CPU for a 640x480 pair: a
whole frame interval at 30 fps, on a machine whose other cores run the rest of the station. A
pair that takes longer than its interval lowers the frame rate, and every pair's age grows by
its render time. So, after WebRTC's "maintain framerate" degradation (which steps the encoded
size down while the encoder's CPU use is over its budget), the sim source renders at a fraction
of its size while a pair's render time is over its budget, and the stream's encoder scales the
picture back to the size the client asked for: the frame rate and the picture's geometry stay
(the AR overlay and the calibration hold), the detail falls. A GPU renders the full size well
inside the budget, so the scale then stays at 1.

The rule, on the median render time of the last WINDOW pairs at the current scale:

- above OVERUSE of the frame interval: one step down the ladder, no lower than FLOOR (at once,
  no hold);
- below UNDERUSE of the interval *as predicted for the next step up* (time scales with the
  pixels, a square of the scale): one step up, but only HOLD_S after the last change, and a step
  up that has to be undone within its hold doubles the next hold (up to MAX_HOLD_S), so a
  machine that can nearly afford the bigger size does not flip between the two.

Pure: durations and times are arguments, so tests drive it with a fake clock.
"""

from __future__ import annotations

import statistics
from collections import deque

LADDER = (1.0, 0.75, 0.5, 0.375, 0.25)  # linear scale of the render, biggest first
# The adaptation's floor. Below half, the render's fixed part (posing the scene, the GL
# pipeline: about 5 of a 640x480 pair's 20 ms alone here) dominates, so the picture would lose
# more than the rate gains; and on a host whose other processes take the CPU, the render's
# time is their preemption as much as its own pixels. Smaller scales can be fixed.
FLOOR = 0.5
OVERUSE = 0.5  # of the frame interval: the other half is the encoder's and the host's (at
# 0.6, 0.75 of 640x480 stayed while the station ran, and frames aged by tens of ms)
UNDERUSE = 0.4  # of the frame interval, predicted at the next step up
WINDOW = 15  # pairs (half a second at 30 fps): a moment's preemption is not a trend
HOLD_S = 2.0
MAX_HOLD_S = 32.0


class RenderScaler:
    """Chooses the render scale from measured render times.

    `fixed`: a scale from LADDER to keep whatever the times (1.0 turns the adaptation off).
    `min_scale`: the smallest scale the adaptation may choose (FLOOR).
    """

    def __init__(self, frame_interval_s: float, *, fixed: float | None = None,
                 min_scale: float = FLOOR):
        if not frame_interval_s > 0:
            raise ValueError(f"the frame interval must be positive, got {frame_interval_s}")
        if fixed is not None and fixed not in LADDER:
            raise ValueError(f"a fixed render scale must be one of {LADDER}, got {fixed}")
        if min_scale not in LADDER:
            raise ValueError(f"the smallest render scale must be one of {LADDER}, got {min_scale}")
        self._interval_s = frame_interval_s
        self._fixed = fixed
        self._steps = LADDER[:LADDER.index(min_scale) + 1]
        self._step = self._steps.index(fixed) if fixed is not None else 0
        self._times: deque[float] = deque(maxlen=WINDOW)
        self._changed_s: float | None = None
        self._hold_s = HOLD_S
        self._raised_s: float | None = None  # when the last step up was taken

    @property
    def scale(self) -> float:
        return self._steps[self._step]

    def observe(self, render_s: float, now_s: float) -> float:
        """Record one pair's render time (seconds, at the current scale); the scale to render
        the next pair at."""
        if self._fixed is not None:
            return self.scale
        if self._changed_s is None:
            self._changed_s = now_s
        self._times.append(render_s)
        if len(self._times) < WINDOW:
            return self.scale
        median = statistics.median(self._times)
        if median > OVERUSE * self._interval_s and self._step + 1 < len(self._steps):
            undone = self._raised_s is not None and now_s - self._raised_s < self._hold_s
            self._hold_s = min(self._hold_s * 2, MAX_HOLD_S) if undone else HOLD_S
            self._change(self._step + 1, now_s)
        elif self._step > 0 and now_s - self._changed_s >= self._hold_s:
            bigger = self._steps[self._step - 1]
            predicted_s = median * (bigger / self.scale) ** 2
            if predicted_s < UNDERUSE * self._interval_s:
                self._change(self._step - 1, now_s)
                self._raised_s = now_s
        return self.scale

    def _change(self, step: int, now_s: float) -> None:
        self._step = step
        self._changed_s = now_s
        self._times.clear()
