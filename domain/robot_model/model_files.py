"""Locations of the generated, committed MJCF files (written by ``mjcf.py``)."""

from __future__ import annotations

from pathlib import Path

MODEL_DIR = Path(__file__).resolve().parent
ROBOT_XML_PATH = MODEL_DIR / "puma560.xml"  # the arm alone: Pinocchio loads this
SCENE_XML_PATH = MODEL_DIR / "scene.xml"  # the work cell including the arm: MuJoCo loads this
