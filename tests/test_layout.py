"""The packages keep the architecture's shape: who may import whom, and no circles.

    wire/, domain/, discovery/   shared by both stations
    services/                    the slave station
    clients/                     the operator's side: never imports services/
    bench/, tests/               import the product; the product never imports them

The import graph is read from the source (ast), so a test here starts nothing and imports
nothing of what it checks. Imports inside functions and under TYPE_CHECKING count too: a
circle that only a lazy import hides is still a circle.
"""

from __future__ import annotations

import ast
import functools
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
PACKAGES = ("wire", "domain", "discovery", "services", "clients", "bench", "tests")
PRODUCT = ("wire", "domain", "discovery", "services", "clients", "bench")


def module_files() -> dict[str, Path]:
    """Every module of the project's packages by dotted name (a package by its own name)."""
    modules = {}
    for package in PACKAGES:
        for path in (REPO / package).rglob("*.py"):
            parts = path.relative_to(REPO).with_suffix("").parts
            if parts[-1] == "__init__":
                parts = parts[:-1]
            modules[".".join(parts)] = path
    return modules


@functools.cache
def import_graph() -> dict[str, set[str]]:
    """module -> the project's modules it imports (a name imported from a package counts as
    that submodule when it is one, else as the package)."""
    modules = module_files()

    def known(name: str) -> str | None:
        while name and name not in modules:
            name = name.rpartition(".")[0]
        return name or None

    graph = {}
    for name, path in modules.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        found = set()
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Import):
                found.update(known(alias.name) for alias in node.names)
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    parent = package.split(".")[:len(package.split(".")) - node.level + 1]
                    base = ".".join([*parent, *([base] if base else [])])
                for alias in node.names:
                    found.add(known(f"{base}.{alias.name}") if f"{base}.{alias.name}" in modules
                              else known(base))
        graph[name] = found - {None, name}
    return graph


def circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan, iterative)."""
    index, low, on_stack, stack, found = {}, {}, set(), [], []
    for root in graph:
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, edges = work[-1]
            for target in edges:
                if target not in index:
                    index[target] = low[target] = len(index)
                    stack.append(target)
                    on_stack.add(target)
                    work.append((target, iter(sorted(graph[target]))))
                    break
                if target in on_stack:
                    low[node] = min(low[node], index[target])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    component = []
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        component.append(member)
                        if member == node:
                            break
                    if len(component) > 1:
                        found.append(sorted(component))
    return found


def imports_of(graph, packages) -> set[tuple[str, str]]:
    return {(module, target) for module, targets in graph.items()
            if module.split(".")[0] in packages for target in targets}


def test_the_operators_side_never_imports_the_slave_station():
    graph = import_graph()
    wrong = {(m, t) for m, t in imports_of(graph, ("clients",)) if t.startswith("services")}
    assert not wrong, sorted(wrong)


def test_the_shared_packages_import_neither_station():
    graph = import_graph()
    wrong = {(m, t) for m, t in imports_of(graph, ("wire", "domain", "discovery"))
             if t.split(".")[0] in ("services", "clients")}
    assert not wrong, sorted(wrong)


def test_the_product_never_imports_the_tests():
    graph = import_graph()
    wrong = {(m, t) for m, t in imports_of(graph, PRODUCT) if t.startswith("tests")}
    assert not wrong, sorted(wrong)


def test_the_domain_never_imports_grpc_or_the_generated_code():
    for path in (REPO / "domain").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                     else [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            for name in names:
                assert name.split(".")[0] not in ("grpc", "telerobot"), (path, name)


def test_no_circle_among_the_projects_modules():
    assert circles(import_graph()) == []


def test_the_circle_finder_finds_a_circle():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}, "e": set()}
    assert circles(graph) == [["a", "b", "c"]]


# Not the Python client's: the station's, the console's and the operator station's weight.
HEAVY = ("mujoco", "pinocchio", "pin", "cv2", "opencv_python_headless", "uvicorn", "foxglove",
         "foxglove_sdk")


@pytest.mark.e2e
@pytest.mark.slow
def test_pip_install_dot_gives_the_python_client_without_the_stations_weight(tmp_path):
    """`pip install .` into a fresh venv, then `import clients.python`: none of MuJoCo,
    Pinocchio, OpenCV, uvicorn or Foxglove is installed or imported."""
    source = tmp_path / "source"  # a copy: pip builds in the tree it is given
    source.mkdir()
    shutil.copy(REPO / "pyproject.toml", source)
    for package in ("wire", "domain", "discovery", "services", "clients", "gen"):
        shutil.copytree(REPO / package, source / package,
                        ignore=shutil.ignore_patterns("__pycache__"))
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    python = str(venv / "bin" / "python")
    env = {**os.environ, "PIP_DISABLE_PIP_VERSION_CHECK": "1"}
    subprocess.run([python, "-m", "pip", "install", "--quiet", str(source)], check=True, env=env,
                   cwd=tmp_path, timeout=600)
    installed = subprocess.run([python, "-m", "pip", "list", "--format=freeze"], check=True,
                               capture_output=True, text=True, cwd=tmp_path).stdout.lower()
    names = {line.split("==")[0].replace("-", "_") for line in installed.split()}
    assert not names & set(HEAVY), names & set(HEAVY)
    imported = subprocess.run(
        [python, "-c", "import sys, clients.python; print(' '.join(sys.modules))"],
        check=True, capture_output=True, text=True, cwd=tmp_path).stdout.split()
    assert "clients.python" in imported
    assert not {m.split(".")[0] for m in imported} & set(HEAVY)
