"""The render scale against a fake renderer whose cost is a fixed part plus a part per pixel,
on a fake clock at 30 pairs a second."""

from __future__ import annotations

import pytest

from services.stereo_camera.render_scale import (
    FLOOR,
    HOLD_S,
    LADDER,
    OVERUSE,
    UNDERUSE,
    WINDOW,
    RenderScaler,
)

FPS = 30.0
INTERVAL_S = 1 / FPS


class FakeRenderer:
    """What one pair costs at a scale: `fixed_s` whatever the size, plus `full_s` for the
    pixels of the full size (a square of the scale)."""

    def __init__(self, full_s: float, fixed_s: float = 0.001):
        self.full_s = full_s
        self.fixed_s = fixed_s

    def cost(self, scale: float) -> float:
        return self.fixed_s + self.full_s * scale**2


def run(scaler: RenderScaler, renderer: FakeRenderer, seconds: float,
        start_s: float = 0.0) -> list[float]:
    """The scale of each pair rendered over `seconds` from `start_s`."""
    scales = []
    for k in range(round(seconds * FPS)):
        scale = scaler.scale
        scales.append(scale)
        scaler.observe(renderer.cost(scale), start_s + k * INTERVAL_S)
    return scales


def test_a_renderer_that_fits_its_budget_keeps_the_full_size():
    scales = run(RenderScaler(INTERVAL_S), FakeRenderer(full_s=0.5 * OVERUSE * INTERVAL_S), 30)
    assert set(scales) == {1.0}


def test_a_costly_renderer_steps_down_to_the_biggest_scale_within_budget_and_stays():
    # a software renderer: 26 ms for the full size
    renderer = FakeRenderer(full_s=0.025)
    scaler = RenderScaler(INTERVAL_S)
    scales = run(scaler, renderer, 60)
    budget = OVERUSE * INTERVAL_S
    expected = next(s for s in LADDER if renderer.cost(s) <= budget)
    assert expected == 0.75
    assert scales[-1] == expected
    # one window per step down, then no change for the rest of the minute
    settled = scales.index(expected)
    assert settled == WINDOW
    assert set(scales[settled:]) == {expected}


def test_a_load_that_comes_and_goes_steps_down_then_back_up_after_the_hold():
    scaler = RenderScaler(INTERVAL_S)
    loaded = FakeRenderer(full_s=0.2)  # preempted: everything takes six times as long
    quiet = FakeRenderer(full_s=0.008)  # a fast renderer
    down = run(scaler, loaded, 5)
    assert down[-1] == FLOOR
    assert down == sorted(down, reverse=True)  # only down while loaded
    up = run(scaler, quiet, 30, start_s=5)
    assert up[-1] == 1.0
    assert up == sorted(up)  # only up once quiet
    # each step up waits for the hold after the one before
    changes = [k for k in range(1, len(up)) if up[k] != up[k - 1]]
    assert len(changes) == LADDER.index(FLOOR)
    assert all((b - a) * INTERVAL_S >= HOLD_S - INTERVAL_S
               for a, b in zip(changes, changes[1:], strict=False))


def test_a_renderer_that_nearly_fits_the_bigger_size_backs_off_instead_of_flipping():
    """The prediction says the next size up fits, the render says it does not: each failed
    step up doubles the wait before the next."""

    class Borderline(FakeRenderer):
        def cost(self, scale: float) -> float:
            # at 0.5 it looks cheap enough to try 0.75, but 0.75 costs more than predicted
            return 0.004 if scale <= 0.5 else OVERUSE * INTERVAL_S * 1.5

    scaler = RenderScaler(INTERVAL_S)
    scales = run(scaler, Borderline(full_s=0), 120)
    assert UNDERUSE * INTERVAL_S > 0.004 * (0.75 / 0.5) ** 2  # the premise
    ups = [k for k in range(1, len(scales)) if scales[k] > scales[k - 1]]
    # holds of 2, 4, 8, 16, 32, 32... s: a few tries in two minutes, not one every 2 s
    assert 2 <= len(ups) <= 6
    gaps = [(b - a) * INTERVAL_S for a, b in zip(ups, ups[1:], strict=False)]
    assert gaps == sorted(gaps)
    assert scales.count(0.75) == WINDOW * (len(ups) + 1)  # the way down, then each try: a window


def test_a_fixed_scale_never_changes():
    scaler = RenderScaler(INTERVAL_S, fixed=0.5)
    assert set(run(scaler, FakeRenderer(full_s=1.0), 5)) == {0.5}
    scaler = RenderScaler(INTERVAL_S, fixed=1.0)
    assert set(run(scaler, FakeRenderer(full_s=1.0), 5)) == {1.0}


def test_the_smallest_scale_is_a_floor():
    assert run(RenderScaler(INTERVAL_S), FakeRenderer(full_s=1.0), 5)[-1] == FLOOR
    scaler = RenderScaler(INTERVAL_S, min_scale=LADDER[-1])
    scales = run(scaler, FakeRenderer(full_s=1.0), 5)
    assert sorted(set(scales), reverse=True) == list(LADDER)  # every step, to the last


@pytest.mark.parametrize("options, message", [
    ({"fixed": 0.6}, "fixed render scale"),
    ({"min_scale": 0.1}, "smallest render scale"),
])
def test_bad_settings_are_refused(options, message):
    with pytest.raises(ValueError, match=message):
        RenderScaler(INTERVAL_S, **options)
    with pytest.raises(ValueError, match="frame interval"):
        RenderScaler(0.0)
