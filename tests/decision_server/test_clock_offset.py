"""The master's clock offset, estimated from the session's exchanges against clocks whose
offset the test sets: the estimate lands within its own error bound of the truth, queueing in
one direction does not fool it, and impossible or unknown receipts are refused."""

from __future__ import annotations

import numpy as np
import pytest

from services.decision_server.clock_offset import WINDOW, ClockOffsetEstimator

OFFSET_NS = 3_700_000_123  # the server's clock is 3.7 s ahead of the master's
MS = 1_000_000
EPOCH_NS = 1_795_000_000 * 1_000_000_000  # wall-clock time, as both clocks read it


def exchange(estimator: ClockOffsetEstimator, sequence: int, at_ns: int, up_ns: int,
             server_ns: int, down_ns: int) -> bool:
    """One command sent at `at_ns` (true time = server clock), `up_ns` on the way, `server_ns`
    in the server, `down_ns` back; the master's clock reads OFFSET_NS behind."""
    sent = EPOCH_NS + at_ns - OFFSET_NS
    received = EPOCH_NS + at_ns + up_ns
    answered = received + server_ns
    acked = answered + down_ns - OFFSET_NS
    estimator.answered(sequence, sent, received, answered)
    return estimator.receipt(sequence, acked)


def test_no_estimate_before_a_receipt():
    estimator = ClockOffsetEstimator()
    estimator.answered(1, 1, 2, 3)
    assert estimator.estimate() is None


def test_a_symmetric_exchange_gives_the_offset_exactly():
    estimator = ClockOffsetEstimator()
    assert exchange(estimator, 1, 10_000 * MS, 5 * MS, 2 * MS, 5 * MS)
    estimate = estimator.estimate()
    assert estimate.offset_ns == OFFSET_NS
    assert estimate.error_ns == 5 * MS  # half the 10 ms on the wire


def test_queueing_in_one_direction_is_filtered_by_the_shortest_exchange():
    rng = np.random.default_rng(7)
    estimator = ClockOffsetEstimator()
    for sequence in range(1, 40):
        # 2 ms each way, plus up to 80 ms of queueing on the way up in most exchanges.
        queued = int(rng.uniform(0, 80) * MS) if sequence % 5 else 0
        exchange(estimator, sequence, sequence * 20 * MS, 2 * MS + queued, MS, 2 * MS)
    estimate = estimator.estimate()
    assert abs(estimate.offset_ns - OFFSET_NS) <= estimate.error_ns
    assert estimate.error_ns == 2 * MS  # an unqueued exchange is among the last WINDOW
    assert WINDOW >= 5


def test_the_truth_is_always_within_the_error_bound():
    rng = np.random.default_rng(11)
    estimator = ClockOffsetEstimator()
    for sequence in range(1, 200):
        up, down = (int(rng.exponential(10) * MS) for _ in range(2))
        exchange(estimator, sequence, sequence * 10 * MS, up, int(rng.uniform(0, 3) * MS), down)
        estimate = estimator.estimate()
        assert abs(estimate.offset_ns - OFFSET_NS) <= estimate.error_ns + 1


@pytest.mark.parametrize("sequence", [0, -1])
def test_an_exchange_without_a_sequence_is_not_kept(sequence):
    estimator = ClockOffsetEstimator()
    estimator.answered(sequence, 1, 2, 3)
    assert not estimator.receipt(sequence, 4)


def test_an_unknown_or_impossible_receipt_is_refused():
    estimator = ClockOffsetEstimator()
    assert not estimator.receipt(5, 10)  # never answered
    estimator.answered(1, sent_ns=1_000 * MS, received_ns=5_000 * MS, answered_ns=5_010 * MS)
    assert not estimator.receipt(1, 1_005 * MS)  # acked 5 ms after sending, 10 ms in the server
    assert estimator.estimate() is None
    assert not estimator.receipt(1, 2_000 * MS)  # an exchange is used once
