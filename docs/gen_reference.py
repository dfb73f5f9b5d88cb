"""python docs/gen_reference.py: docs/reference.md, every flag and environment variable.

Generated, never written by hand: each command's argparse parser is built in this process (its
module run as __main__ until it would parse its arguments, which is where this stops it), with
every TELEROBOT_* variable cleared, so the defaults shown are the code's own. Each environment
variable a flag's default reads is noted beside the flag. The variables read elsewhere are the
module constants named *_ENV, and the per-service addresses of ``wire.addresses``.

``tests/docs/test_reference.py`` fails when docs/reference.md differs from what this writes.
"""

from __future__ import annotations

import argparse
import ast
import contextlib
import enum
import os
import runpy
import sys
import warnings
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
TARGET = REPO / "docs" / "reference.md"
PACKAGES = ("discovery", "domain", "wire", "services", "clients", "bench")

# The commands, grouped as the docs present them: (module, what it is).
COMMANDS = (
    ("The slave station", (
        ("services.launcher", "`make serve`: every service in its own process"),
        ("services.world", "the simulated hardware"),
        ("services.proxy_robot", "ProxyRobot"),
        ("services.force_sensor", "ForceSensor"),
        ("services.stereo_camera", "StereoCamera"),
        ("services.emergency_stop", "the emergency-stop band"),
        ("services.decision_server", "the DecisionServer"),
        ("services.web_console", "the web console"),
        ("services.foxglove", "the Foxglove live view"),
        ("services.zenoh_router", "the Zenoh router observers subscribe through"),
        ("services.observation", "the observation's publisher into Zenoh"),
        ("services.impairment", "the impairment link"),
    )),
    ("The operator's side", (
        ("clients.teleop", "`make teleop`: the operator station"),
        ("clients.teleop.mcap_inspect", "what a session.mcap holds"),
        ("clients.video_probe", "the stereo stream's rate and age"),
        ("clients.observe", "watch a station through a Zenoh router"),
        ("discovery", "mDNS: list, watch and advertise stations"),
    )),
    ("Tools", (
        ("services.security.pki", "`make certs`: the development PKI"),
        ("services.security.tokens", "bearer tokens"),
        ("services.decision_server.recording_convert", "JSONL and MCAP recordings"),
        ("services.world.measure", "the hardware link's latency"),
        ("services.stereo_camera.measure", "a stereo source's rate and latency"),
        ("domain.robot_model.mjcf", "the PUMA 560's MJCF files"),
        ("bench", "`make bench`"),
        ("bench.readme", "the Performance page's tables"),
    )),
)

# What a variable read outside any flag does, when its definition carries no comment.
ENV_TEXT = {
    "TELEROBOT_TLS_DIR": "a directory with `ca.pem` and certificates: every server serves "
                         "mutual TLS, every client presents one (`make certs` writes var/pki)",
    "TELEROBOT_IDENTITY": "which client certificate of the TLS directory a client presents "
                          "(default `operator`)",
    "TELEROBOT_TOKEN": "a bearer token a client sends instead of a certificate (TLS only)",
    "TELEROBOT_PARENT_PID": "set by the launcher for its children: a child whose parent is "
                            "gone stops itself",
    "TELEROBOT_SUPERVISOR_STATE": "the launcher's state file, where the DecisionServer reads "
                                  "which service is being restarted",
    "TELEROBOT_WORLD_SHM": "the name of the world's shared-memory segment",
    "TELEROBOT_STATION_NAME": "the name a station advertises over mDNS (default <host>:<port>)",
    "TELEROBOT_ADVERTISE": "1, 0 or auto: whether the station advertises itself over mDNS",
    "TELEROBOT_TOKENS_FILE": "where bearer tokens are kept, hashed (default var/tokens.json)",
    "TELEROBOT_AUDIT_DIR": "where each service writes its audit log (default var/audit)",
}


class _Parsed(Exception):
    """Raised instead of parsing: the parser as the command built it."""

    def __init__(self, parser: argparse.ArgumentParser):
        super().__init__(parser.prog)
        self.parser = parser


@dataclass
class _Reads:
    """Environment variables read while a parser is built, each given to the next flag."""
    pending: list[str] = field(default_factory=list)
    by_action: dict[int, list[str]] = field(default_factory=dict)


@contextlib.contextmanager
def _capturing():
    """Within: parse_args raises _Parsed, and every os.environ read is noted in the _Reads
    yielded; TELEROBOT_* variables are cleared, then restored."""
    reads = _Reads()
    environ_class = type(os.environ)
    get_item = environ_class.__getitem__
    add_argument = argparse._ActionsContainer.add_argument
    parse_known = argparse.ArgumentParser.parse_known_args
    init = argparse.ArgumentParser.__init__
    saved = {name: value for name, value in os.environ.items()
             if name.startswith("TELEROBOT_") or name == "QUICK"}

    def noted_get_item(self, key):
        if (key.startswith("TELEROBOT_") or key == "QUICK") and key not in reads.pending:
            reads.pending.append(key)
        return get_item(self, key)

    def new_parser(self, *args, **kwargs):
        reads.pending[:] = []  # what was read before a parser existed belongs to no flag
        init(self, *args, **kwargs)

    def noted_add_argument(self, *args, **kwargs):
        action = add_argument(self, *args, **kwargs)
        reads.by_action[id(action)], reads.pending[:] = list(reads.pending), []
        return action

    def stop(self, *_args, **_kwargs):
        raise _Parsed(self)

    for name in saved:
        del os.environ[name]
    environ_class.__getitem__ = noted_get_item
    argparse._ActionsContainer.add_argument = noted_add_argument
    argparse.ArgumentParser.parse_known_args = stop
    argparse.ArgumentParser.__init__ = new_parser
    try:
        yield reads
    finally:
        environ_class.__getitem__ = get_item
        argparse._ActionsContainer.add_argument = add_argument
        argparse.ArgumentParser.parse_known_args = parse_known
        argparse.ArgumentParser.__init__ = init
        os.environ.update(saved)


def parser_of(module: str) -> tuple[argparse.ArgumentParser, dict[int, list[str]]]:
    """`module`'s parser, built as `python -m module` builds it, and the variables each of its
    flags read for its default (by id of the action)."""
    argv = sys.argv
    with _capturing() as reads:
        sys.argv = [module]
        try:
            with warnings.catch_warnings():  # "found in sys.modules": run again, on purpose
                warnings.simplefilter("ignore", RuntimeWarning)
                runpy.run_module(module, run_name="__main__", alter_sys=False)
        except _Parsed as parsed:
            return parsed.parser, reads.by_action
        finally:
            sys.argv = argv
    raise RuntimeError(f"{module} ran without parsing its arguments")


def _default(action: argparse.Action) -> str:
    value = action.default
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, str) and value.startswith(str(REPO) + os.sep):
        return value[len(str(REPO)) + 1:]  # a path in the repository, from its root
    if value is None or value == argparse.SUPPRESS or value == "" or value == ():
        return "–"
    if isinstance(value, enum.Enum):
        return value.name.lower()
    if isinstance(value, (list, tuple)):
        return " ".join(str(item) for item in value) or "–"
    return str(value)


def _cell(text: str) -> str:
    return " ".join(str(text).split()).replace("|", "\\|")


def _help(parser: argparse.ArgumentParser, action: argparse.Action) -> str:
    if not action.help:
        text = ""
    else:
        text = parser._get_formatter()._expand_help(action)
    if (action.choices and not isinstance(action, argparse._SubParsersAction)
            and len(action.choices) <= 12):
        choices = ", ".join(str(choice) for choice in action.choices)
        text = f"{text} (one of: {choices})" if text else f"one of: {choices}"
    return _cell(text) or "–"


def _flag(action: argparse.Action) -> str:
    if action.option_strings:
        names = ", ".join(f"`{name}`" for name in action.option_strings)
        if action.nargs != 0 and action.metavar:
            names += f" `{action.metavar}`"
        return names
    return f"`{action.metavar or action.dest}` (positional)"


def _table(parser: argparse.ArgumentParser, reads: dict[int, list[str]],
           env_flags: dict[str, list[str]], command: str) -> list[str]:
    rows = []
    for action in parser._actions:
        if isinstance(action, (argparse._HelpAction, argparse._SubParsersAction)):
            continue
        env = reads.get(id(action), [])
        for name in env:
            env_flags.setdefault(name, []).append(
                (f"`{command}` "
                 f"{action.option_strings[0] if action.option_strings else action.dest}",
                 _help(parser, action)))
        rows.append(f"| {_flag(action)} | {_cell(_default(action))} | "
                    f"{', '.join(f'`{name}`' for name in env) or '–'} | {_help(parser, action)} |")
    if not rows:
        return ["No flags."]
    return ["| flag | default | environment | what |", "|---|---|---|---|", *rows]


def _subcommands(parser: argparse.ArgumentParser):
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            helps = {choice.dest: choice.help for choice in action._choices_actions}
            for name, sub in action.choices.items():
                yield name, helps.get(name), sub


def _description(parser: argparse.ArgumentParser) -> str:
    return " ".join((parser.description or "").strip().split("\n\n")[0].split())


def _env_constants() -> dict[str, tuple[str, str]]:
    """Every module constant named *_ENV whose value is an environment variable's name:
    name -> (module path, its comment, or "")."""
    found: dict[str, tuple[str, str]] = {}
    for package in PACKAGES:
        for path in sorted((REPO / package).rglob("*.py")):
            source = path.read_text()
            lines = source.splitlines()
            for node in ast.parse(source).body:
                if not (isinstance(node, ast.Assign) and len(node.targets) == 1
                        and isinstance(node.targets[0], ast.Name)
                        and node.targets[0].id.endswith("_ENV")
                        and isinstance(node.value, ast.Constant)
                        and isinstance(node.value.value, str)):
                    continue
                line = lines[node.lineno - 1]
                comment = line.split("#", 1)[1].strip() if "#" in line else ""
                above = lines[node.lineno - 2].strip() if node.lineno > 1 else ""
                if not comment and above.startswith("#"):
                    comment = above.lstrip("# ").strip()
                found.setdefault(node.value.value,
                                 (str(path.relative_to(REPO)), comment))
    return found


def render() -> str:
    from wire.addresses import DEFAULT_HOST, DEFAULT_PORTS, env_name

    lines = [
        "# Reference: flags and environment variables",
        "",
        "<!-- Generated by `python docs/gen_reference.py` from the parsers and the code's "
        "environment variables: do not edit. tests/docs/test_reference.py fails when it is "
        "stale. -->",
        "",
        "Every command's flags, as its parser defines them, and every environment variable the "
        "code reads. A flag's default comes from the environment variable beside it when that "
        "is set. `python -m <module> --help` prints the same.",
        "",
    ]
    env_flags: dict[str, list[tuple[str, str]]] = {}
    for group, commands in COMMANDS:
        lines += [f"## {group}", ""]
        for module, what in commands:
            parser, reads = parser_of(module)
            description = _description(parser) or f"{what[0].upper()}{what[1:]}."
            lines += [f"### `python -m {module}`", "", description, ""]
            subcommands = list(_subcommands(parser))
            if subcommands or any(not isinstance(a, argparse._HelpAction)
                                  for a in parser._actions):
                lines += [*_table(parser, reads, env_flags, module), ""]
            for name, help_text, sub in subcommands:
                lines += [f"#### `python -m {module} {name}`", ""]
                if help_text:
                    lines += [f"{_cell(help_text)[0].upper()}{_cell(help_text)[1:]}.", ""]
                lines += [*_table(sub, reads, env_flags, f"{module} {name}"), ""]

    lines += ["## Environment variables", "",
              "### Where each service listens", "",
              "`TELEROBOT_<SERVICE>_ADDRESS` (`wire/addresses.py`): the service's `--address`, "
              "and where the launcher, the clients and the other services look for it.", "",
              "| variable | default |", "|---|---|"]
    for service, port in DEFAULT_PORTS.items():
        lines.append(f"| `{env_name(service, 'address')}` | {DEFAULT_HOST}:{port} |")
    lines += ["", "Each gRPC service also reads `TELEROBOT_<SERVICE>_TOKEN_ADDRESS` "
              "(`--token-address`) and `TELEROBOT_<SERVICE>_METRICS_ADDRESS` "
              "(`--metrics-address`).", "",
              "### Every variable", "",
              "| variable | read by | what |", "|---|---|---|"]
    constants = _env_constants()
    names = sorted(set(env_flags) | set(constants))
    for name in names:
        setting = name.removeprefix("TELEROBOT_")
        if any(setting == f"{service.upper()}_{kind}" for service in DEFAULT_PORTS
               for kind in ("ADDRESS", "TOKEN_ADDRESS", "METRICS_ADDRESS")):
            continue  # the per-service addresses: above, and beside each command's flags
        flags = env_flags.get(name, [])
        where = ", ".join(sorted({flag for flag, _ in flags})) or f"`{constants[name][0]}`"
        what = ENV_TEXT.get(name) or (constants.get(name, ("", ""))[1])
        if not what and flags:
            what = next((text for _, text in flags if text != "–"), "")
        lines.append(f"| `{name}` | {_cell(where)} | {_cell(what) or '–'} |")
    return "\n".join(lines) + "\n"


def main() -> int:
    TARGET.write_text(render())
    print(f"wrote {TARGET.relative_to(REPO)}")
    return 0


if __name__ == "__main__":
    sys.path.insert(0, str(REPO))
    raise SystemExit(main())
