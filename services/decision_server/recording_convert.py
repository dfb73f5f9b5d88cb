"""Convert a DecisionServer recording between its two formats.

    python -m services.decision_server.recording_convert IN.jsonl [OUT.mcap]
    python -m services.decision_server.recording_convert IN.mcap [OUT.jsonl]

The output defaults to IN with the other suffix, and is never overwritten. JSONL → MCAP writes
the increments (/recording/increment) and the "recording" metadata; MCAP → JSONL keeps only
the increments (the acks, state, wrench and events have no place in JSONL). Put the output in
the DecisionServer's recordings directory (var/recordings by default) and StartReplay finds it
by its file name. A bad file exits with status 2 and a message, no traceback.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from services.decision_server import recording_mcap
from services.decision_server.recordings import NAME_PATTERN, read_jsonl, read_mcap, write_jsonl
from wire.errors import TelerobotError

OTHER = {".jsonl": ".mcap", ".mcap": ".jsonl"}


def convert(source: Path, target: Path | None = None) -> tuple[Path, int]:
    """Writes `target` from `source`; returns (target, increments). TelerobotError or
    OSError for a file that cannot be read or written."""
    suffix = source.suffix.lower()
    if suffix not in OTHER:
        raise ValueError(f"{source}: a recording ends in .jsonl or .mcap")
    target = target or source.with_suffix(OTHER[suffix])
    if target.suffix.lower() != OTHER[suffix]:
        raise ValueError(f"{target}: converting {suffix} writes {OTHER[suffix]}")
    if target.exists():
        raise ValueError(f"{target} exists: delete it or name another output")
    if not NAME_PATTERN.fullmatch(target.stem):
        raise ValueError(f"{target}: the DecisionServer finds recordings named "
                         "[A-Za-z0-9_-]{1,64}")
    if suffix == ".jsonl":
        name, created, commands = read_jsonl(source)
        partial = target.with_name(target.name + ".partial")
        try:
            recording_mcap.write_commands(partial, target.stem, created, commands)
        except BaseException:
            partial.unlink(missing_ok=True)
            raise
        partial.replace(target)
    else:
        name, created, commands = read_mcap(source)
        write_jsonl(target, target.stem, created, commands)
    return target, len(commands)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m services.decision_server.recording_convert",
        description="Convert a DecisionServer recording: JSONL to MCAP, or MCAP to JSONL.")
    parser.add_argument("source", type=Path, help="IN.jsonl or IN.mcap")
    parser.add_argument("target", type=Path, nargs="?",
                        help="OUT (default: IN with the other suffix; never overwritten)")
    args = parser.parse_args(argv)
    try:
        if not args.source.is_file():
            raise ValueError(f"{args.source}: no such file")
        target, count = convert(args.source, args.target)
    except TelerobotError as error:
        print(f"error: {error.message}", file=sys.stderr)
        return 2
    except (ValueError, OSError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    print(f"{target}: {count} increments")
    return 0


if __name__ == "__main__":
    sys.exit(main())
