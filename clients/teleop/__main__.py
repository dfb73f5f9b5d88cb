"""python -m clients.teleop (`make teleop`): a whole operator session on the slave station.

It connects to the DecisionServer at TELEROBOT_DECISION_SERVER_ADDRESS (default
127.0.0.1:50051, or found with --discover), starting a local station first if nothing answers
there on loopback; takes control;
runs the scripted peg-in-hole task with force feedback to the operator, then with active
compliance on the server; shows a live status line, and a line of its own whenever one of the
station's services (ProxyRobot, ForceSensor, StereoCamera, the band) changes state; and leaves
in runs/teleop-<time>/ the stereo video with the AR overlay (stereo.mp4), plots (force.png,
tool_path.png, latency.png) and summary.json (with the dependencies' final states), then
prints a summary table.

Across a broken link the session resumes by itself (clients.python.teleoperate): the station
says "link lost", holds still while the arm holds, and goes on once the session is back. When
it cannot go on, it says why and exits 3 (see `main`).
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import os
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from clients.ar import RobotModel
from clients.python.decision_server import DecisionClient
from clients.teleop.artifacts import plot, write_summary
from clients.teleop.dependencies import DependencyMonitor, as_json, describe
from clients.teleop.mcap_log import RobotStateFeed, SessionRecorder
from clients.teleop.stack import station_at
from clients.teleop.task import PegInHole, Result, go_home, ready_the_arm
from clients.teleop.video import StereoView
from discovery import DiscoveryError, discovered_address
from domain.robot_model import workspace
from domain.robot_model.description import ArmDescriptionError, UnknownArmError, select_arm
from telerobot.v1 import decision_server_pb2 as ds_pb
from wire.addresses import address_for, env_name
from wire.errors import TelerobotError

MODES = ("feedback", "compliance")
DISCOVERY_TIMEOUT_S = 5.0
RETRACT_STEP_M = 0.04


class StatusLine:
    """One terminal line, rewritten four times a second; `note(text)` puts a line of its own
    above it (from any thread)."""

    def __init__(self, stream=sys.stdout):
        self._stream = stream
        self._last = 0.0
        self._started = time.monotonic()
        self._count = 0
        self._width = 0  # of the status line on screen
        self._lock = threading.Lock()
        self.video: Callable[[], str] | None = None  # the stereo view's figures, when it runs

    def __call__(self, *, mode, clutch, force, commands, acks, round_trips,
                 link_down=False) -> None:
        now = time.monotonic()
        if now - self._last < 0.25:
            return
        elapsed = max(now - self._started, 1e-6)
        recent = round_trips[-50:] or [0.0]
        line = (f"[{mode:10}] {'CLUTCH ' if clutch else 'engaged'}  cmd {commands / elapsed:5.1f}/s"
                f"  acks {acks / elapsed:5.1f}/s  rtt p50 {np.median(recent):5.1f} ms"
                f"  F {force:6.2f} N  "
                f"{'LINK LOST: reconnecting, the arm holds' if link_down else 'lock held'}"
                f"{'  ' + self.video() if self.video else ''}")
        with self._lock:
            self._stream.write("\r" + line)
            self._stream.flush()
            self._width = len(line)
        self._last = now

    def note(self, text: str) -> None:
        """`text` on a line of its own, over the status line (which the next update redraws)."""
        with self._lock:
            self._stream.write("\r" + text.ljust(self._width) + "\n")
            self._stream.flush()
            self._width = 0
        self._last = 0.0

    def restart(self) -> None:
        self._started = time.monotonic()
        with self._lock:
            self._stream.write("\n")
            self._width = 0


def retract(client: DecisionClient, start: np.ndarray) -> None:
    """Back up out of the hole, then to the start position, in straight steps of at most
    RETRACT_STEP_M (up first, so the peg clears the hole before it moves sideways)."""
    for _ in range(50):
        here = client.robot.get_state().tool_pose.translation
        error = start - here
        if np.max(np.abs(error)) < 2e-4:
            return
        if here[2] < start[2] - 2e-4:
            error[:2] = 0.0  # straight up first
        step = error * min(1.0, RETRACT_STEP_M / np.linalg.norm(error))
        client.robot.move_cartesian(step)
        deadline = time.monotonic() + 10
        while client.robot.get_status().status.name != "READY" and time.monotonic() < deadline:
            time.sleep(0.02)


def table(results: list[Result]) -> str:
    rows = [("mode", "success", "time s", "depth mm", "peak N", "final N", "rtt p50", "rtt p99",
             "drift mm", "passivity")]
    rows += [(r.mode, "yes" if r.success else "NO", f"{r.duration_s:.1f}", f"{r.depth_m * 1e3:.1f}",
              f"{r.peak_force_n:.1f}", f"{r.final_force_n:.1f}", f"{r.round_trip_p50_ms:.2f}",
              f"{r.round_trip_p99_ms:.2f}",
              f"{r.drift_m * 1e3:.1f}" if r.mode == "feedback" else "-",
              _passivity_text(r)) for r in results]
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    return "\n".join("  ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True))
                     for row in rows)


def _passivity_text(result: Result) -> str:
    if result.mode != "feedback":
        return "-"
    if not result.energy:
        return "off"
    return (f"TDPA: {result.energy['slave_dissipated_j'] * 1e3:.0f} mJ kept from the "
            f"environment, {result.energy['master_dissipated_j'] * 1e3:.0f} mJ from the hand")


class LinkNotes:
    """What the session says of its link, as lines over the status line: lost, the first
    reconnect try, resumed, gave up (not every try: a 3 s cut makes several)."""

    def __init__(self, note: Callable[[str], None]):
        self._note = note

    def __call__(self, state: str, detail: str) -> None:
        if state == "lost":
            self._note(f"link lost ({detail}): the arm holds; reconnecting")
        elif state == "reconnecting" and detail.endswith(" 1"):
            self._note("reconnecting to the DecisionServer...")
        elif state == "resumed":
            self._note(f"link back: session resumed {detail}")
        elif state == "gave up":
            self._note(f"link lost for good: {detail}")


# Why a session can end early, and what the operator can do: by the error's reason or code.
ADVICE = {
    "LINK_LOST": "The arm holds. Check the network to the station, then run again.",
    "NO_SESSION": "The DecisionServer no longer knows this session (it restarted, or the "
                  "link was down past the resume window); the arm holds. Run again.",
    "NO_CONTROL": "The control lease is gone (it lapsed or was taken); the arm holds. Run "
                  "again to take control anew.",
    "CONTROL_LOST": "The control lease is gone; the arm holds. Run again.",
    "UNAVAILABLE": "The DecisionServer is unreachable; the arm holds (its watchdog). Check that "
                   "the station runs (make serve) and the network to it.",
}


def explain(error: TelerobotError) -> str:
    advice = ADVICE.get(error.reason or "") or ADVICE.get(error.code.name, "The arm holds.")
    return f"teleop: the session ended: {error}\n{advice}"


# The local station's choice of driver (the launcher's --driver), inherited as the arm's is.
DRIVER_ENV = env_name("proxy_robot", "driver")
DRIVERS = ("sim", "franka-sim")


def main(argv: list[str] | None = None) -> int:
    """The operator station; exits 0 when every run succeeded, 1 when one failed, 3 when the
    session ended early (a lost link, a lost lease, a dead DecisionServer), with a message and
    no traceback, and 130 on Ctrl-C."""
    parser = argparse.ArgumentParser(prog="python -m clients.teleop", description=__doc__)
    parser.add_argument("--address", default=address_for("decision_server"))
    parser.add_argument("--discover", nargs="?", const="", default=None, metavar="NAME",
                        help="find the slave station on the local network (zeroconf, "
                             "_telerobot._tcp) instead of --address; NAME picks one of several "
                             "(python -m discovery list shows them)")
    parser.add_argument("--modes", nargs="+", choices=MODES, default=list(MODES))
    parser.add_argument("--out", type=Path, default=None,
                        help="artifacts folder (default runs/teleop-<time>)")
    parser.add_argument("--arm", default=None,
                        help="the arm a local station is started with (env TELEROBOT_ARM; "
                             "default puma560); a station that answers already must drive it")
    parser.add_argument("--driver", choices=DRIVERS, default=None,
                        help="the arm's driver a local station is started with: sim (the "
                             "default), or franka-sim (franka-sim as a Franka FR3, through "
                             f"libfranka; with --arm fr3) (env {DRIVER_ENV})")
    parser.add_argument("--calibration", type=Path, default=None,
                        help="saved camera identification (made on the first run; default "
                             "var/cameras-<arm>.json)")
    parser.add_argument("--no-video", action="store_true", help="skip the stereo video")
    parser.add_argument("--no-passivity", action="store_true",
                        help="feedback mode without TDPA (on by default: it keeps the channel "
                             "passive under delay; off, for comparison)")
    parser.add_argument("--mcap", action="store_true",
                        help="also record the session as <out>/session.mcap (commands, acks, "
                             "tool pose and wrench, stereo pairs, the DecisionServer's events, "
                             "the arm's state, and Foxglove's /tf, images, force arrow; "
                             "python -m clients.teleop.mcap_inspect FILE summarizes it)")
    parser.add_argument("--episodes", type=int, default=0, metavar="N",
                        help="record N demonstration episodes: the scripted operator runs the "
                             "task N times (the modes in turn), each recorded by the "
                             "DecisionServer with --task and its outcome (python -m "
                             "clients.teleop.export_lerobot makes a LeRobot dataset of them)")
    parser.add_argument("--task", default=None,
                        help=f"the episodes' task label (default {DEFAULT_TASK!r}); alone, "
                             "each mode's run is an episode")
    args = parser.parse_args(argv)
    if args.episodes < 0:
        parser.error("--episodes must be >= 0")
    try:
        if args.arm is not None:
            select_arm(args.arm)  # a local station inherits it
        if args.driver is not None:
            os.environ[DRIVER_ENV] = args.driver  # as the arm
        if args.discover is not None:
            args.address = discovered_address(args.discover or None, DISCOVERY_TIMEOUT_S)
            print(f"teleop: found the slave station at {args.address}")
        return run(args)
    except (DiscoveryError, UnknownArmError, ArmDescriptionError, WrongArm) as error:
        print(f"teleop: {error}", file=sys.stderr)
        return 3
    except TelerobotError as error:
        print("\n" + explain(error), file=sys.stderr)
        return 3
    except KeyboardInterrupt:
        print("\nteleop: interrupted; the arm holds (the session's watchdog)", file=sys.stderr)
        return 130


DEFAULT_TASK = "insert the peg"


def run_episode(client: DecisionClient, task: PegInHole, label: str, episodes: list[dict]):
    """`task` run as a recorded episode: SUCCEEDED or FAILED as the run says; DISCARDED when
    it breaks off (the exception goes on), so no half-run episode reads as a demonstration."""
    client.start_episode(label)
    try:
        result = task.run()
    except BaseException:
        with contextlib.suppress(TelerobotError):
            client.end_episode(ds_pb.EPISODE_OUTCOME_DISCARDED)
        raise
    saved = client.end_episode(ds_pb.EPISODE_OUTCOME_SUCCEEDED if result.success
                               else ds_pb.EPISODE_OUTCOME_FAILED)
    episodes.append({"name": saved.name, "task": saved.task, "outcome": saved.outcome,
                     "commands": saved.command_count, "video_frames": saved.video_frames,
                     "duration_s": saved.duration_s})
    return result


class WrongArm(Exception):
    """The station that answers drives another arm than --arm asked for."""


def run(args: argparse.Namespace) -> int:
    out = args.out or Path("runs") / time.strftime("teleop-%Y%m%d-%H%M%S")
    out.mkdir(parents=True, exist_ok=True)

    recorder = SessionRecorder(out / "session.mcap") if args.mcap else None
    episodes: list[dict] = []  # each recorded episode: name, task, outcome, frames
    with station_at(args.address) as started, recorder or contextlib.nullcontext():
        client = DecisionClient(args.address, default_timeout=10.0)
        with client:
            client.acquire_control("teleop", lease_duration_s=30.0)
            arm = client.robot.get_arm_info().name
            if args.arm is not None and arm != args.arm:
                raise WrongArm(f"the station at {args.address} drives the {arm}, not the "
                               f"{args.arm}: stop it, or leave --arm out")
            cell = workspace.cell_for(arm)
            calibration = args.calibration or Path("var") / f"cameras-{arm}.json"
            calibration.parent.mkdir(parents=True, exist_ok=True)
            ready_the_arm(client)
            go_home(client)
            client.sensor.tare(0.2)
            start = client.robot.get_state().tool_pose.translation.copy()
            model = RobotModel(client.robot.get_state().tool_pose)
            view = None
            if not args.no_video:
                view = StereoView(client.camera, client.robot, model, out, calibration,
                                  on_frame=recorder and recorder.stereo, cell=cell)
                view.start()
            status, results, traces = StatusLine(), [], []
            status.video = view.status if view else None
            # The station's services as the session goes: what is down now, then every change.
            monitor = DependencyMonitor(client, status.note,
                                        on_event=recorder and recorder.event).start()
            # The arm's state samples, for the recording's /robot/state, /tf and /joint_states:
            # a stream of their own, so the monitor's stays free of their flood.
            states = RobotStateFeed(client, recorder.robot_state).start() if recorder else None
            for dependency in monitor.initial():
                if not dependency.serving:
                    status.note(describe(dependency))
            episode_task = args.task or (DEFAULT_TASK if args.episodes else None)
            plan = ([args.modes[k % len(args.modes)] for k in range(args.episodes)]
                    if args.episodes else args.modes)
            try:
                for mode in plan:
                    retract(client, start)
                    status.restart()
                    task = PegInHole(client, mode, model, status, on_link=LinkNotes(status.note),
                                     recorder=recorder, passivity=not args.no_passivity,
                                     cell=cell)
                    began = time.time_ns()
                    if episode_task:
                        results.append(run_episode(client, task, episode_task, episodes))
                    else:
                        results.append(task.run())
                    if recorder is not None:
                        recorder.run(mode, began, time.time_ns())
                    traces.append(task.trace)
                    client.renew_control()
                print()
                retract(client, start)
            finally:
                if view is not None:
                    view.stop()
                monitor.stop()
                if states is not None:
                    states.stop()
            dependencies = monitor.final()
    artifacts = plot(traces, out)
    summary = {
        "station": "started locally" if started else f"found at {args.address}",
        "arm": arm,
        "runs": [dataclasses.asdict(result) for result in results],
        "episodes": episodes,
        "video": str(out / "stereo.mp4") if view and view.recorder else None,
        "video_frames": view.recorder.frames if view and view.recorder else 0,
        "video_error": view.error if view else None,
        # What the operator's stream delivered: fps, age (capture to shown) p50/p95, kbit/s.
        "video_stream": view.summary() if view else {},
        "cameras_identified_now": bool(view and view.identified_now),
        "plots": [str(path) for path in artifacts],
        # Each of the station's services at the end, and every change during the session.
        "dependencies": dependencies,
        "dependency_changes": [as_json(d) for d in monitor.changes],
        "mcap": str(recorder.path) if recorder else None,
        "mcap_counts": dict(recorder.counts) if recorder else None,
        "mcap_error": recorder.error if recorder else None,
        "mcap_state_samples": states.samples if states else 0,
        "mcap_state_feed_error": states.error if states else None,
    }
    write_summary(summary, out)
    print(table(results))
    print(f"\nartifacts in {out}/: stereo.mp4, force.png, tool_path.png, latency.png, "
          f"summary.json{', session.mcap' if recorder else ''}")
    return 0 if all(result.success for result in results) else 1


if __name__ == "__main__":
    raise SystemExit(main())
