"""The wrench fan-out: one message for many subscribers is encoded once, and every subscriber's
bytes decode to the message it would have got on its own (same samples, same batches, its own
dropped_count); the fastest subscriber is served first; a waiting stream wakes for a batch."""

from __future__ import annotations

import gc
import os
import threading

import numpy as np

from services.common.fanout import Fanout
from services.force_sensor.servicer import encode_samples, reading_to_proto, stream_message
from services.force_sensor.subscribers import (
    StreamOptions,
    WrenchFanout,
    WrenchReading,
    WrenchSubscription,
)
from telerobot.v1 import force_sensor_pb2 as pb
from tests.conftest import wait_for


def reading(sequence: int) -> WrenchReading:
    """A wrench that wanders, so change filters let some samples through and not others."""
    phase = sequence * 0.7
    return WrenchReading(sequence, 1_767_225_600_000_000_000 + sequence * 1_000_000,
                         np.array([np.sin(phase), 0.5 * np.cos(phase), -2.0 + 0.1 * sequence]),
                         np.array([0.01 * sequence, 0.0, -0.03 * np.sin(phase)]))


class Pair:
    """A subscriber on the shared fan-out, and its twin alone on a plain Fanout, attached at the
    same moment with the same options: what that subscriber would have got on its own."""

    def __init__(self, shared: WrenchFanout, alone: Fanout, **options):
        self.subscription = shared.attach(WrenchSubscription(shared, StreamOptions(**options)))
        self.twin = alone.attach(WrenchSubscription(alone, StreamOptions(**options)))

    def drain(self) -> tuple[list, list[bytes], list[bytes]]:
        """(batches, the bytes this subscriber's stream sends, the twin's messages serialized
        the way a message per subscriber used to be)."""
        batches, sent, expected = [], [], []
        while (batch := self.subscription.get(0)) is not None:
            batches.append(batch)
            sent.append(stream_message(batch, self.subscription.dropped))
        while (batch := self.twin.get(0)) is not None:
            expected.append(pb.StreamWrenchResponse(
                samples=[reading_to_proto(r) for r in batch],
                dropped_count=self.twin.dropped).SerializeToString())
        return batches, sent, expected


def publish(fanouts, first: int, last: int) -> None:
    for sequence in range(first, last + 1):
        item = reading(sequence)
        for fanout in fanouts:
            fanout.publish(item)


def test_every_subscriber_sends_the_message_it_would_have_got_alone():
    shared, alone = WrenchFanout(), Fanout()
    pairs = [Pair(shared, alone),  # the operator: every sample, one per message
             Pair(shared, alone, decimation=10),  # observers at 100 Hz
             Pair(shared, alone, decimation=10),
             Pair(shared, alone, decimation=10, batch_size=3),
             Pair(shared, alone, batch_size=5),
             Pair(shared, alone, threshold_force_n=0.9),
             Pair(shared, alone, decimation=2, threshold_torque_nm=0.02, batch_size=2),
             Pair(shared, alone, queue_capacity=4)]  # overflows: its dropped_count counts
    publish([shared, alone], 1, 4)
    pairs.append(Pair(shared, alone, decimation=10))  # joins later: another phase
    publish([shared, alone], 5, 60)
    for pair in pairs:
        batches, sent, expected = pair.drain()
        assert batches, pair.subscription.options
        assert sent == expected  # byte for byte
        for raw, batch in zip(sent, batches, strict=True):
            message = pb.StreamWrenchResponse.FromString(raw)
            assert [s.sequence for s in message.samples] == [r.sequence for r in batch]
    assert pairs[-2].subscription.dropped == 60 - 4  # and its messages said so, as above


def test_subscribers_that_chose_the_same_samples_share_one_batch_encoded_once(monkeypatch):
    encoded: list[tuple[int, ...]] = []

    def counting_encode(readings):
        encoded.append(tuple(r.sequence for r in readings))
        return encode_samples(readings)

    monkeypatch.setattr("services.force_sensor.servicer.encode_samples", counting_encode)
    fanout = WrenchFanout()

    def subscribe(**options) -> WrenchSubscription:
        return fanout.attach(WrenchSubscription(fanout, StreamOptions(**options)))

    operator = subscribe()
    observers = [subscribe(decimation=10) for _ in range(3)]
    publish([fanout], 1, 3)
    late = subscribe(decimation=10)  # first sees sample 4: out of step with the others
    batched = [subscribe(batch_size=5) for _ in range(2)]
    publish([fanout], 4, 30)

    def drain(subscription):
        batches = []
        while (batch := subscription.get(0)) is not None:
            batches.append(batch)
        return batches

    got = {id(s): drain(s) for s in [operator, *observers, late, *batched]}
    messages = {id(s): [stream_message(b, s.dropped) for b in got[id(s)]]
                for s in [operator, *observers, late, *batched]}
    # The observers in step got the very same batches (and bytes) as one another, and as the
    # operator for the samples they share; the late one its own phase's samples.
    first = got[id(observers[0])]
    assert [b.readings[0].sequence for b in first] == [1, 11, 21]
    for other in observers[1:]:
        assert all(a is b for a, b in zip(got[id(other)], first, strict=True))
        assert all(a is b for a, b in zip(messages[id(other)], messages[id(observers[0])],
                                          strict=True))
    by_sequence = {b.readings[0].sequence: b for b in got[id(operator)]}
    assert all(b is by_sequence[b.readings[0].sequence] for b in first)
    assert all(b is by_sequence[b.readings[0].sequence] for b in got[id(late)])
    assert [b.readings[0].sequence for b in got[id(late)]] == [4, 14, 24]
    assert all(a is b for a, b in zip(*(got[id(s)] for s in batched), strict=True))
    # One encoding per distinct message: 30 single samples and the batched pair's 5 batches
    # of 5 (4..28; 29 and 30 still wait), whatever the number of subscribers.
    assert sorted(encoded) == sorted([(n,) for n in range(1, 31)]
                                     + [tuple(range(n, n + 5)) for n in range(4, 29, 5)])


def test_a_subscriber_that_dropped_sends_the_shared_bytes_and_its_own_count():
    fanout = WrenchFanout()
    keeping = fanout.attach(WrenchSubscription(fanout, StreamOptions()))
    dropping = fanout.attach(WrenchSubscription(fanout, StreamOptions(queue_capacity=2)))
    publish([fanout], 1, 5)
    assert dropping.dropped == 3
    kept = [keeping.get(0) for _ in range(5)]
    for expected_sequence in (4, 5):
        batch = dropping.get(0)
        assert batch is kept[expected_sequence - 1]
        raw = stream_message(batch, dropping.dropped)
        assert raw.startswith(stream_message(batch, keeping.dropped))  # the shared bytes first
        message = pb.StreamWrenchResponse.FromString(raw)
        assert message.dropped_count == 3
        assert [s.sequence for s in message.samples] == [expected_sequence]
        assert message == pb.StreamWrenchResponse(samples=[reading_to_proto(batch.readings[0])],
                                                  dropped_count=3)


def test_the_fastest_subscriber_is_served_first_whatever_the_order_they_came_in(monkeypatch):
    fanout = WrenchFanout()
    observer = fanout.attach(WrenchSubscription(fanout, StreamOptions(decimation=10)))
    slower = fanout.attach(WrenchSubscription(fanout, StreamOptions(decimation=100)))
    operator = fanout.attach(WrenchSubscription(fanout, StreamOptions()))
    second_operator = fanout.attach(WrenchSubscription(fanout, StreamOptions()))
    served = []
    for name, subscription in (("observer", observer), ("slower", slower),
                               ("operator", operator), ("second operator", second_operator)):
        deliver = subscription.deliver
        monkeypatch.setattr(subscription, "deliver",
                            lambda batch, name=name, deliver=deliver: (served.append(name),
                                                                       deliver(batch)))
    fanout.publish(reading(1))  # the first sample: every one of them takes it
    assert served == ["operator", "second operator", "observer", "slower"]


def test_a_waiting_stream_is_woken_by_a_batch_and_by_close():
    fanout = WrenchFanout()
    subscription = fanout.attach(WrenchSubscription(fanout, StreamOptions()))
    got: list = []
    # get() with no timeout: only a delivery or close() ends it.
    waiter = threading.Thread(target=lambda: [got.append(subscription.get()) for _ in range(2)])
    waiter.start()
    wait_for(lambda: subscription._waiting, 5.0, "the stream waiting for a batch")
    fanout.publish(reading(1))
    wait_for(lambda: got, 5.0, "the stream to take the batch")
    assert [r.sequence for r in got[0]] == [1]
    wait_for(lambda: subscription._waiting, 5.0, "the stream waiting again")
    subscription.close()
    waiter.join(5.0)
    assert not waiter.is_alive() and got[1] is None
    assert fanout.subscriber_count == 0


def test_subscriptions_give_back_their_file_descriptors():
    def open_fds() -> int:
        return len(os.listdir("/proc/self/fd"))

    fanout = WrenchFanout()
    before = open_fds()
    for _ in range(200):
        with fanout.attach(WrenchSubscription(fanout, StreamOptions())):
            fanout.publish(reading(1))
    gc.collect()
    assert open_fds() <= before
