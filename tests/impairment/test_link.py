"""The link model's schedule, exactly and without sleeping: times are arguments."""

from __future__ import annotations

import random

import pytest

from services.impairment.link import LinkProfile, LinkSchedule


def schedule_of(profile: LinkProfile, chunks: list[tuple[float, int]]) -> list[float]:
    """Release times of (arrival_s, size_bytes) chunks through a fresh schedule."""
    schedule = LinkSchedule(profile)
    return [schedule.release_time(arrival_s, size) for arrival_s, size in chunks]


def test_a_delay_alone_shifts_every_chunk_by_it():
    releases = schedule_of(LinkProfile(delay_s=0.05), [(0.0, 100), (0.01, 100), (1.0, 5)])
    assert releases == pytest.approx([0.05, 0.06, 1.05], abs=1e-12)


def test_no_impairment_releases_at_arrival():
    assert schedule_of(LinkProfile(), [(0.5, 10), (0.7, 10)]) == [0.5, 0.7]


def test_jitter_stays_within_delay_plus_or_minus_jitter():
    # Chunks 1 s apart never wait for each other, so each shows its own draw.
    profile = LinkProfile(delay_s=0.05, jitter_s=0.005, seed=3)
    arrivals = [float(i) for i in range(500)]
    delays = [release - arrival for arrival, release
              in zip(arrivals, schedule_of(profile, [(a, 100) for a in arrivals]), strict=True)]
    assert all(0.045 - 1e-12 <= delay <= 0.055 + 1e-12 for delay in delays)
    assert min(delays) < 0.046 and max(delays) > 0.054  # it does spread over the range


def test_jitter_larger_than_the_delay_never_makes_it_negative():
    profile = LinkProfile(delay_s=0.001, jitter_s=0.01, seed=1)
    arrivals = [float(i) for i in range(200)]
    releases = schedule_of(profile, [(a, 1) for a in arrivals])
    assert all(release >= arrival for arrival, release in zip(arrivals, releases, strict=True))


def test_jitter_never_reorders_a_chunk_before_the_previous_one():
    # Chunks 1 ms apart with ± 20 ms of jitter would overtake each other on a datagram link.
    profile = LinkProfile(delay_s=0.05, jitter_s=0.02, seed=7)
    arrivals = [i * 0.001 for i in range(300)]
    releases = schedule_of(profile, [(a, 100) for a in arrivals])
    assert releases == sorted(releases)
    held = sum(1 for before, after in zip(releases[:-1], releases[1:], strict=True)
               if after == before)
    assert held > 50  # many were held behind a later-drawn predecessor, not dropped or early
    assert all(r >= a + 0.03 - 1e-12 for a, r in zip(arrivals, releases, strict=True))


def test_bandwidth_serializes_chunks_one_after_another():
    # 1 Mbit/s: 12,500 bytes take 100 ms on the line.
    profile = LinkProfile(delay_s=0.01, bandwidth_bps=1e6)
    releases = schedule_of(profile, [(0.0, 12_500), (0.0, 12_500), (0.0, 1_250), (5.0, 12_500)])
    assert releases == pytest.approx([0.11, 0.21, 0.22, 5.11], abs=1e-12)


def test_a_stall_holds_the_chunk_and_everything_behind_it():
    profile = LinkProfile(delay_s=0.05, stall_probability=1.0, stall_s=0.2)
    schedule = LinkSchedule(profile)
    assert schedule.release_time(0.0, 10) == pytest.approx(0.25)
    assert schedule.stalls == 1

    # With some stalls: a stalled chunk comes stall_s late, and the next ones not before it.
    profile = LinkProfile(delay_s=0.05, stall_probability=0.2, stall_s=0.2, seed=5)
    schedule = LinkSchedule(profile)
    arrivals = [i * 0.01 for i in range(200)]
    releases = [schedule.release_time(a, 10) for a in arrivals]
    late = [r - a for a, r in zip(arrivals, releases, strict=True)]
    assert 20 <= schedule.stalls <= 60
    assert releases == sorted(releases)
    assert max(late) >= 0.25 - 1e-12
    assert min(late) == pytest.approx(0.05)
    # a chunk 10 ms behind a stalled one comes out with it: held, not early
    assert sum(1 for d in late if 0.05 + 1e-9 < d < 0.25 - 1e-9) > 0


def test_the_same_seed_repeats_the_schedule_and_another_does_not():
    chunks = [(i * 0.002, 500) for i in range(200)]
    profile = LinkProfile(delay_s=0.05, jitter_s=0.01, stall_probability=0.05, stall_s=0.1,
                          bandwidth_bps=2e6, seed=42)
    assert schedule_of(profile, chunks) == schedule_of(profile, chunks)
    other = LinkProfile(**{**profile.__dict__, "seed": 43})
    assert schedule_of(profile, chunks) != schedule_of(other, chunks)
    # An explicit generator wins over the profile's seed.
    explicit = LinkSchedule(profile, random.Random(42))
    assert [explicit.release_time(*c) for c in chunks] == schedule_of(profile, chunks)


def test_a_seed_places_the_same_stalls_with_or_without_jitter():
    chunks = [(float(i), 10) for i in range(300)]
    stalls = dict(stall_probability=0.1, stall_s=0.5, seed=9)

    def stalled(profile):
        return [r - a > 0.4 for (a, _), r in zip(chunks, schedule_of(profile, chunks),
                                                    strict=True)]

    assert stalled(LinkProfile(**stalls)) == stalled(LinkProfile(jitter_s=0.01, **stalls))


def test_hold_releases_nothing_before_the_cut_ends():
    schedule = LinkSchedule(LinkProfile(delay_s=0.05, bandwidth_bps=1e6))
    assert schedule.release_time(0.0, 1_250) == pytest.approx(0.06)
    schedule.hold(until_s=3.0)
    # arrived during the cut: on the line once it is back, then the delay
    assert schedule.release_time(1.0, 1_250) == pytest.approx(3.06)
    # after the cut: as usual
    assert schedule.release_time(4.0, 1_250) == pytest.approx(4.06)


@pytest.mark.parametrize("field, value", [("delay_s", -0.1), ("jitter_s", float("nan")),
                                          ("bandwidth_bps", -1.0), ("stall_s", float("inf")),
                                          ("stall_probability", 1.5)])
def test_a_profile_refuses_impossible_values(field, value):
    with pytest.raises(ValueError, match=field):
        LinkProfile(**{field: value})


def test_a_profile_describes_itself():
    profile = LinkProfile(delay_s=0.05, jitter_s=0.005, bandwidth_bps=1e6,
                          stall_probability=0.01, stall_s=0.2, seed=1)
    assert profile.describe() == ("delay 50 ms ± 5 ms, 1 Mbit/s, stalls of 200 ms with "
                                  "probability 0.01 per chunk, seed 1")
