"""python -m clients.teleop.mcap_inspect FILE: what an MCAP recording holds.

For each channel: its topic, schema (a protobuf message name), message count and first/last
log time; then the file's time range, which of Foxglove's channels it has (and the frame tree
its first /tf message gives), its video if it has one (/camera/stereo/video: frames, key frames,
bytes, and whether it starts at a key frame, as a player needs) and its metadata (make teleop's
counts and runs). It scans every message, so the times are exact. Exits 2 when the file cannot
be read.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path

from foxglove_schemas_protobuf.CompressedVideo_pb2 import CompressedVideo
from foxglove_schemas_protobuf.FrameTransforms_pb2 import FrameTransforms
from google.protobuf.message import DecodeError
from mcap.exceptions import McapError
from mcap.reader import make_reader

from wire.foxglove import FOXGLOVE_TOPICS, STEREO_VIDEO, TF, h264_is_keyframe


@dataclass
class ChannelSummary:
    topic: str
    schema: str
    encoding: str
    count: int = 0
    first_ns: int | None = None
    last_ns: int | None = None


@dataclass
class VideoSummary:
    """The video channel's frames (CompressedVideo): how many, how many key frames (IDR), their
    bytes, their formats, and whether the first (by log time) is a key frame."""

    frames: int = 0
    keyframes: int = 0
    bytes: int = 0
    formats: set[str] = field(default_factory=set)
    starts_at_keyframe: bool = False
    unreadable: int = 0  # messages that did not parse as CompressedVideo
    first_ns: int | None = None

    def add(self, data: bytes, log_time_ns: int) -> None:
        try:
            video = CompressedVideo.FromString(data)
        except DecodeError:
            self.unreadable += 1
            return
        key = video.format == "h264" and h264_is_keyframe(video.data)
        self.frames += 1
        self.keyframes += key
        self.bytes += len(video.data)
        self.formats.add(video.format)
        if self.first_ns is None or log_time_ns < self.first_ns:
            self.first_ns, self.starts_at_keyframe = log_time_ns, key


@dataclass
class FileSummary:
    path: Path
    profile: str
    library: str
    channels: list[ChannelSummary]
    metadata: dict[str, dict[str, str]]
    tf_frames: list[tuple[str, str]] = field(default_factory=list)  # first /tf: (parent, child)
    video: VideoSummary | None = None  # /camera/stereo/video, if the file has it

    @property
    def foxglove_topics(self) -> list[str]:
        """Foxglove's channels (wire.foxglove) the file holds, in their order."""
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
        video: VideoSummary | None = None
        for schema, channel, message in reader.iter_messages(log_time_order=False):
            summary = channels.get(channel.id)
            if summary is None:
                summary = channels[channel.id] = ChannelSummary(
                    channel.topic, schema.name if schema else "", channel.message_encoding)
            summary.count += 1
            if channel.topic == TF and summary.count == 1:
                tf_frames = _frames(message.data)
            if channel.topic == STEREO_VIDEO:
                video = video or VideoSummary()
                video.add(message.data, message.log_time)
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
                       sorted(channels.values(), key=lambda c: c.topic), metadata, tf_frames,
                       video)


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
    video = summary.video
    if video is not None:
        video_channel = next(c for c in summary.channels if c.topic == STEREO_VIDEO)
        span = (video_channel.last_ns - video_channel.first_ns) / 1e9
        rate = f", {video.bytes * 8 / span / 1e3:.0f} kbit/s" if span > 0 else ""
        lines.append(
            f"video {STEREO_VIDEO}: {video.frames} frames ({', '.join(sorted(video.formats))}), "
            f"{video.keyframes} key frame{'' if video.keyframes == 1 else 's'}, "
            f"{video.bytes} bytes{rate}, "
            + ("starts at a key frame" if video.starts_at_keyframe
               else "does NOT start at a key frame (a player shows nothing until one)")
            + (f", {video.unreadable} unreadable" if video.unreadable else ""))
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
