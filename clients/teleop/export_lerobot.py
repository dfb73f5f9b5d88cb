"""python -m clients.teleop.export_lerobot RUNS... --out DIR [--fps 30]

Turns recorded episodes (DecisionServer recordings with a task: `make teleop EPISODES=N`, or
StartRecording with a task from any client) into a LeRobotDataset v3.0 in DIR
(clients/teleop/lerobot_dataset.py says what it holds). RUNS are episode files (<name>.mcap)
or directories of them (the DecisionServer's --recordings-dir), in name order.

- Episodes marked DISCARDED are left out; FAILED ones too, unless --include-failed.
- An episode whose file was never finished (the server was killed mid-episode: the file ends
  in .mcap.partial, or is cut short) is named and left out; the earlier ones export whole.
- Without video, the dataset has no image features, and says so.
- The dataset's robot_type is the arm the station recorded (--robot-type names it for
  episodes recorded without it); episodes of different arms are refused.
- DIR must not exist, unless --append: the episodes then follow the dataset's own (the same
  fps, arm and features), numbered on from its last, in files of their own. An episode file
  the dataset already holds (the same bytes) is skipped, so appending a recordings directory
  again adds only the episodes recorded since (a file given twice is exported once).
- Either way the dataset is written beside, as DIR.partial (an append's existing files as
  hard links, not copies), and takes DIR's place only when whole: an export that fails leaves
  DIR as it was.
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
from pathlib import Path

from clients.teleop.episode_file import (
    PARTIAL,
    Episode,
    IncompleteEpisode,
    NotAnEpisode,
    read_episode,
)
from clients.teleop.lerobot_dataset import (
    file_digest,
    on_grid,
    read_appended,
    write_dataset,
)


def episode_files(runs: list[Path]) -> list[Path]:
    """The episode files among `runs` (files, or directories holding them), in name order."""
    files: list[Path] = []
    for run in runs:
        if run.is_dir():
            files += sorted(p for p in run.iterdir()
                            if p.name.endswith(".mcap") or p.name.endswith(".mcap" + PARTIAL))
        elif run.exists():
            files.append(run)
        else:
            raise FileNotFoundError(f"{run}: no such file or directory")
    return files


def export(runs: list[Path], out: Path, fps: int = 30, include_failed: bool = False,
           robot_type: str | None = None, append: bool = False, report=print) -> dict:
    """Write the dataset (or append to it); its info.json. ValueError when there is nothing
    to export, or it does not fit."""
    if out.exists() and not append:
        raise FileExistsError(f"{out} exists: give a new --out, or --append to add episodes "
                              "to it")
    if not 1 <= fps <= 120:
        raise ValueError(f"--fps must be 1..120, not {fps}")
    appended = read_appended(out) if out.exists() else None
    episodes = _exported_episodes(runs, include_failed, report)
    episodes, digests = _new_episodes(episodes, [file_digest(e.path) for e in episodes],
                                      appended.sources if appended else [], report)
    robot_type = robot_type or _recorded_robot(episodes)
    with_video = all(e.has_video for e in episodes)
    if not with_video:
        missing = [e.path.name for e in episodes if not e.has_video]
        report(f"no video in {', '.join(missing)}: the dataset is exported without images")
        for episode in episodes:
            episode.video_frames, episode.eye_size = [], None
    frames = [on_grid(episode, fps) for episode in episodes]
    # Written beside and renamed when whole: an export that fails (a full disk, an episode
    # whose video will not decode) leaves no half dataset behind to be trained on.
    partial = out.with_name(out.name + PARTIAL)
    shutil.rmtree(partial, ignore_errors=True)
    try:
        if appended:
            shutil.copytree(out, partial, copy_function=os.link)
        info = write_dataset(partial, frames, digests, fps, robot_type, appended)
    except BaseException:
        shutil.rmtree(partial, ignore_errors=True)
        raise
    _replace(out, partial)
    first = info["total_episodes"] - len(frames)
    for number, f in enumerate(frames, start=first):
        report(f"episode {number}: {f.episode.path.name}, {f.episode.task!r}, "
               f"{f.episode.outcome}, {len(f.times_ns)} frames")
    report(f"wrote {out}: {info['total_episodes']} episodes"
           + (f" ({len(frames)} appended)" if appended else "")
           + f", {info['total_frames']} frames at {fps} fps, {info['total_tasks']} tasks"
           + ("" if with_video else ", no images"))
    return info


def _exported_episodes(runs: list[Path], include_failed: bool, report) -> list[Episode]:
    episodes: list[Episode] = []
    for path in episode_files(runs):
        try:
            episode = read_episode(path)
        except IncompleteEpisode as why:
            report(f"incomplete: {why}")
            continue
        except NotAnEpisode as why:
            report(f"skipped: {why}")
            continue
        if episode.outcome == "DISCARDED" or (episode.outcome == "FAILED"
                                              and not include_failed):
            report(f"skipped: {path.name} ({episode.task!r}) is marked {episode.outcome}")
            continue
        episodes.append(episode)
    if not episodes:
        raise ValueError("no episode to export (see above)")
    return episodes


def _new_episodes(episodes: list[Episode], digests: list[str], sources: list[dict], report
                  ) -> tuple[list[Episode], list[str]]:
    """The episodes (and their digests) whose files are neither in the dataset (`sources`,
    its SOURCES_PATH entries) nor given before them; ValueError when none is left."""
    held = {source["sha256"]: f"already in the dataset, as episode {source['episode_index']}"
            for source in sources}
    kept = []
    for episode, digest in zip(episodes, digests, strict=True):
        if digest in held:
            report(f"skipped: {episode.path.name} is {held[digest]}")
            continue
        held[digest] = f"the same file as {episode.path.name}"
        kept.append((episode, digest))
    if not kept:
        raise ValueError("no new episode to export: the dataset holds them all (see above)")
    return [episode for episode, _ in kept], [digest for _, digest in kept]


def _recorded_robot(episodes: list[Episode]) -> str:
    """The one arm the episodes were recorded on; ValueError when they do not say, or differ."""
    robots = {episode.robot for episode in episodes}
    if robots == {""}:
        raise ValueError("the episodes do not name their arm: give --robot-type")
    if len(robots) > 1:
        by_robot = ", ".join(f"{e.path.name}: {e.robot or 'not named'}" for e in episodes)
        raise ValueError(f"the episodes come from different arms ({by_robot}): export each "
                         "arm's apart, or give --robot-type")
    return robots.pop()


def _replace(out: Path, partial: Path) -> None:
    """`partial` takes `out`'s place; the replaced dataset is removed once it has."""
    replaced = out.with_name(out.name + ".replaced")
    shutil.rmtree(replaced, ignore_errors=True)
    if out.exists():
        out.rename(replaced)
    partial.rename(out)
    shutil.rmtree(replaced, ignore_errors=True)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m clients.teleop.export_lerobot",
                                     description=__doc__.split("\n\n")[1])
    parser.add_argument("runs", nargs="+", type=Path, metavar="RUNS",
                        help="episode files (.mcap) or directories of them")
    parser.add_argument("--out", type=Path, required=True,
                        help="the dataset's directory (new, unless --append)")
    parser.add_argument("--append", action="store_true",
                        help="add the episodes to the dataset in --out")
    parser.add_argument("--fps", type=int, default=30, help="the dataset's frame rate")
    parser.add_argument("--include-failed", action="store_true",
                        help="also export episodes marked FAILED")
    parser.add_argument("--robot-type",
                        help="info.json's robot_type (default: the arm the episodes name)")
    args = parser.parse_args(argv)
    try:
        export(args.runs, args.out, args.fps, args.include_failed, args.robot_type,
               args.append)
    except (ValueError, FileExistsError, FileNotFoundError) as error:
        print(f"export_lerobot: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
