"""The docs site builds with --strict: a broken link or anchor, or a page missing from
mkdocs.yml's nav, fails here (in-process, into a temporary directory)."""

from __future__ import annotations

import logging
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def test_the_site_builds_strictly(tmp_path):
    from mkdocs.commands.build import build
    from mkdocs.config import load_config

    logging.getLogger("mkdocs").setLevel(logging.WARNING)  # strict counts warnings it sees
    config = load_config(str(REPO / "mkdocs.yml"), strict=True, site_dir=str(tmp_path / "site"))
    build(config)  # raises mkdocs.exceptions.Abort on any warning
    assert (tmp_path / "site" / "reference" / "index.html").exists()
