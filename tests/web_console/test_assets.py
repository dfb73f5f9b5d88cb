"""The committed page is what the sources build: the types generated from protos/ and the
bundle in services/web_console/static/app.js (`make web` rebuilds both)."""

from __future__ import annotations

import filecmp
import subprocess
from pathlib import Path

import pytest

from tests.processes import REPO

pytestmark = pytest.mark.e2e

WEB = REPO / "web"
BIN = WEB / "node_modules" / ".bin"


@pytest.fixture(scope="module")
def tools():
    if not (BIN / "esbuild").exists() or not (BIN / "protoc-gen-es").exists():
        pytest.fail("web/node_modules is missing: `make install` (or `make test`) installs it")


def _files(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*"))
            if p.is_file()}


def test_generated_types_match_the_protos(tools, tmp_path):
    subprocess.run([str(BIN / "buf"), "generate", "..", "--template", "buf.gen.yaml",
                    "-o", str(tmp_path)], cwd=WEB, check=True, capture_output=True)
    fresh = _files(tmp_path / "src" / "gen")
    assert fresh, "buf generate wrote nothing"
    assert fresh == _files(WEB / "src" / "gen"), (
        "web/src/gen is stale against protos/: run `make web` and commit the result")


def test_bundle_matches_the_sources(tools, tmp_path):
    out = tmp_path / "app.js"
    subprocess.run([str(BIN / "esbuild"), "src/main.ts", "--bundle", "--format=esm",
                    "--target=es2022", "--minify", f"--outfile={out}", "--log-level=error"],
                   cwd=WEB, check=True)
    committed = REPO / "services" / "web_console" / "static" / "app.js"
    assert filecmp.cmp(out, committed, shallow=False), (
        "services/web_console/static/app.js is stale: run `make web` and commit it")
