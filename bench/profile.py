"""`python -m bench --only decision --profile`: where the hot path's time goes.

After the decision group's scenarios, Teleoperate streams at 1 kHz once more (the same
pipelined worker as teleop_1000) while py-spy records the DecisionServer and ProxyRobot
processes: `--gil` (only the thread holding the GIL is sampled, so the shares are of the
interpreter's busy time, not of threads sleeping), 500 samples/s, `--nonblocking` (the processes
are not paused to be read). Raw stacks go to `<out>/profile_<service>.txt` (flamegraph's
collapsed format) and the top functions, by inclusive and by self share, are printed. Not part
of the measured scenarios: sampling costs the processes some time.
"""

from __future__ import annotations

import collections
import shutil
import subprocess
import sys
from pathlib import Path

SAMPLE_RATE_HZ = 500
TOP = 25


def py_spy() -> str:
    """The py-spy executable beside this interpreter (the bench extra installs it)."""
    found = shutil.which("py-spy", path=str(Path(sys.executable).parent)) or shutil.which("py-spy")
    if found is None:
        raise FileNotFoundError("py-spy is not installed: `make bench` installs it "
                                "(pip install py-spy)")
    return found


class Recording:
    """py-spy recording each of `pids` ({service: pid}) for `seconds`, into `out_dir`."""

    def __init__(self, pids: dict[str, int], seconds: float, out_dir: Path):
        out_dir.mkdir(parents=True, exist_ok=True)
        self.paths = {name: out_dir / f"profile_{name}.txt" for name in pids}
        self._spies = {name: subprocess.Popen(
            [py_spy(), "record", "--pid", str(pid), "--duration", str(max(1, round(seconds))),
             "--rate", str(SAMPLE_RATE_HZ), "--gil", "--nonblocking", "--format", "raw",
             "--output", str(self.paths[name])],
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            for name, pid in pids.items()}

    def finish(self, timeout_s: float = 60.0) -> dict[str, str]:
        """Wait for py-spy; {service: summary text, or why there is none}."""
        summaries = {}
        for name, spy in self._spies.items():
            _, errors = spy.communicate(timeout=timeout_s)
            path = self.paths[name]
            summaries[name] = (summarize(path) if path.exists() else
                               f"py-spy recorded nothing: {errors.strip()[-500:]}")
        return summaries


def _function(frame: str) -> str:
    """'name (path/file.py:line)' -> 'name (file.py)'."""
    name, _, where = frame.partition(" (")
    return f"{name} ({where.rsplit('/', 1)[-1].split(':')[0]})" if where else name


def summarize(path: Path, top: int = TOP) -> str:
    """The functions holding the GIL most often, inclusive (anywhere on the stack) and self
    (on top of it), as shares of all samples."""
    inclusive: collections.Counter[str] = collections.Counter()
    own: collections.Counter[str] = collections.Counter()
    total = 0
    for line in path.read_text().splitlines():
        stack, _, count = line.rpartition(" ")
        if not stack or not count.isdigit():
            continue
        samples = int(count)
        total += samples
        frames = [_function(frame) for frame in stack.split(";")]
        for function in set(frames):
            inclusive[function] += samples
        own[frames[-1]] += samples
    if not total:
        return "no samples"
    lines = [f"{total} samples holding the GIL", "inclusive:"]
    lines += [f"  {n / total:6.1%}  {f}" for f, n in inclusive.most_common(top)]
    lines += ["self:"] + [f"  {n / total:6.1%}  {f}" for f, n in own.most_common(top)]
    return "\n".join(lines)
