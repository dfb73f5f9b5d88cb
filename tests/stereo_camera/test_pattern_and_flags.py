"""The pattern source's drawn tick and the camera-status flags, without a server."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from services.stereo_camera.pattern import PatternSource, disparity_px, pattern_image, read_tick
from services.stereo_camera.source import LEFT, RIGHT, EyeFrame, PairAssembler


@pytest.mark.parametrize("tick", [0, 1, 37, 65_535, 2**31 + 5])
def test_the_drawn_tick_reads_back_from_both_eyes(tick):
    for eye in (LEFT, RIGHT):
        assert read_tick(pattern_image(tick, eye, 160, 120)) == tick


def test_the_tick_survives_jpeg_and_resizing():
    image = pattern_image(123_456, LEFT, 320, 240)
    ok, jpeg = cv2.imencode(".jpg", image, [cv2.IMWRITE_JPEG_QUALITY, 30])
    assert ok and read_tick(cv2.imdecode(jpeg, cv2.IMREAD_COLOR)) == 123_456
    assert read_tick(cv2.resize(image, (96, 72), interpolation=cv2.INTER_AREA)) == 123_456


def test_a_damaged_code_reads_as_nothing():
    image = pattern_image(99, LEFT, 160, 120)
    image[:12] = 255  # the data rows and their inverse now disagree
    assert read_tick(image) is None


def test_the_right_eye_sees_the_card_shifted_by_the_disparity():
    width = 320
    left = pattern_image(5, LEFT, width, 240)
    right = pattern_image(5, RIGHT, width, 240)
    below_labels = slice(120, 240)
    shifted = np.roll(left, -disparity_px(width), axis=1)
    assert np.array_equal(shifted[below_labels], right[below_labels])
    assert not np.array_equal(left[below_labels], right[below_labels])


def test_pattern_images_change_every_tick():
    assert not np.array_equal(pattern_image(1, LEFT, 160, 120), pattern_image(2, LEFT, 160, 120))


def test_the_pattern_source_grabs_both_eyes_of_one_tick():
    source = PatternSource(160, 120, cost_ms=4)
    source.open()
    left, right = source.grab(42)
    assert left.tick == right.tick == 42
    assert read_tick(left.image) == read_tick(right.image) == 42
    assert right.capture_time_ns >= left.capture_time_ns  # read out one after the other


def _frame(tick: int) -> EyeFrame:
    return EyeFrame(tick, np.zeros((2, 2, 3), np.uint8), tick * 1000)


def test_flags_pair_the_eyes_of_one_tick_in_either_order():
    flags = PairAssembler()
    assert flags.offer(LEFT, _frame(1)) is None
    left, right = flags.offer(RIGHT, _frame(1))
    assert left.tick == right.tick == 1
    assert flags.offer(RIGHT, _frame(2)) is None
    left, right = flags.offer(LEFT, _frame(2))
    assert (left.tick, right.tick) == (2, 2)
    assert flags.mismatched == 0


def test_flags_never_pair_two_ticks():
    flags = PairAssembler()
    assert flags.offer(LEFT, _frame(1)) is None
    assert flags.offer(RIGHT, _frame(2)) is None  # left 1 can no longer complete: dropped
    assert flags.offer(LEFT, _frame(1)) is None  # a late left eye of a gone tick
    assert flags.offer(LEFT, _frame(3)) is None  # right 2 dropped
    left, right = flags.offer(RIGHT, _frame(3))
    assert (left.tick, right.tick) == (3, 3)
    assert flags.mismatched == 3


def test_an_eye_that_comes_twice_replaces_its_unpaired_frame():
    flags = PairAssembler()
    flags.offer(LEFT, _frame(1))
    flags.offer(LEFT, _frame(2))
    left, right = flags.offer(RIGHT, _frame(2))
    assert (left.tick, right.tick) == (2, 2)
    assert flags.mismatched == 1
