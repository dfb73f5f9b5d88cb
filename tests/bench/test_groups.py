"""Every group `python -m bench --only` takes has its module in bench/groups/, run in the order
bench.plan.GROUPS gives, each counting the progress steps it takes."""

from __future__ import annotations

from bench.plan import GROUPS, Plan
from bench.run import GROUP_MODULES, Bench


def test_each_group_has_its_module_in_the_order_they_run():
    assert tuple(GROUP_MODULES) == GROUPS
    for name, module in GROUP_MODULES.items():
        assert module.__name__ == f"bench.groups.{name}"
        assert callable(module.run) and module.steps(Plan(quick=True)) >= 1


def test_the_progress_counts_the_station_the_groups_asked_for_and_the_world_loop():
    plan = Plan(quick=True, only=("estop", "closed_loop"))
    bench = Bench(plan, out_dir=None)  # nothing started yet but its scratch directory
    try:
        assert bench.progress.total == 2 + 3 + 1
    finally:
        bench.procs.stop_all()


def test_subscribers_split_over_workers_of_at_most_their_size_in_order():
    from bench.procs import worker_sizes

    assert worker_sizes(70, 32) == [32, 32, 6]
    assert worker_sizes(1024, 32) == [32] * 32
    assert worker_sizes(1, 8) == [1]
    assert sum(worker_sizes(257, 32)) == 257
