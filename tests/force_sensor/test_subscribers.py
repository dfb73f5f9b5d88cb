"""Per-subscriber decimation, change filter, batching and drop-oldest, with no threads."""

from __future__ import annotations

import numpy as np
import pytest

from services.common.fanout import Fanout
from services.force_sensor.settings import SensorSettings, exceeds
from services.force_sensor.subscribers import StreamOptions, WrenchReading, WrenchSubscription
from wire.errors import InvalidArgumentError


def reading(sequence: int, fz: float = 0.0, tz: float = 0.0) -> WrenchReading:
    return WrenchReading(sequence, sequence * 1_000_000, np.array([0.0, 0.0, fz]),
                         np.array([0.0, 0.0, tz]))


def subscribe(**options) -> tuple[Fanout, WrenchSubscription]:
    fanout: Fanout = Fanout()
    return fanout, fanout.attach(WrenchSubscription(fanout, StreamOptions(**options)))


def drain(subscription) -> list[list[int]]:
    batches = []
    while (batch := subscription.get(0)) is not None:
        batches.append([r.sequence for r in batch])
    return batches


def test_decimation_keeps_every_nth_sample():
    fanout, sub = subscribe(decimation=10)
    for i in range(1, 31):
        fanout.publish(reading(i))
    assert drain(sub) == [[1], [11], [21]]


def test_batches_carry_batch_size_samples_in_order():
    fanout, sub = subscribe(batch_size=4)
    for i in range(1, 11):
        fanout.publish(reading(i))
    assert drain(sub) == [[1, 2, 3, 4], [5, 6, 7, 8]]  # 9 and 10 wait for two more


def test_change_filter_forwards_only_real_changes():
    fanout, sub = subscribe(threshold_force_n=0.5)
    for i, fz in enumerate([0.0, 0.1, 0.3, 0.6, 0.7, 1.2, 1.0], start=1):
        fanout.publish(reading(i, fz=fz))
    assert drain(sub) == [[1], [4], [6]]  # 0.6 − 0.0 > 0.5, 1.2 − 0.6 > 0.5


def test_a_zero_threshold_leaves_its_components_out():
    fanout, sub = subscribe(threshold_torque_nm=0.1)
    fanout.publish(reading(1))
    fanout.publish(reading(2, fz=50.0))  # force is not watched
    fanout.publish(reading(3, fz=50.0, tz=0.2))
    assert drain(sub) == [[1], [3]]
    assert exceeds(0.0, 0.0, 0.0, 0.0)  # no thresholds: everything passes


def test_a_full_queue_drops_the_oldest_and_counts():
    fanout, sub = subscribe(queue_capacity=3)
    for i in range(1, 11):
        fanout.publish(reading(i))
    assert drain(sub) == [[8], [9], [10]]
    assert sub.dropped == 7


def test_one_full_subscriber_does_not_touch_another():
    fanout, slow = subscribe(queue_capacity=2)
    fast = fanout.attach(WrenchSubscription(fanout, StreamOptions()))
    for i in range(1, 6):
        fanout.publish(reading(i))
    assert drain(fast) == [[1], [2], [3], [4], [5]] and fast.dropped == 0
    assert slow.dropped == 3


def test_each_batch_reports_how_long_it_waited_for_its_stream():
    now = [100.0]
    fanout: Fanout = Fanout(clock=lambda: now[0])
    lags: list[float] = []
    fanout.on_lag = lags.append
    sub = fanout.attach(WrenchSubscription(fanout, StreamOptions()))
    fanout.publish(reading(1))
    now[0] += 0.003
    fanout.publish(reading(2))
    now[0] += 0.001
    assert drain(sub) == [[1], [2]]
    assert lags == pytest.approx([0.004, 0.001])


@pytest.mark.parametrize("fields", [
    dict(decimation=-1, threshold_force_n=0, threshold_torque_nm=0, batch_size=0,
         queue_capacity=0),
    dict(decimation=0, threshold_force_n=float("nan"), threshold_torque_nm=0, batch_size=0,
         queue_capacity=0),
    dict(decimation=0, threshold_force_n=0, threshold_torque_nm=-1, batch_size=0,
         queue_capacity=0),
    dict(decimation=0, threshold_force_n=0, threshold_torque_nm=0, batch_size=5000,
         queue_capacity=0),
])
def test_bad_stream_options_are_invalid(fields):
    with pytest.raises(InvalidArgumentError):
        StreamOptions.from_request(**fields)


def test_zeros_mean_defaults():
    options = StreamOptions.from_request(0, 0.0, 0.0, 0, 0)
    assert (options.decimation, options.batch_size, options.queue_capacity) == (1, 1, 64)


@pytest.mark.parametrize("settings", [
    SensorSettings(period_s=0.0), SensorSettings(period_s=-0.001), SensorSettings(period_s=2.0),
    SensorSettings(period_s=0.0005), SensorSettings(threshold_force_n=float("nan")),
    SensorSettings(threshold_torque_nm=-0.1),
])
def test_bad_settings_are_invalid(settings):
    with pytest.raises(InvalidArgumentError):
        settings.validated()
