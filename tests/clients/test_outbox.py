"""The Teleoperate client's outbox: commands that wait together to be sent go as one, the
newest sequence carrying their composed increment, each acked; and the clock-offset receipts."""

from __future__ import annotations

import threading
import time

import numpy as np
import pinocchio as pin
import pytest

from clients.python import DecisionClient
from clients.python.outbox import Outbox, compose_increments
from clients.python.values import CommandOutcome
from domain.geometry import moved_by
from tests.conftest import wait_for

END = object()


def rotation(axis: str, angle: float) -> np.ndarray:
    return pin.utils.rotate(axis, angle)


def numbers_outbox() -> Outbox:
    """Integers merge (into their sum) while positive; zero does not."""
    return Outbox(END, lambda n: n > 0, sum)


def test_items_waiting_together_are_taken_as_one_when_mergeable():
    box = numbers_outbox()
    for n in (1, 2, 3, 0, 4, 5):
        box.put(n)
    box.put(END)
    assert list(box) == [6, 0, 9]
    assert list(box) == []  # ended for good


def test_an_item_taken_alone_is_not_merged():
    box = numbers_outbox()
    taken = []
    reader = threading.Thread(target=lambda: taken.extend(box))
    reader.start()
    box.put(7)
    wait_for(lambda: taken == [7], what="the first item taken")  # taken as it came
    box.put(8)
    box.put(END)
    reader.join(5)
    assert taken == [7, 8]


@pytest.mark.parametrize("frame", ["BASE", "TOOL"])
def test_composed_increments_move_the_tool_as_the_increments_one_by_one(frame):
    rng = np.random.default_rng(3)
    increments = [(rng.normal(0, 0.002, 3), rotation("xyz"[i % 3], rng.normal(0, 0.05)))
                  for i in range(6)]
    tool = pin.SE3(rotation("y", 0.4), np.array([0.3, -0.1, 0.5]))
    one_by_one = tool
    for dx, dm in increments:
        one_by_one = moved_by(one_by_one, pin.SE3(dm, dx), frame)
    dx, dm = compose_increments(increments, frame)
    at_once = moved_by(tool, pin.SE3(dm, dx), frame)
    np.testing.assert_allclose(at_once.translation, one_by_one.translation, atol=1e-12)
    np.testing.assert_allclose(at_once.rotation, one_by_one.rotation, atol=1e-12)


def test_commands_waiting_to_be_sent_go_as_one_and_each_is_acked(fake_station):  # noqa: F811
    """The link is held (gRPC's sender cannot take a message) while three commands are sent:
    the server receives one, the newest, with their sum; the client hears three acks."""
    station, slave = fake_station
    with DecisionClient(station.address) as client:
        client.acquire_control("ann")
        received = []
        with client.teleoperate(watchdog_timeout_s=1.0, on_ack=received.append) as session:
            assert session.send((0, 0, 0.001)).applied
            outbox = session._requests
            with outbox._ready:  # gRPC's sending thread waits for the outbox meanwhile
                sent = [session.send_nowait((0, 0.001, 0)) for _ in range(3)]
            wait_for(lambda: len(received) == 4, what="the three acks")
            assert [a.sequence for a in received] == [1, *sent]
            assert all(a.outcome is CommandOutcome.APPLIED for a in received)
            assert "merged by the client into command 4" in received[1].detail
            assert session.merged == 2 and session.commands_acked == 4
            moves = [c.detail[1] for c in slave.commands if c.kind == "cartesian"]
            assert len(moves) == 2  # the first command's, then one for the three
            np.testing.assert_allclose(moves[1], [0, 0.003, 0], atol=1e-12)


def test_the_session_reports_ack_receipts_and_acks_carry_the_clock_offset(fake_station):
    station, _ = fake_station
    with DecisionClient(station.address) as client:
        client.acquire_control("ann")
        with client.teleoperate(watchdog_timeout_s=1.0, max_command_age_s=0.02) as session:
            assert session.max_command_age_s == pytest.approx(0.02)
            # The fake station's clock stands still: its offset from this machine's shrinks
            # as this one runs, from `before` to `after`.
            before = station.core.clock.time_ns() - time.time_ns()
            first = session.send((0, 0, 0.001))
            assert first.clock_offset_s is None and first.sent_to_applied_s is None
            second = session.send((0, 0, 0.001))  # carries the receipt of the first's ack
            after = station.core.clock.time_ns() - time.time_ns()
            offset, error = second.clock_offset_s, second.clock_offset_error_s
            assert offset is not None and second.sent_to_applied_s is not None
            assert (after - error * 1e9) * 1e-9 <= offset <= (before + error * 1e9) * 1e-9
