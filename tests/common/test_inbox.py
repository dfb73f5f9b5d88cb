"""Inbox: a stream read on its own thread, taken in batches; the order of events is set with
explicit gates, never with sleeps."""

from __future__ import annotations

import threading

import pytest

from services.common.inbox import Inbox, Producer
from tests.conftest import wait_for
from wire.errors import ResourceExhaustedError


class Gate:
    """An iterator that yields each value only once the test lets it through."""

    def __init__(self, values, error: Exception | None = None):
        self._values = list(values)
        self._error = error
        self._allowed = threading.Semaphore(0)
        self.read = 0

    def let(self, count: int) -> None:
        for _ in range(count):
            self._allowed.release()

    def __iter__(self):
        for value in self._values:
            self._allowed.acquire()
            self.read += 1
            yield value
        if self._error is not None:
            self._allowed.acquire()
            raise self._error


def test_take_returns_everything_that_arrived_since_the_last_take_in_order():
    gate = Gate(range(6))
    inbox = Inbox(iter(gate), lambda v: v * 10)
    gate.let(3)
    wait_for(lambda: gate.read == 3, what="three messages read")
    assert inbox.take() == [0, 10, 20]
    gate.let(1)
    assert inbox.take() == [30]  # waits for at least one
    gate.let(2)
    wait_for(lambda: gate.read == 6, what="all read")
    assert inbox.take(limit=1) == [40]
    assert inbox.take() == [50]
    assert inbox.take() == []  # the messages ended


def test_an_error_while_reading_reaches_the_taker_after_the_messages_before_it():
    gate = Gate([1, 2], error=ValueError("bad message 3"))
    inbox = Inbox(iter(gate), lambda v: v)
    gate.let(3)
    taken = []
    with pytest.raises(ValueError, match="bad message 3"):
        while True:
            taken += inbox.take()
    assert taken == [1, 2]


def test_a_stamp_that_raises_ends_the_inbox_with_that_error():
    def stamp(value):
        if value == 2:
            raise KeyError("refused")
        return value

    gate = Gate([1, 2, 3])
    inbox = Inbox(iter(gate), stamp)
    gate.let(3)
    assert inbox.take() == [1]
    with pytest.raises(KeyError, match="refused"):
        inbox.take()


def test_a_producer_yields_what_it_emits_in_order_then_raises_its_error():
    def produce(emit):
        for value in range(5):
            emit(value)
        raise LookupError("no more")

    got = []
    with pytest.raises(LookupError, match="no more"):
        for value in Producer(produce):
            got.append(value)
    assert got == [0, 1, 2, 3, 4]


def test_a_reader_that_falls_too_far_behind_ends_the_producing():
    """A client that never reads its acks: the answers pending stop at the bound, the producer
    stops acting, and the reader gets the error after what was pending."""
    produced, gave_up = [], threading.Event()

    def produce(emit):
        try:
            for value in range(100):
                emit(value)
                produced.append(value)
        finally:
            gave_up.set()

    stream = Producer(produce, max_pending=8)
    assert gave_up.wait(5)  # nobody read meanwhile
    got = []
    with pytest.raises(ResourceExhaustedError, match="8 answers wait to be read"):
        for value in stream:
            got.append(value)
    assert got == produced == list(range(8))


def test_a_closed_inbox_ends_the_producer_that_takes_from_it():
    gate = Gate(range(100))
    inbox = Inbox(iter(gate), lambda v: v)

    def produce(emit):
        while batch := inbox.take():
            emit(batch)

    gate.let(1)
    stream = iter(Producer(produce))
    assert next(stream) == [0]
    inbox.close()
    assert list(stream) == []
