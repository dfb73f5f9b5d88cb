"""What a session leaves behind for a person: the stereo video with the overlay (MP4), plots of
force, tool path and latency (PNG), and a JSON summary."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import cv2
import numpy as np

VIDEO_FPS = 10.0  # what the simulated cameras deliver here; playback runs at capture rate


@dataclass
class Trace:
    """One run's measurements, in time order (seconds since the run started)."""

    mode: str
    command_time_s: list[float] = field(default_factory=list)
    round_trip_ms: list[float] = field(default_factory=list)
    force_time_s: list[float] = field(default_factory=list)
    force_n: list[np.ndarray] = field(default_factory=list)
    tool_time_s: list[float] = field(default_factory=list)
    tool_position_m: list[np.ndarray] = field(default_factory=list)


class VideoRecorder:
    """Side-by-side stereo frames (RGB) into an MP4 file."""

    def __init__(self, path: Path, width: int, height: int):
        self.path = path
        self._writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*"mp4v"), VIDEO_FPS,
                                       (width, height))
        if not self._writer.isOpened():
            raise RuntimeError(f"cannot write a video to {path}")
        self.frames = 0

    def add(self, rgb: np.ndarray) -> None:
        self._writer.write(cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR))
        self.frames += 1

    def close(self) -> None:
        self._writer.release()


def plot(traces: list[Trace], out: Path) -> list[Path]:
    """force.png, tool_path.png and latency.png comparing the runs."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    paths = []
    figure, axis = plt.subplots(figsize=(8, 4))
    for trace in traces:
        if trace.force_n:
            axis.plot(trace.force_time_s, [-f[2] for f in trace.force_n], label=trace.mode)
    axis.set(xlabel="time (s)", ylabel="contact force along the peg, −F_z (N)",
             title="Force at the tool during the peg-in-hole task")
    axis.legend()
    axis.grid(alpha=0.3)
    paths.append(_save(figure, out / "force.png"))

    figure, axes = plt.subplots(1, 2, figsize=(10, 4))
    for trace in traces:
        if trace.tool_position_m:
            path = np.array(trace.tool_position_m)
            axes[0].plot(path[:, 0] * 1e3, path[:, 2] * 1e3, label=trace.mode)
            axes[1].plot(trace.tool_time_s, path[:, 2] * 1e3, label=trace.mode)
    axes[0].set(xlabel="x (mm)", ylabel="z (mm)", title="Tool path (side view)")
    axes[1].set(xlabel="time (s)", ylabel="z (mm)", title="Tool height")
    for axis in axes:
        axis.legend()
        axis.grid(alpha=0.3)
    paths.append(_save(figure, out / "tool_path.png"))

    figure, axis = plt.subplots(figsize=(8, 4))
    for trace in traces:
        if trace.round_trip_ms:
            values = np.sort(trace.round_trip_ms)
            axis.plot(values, np.linspace(0, 1, len(values)), label=trace.mode)
    axis.set(xlabel="command round trip (ms)", ylabel="fraction of commands",
             title="Command → ack round trip (CDF)")
    axis.legend()
    axis.grid(alpha=0.3)
    paths.append(_save(figure, out / "latency.png"))
    return paths


def _save(figure, path: Path) -> Path:
    figure.tight_layout()
    figure.savefig(path, dpi=100)
    import matplotlib.pyplot as plt

    plt.close(figure)
    return path


def write_summary(summary: dict, out: Path) -> Path:
    path = out / "summary.json"
    path.write_text(json.dumps(summary, indent=2))
    return path
