"""python -m clients.teleop.replay_dataset DIR --episode K [--address HOST:PORT]

Replays a LeRobot dataset episode (as clients.teleop.export_lerobot writes them) on the station,
to check a dataset on the arm: the arm goes to the episode's first joint angles in joint space,
then the DecisionServer replays the episode's actions (StartReplay with the increments in the
request: each frame's end-effector increment, in the base frame, at its frame's time). Prints
one JSON line: the frames replayed; how far the tool ended from where the recording had it
(`final_error_mm`); from where the episode's actions lead from its first pose
(`actions_error_mm`, the replay's own accuracy); and how far the recording's own motion was
from its actions' sum (`actions_gap_mm`, which no faithful replay of the actions closes).
Needs the control lock (it takes it) and a READY arm (it readies it).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np
import pinocchio as pin
import pyarrow.compute as pc
import pyarrow.parquet as pq

from clients.python.decision_server import DecisionClient
from clients.teleop.lerobot_dataset import ACTION_NAMES, TOOL_NAMES
from clients.teleop.task import move_to_joints, ready_the_arm
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import types_pb2
from wire import convert
from wire.addresses import address_for
from wire.errors import AbortedError, TelerobotError, UnavailableError

SETTLE_S = 1.0  # after the replay's last increment, for the arm to come to rest
REPLAY_SLACK_S = 60.0  # how much later than its length a replay may end
STILL_M_PER_S = 1e-4


def load_episode(root: Path, episode: int) -> tuple[int, np.ndarray, np.ndarray, list[str]]:
    """(fps, states, actions, state names) of `episode`; ValueError naming what is wrong."""
    info_path = root / "meta" / "info.json"
    if not info_path.exists():
        raise ValueError(f"{root}: no meta/info.json: not a LeRobot dataset")
    info = json.loads(info_path.read_text())
    features = info["features"]
    if features.get("action", {}).get("names") != list(ACTION_NAMES):
        raise ValueError(f"{root}: its action is not an end-effector increment "
                         f"({', '.join(ACTION_NAMES)}): not a dataset of this station's")
    if not 0 <= episode < info["total_episodes"]:
        raise ValueError(f"{root} has episodes 0..{info['total_episodes'] - 1}, not {episode}")
    tables = [pq.read_table(path, columns=["episode_index", "frame_index",
                                           "observation.state", "action"])
              for path in sorted((root / "data").glob("*/*.parquet"))]
    rows = [t.filter(pc.equal(t.column("episode_index"), episode)) for t in tables]
    states = np.concatenate([np.array(r.column("observation.state").to_pylist()) for r in rows])
    actions = np.concatenate([np.array(r.column("action").to_pylist()) for r in rows])
    return int(info["fps"]), states, actions, features["observation.state"]["names"]


def increments(actions: np.ndarray, fps: int) -> list[pb.RecordedIncrement]:
    """Each frame's action but the last (which leads past the episode's end) at k / fps."""
    return [pb.RecordedIncrement(
        offset=convert.duration(k / fps), frame=types_pb2.REFERENCE_FRAME_BASE,
        delta_position_m=convert.vector3_to_proto(action[:3]),
        delta_rotation=types_pb2.Matrix3(row_major=pin.exp3(action[3:]).ravel().tolist()))
        for k, action in enumerate(actions[:-1])]


def replay(client: DecisionClient, root: Path, episode: int, speed: float = 1.0) -> dict:
    fps, states, actions, names = load_episode(root, episode)
    joints = [i for i, name in enumerate(names) if name.startswith("joint_")]
    tool = [names.index(name) for name in TOOL_NAMES[:3]]
    client.acquire_control("replay_dataset", lease_duration_s=60.0)
    ready_the_arm(client)
    move_to_joints(client, states[0, joints], f"episode {episode}'s first pose")
    started = time.monotonic()
    name = f"dataset-episode-{episode}"
    length_s = (len(actions) - 1) / fps / speed
    # Followed from before it starts: its end is the DecisionServer's word, not a sleep of its
    # length (a loaded station replays late, and the arm may pause on the way).
    with client.stream_events(timeout=length_s + REPLAY_SLACK_S) as events:
        client.start_replay(name, speed, increments=increments(actions, fps))
        progress = next((e.replay_progress for e in events
                         if e.WhichOneof("event") == "replay_progress"
                         and e.replay_progress.name == name
                         and e.replay_progress.state != pb.REPLAY_STATE_RUNNING), None)
    if progress is None:
        raise UnavailableError("the DecisionServer's events ended before the replay did")
    if progress.state != pb.REPLAY_STATE_FINISHED:
        raise AbortedError(f"the replay of episode {episode} stopped at command "
                           f"{progress.commands_replayed} of {progress.command_count}: "
                           f"{progress.detail}", reason="REPLAY_INTERRUPTED")
    deadline = time.monotonic() + SETTLE_S * 10
    last = client.robot.get_state().tool_pose.translation
    while time.monotonic() < deadline:  # then at rest
        time.sleep(SETTLE_S / 10)
        now = client.robot.get_state().tool_pose.translation
        if np.linalg.norm(now - last) < STILL_M_PER_S * SETTLE_S / 10:
            break
        last = now
    # Where the actions lead from the episode's first pose: the replay's own accuracy is
    # against it, and the recording's motion that its actions do not account for is the
    # rest of the final error.
    led_to = states[0, tool] + actions[:-1, :3].sum(0)
    return {"episode": episode, "frames": len(actions), "fps": fps,
            "seconds": round(time.monotonic() - started, 2),
            "final_error_mm": _mm(last - states[-1, tool]),
            "actions_error_mm": _mm(last - led_to),
            "actions_gap_mm": _mm(states[-1, tool] - led_to)}


def _mm(offset: np.ndarray) -> float:
    return round(float(np.linalg.norm(offset)) * 1e3, 2)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m clients.teleop.replay_dataset",
                                     description=__doc__.split("\n\n")[1])
    parser.add_argument("dataset", type=Path, metavar="DIR")
    parser.add_argument("--episode", type=int, required=True, metavar="K")
    parser.add_argument("--address", default=address_for("decision_server"))
    parser.add_argument("--speed", type=float, default=1.0,
                        help="time scale (0.1..10, as StartReplay's)")
    args = parser.parse_args(argv)
    try:
        with DecisionClient(args.address, default_timeout=10.0) as client:
            print(json.dumps(replay(client, args.dataset, args.episode, args.speed)))
    except (ValueError, TelerobotError) as error:
        print(f"replay_dataset: {getattr(error, 'message', error)}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
