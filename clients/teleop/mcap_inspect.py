"""python -m clients.teleop.mcap_inspect FILE: what an MCAP recording holds.

For each channel: its topic, schema (a protobuf message name), message count and first/last
log time; then the file's time range, which of Foxglove's channels it has (and the frame tree
its first /tf message gives) and its metadata (make teleop's counts and runs). It scans every
message, so the times are exact. Exits 2 when the file cannot be read.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path

from foxglove_schemas_protobuf.FrameTransforms_pb2 import FrameTransforms
from google.protobuf.message import DecodeError
from mcap.exceptions import McapError
from mcap.reader import make_reader

from services.foxglove.channels import FOXGLOVE_TOPICS, TF


@dataclass
class ChannelSummary:
    topic: str
    schema: str
    encoding: str
    count: int = 0
    first_ns: int | None = None
    last_ns: int | None = None


@dataclass
class FileSummary:
    path: Path
    profile: str
    library: str
    channels: list[ChannelSummary]
    metadata: dict[str, dict[str, str]]
    tf_frames: list[tuple[str, str]] = field(default_factory=list)  # first /tf: (parent, child)

    @property
    def foxglove_topics(self) -> list[str]:
        """Foxglove's channels (services.foxglove.channels) the file holds, in their order."""
        present = {c.topic for c in self.channels}
        return [topic for topic in FOXGLOVE_TOPICS if topic in present]

    @property
    def messages(self) -> int:
        return sum(channel.count for channel in self.channels)

    @property
    def start_ns(self) -> int | None:
        starts = [c.first_ns for c in self.channels if c.first_ns is not None]
        return min(starts) if starts else None

    @property
    def end_ns(self) -> int | None:
        ends = [c.last_ns for c in self.channels if c.last_ns is not None]
        return max(ends) if ends else None


def summarize(path: Path) -> FileSummary:
    """Channels, schemas, counts and time ranges of the MCAP file at `path` (by a full scan of
    its messages: exact first and last times per channel, and it works on a file cut short)."""
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        header = reader.get_header()
        channels: dict[int, ChannelSummary] = {}
        tf_frames: list[tuple[str, str]] = []
        for schema, channel, message in reader.iter_messages(log_time_order=False):
            summary = channels.get(channel.id)
            if summary is None:
                summary = channels[channel.id] = ChannelSummary(
                    channel.topic, schema.name if schema else "", channel.message_encoding)
            summary.count += 1
            if channel.topic == TF and summary.count == 1:
                tf_frames = _frames(message.data)
            t = message.log_time
            summary.first_ns = t if summary.first_ns is None else min(summary.first_ns, t)
            summary.last_ns = t if summary.last_ns is None else max(summary.last_ns, t)
        metadata = {}
        try:
            for record in reader.iter_metadata():
                metadata[record.name] = dict(record.metadata)
        except McapError:
            pass  # a file cut short has no metadata index
    return FileSummary(Path(path), header.profile, header.library,
                       sorted(channels.values(), key=lambda c: c.topic), metadata, tf_frames)


def _frames(data: bytes) -> list[tuple[str, str]]:
    try:
        transforms = FrameTransforms.FromString(data).transforms
    except DecodeError:
        return []
    return [(t.parent_frame_id, t.child_frame_id) for t in transforms]


def _time(ns: int | None) -> str:
    if ns is None:
        return "-"
    return datetime.fromtimestamp(ns / 1e9, UTC).strftime("%Y-%m-%d %H:%M:%S.%f")[:-3]


def report(summary: FileSummary) -> str:
    lines = [f"{summary.path}: profile {summary.profile or '-'}, written by {summary.library}"]
    rows = [("topic", "schema", "messages", "first (UTC)", "last (UTC)", "span s")]
    for c in summary.channels:
        span = (c.last_ns - c.first_ns) / 1e9 if c.first_ns is not None else 0.0
        rows.append((c.topic, c.schema, str(c.count), _time(c.first_ns), _time(c.last_ns),
                     f"{span:.3f}"))
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines += ["  ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True)).rstrip()
              for row in rows]
    start, end = summary.start_ns, summary.end_ns
    duration = (end - start) / 1e9 if start is not None else 0.0
    lines.append(f"{len(summary.channels)} channels, {summary.messages} messages, "
                 f"{_time(start)} to {_time(end)} ({duration:.3f} s)")
    foxglove = summary.foxglove_topics
    missing = [topic for topic in FOXGLOVE_TOPICS if topic not in foxglove]
    lines.append(f"Foxglove channels: {len(foxglove)} of {len(FOXGLOVE_TOPICS)}"
                 + (f" (none on {', '.join(missing)})" if missing else ""))
    if summary.tf_frames:
        lines.append("frames (first /tf): " + ", ".join(
            f"{parent}->{child}" for parent, child in summary.tf_frames))
    for name, values in summary.metadata.items():
        lines.append(f"metadata {name}:")
        lines += [f"  {key}: {value}" for key, value in values.items()]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m clients.teleop.mcap_inspect",
                                     description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file", type=Path)
    args = parser.parse_args(argv)
    try:
        print(report(summarize(args.file)))
    except (OSError, McapError) as error:
        print(f"mcap_inspect: cannot read {args.file}: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
