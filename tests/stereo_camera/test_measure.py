"""The benchmark's measurement runs end to end (its numbers are reported, never asserted)."""

from __future__ import annotations

import pytest

from services.stereo_camera.measure import measure_source
from services.stereo_camera.pattern import PatternSource


@pytest.mark.parametrize("mode", ["single", "double"])
def test_measure_streams_decodes_and_times_pairs(mode):
    result = measure_source(PatternSource(96, 72, fps=100, cost_ms=2), mode, pairs=5,
                            encoding="png")
    assert result.pairs == result.latency.samples == 5
    assert (result.source, result.mode, result.width_px, result.height_px) == (
        "pattern", mode, 96, 72)
    assert result.fps > 0 and result.latency.p50_ms > 0 and result.mean_pair_bytes > 0
    assert result.mean_eye_skew_ms > 0  # the pattern reads its eyes out one after the other
