"""Episodes into a LeRobotDataset, format v3.0, as lerobot 0.4-0.6 reads it.

The layout (one file of each kind per export: an append adds the next file-NNN of each kind;
lerobot reads any number, in name order):

    meta/info.json                      fps, features, counts, path templates
    meta/tasks.parquet                  the task strings (pandas index "task") and task_index
    meta/episodes/chunk-000/file-000.parquet   a row per episode: where its rows and frames are,
                                        its task, length and stats
    meta/stats.json                     min, max, mean, std, count, q01..q99 per feature
    meta/telerobot_sources.json         the episode file each episode came from, by its
                                        SHA-256 (lerobot does not read it): an append skips
                                        a file the dataset already holds
    data/chunk-000/file-000.parquet     a row per frame
    videos/observation.images.<eye>/chunk-000/file-000.mp4   every episode's frames, back to back

Frames are on a grid at the dataset's fps, from the episode's first moment with both a state
and a picture to its last. On frame k at time t_k (the station's clock):
- observation.state: the joint angles and the tool pose interpolated at t_k, and the newest
  wrench sample at t_k: all as the arm was when the picture was taken;
- observation.images.left / right: the newest stereo frame *captured* at or before t_k (capture
  time, not arrival);
- action: the end-effector increment the station applied from t_k to t_k+1, summed (rotations
  composed), in the base frame: dx, dy, dz (m), then the rotation vector (rad). The first
  frame's also carries what the arm had still to make at t_0 of the increments applied before
  it (from its position then to their target), so that a replay of the actions from the first
  state leads where the station's commands led.
Each video is H.264 (libx264, yuv420p, no B-frames, constant frame rate), frame i at pts i/fps,
which is how lerobot finds a frame (from_timestamp + timestamp, within 1e-4 s).
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import math
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

import av
import numpy as np
import pandas as pd
import pinocchio as pin
import pyarrow as pa
import pyarrow.parquet as pq

from clients.teleop.episode_file import Episode
from wire.checks import gram_schmidt
from wire.video import H264Decoder, VideoDecodeError

CODEBASE_VERSION = "v3.0"
CHUNK_FILE = "chunk-{chunk_index:03d}/file-{file_index:03d}"
DATA_PATH = "data/" + CHUNK_FILE + ".parquet"
VIDEO_PATH = "videos/{video_key}/" + CHUNK_FILE + ".mp4"
EPISODES_PATH = "meta/episodes/" + CHUNK_FILE + ".parquet"
SOURCES_PATH = "meta/telerobot_sources.json"
EYES = ("left", "right")
IMAGE_KEY = "observation.images.{eye}"
QUANTILES = (0.01, 0.10, 0.50, 0.90, 0.99)
GOP = 10  # a key frame every 10 frames: random access for training at a modest size cost
IMAGE_STATS_FRAMES = 100  # frames per episode an image's stats are estimated from
ACTION_NAMES = ("delta_x_m", "delta_y_m", "delta_z_m", "delta_rx_rad", "delta_ry_rad",
                "delta_rz_rad")
WRENCH_NAMES = ("force_x_n", "force_y_n", "force_z_n", "torque_x_nm", "torque_y_nm",
                "torque_z_nm")
TOOL_NAMES = ("tool_x_m", "tool_y_m", "tool_z_m", "tool_qw", "tool_qx", "tool_qy", "tool_qz")


@dataclass
class EpisodeFrames:
    """One episode on the dataset's grid."""

    episode: Episode
    times_ns: np.ndarray  # (n,)
    state: np.ndarray  # (n, D) float32
    action: np.ndarray  # (n, 6) float32
    video_index: np.ndarray | None  # (n,) which recorded frame each grid frame shows


def state_names(joints: int) -> list[str]:
    return [f"joint_{i + 1}_rad" for i in range(joints)] + list(TOOL_NAMES) + list(WRENCH_NAMES)


def on_grid(episode: Episode, fps: int) -> EpisodeFrames:
    """The episode resampled at `fps` (see the module docstring). ValueError when it is too
    short for one frame."""
    start, end = episode.state_ns[0], episode.state_ns[-1]
    if episode.has_video:
        start, end = max(start, episode.video_ns[0]), min(end, episode.video_ns[-1])
    if end < start:
        raise ValueError(f"{episode.path}: its state and its video do not overlap in time")
    step_ns = 1e9 / fps
    count = int((end - start) // step_ns) + 1
    times = start + np.round(np.arange(count) * step_ns).astype(np.int64)
    state = np.hstack([_joints_at(episode, times), _tool_at(episode, times),
                       _wrench_at(episode, times)]).astype(np.float32)
    action = _actions(episode, times, int(round(step_ns))).astype(np.float32)
    video_index = None
    if episode.has_video:
        video_index = np.searchsorted(episode.video_ns, times, side="right") - 1
    return EpisodeFrames(episode, times, state, action, video_index)


def _joints_at(episode: Episode, times: np.ndarray) -> np.ndarray:
    return np.column_stack([np.interp(times, episode.state_ns, episode.joints_rad[:, j])
                            for j in range(episode.joints_rad.shape[1])])


def _tool_at(episode: Episode, times: np.ndarray) -> np.ndarray:
    """Position interpolated; orientation from the nearer sample, as a unit quaternion (w first,
    w >= 0)."""
    position = _position_at(episode, times)
    nearest = _nearest(episode.state_ns, times)
    quaternions = []
    for rotation in episode.tool_rotation[nearest]:
        q = pin.Quaternion(gram_schmidt(rotation))
        w, x, y, z = q.w, q.x, q.y, q.z
        quaternions.append([w, x, y, z] if w >= 0 else [-w, -x, -y, -z])
    return np.hstack([position, np.array(quaternions).reshape(-1, 4)])


def _position_at(episode: Episode, times: np.ndarray) -> np.ndarray:
    """The tool's position at `times`, interpolated, base frame: (n, 3)."""
    return np.column_stack([np.interp(times, episode.state_ns, episode.tool_position_m[:, a])
                            for a in range(3)])


def _wrench_at(episode: Episode, times: np.ndarray) -> np.ndarray:
    if not len(episode.wrench_ns):
        return np.zeros((len(times), 6))
    newest = np.clip(np.searchsorted(episode.wrench_ns, times, side="right") - 1, 0, None)
    return episode.wrench[newest]


def _actions(episode: Episode, times: np.ndarray, step_ns: int) -> np.ndarray:
    """Each grid frame's applied increments, summed in the base frame; the first frame's also
    carries the motion still to come at its time from the commands before it."""
    actions = np.zeros((len(times), 6))
    if not len(episode.increment_ns):
        return actions
    frame_of = np.searchsorted(times, episode.increment_ns, side="right") - 1
    inside = (frame_of >= 0) & (episode.increment_ns < times[-1] + step_ns)
    tool = _nearest(episode.state_ns, episode.increment_ns)
    rotations = [np.eye(3) for _ in times]
    for k in np.flatnonzero(inside):
        delta_p, delta_r = _in_base_frame(episode, k, tool[k])
        frame = frame_of[k]
        actions[frame, :3] += delta_p
        rotations[frame] = delta_r @ rotations[frame]
    before = np.flatnonzero(episode.increment_ns < times[0])
    if len(before):
        # Commands before the first frame (which waits for the first picture) that the arm
        # had not all made by then: the first action takes on the rest, the way from where
        # the arm was at t_0 to the target they had led it to.
        actions[0, :3] += (episode.increment_target_m[before[-1]]
                           - _position_at(episode, times[:1])[0])
    actions[:, 3:] = [pin.log3(rotation) for rotation in rotations]
    return actions


def _in_base_frame(episode: Episode, k: int, tool: int) -> tuple[np.ndarray, np.ndarray]:
    """Increment k (position, rotation) in the base frame; `tool`: the state sample nearest
    to it, whose axes a TOOL or WRIST increment is in."""
    delta_p, delta_r = episode.increment_position_m[k], gram_schmidt(
        episode.increment_rotation[k])
    if episode.increment_frame[k] != "BASE":
        axes = gram_schmidt(episode.tool_rotation[tool])
        delta_p, delta_r = axes @ delta_p, axes @ delta_r @ axes.T
    return delta_p, delta_r


def _nearest(sample_ns: np.ndarray, times: np.ndarray) -> np.ndarray:
    after = np.clip(np.searchsorted(sample_ns, times), 0, len(sample_ns) - 1)
    before = np.clip(after - 1, 0, len(sample_ns) - 1)
    closer_before = np.abs(times - sample_ns[before]) <= np.abs(sample_ns[after] - times)
    return np.where(closer_before, before, after)


# -- the stats ----------------------------------------------------------------------------------

def vector_stats(values: np.ndarray) -> dict[str, np.ndarray]:
    """min, max, mean, std, count and the quantiles of each column of (n, D) values."""
    values = np.asarray(values, dtype=np.float64).reshape(len(values), -1)
    stats = {"min": values.min(0), "max": values.max(0), "mean": values.mean(0),
             "std": values.std(0), "count": np.array([len(values)])}
    for q in QUANTILES:
        stats[f"q{round(q * 100):02d}"] = np.quantile(values, q, axis=0)
    return stats


def image_stats(images: list[np.ndarray]) -> dict[str, np.ndarray]:
    """Per channel over `images` (RGB8), as fractions of 255, shaped (3, 1, 1)."""
    pixels = np.concatenate([image.reshape(-1, 3) for image in images]).astype(np.float64) / 255
    stats = vector_stats(pixels)
    return {key: value if key == "count" else value.reshape(3, 1, 1)
            for key, value in {**stats, "count": np.array([len(images)])}.items()}


def merge_stats(parts: list[dict[str, np.ndarray]]) -> dict[str, np.ndarray]:
    """Episodes' stats into the dataset's: mean count-weighted, std by parallel variance,
    min and max global, quantiles count-weighted (as lerobot 0.4-0.6 aggregates)."""
    counts = np.array([part["count"][0] for part in parts], dtype=np.float64)
    weights = counts / counts.sum()
    mean = sum(w * part["mean"] for w, part in zip(weights, parts, strict=True))
    variance = sum(w * (part["std"] ** 2 + (part["mean"] - mean) ** 2)
                   for w, part in zip(weights, parts, strict=True))
    merged = {"min": np.min([p["min"] for p in parts], axis=0),
              "max": np.max([p["max"] for p in parts], axis=0),
              "mean": mean, "std": np.sqrt(variance), "count": np.array([int(counts.sum())])}
    for key in parts[0]:
        if key.startswith("q"):
            merged[key] = sum(w * part[key] for w, part in zip(weights, parts, strict=True))
    return merged


# -- the writer ----------------------------------------------------------------------------------

class VideoWriter:
    """One eye's mp4: every episode's frames back to back, frame i at pts i/fps."""

    def __init__(self, path: Path, width: int, height: int, fps: int):
        path.parent.mkdir(parents=True, exist_ok=True)
        self._container = av.open(str(path), "w")
        self._stream = self._container.add_stream(
            "libx264", rate=fps, options={"bf": "0", "g": str(GOP), "preset": "veryfast",
                                          "crf": "23"})
        self._stream.width, self._stream.height = width, height
        self._stream.pix_fmt = "yuv420p"
        self._stream.codec_context.time_base = Fraction(1, fps)
        self.frames = 0

    def add(self, image: np.ndarray) -> None:
        frame = av.VideoFrame.from_ndarray(np.ascontiguousarray(image), format="rgb24")
        frame.pts = self.frames
        self._container.mux(self._stream.encode(frame))
        self.frames += 1

    def close(self) -> None:
        self._container.mux(self._stream.encode(None))
        self._container.close()


def decoded_eyes(episode: Episode):
    """Each recorded stereo frame decoded, as (left, right) RGB8 arrays, in order; a frame that
    does not decode repeats the last one (the recording starts at a key frame)."""
    decoder = H264Decoder()
    last = None
    for data in episode.video_frames:
        with contextlib.suppress(VideoDecodeError):
            last = decoder.decode(data) or last
        if last is None:
            raise ValueError(f"{episode.path}: its video does not start at a decodable frame")
        yield last


@dataclass
class Appended:
    """The dataset new episodes are appended to: where they continue from."""

    info: dict
    tasks: list[str]  # in task_index order
    stats: dict[str, dict[str, np.ndarray]]
    file_number: int  # the next file of each kind, counted across chunks
    sources: list[dict]  # SOURCES_PATH's entries: episode_index, file, sha256


def file_digest(path: Path) -> str:
    """The SHA-256 of a file's bytes: a finished episode file's identity."""
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def read_appended(root: Path) -> Appended:
    """The dataset at `root`, to append to; ValueError naming what makes it unfit."""
    info_path = root / "meta" / "info.json"
    if not info_path.exists():
        raise ValueError(f"{root}: no meta/info.json: not a LeRobot dataset to append to")
    info = json.loads(info_path.read_text())
    if info.get("codebase_version") != CODEBASE_VERSION:
        raise ValueError(f"{root} is a LeRobot dataset {info.get('codebase_version')}, not "
                         f"{CODEBASE_VERSION}: it cannot be appended to")
    tasks = pd.read_parquet(root / "meta" / "tasks.parquet").sort_values("task_index")
    stats = {feature: {stat: np.array(value) for stat, value in values.items()}
             for feature, values in json.loads((root / "meta" / "stats.json").read_text()
                                               ).items()}
    files = list((root / "meta" / "episodes").glob("chunk-*/file-*.parquet"))
    sources_path = root / SOURCES_PATH  # (none in a dataset another tool made)
    sources = json.loads(sources_path.read_text())["episodes"] if sources_path.exists() else []
    return Appended(info, list(tasks.index), stats, len(files), sources)


def write_dataset(out: Path, episodes: list[EpisodeFrames], digests: list[str], fps: int,
                  robot_type: str, appended: Appended | None = None) -> dict:
    """The whole dataset into `out` (which must not exist yet), or, with `appended`, the
    episodes after those of the dataset already in `out`, in files of their own (the
    dataset's meta files are written anew; nothing else is opened for writing). `digests`:
    each episode file's file_digest, in order, for SOURCES_PATH. Its info.json as a dict;
    ValueError when the episodes do not fit the appended dataset."""
    tasks = list(dict.fromkeys([*(appended.tasks if appended else []),
                                *(frames.episode.task for frames in episodes)]))
    with_video = all(frames.video_index is not None for frames in episodes)
    joints = episodes[0].state.shape[1] - len(TOOL_NAMES) - len(WRENCH_NAMES)
    first_episode = appended.info["total_episodes"] if appended else 0
    index = appended.info["total_frames"] if appended else 0
    info = _info(episodes, tasks, fps, robot_type, joints, with_video, first_episode, index)
    if appended:
        _check_fits(appended.info, info)
    out.mkdir(parents=True, exist_ok=appended is not None)
    chunk, file = divmod(appended.file_number if appended else 0, info["chunks_size"])
    where = {"chunk_index": chunk, "file_index": file}
    writers: dict[str, VideoWriter] = {}
    rows: list[dict] = []
    episode_rows: list[dict] = []
    per_episode_stats: list[dict[str, dict]] = []
    try:
        for number, frames in enumerate(episodes, start=first_episode):
            length = len(frames.times_ns)
            task_index = tasks.index(frames.episode.task)
            timestamps = (np.arange(length) / fps).astype(np.float32)
            columns = {"observation.state": frames.state, "action": frames.action,
                       "timestamp": timestamps, "frame_index": np.arange(length),
                       "episode_index": np.full(length, number),
                       "index": np.arange(index, index + length),
                       "task_index": np.full(length, task_index)}
            rows.append(columns)
            stats = {key: vector_stats(value) for key, value in columns.items()}
            row = {"episode_index": number, "tasks": [frames.episode.task], "length": length,
                   "data/chunk_index": chunk, "data/file_index": file,
                   "dataset_from_index": index, "dataset_to_index": index + length}
            if with_video:
                samples = _write_eyes(out, frames, fps, writers, row, where)
                for eye in EYES:
                    stats[IMAGE_KEY.format(eye=eye)] = image_stats(samples[eye])
            row.update({"meta/episodes/chunk_index": chunk, "meta/episodes/file_index": file})
            for feature, values in stats.items():
                for stat, value in values.items():
                    row[f"stats/{feature}/{stat}"] = value.tolist()
            episode_rows.append(row)
            per_episode_stats.append(stats)
            index += length
    finally:
        for writer in writers.values():
            writer.close()
    _write_data(out / DATA_PATH.format(**where), rows, episodes[0].state.shape[1])
    _write_parquet(out / EPISODES_PATH.format(**where), pa.Table.from_pylist(episode_rows))
    # The meta files last, each anew (unlinked first: an append's are links to the original's).
    _write_tasks(out, tasks)
    earlier = [appended.stats] if appended else []
    dataset_stats = {feature: merge_stats([s[feature] for s in earlier + per_episode_stats])
                     for feature in per_episode_stats[0]}
    _write_anew(out / "meta" / "stats.json", json.dumps(
        {feature: {stat: value.tolist() for stat, value in stats.items()}
         for feature, stats in dataset_stats.items()}, indent=2))
    sources = [*(appended.sources if appended else []),
               *({"episode_index": number, "file": frames.episode.path.name, "sha256": digest}
                 for number, (frames, digest) in enumerate(
                     zip(episodes, digests, strict=True),
                     start=first_episode))]
    _write_anew(out / SOURCES_PATH, json.dumps({"episodes": sources}, indent=2))
    _write_anew(out / "meta" / "info.json", json.dumps(info, indent=2))
    return info


def _check_fits(existing: dict, new: dict) -> None:
    """ValueError naming each way the new episodes differ from the dataset's."""
    differences = [f"{key} {new[key]!r} (the dataset's: {existing.get(key)!r})"
                   for key in ("fps", "robot_type") if new[key] != existing.get(key)]
    features = existing.get("features", {})
    for name in sorted(set(new["features"]) | set(features)):
        if new["features"].get(name) != features.get(name):
            differences.append(f"feature {name}")
    if differences:
        raise ValueError("the episodes do not fit the dataset they would be appended to: "
                         + "; ".join(differences))


def _write_eyes(out: Path, frames: EpisodeFrames, fps: int, writers: dict,
                row: dict, where: dict) -> dict[str, list[np.ndarray]]:
    """The episode's grid frames into each eye's mp4; the episode row's video columns; a
    sample of the frames for the stats."""
    width, height = frames.episode.eye_size
    for eye in EYES:
        key = IMAGE_KEY.format(eye=eye)
        if key not in writers:
            writers[key] = VideoWriter(out / VIDEO_PATH.format(video_key=key, **where),
                                       width, height, fps)
        row.update({f"videos/{key}/chunk_index": where["chunk_index"],
                    f"videos/{key}/file_index": where["file_index"],
                    f"videos/{key}/from_timestamp": writers[key].frames / fps})
    wanted = frames.video_index
    every = max(1, math.ceil(len(wanted) / IMAGE_STATS_FRAMES))
    samples: dict[str, list[np.ndarray]] = {eye: [] for eye in EYES}
    position = 0
    for recorded, eyes in enumerate(decoded_eyes(frames.episode)):
        while position < len(wanted) and wanted[position] <= recorded:
            for eye, image in zip(EYES, eyes, strict=True):
                writers[IMAGE_KEY.format(eye=eye)].add(image)
                if position % every == 0:
                    samples[eye].append(image[::2, ::2])
            position += 1
    for eye in EYES:
        key = IMAGE_KEY.format(eye=eye)
        row[f"videos/{key}/to_timestamp"] = writers[key].frames / fps
    if position != len(wanted):
        raise ValueError(f"{frames.episode.path}: {len(wanted) - position} of its frames "
                         "have no decoded picture")
    return samples


def _write_data(path: Path, rows: list[dict], state_size: int) -> None:
    def vectors(key: str, size: int) -> pa.Array:
        values = np.concatenate([r[key] for r in rows]).astype(np.float32).reshape(-1)
        return pa.FixedSizeListArray.from_arrays(pa.array(values, pa.float32()), size)

    def column(key: str, dtype) -> pa.Array:
        return pa.array(np.concatenate([r[key] for r in rows]), dtype)

    table = pa.table({
        "observation.state": vectors("observation.state", state_size),
        "action": vectors("action", len(ACTION_NAMES)),
        "timestamp": column("timestamp", pa.float32()),
        "frame_index": column("frame_index", pa.int64()),
        "episode_index": column("episode_index", pa.int64()),
        "index": column("index", pa.int64()),
        "task_index": column("task_index", pa.int64())})
    _write_parquet(path, table)


def _write_tasks(out: Path, tasks: list[str]) -> None:
    """Indexed by the task string: lerobot reads a sample's task as its row's index."""
    table = pd.DataFrame({"task_index": range(len(tasks))}, index=pd.Index(tasks, name="task"))
    path = out / "meta" / "tasks.parquet"
    path.unlink(missing_ok=True)
    _write_parquet(path, pa.Table.from_pandas(table, preserve_index=True))


def _write_parquet(path: Path, table: pa.Table) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    pq.write_table(table, path, compression="snappy")


def _write_anew(path: Path, text: str) -> None:
    path.unlink(missing_ok=True)
    path.write_text(text)


def _info(episodes: list[EpisodeFrames], tasks: list[str], fps: int, robot_type: str,
          joints: int, with_video: bool, earlier_episodes: int, earlier_frames: int) -> dict:
    total = earlier_frames + sum(len(frames.times_ns) for frames in episodes)
    total_episodes = earlier_episodes + len(episodes)
    features = {
        "observation.state": {"dtype": "float32", "shape": [episodes[0].state.shape[1]],
                              "names": state_names(joints)},
        "action": {"dtype": "float32", "shape": [len(ACTION_NAMES)],
                   "names": list(ACTION_NAMES)},
    }
    if with_video:
        width, height = episodes[0].episode.eye_size
        for eye in EYES:
            features[IMAGE_KEY.format(eye=eye)] = {
                "dtype": "video", "shape": [height, width, 3],
                "names": ["height", "width", "channels"],
                "info": {"video.height": height, "video.width": width, "video.codec": "h264",
                         "video.pix_fmt": "yuv420p", "video.is_depth_map": False,
                         "video.fps": fps, "video.channels": 3, "has_audio": False,
                         "is_depth_map": False}}
    for name in ("timestamp", "frame_index", "episode_index", "index", "task_index"):
        features[name] = {"dtype": "float32" if name == "timestamp" else "int64",
                          "shape": [1], "names": None}
    return {"codebase_version": CODEBASE_VERSION, "robot_type": robot_type,
            "total_episodes": total_episodes, "total_frames": total, "total_tasks": len(tasks),
            "chunks_size": 1000, "data_files_size_in_mb": 100, "video_files_size_in_mb": 200,
            "fps": fps, "splits": {"train": f"0:{total_episodes}"}, "data_path": DATA_PATH,
            "video_path": VIDEO_PATH if with_video else None, "features": features}
