"""PNG plots of the results (matplotlib, Agg backend): latency distributions per family, with
the baselines beside the project, and the observers curve (the Parma table as a figure)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from bench.goals import goal_for
from bench.report import family

_GROUPS = {
    "commands": ("command", "teleop"),
    "force": ("force",),
    "estop": ("estop",),
    "closed_loop": ("closed",),
}
# The goal whose p99 bound each plot draws as a line (goals.py).
_GOAL_LINE = {"commands": "teleop_1000", "force": "force_1000", "estop": "estop_idle",
              "closed_loop": "closed_loop", "observers": "observers_32"}


def _p99_goal(group: str) -> float | None:
    goal = goal_for(_GOAL_LINE[group])
    return goal.p99_ms if goal is not None else None


ZENOH_ROWS = "observers_zenoh_"  # bench/groups/observers_zenoh.py


def _zenoh_plot(plt, out_dir: Path, rows: list[tuple[int, dict]]) -> Path:
    """observers_zenoh.png: the operator's stream, where the CPU goes, and what each
    subscriber gets, against the number of subscribers behind the router."""
    counts = [n for n, _ in rows]
    figure, axes = plt.subplots(1, 3, figsize=(14, 4.4))
    axes[0].plot(counts, [r["p50_ms"] for _, r in rows], "o-", label="p50")
    axes[0].plot(counts, [r["p99_ms"] for _, r in rows], "s-", label="p99")
    axes[0].axhline(_p99_goal("observers"), color="red", alpha=0.6, label="goal (p99)")
    axes[0].set_title("operator's 1 kHz force stream: latency")
    axes[0].set_ylabel("ms")
    for key, label in (("station_cpu_pct", "station (its services and the publisher)"),
                       ("world_cpu_pct", "of which the world (fixed work)"),
                       ("router_cpu_pct", "the router"),
                       ("subscribers_cpu_pct", "the subscribers' processes")):
        axes[1].plot(counts, [r.get(key) for _, r in rows], "o-", label=label)
    axes[1].set_title("CPU while measured")
    axes[1].set_ylabel("% of one core")
    axes[2].plot(counts, [r.get("subscriber_lag_p50_ms_median") for _, r in rows], "o-",
                 label="lag p50 (median subscriber)")
    axes[2].plot(counts, [r.get("subscriber_lag_p99_ms_median") for _, r in rows], "s-",
                 label="lag p99 (median subscriber)")
    axes[2].set_yscale("log")
    axes[2].set_title("each subscriber: sample taken -> received")
    axes[2].set_ylabel("ms")
    for axis in axes:
        axis.set_xlabel("Zenoh subscribers behind the router")
        axis.set_xscale("symlog", linthresh=1)
        axis.set_xticks(counts, [str(c) for c in counts])
        axis.grid(True, alpha=0.3)
        axis.legend(fontsize=8)
    figure.tight_layout()
    path = out_dir / "observers_zenoh.png"
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path


def write_plots(out_dir: Path, results: dict[str, dict], raw: dict[str, list[float]]
                ) -> list[Path]:
    """Write the PNGs into out_dir; returns their paths."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    def plain_log(axis) -> None:
        """Log scale labelled 0.5, 1, 2, 5, 10... instead of powers of ten."""
        axis.set_xscale("log")
        axis.xaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
        axis.xaxis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
        axis.xaxis.set_minor_formatter(NullFormatter())

    written = []
    for group, families in _GROUPS.items():
        names = [n for n in raw if family(n) in families and raw[n]]
        if not names:
            continue
        figure, (cdf, box) = plt.subplots(1, 2, figsize=(13, 5.2),
                                          gridspec_kw={"width_ratios": [3, 2]})
        colors = plt.cm.tab20(np.linspace(0, 1, 20))
        for index, name in enumerate(names):
            values = np.sort(np.asarray(raw[name], dtype=float))
            values = np.clip(values, 1e-3, None)
            quantiles = np.arange(1, values.size + 1) / values.size
            style = "--" if name.endswith(("_zmq", "_tcp")) else "-"
            cdf.plot(values, quantiles, style, label=name, linewidth=1.4,
                     color=colors[(2 * index) % 20 + (2 * index) // 20 % 2])
        budget = _p99_goal(group)
        if budget:
            cdf.axvline(budget, color="red", linewidth=1, alpha=0.6)
            cdf.text(budget, 0.5, f" goal {budget:g} ms (p99)", color="red", fontsize=8,
                     rotation=90, va="center")
        cdf.axhline(0.99, color="grey", linewidth=0.6, linestyle=":")
        plain_log(cdf)
        cdf.set_xlabel("latency (ms, log scale)")
        cdf.set_ylabel("fraction of samples at or below")
        cdf.set_title(f"{group}: latency distribution (CDF)")
        cdf.grid(True, which="both", alpha=0.3)
        cdf.legend(fontsize=7, loc="lower right")
        box.boxplot([raw[n] for n in names], vert=False, whis=(1, 99), showfliers=False)
        box.set_yticks(range(1, len(names) + 1), names, fontsize=7)
        plain_log(box)
        box.set_xlabel("latency (ms): box p25-p75, whiskers p1-p99")
        box.grid(True, which="both", alpha=0.3)
        figure.tight_layout()
        path = out_dir / f"latency_{group}.png"
        figure.savefig(path, dpi=110)
        plt.close(figure)
        written.append(path)

    observers = sorted((r["observers"], r) for n, r in results.items()
                       if family(n) == "observers" and not n.startswith(ZENOH_ROWS)
                       and r.get("p99_ms") is not None)
    if observers:
        counts = [n for n, _ in observers]
        figure, axes = plt.subplots(1, 3, figsize=(14, 4.4))
        axes[0].plot(counts, [r["delivered_hz"] for _, r in observers], "o-")
        axes[0].axhline(1000, color="grey", linestyle=":")
        axes[0].set_title("operator's 1 kHz force stream: delivered rate")
        axes[0].set_ylabel("Hz")
        axes[1].plot(counts, [r["p50_ms"] for _, r in observers], "o-", label="p50")
        axes[1].plot(counts, [r["p99_ms"] for _, r in observers], "s-", label="p99")
        axes[1].axhline(_p99_goal("observers"), color="red", alpha=0.6,
                        label="goal (p99)")
        axes[1].set_title("sample -> operator latency")
        axes[1].set_ylabel("ms")
        axes[1].legend(fontsize=8)
        axes[2].plot(counts, [r.get("jitter_ms") for _, r in observers], "o-",
                     label="std of inter-arrival")
        axes[2].plot(counts, [r.get("interarrival_p99_ms") for _, r in observers], "s-",
                     label="p99 inter-arrival")
        axes[2].axhline(1.0, color="grey", linestyle=":", label="nominal 1 ms")
        axes[2].set_title("inter-arrival at the operator")
        axes[2].set_ylabel("ms")
        axes[2].legend(fontsize=8)
        for axis in axes:
            axis.set_xlabel("observers streaming at 100 Hz")
            axis.set_xscale("symlog", linthresh=1)
            axis.set_xticks(counts, [str(c) for c in counts])
            axis.grid(True, alpha=0.3)
        figure.tight_layout()
        path = out_dir / "observers.png"
        figure.savefig(path, dpi=110)
        plt.close(figure)
        written.append(path)

    zenoh = sorted((r["observers"], r) for n, r in results.items()
                   if n.startswith(ZENOH_ROWS) and r.get("p99_ms") is not None)
    if zenoh:
        written.append(_zenoh_plot(plt, out_dir, zenoh))

    series = (results.get("soak") or {}).get("rss_series")
    if series and series.get("t_s"):
        minutes = np.asarray(series["t_s"], dtype=float) / 60.0
        figure, axis = plt.subplots(figsize=(10, 4.8))
        for name, values in series["rss_mib"].items():
            axis.plot(minutes, [np.nan if v is None else v for v in values], label=name)
        warmup = results["soak"].get("warmup_fraction", 0.0) * minutes[-1]
        axis.axvspan(0, warmup, color="grey", alpha=0.15, label="warm-up (not fitted)")
        axis.set_xlabel("minutes into the soak")
        axis.set_ylabel("RSS (MiB)")
        axis.set_title("soak: RSS of every station process")
        axis.grid(True, alpha=0.3)
        axis.legend(fontsize=8)
        figure.tight_layout()
        path = out_dir / "soak_rss.png"
        figure.savefig(path, dpi=110)
        plt.close(figure)
        written.append(path)
    return written
