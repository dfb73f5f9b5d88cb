"""An episode as the DecisionServer recorded it: one MCAP file (RecordingFormat MCAP with a task,
decision_server.proto), read into arrays for a dataset export.

What an episode holds, each on the station's clock (ns):
- the arm's state samples (/robot/state: joint angles and the tool pose, 100 Hz);
- the wrench at the tool (/robot/wrench, tool axes);
- every applied increment (/recording/increment: frame, ΔX, ΔR, the tool target it led to);
- the stereo video (/camera/stereo/video: H.264, both eyes side by side, at capture time) and
  its header (/camera/stereo_header: the per-eye size and calibration);
- the "recording" metadata: name, task, outcome and the arm's name ("robot").

A file the server did not finish (it was killed mid-episode: the file still ends in
.mcap.partial, or has no footer) is `IncompleteEpisode`, naming the file and what is missing.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from mcap.exceptions import McapError
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory

from wire.convert import rotation_value, vector3_value

METADATA = "recording"
STATE, WRENCH, INCREMENT = "/robot/state", "/robot/wrench", "/recording/increment"
STEREO_HEADER, STEREO_VIDEO = "/camera/stereo_header", "/camera/stereo/video"
PARTIAL = ".partial"
FRAMES = {1: "BASE", 2: "WRIST", 3: "TOOL"}  # ReferenceFrame values of a Cartesian increment


class IncompleteEpisode(Exception):
    """An episode file that cannot be exported whole; the message says which and why."""


class NotAnEpisode(Exception):
    """A file that is not an episode (no task, not a DecisionServer recording)."""


@dataclass
class Episode:
    path: Path
    name: str
    task: str
    outcome: str  # SUCCEEDED, FAILED, DISCARDED or UNSPECIFIED
    state_ns: np.ndarray  # (n,) sample times
    joints_rad: np.ndarray  # (n, joints)
    tool_position_m: np.ndarray  # (n, 3), base frame
    tool_rotation: np.ndarray  # (n, 3, 3), base frame
    wrench_ns: np.ndarray  # (m,)
    wrench: np.ndarray  # (m, 6): force (N), torque (N m), tool axes
    increment_ns: np.ndarray  # (k,) when applied (the recording's start + offset)
    increment_frame: list[str]  # BASE, WRIST or TOOL
    increment_position_m: np.ndarray  # (k, 3) in its frame
    increment_rotation: np.ndarray  # (k, 3, 3) in its frame
    increment_target_m: np.ndarray  # (k, 3) the tool position it led to (the arm's target)
    video_ns: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))  # capture
    video_frames: list[bytes] = field(default_factory=list)  # H.264 access units (Annex B)
    eye_size: tuple[int, int] | None = None  # (width, height) per eye
    robot: str = ""  # the arm's name, as the station recorded it (empty if it could not say)

    @property
    def has_video(self) -> bool:
        return bool(self.video_frames)


def read_episode(path: Path) -> Episode:
    """The episode in `path`; IncompleteEpisode when it is not a finished episode file."""
    path = Path(path)
    if path.name.endswith(PARTIAL):
        raise IncompleteEpisode(
            f"{path}: the recording was never finished (the DecisionServer stopped, or was "
            "killed, before StopRecording): the episode is incomplete and is not exported")
    try:
        with open(path, "rb") as stream:
            reader = make_reader(stream, decoder_factories=[DecoderFactory()])
            summary = reader.get_summary()
            if summary is None:
                raise IncompleteEpisode(f"{path}: no summary: the file was cut short")
            metadata = next((dict(m.metadata) for m in reader.iter_metadata()
                             if m.name == METADATA), None)
            if metadata is None:
                raise NotAnEpisode(f"{path}: no '{METADATA}' metadata: not a DecisionServer "
                                   "recording")
            if not metadata.get("task"):
                raise NotAnEpisode(f"{path}: a recording without a task, not an episode "
                                   "(StartRecording with a task makes one)")
            return _contents(path, metadata, reader)
    except (IncompleteEpisode, NotAnEpisode):
        raise
    except (McapError, OSError, ValueError, EOFError) as error:
        raise IncompleteEpisode(f"{path}: cannot be read ({error or type(error).__name__}): "
                                "the file is truncated or not MCAP") from error


def _contents(path: Path, metadata: dict, reader) -> Episode:
    created = int(metadata.get("create_time_ns", "0"))
    state_ns, joints, positions, rotations = [], [], [], []
    wrench_ns, wrenches = [], []
    inc_ns, inc_frames, inc_positions, inc_rotations, inc_targets = [], [], [], [], []
    video_ns, video, header = [], [], None
    for _, channel, message, decoded in reader.iter_decoded_messages(log_time_order=True):
        topic = channel.topic
        if topic == STATE and decoded.joint_positions_rad:
            state_ns.append(message.publish_time)
            joints.append(list(decoded.joint_positions_rad))
            positions.append(vector3_value(decoded.tool_pose.position_m))
            rotations.append(rotation_value(decoded.tool_pose.rotation))
        elif topic == WRENCH:
            wrench_ns.append(message.publish_time)
            wrenches.append([*vector3_value(decoded.force_n), *vector3_value(decoded.torque_nm)])
        elif topic == INCREMENT:
            if decoded.frame not in FRAMES:
                raise NotAnEpisode(f"{path}: joint increments cannot be exported (the "
                                   "dataset's action is a Cartesian increment)")
            inc_ns.append(created + decoded.offset.ToNanoseconds())
            inc_frames.append(FRAMES[decoded.frame])
            inc_positions.append(vector3_value(decoded.delta_position_m))
            inc_rotations.append(rotation_value(decoded.delta_rotation))
            inc_targets.append(vector3_value(decoded.target_position_m))
        elif topic == STEREO_HEADER:
            header = decoded
        elif topic == STEREO_VIDEO:
            video_ns.append(decoded.timestamp.ToNanoseconds())
            video.append(bytes(decoded.data))
    if not state_ns:
        raise NotAnEpisode(f"{path}: no arm state with joint angles was recorded")
    return Episode(
        path, metadata.get("name", path.stem), metadata["task"],
        metadata.get("outcome", "UNSPECIFIED"),
        np.array(state_ns, np.int64), np.array(joints), np.array(positions),
        np.array(rotations), np.array(wrench_ns, np.int64),
        np.array(wrenches).reshape(-1, 6), np.array(inc_ns, np.int64), inc_frames,
        np.array(inc_positions).reshape(-1, 3), np.array(inc_rotations).reshape(-1, 3, 3),
        np.array(inc_targets).reshape(-1, 3),
        np.array(video_ns, np.int64), video,
        (header.width_px, header.height_px) if header is not None and video else None,
        metadata.get("robot", ""))
