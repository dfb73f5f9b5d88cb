"""Where each arm's description files live (written by ``mjcf.py``, committed).

``arms/<arm>/arm.xml`` is the arm alone (Pinocchio loads it); ``arms/<arm>/scene.xml`` is the work
cell including the arm (MuJoCo loads it).
"""

from __future__ import annotations

from pathlib import Path

MODEL_DIR = Path(__file__).resolve().parent
ARMS_DIR = MODEL_DIR / "arms"
ARM_FILE = "arm.xml"
SCENE_FILE = "scene.xml"
DEFAULT_ARM = "puma560"


def arm_xml_path(arm: str) -> Path:
    return ARMS_DIR / arm / ARM_FILE


def scene_xml_path(arm: str) -> Path:
    return ARMS_DIR / arm / SCENE_FILE
