"""deploy/Containerfile and deploy/compose.yaml, checked without a container runtime (none
runs here): what they copy and run exists, their ports are the project's, the addresses they
set are ones the code reads, and the PKI lands where the image looks for it."""

from __future__ import annotations

import importlib.util
import json
import re
import shlex
from pathlib import Path

import pytest

from services.security.pki import DEFAULT_PKI_DIR
from wire.addresses import DEFAULT_PORTS, env_name

yaml = pytest.importorskip("yaml")  # pyproject's dev extras

REPO = Path(__file__).resolve().parents[2]
DEPLOY = REPO / "deploy"
# What an operator station on another host reaches: the DecisionServer (everything, the
# camera included, through one port) and the emergency-stop band.
PUBLISHED = {"decision_server", "emergency_stop"}


def instructions() -> list[tuple[str, str]]:
    """(INSTRUCTION, arguments) of the Containerfile, continuation lines joined."""
    text = re.sub(r"\\\n", " ", (DEPLOY / "Containerfile").read_text())
    found = []
    for line in text.splitlines():
        line = line.strip()
        if line and not line.startswith("#"):
            keyword, _, rest = line.partition(" ")
            found.append((keyword.upper(), rest.strip()))
    return found


def arguments(keyword: str) -> list[str]:
    return [rest for kw, rest in instructions() if kw == keyword]


def env_settings() -> dict[str, str]:
    settings = {}
    for rest in arguments("ENV"):
        for item in shlex.split(rest):
            key, _, value = item.partition("=")
            settings[key] = value
    return settings


def compose() -> dict:
    return yaml.safe_load((DEPLOY / "compose.yaml").read_text())


def slave() -> dict:
    return compose()["services"]["slave"]


def station_code() -> str:
    """The Python source of every package the image copies."""
    return "\n".join(p.read_text() for top in ("services", "wire", "domain", "discovery")
                     for p in (REPO / top).rglob("*.py"))


def test_the_image_is_python_311_slim_with_egl_for_offscreen_rendering():
    assert arguments("FROM") == ["python:3.11-slim"]
    (install,) = [r for r in arguments("RUN") if "apt-get install" in r]
    for package in ("libegl1", "libegl-mesa0", "libgl1", "libgl1-mesa-dri", "libosmesa6"):
        assert package in install.split(), package
    assert env_settings()["MUJOCO_GL"] == "egl"  # as the Makefile and the tests set it


def test_what_the_image_copies_exists_and_keys_stay_out():
    sources = []
    for rest in arguments("COPY"):
        *from_, _to = shlex.split(rest)
        sources += from_
    for source in sources:
        assert (REPO / source).exists(), source  # the build context is the repository root
    assert "pyproject.toml" in sources and "services" in sources
    assert not any(s in ("var", ".", "var/pki") for s in sources)  # no private keys baked in
    # Every package of this project the station imports is in the image.
    imported = set(re.findall(r"^\s*(?:from|import) (\w+)", station_code(), re.MULTILINE))
    ours = {p.parent.name for p in REPO.glob("*/__init__.py")}
    assert imported & ours <= set(sources), (imported & ours) - set(sources)


def test_the_image_installs_the_stations_dependencies():
    (install,) = [r for r in arguments("RUN") if r.startswith("pip install")]
    assert "[station,console]" in install  # `pip install .` alone is the Python client only


def test_the_entrypoint_is_the_launcher():
    (entrypoint,) = arguments("ENTRYPOINT")
    assert json.loads(entrypoint) == ["python", "-m", "services.launcher"]
    assert importlib.util.find_spec("services.launcher") is not None


def test_the_image_exposes_and_compose_publishes_the_projects_ports():
    expected = {DEFAULT_PORTS[name] for name in PUBLISHED}
    (exposed,) = arguments("EXPOSE")
    assert {int(p) for p in exposed.split()} == expected
    published = [entry.split(":") for entry in slave()["ports"]]
    assert all(host == container for host, container in published)
    assert {int(container) for _, container in published} == expected


def test_compose_moves_the_published_services_onto_the_containers_own_name():
    service = slave()
    environment = service["environment"]
    for name in PUBLISHED:
        assert environment[env_name(name, "address")] == \
            f"{service['hostname']}:{DEFAULT_PORTS[name]}"
    # The inner services keep their loopback defaults: nothing else is reachable from outside.
    inner = {env_name(n, "address") for n in DEFAULT_PORTS if n not in PUBLISHED}
    assert not inner & set(environment)


def test_every_setting_compose_and_the_image_make_is_one_the_code_reads():
    code = station_code()
    read = set(re.findall(r"TELEROBOT_[A-Z_]+", code))
    read |= {env_name(name, "address") for name in DEFAULT_PORTS}  # built by env_name
    settings = {k for k in (*slave()["environment"], *env_settings()) if k.startswith("TELEROBOT")}
    assert settings and settings <= read, settings - read


def test_the_pki_made_by_make_certs_is_mounted_where_the_image_looks_for_it():
    tls_dir = env_settings()["TELEROBOT_TLS_DIR"]
    mounts = [volume.split(":") for volume in slave()["volumes"]]
    (pki,) = [m for m in mounts if m[1] == tls_dir]
    assert (DEPLOY / pki[0]).resolve() == (REPO / DEFAULT_PKI_DIR).resolve()
    assert pki[2:] == ["ro"]
    data = [m for m in mounts if m[1] == "/var/lib/telerobot"]
    assert data and data[0][0] in compose()["volumes"]


def test_compose_builds_from_the_repository_root_with_the_containerfile():
    build = slave()["build"]
    assert (DEPLOY / build["context"]).resolve() == REPO
    assert (REPO / build["dockerfile"]) == DEPLOY / "Containerfile"
