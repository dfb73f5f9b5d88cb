"""What a bench run runs, and for how long: the groups (`python -m bench --only GROUP`), in the
order they run, and the Plan (`--quick` shortens every scenario)."""

from __future__ import annotations

from dataclasses import dataclass, field

# In the order they run; each is a module of bench/groups/ (bench/run.py dispatches to it).
GROUPS = ("command", "force", "baselines", "observers", "estop", "decision", "closed_loop",
          "stereo", "franka",
          # After the rows it could disturb: 1,024 subscribers take a while to go.
          "observers_zenoh", "soak", "soak_overload", "network", "video")
# `make bench`; the soak and the network experiment (bench/network.py, and its video rows,
# bench/video.py) take minutes. soak_overload (bench/overload.py) runs by default: 45 s, 15 s
# with --quick.
DEFAULT_GROUPS = tuple(group for group in GROUPS if group not in ("soak", "network", "video"))
@dataclass(frozen=True)
class Plan:
    """How long each scenario runs; `quick` shortens all (`make bench QUICK=1`)."""

    quick: bool
    command_rates: tuple[int, ...] = (50, 500, 1000)
    force_rates: tuple[tuple[int, int], ...] = ((1000, 1), (120, 8))  # (name, decimation)
    observer_counts: tuple[int, ...] = (0, 1, 4, 16, 32)
    observer_decimation: int = 10
    zenoh_observer_counts: tuple[int, ...] = (1, 32, 256, 1024)  # observers_zenoh (issue #33)
    load_concurrency: int = 200
    stereo_sources: tuple[str, ...] = ("pattern", "sim")
    stereo_modes: tuple[str, ...] = ("single", "double")
    stereo_source_fps: float = 30.0
    only: tuple[str, ...] = field(default_factory=tuple)
    profile: bool = False  # py-spy the DecisionServer and ProxyRobot at 1 kHz (bench/profile.py)
    soak_minutes: float | None = None  # the soak's length; None: 10 minutes, 1 when quick
    video_s: float | None = None  # each video probe's length; None: video.PROBE_S (quick: less)
    video_long_s: float | None = None  # the video group's long run; None: video.LONG_S
    video_source: str | None = None  # the video group's camera source; None: video.SOURCE
    # The video group's picture per eye, (width, height); None: video.WIDTH_PX x HEIGHT_PX.
    video_size: tuple[int, int] | None = None
    # The sim camera's --sim-render-scale in the video group: auto, or a fixed scale ("1": the
    # full picture, whatever it costs); None: auto.
    video_render_scale: str | None = None

    @property
    def command_s(self) -> float:
        return 2.0 if self.quick else 8.0

    @property
    def force_s(self) -> float:
        return 2.5 if self.quick else 10.0

    @property
    def overhead_pairs(self) -> int:
        """The interleaved (recording off, on) pairs of an `_mcap` row (issue #17)."""
        return 4 if self.quick else 6  # even: as many pairs on first as off first

    @property
    def p99_pairs(self) -> int:
        """The interleaved pairs of a row judged on its p99 ratio (`_tls`, `_episode`) and of
        `teleop_1000_aa`, the noise they are judged in: one pair's p99 ratio at 1 kHz moves
        by more than their bounds by itself on this machine, and so does a median of four."""
        return 8 if self.quick else 12

    # Each leg of those pairs after the twin's own run (the first off leg, as long as the
    # twin): the quick run's length, enough for a steady p50 and CPU per command.
    overhead_teleop_leg_s: float = 2.0
    overhead_force_leg_s: float = 2.5

    @property
    def observers_s(self) -> float:
        return 2.0 if self.quick else 8.0

    @property
    def estop_trials(self) -> int:
        return 12 if self.quick else 50

    @property
    def closed_loop_trials(self) -> int:
        return 8 if self.quick else 30

    @property
    def stereo_pairs(self) -> int:
        return 20 if self.quick else 120

    @property
    def soak_s(self) -> float:
        if self.soak_minutes is not None:
            return 60.0 * self.soak_minutes
        return 60.0 if self.quick else 600.0

    @property
    def overload_s(self) -> float:
        """soak_overload's measured stream (bench/overload.py)."""
        return 15.0 if self.quick else 45.0

    @property
    def soak_sample_s(self) -> float:
        """How often the soak reads every station process's RSS."""
        return 2.0 if self.soak_s <= 120.0 else 5.0

    def wants(self, group: str) -> bool:
        """Whether `group` runs: the ones asked for with --only, else every default group
        (the soak and the network experiment run only when asked for: they take minutes).
        The video rows (bench/video.py) are part of the network group, and a group alone."""
        if not self.only:
            return group in DEFAULT_GROUPS
        return group in self.only or (group == "video" and "network" in self.only)

    @property
    def tls(self) -> bool:
        """Whether a group with a TLS variant runs (then the TLS station is started)."""
        return self.wants("command") or self.wants("decision")
