"""The peg-in-hole run's measures that need no station: the oscillation count at contact."""

from __future__ import annotations

import numpy as np

from clients.teleop.task import SWING_N, contact_oscillation


def test_a_settling_force_has_no_swings_and_a_ringing_one_counts_each():
    times = list(np.linspace(0.0, 1.0, 101))
    settle = [10.0 + 20.0 * np.exp(-5 * t) for t in times]
    assert contact_oscillation(settle, times, 1.0)[0] == 0
    noisy = [10.0 + 0.4 * SWING_N * np.sin(80 * t) for t in times]  # under the hysteresis
    assert contact_oscillation(noisy, times, 1.0)[0] == 0
    ringing = [10.0 + 5.0 * np.sin(2 * np.pi * 4 * t) for t in times]  # 4 Hz, ±5 N
    swings, p2p = contact_oscillation(ringing, times, 1.0)
    assert swings == 8  # a turning point every 1/8 s, each one passed by more than 2 N
    assert p2p == np.float64(max(ringing) - min(ringing))


def test_only_the_last_window_counts():
    times = list(np.linspace(0.0, 3.0, 301))
    forces = [10.0 + (5.0 * np.sin(2 * np.pi * 4 * t) if t < 1.5 else 0.0) for t in times]
    assert contact_oscillation(forces, times, 1.0) == (0, 0.0)
