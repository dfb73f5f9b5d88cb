"""The stream pacer against a simulated bottleneck (tests/fakes/bottleneck.py): an encoder that
makes frames of the target's size at 30 fps, a path that queues honestly, receipts one way
delay back. Time is simulated in 1 ms steps; nothing sleeps."""

from __future__ import annotations

import numpy as np
import pytest

from services.stereo_camera.pacing import RateLimits, StreamPacer
from tests.fakes.bottleneck import Bottleneck

FPS = 30.0
STEP_S = 0.001


class Encoder:
    """Frames of `fill` times the target's share of a second, each `key_every`-th frame
    KEY_FRAME times that, sizes spread lognormally by `spread` (seeded): x264 on the simulated
    scenes makes about two thirds of its target, with key frames several times a delta's size."""

    KEY_FRAME = 4.0

    def __init__(self, fill: float = 1.0, key_every: int = 0, spread: float = 0.0):
        self.fill, self.key_every, self.spread = fill, key_every, spread
        self.frames = 0
        self.random = np.random.default_rng(7)

    def frame_bytes(self, target_bps: float) -> int:
        key = self.key_every and self.frames % self.key_every == 0
        self.frames += 1
        size = self.fill * target_bps / 8 / FPS * (self.KEY_FRAME if key else 1.0)
        if self.spread:
            size *= self.random.lognormal(0.0, self.spread)
        return max(200, int(size))


class Run:
    """A stream through a bottleneck: what the client saw, and what the pacer chose."""

    def __init__(self, bandwidth_bps: float, one_way_s: float,
                 limits: RateLimits | None = None, encoder: Encoder | None = None):
        self.path = Bottleneck(bandwidth_bps, one_way_s)
        self.encoder = encoder or Encoder()
        self.pacer = StreamPacer(limits or RateLimits(), 0.0)
        self.now = 0.0
        self.sequence = 0
        self.next_tick = 0.0
        self.receipts: list[tuple[float, int, int]] = []  # (due, sequence, bytes), in flight
        self.shown: list[tuple[float, float]] = []  # (arrival time, age)
        self.targets: list[tuple[float, float]] = []  # (time, target bit/s)
        self.worst_overshoot = 0

    def until(self, end_s: float) -> None:
        while self.now < end_s:
            self.now += STEP_S
            for sequence, received, at, sent in self.path.arrived_by(self.now):
                self.shown.append((at, at - sent))
                self.receipts.append((at + self.path.one_way_s, sequence, received))
            while self.receipts and self.receipts[0][0] <= self.now:
                _, sequence, received = self.receipts.pop(0)
                self.pacer.received(sequence, received, self.now)
            if self.now >= self.next_tick:  # a capture tick
                self.next_tick += 1 / FPS
                if self.pacer.admit():
                    self.sequence += 1
                    size = self.encoder.frame_bytes(self.pacer.target_bps)
                    self.pacer.sent(self.sequence, size, self.now)
                    self.path.send(self.sequence, size, self.now)
                    self.worst_overshoot = max(
                        self.worst_overshoot,
                        self.pacer.in_flight_bytes - size - self.pacer.window_bytes)
            self.targets.append((self.now, self.pacer.target_bps))

    def fps(self, start_s: float, end_s: float) -> float:
        return sum(start_s <= at < end_s for at, _ in self.shown) / (end_s - start_s)

    def age_p95(self, start_s: float, end_s: float) -> float:
        return float(np.percentile([age for at, age in self.shown if start_s <= at < end_s], 95))

    def target_at(self, t_s: float) -> float:
        return next(target for at, target in self.targets if at >= t_s)


@pytest.mark.parametrize("one_way_s", [0.0, 0.025, 0.0915, 0.2])
@pytest.mark.parametrize("bandwidth_mbit", [2, 4, 8])
def test_the_stream_fills_the_path_without_a_queue(one_way_s, bandwidth_mbit):
    run = Run(bandwidth_mbit * 1e6, one_way_s)
    run.until(20.0)
    # Nearly every tick is sent: a skip is the pacer's sign that it overshot the path.
    assert run.fps(5, 20) >= 27
    assert run.age_p95(5, 20) <= one_way_s + 0.080
    # The target settles about the bottleneck (probing a little past it), or at its ceiling.
    target = run.target_at(20.0)
    assert target <= 1.1 * bandwidth_mbit * 1e6
    assert target >= min(0.5 * bandwidth_mbit * 1e6, 8e6 * 0.99)


def test_the_target_follows_a_bottleneck_that_narrows_and_widens():
    run = Run(8e6, 0.025)
    run.until(15.0)
    before = run.target_at(15.0)
    assert before > 4e6
    run.path.bandwidth_bps = 2e6
    run.until(30.0)
    assert run.target_at(17.0) <= 2e6, "down within two seconds of the narrowing"
    assert run.age_p95(20, 30) <= 0.025 + 0.080, "and the queue it made drains"
    assert run.fps(20, 30) >= 25
    run.path.bandwidth_bps = 8e6
    run.until(50.0)
    assert run.target_at(50.0) > 4e6, "back up once the path widens"
    assert run.age_p95(35, 50) <= 0.025 + 0.080


@pytest.mark.parametrize("one_way_s", [0.0, 0.2])
def test_an_encoder_that_makes_less_than_its_target_builds_no_queue_over_a_minute(one_way_s):
    """Its target stands above the path when the path is full (what is sent, not the target,
    meets the path), and stays near it: the queue does not creep back."""
    run = Run(2e6, one_way_s, encoder=Encoder(fill=0.66, key_every=60, spread=0.3))
    run.until(60.0)
    thirds = [run.age_p95(start, start + 20) for start in (0, 20, 40)]
    assert max(thirds) <= one_way_s + 0.080, thirds
    assert thirds[2] <= thirds[0] + 0.020, thirds
    assert run.fps(40, 60) >= 25


def test_frames_in_flight_stay_within_the_window():
    run = Run(2e6, 0.2)
    run.until(10.0)
    assert run.worst_overshoot <= 0
    pacer = run.pacer
    assert 0.4 <= pacer.min_rtt_s <= 0.4 + 0.05  # the path's round trip, and one frame's line
    assert pacer.window_bytes <= pacer.target_bps / 8 * (pacer.min_rtt_s + 0.040) + 1


def test_a_stale_or_repeated_receipt_changes_nothing():
    pacer = StreamPacer(RateLimits(), 0.0)
    for sequence in (1, 2, 3):
        pacer.sent(sequence, 1000, sequence * 0.01)
    pacer.received(2, 2000, 0.1)
    assert (pacer.acked_bytes, pacer.acked_sequence) == (2000, 2)
    pacer.received(1, 1000, 0.11)  # overtaken by the receipt for 2
    pacer.received(2, 2000, 0.12)
    assert (pacer.acked_bytes, pacer.acked_sequence, pacer.receipts) == (2000, 2, 1)
    assert pacer.in_flight_bytes == 1000


def test_a_receipt_cannot_claim_more_than_was_sent():
    pacer = StreamPacer(RateLimits(), 0.0)
    pacer.sent(1, 1000, 0.0)
    pacer.received(1, 10**9, 0.05)
    assert pacer.in_flight_bytes == 0


def test_the_target_stays_within_its_limits():
    limits = RateLimits(start_kbit=500, min_kbit=300, max_kbit=1000)
    run = Run(50e6, 0.01, limits)
    run.until(20.0)
    assert run.target_at(20.0) == pytest.approx(1e6)
    run.path.bandwidth_bps = 0.1e6  # far below the floor: the window, not the rate, holds
    run.until(40.0)
    assert run.target_at(40.0) == pytest.approx(0.3e6)
    assert run.pacer.in_flight_bytes <= run.pacer.window_bytes + 0.3e6 / 8 / FPS + 200


def test_limits_are_checked():
    with pytest.raises(ValueError):
        RateLimits(start_kbit=100, min_kbit=150)
