"""The element names every arm description file uses, so code finds them on any arm.

An arm's own joints and motors are named by its file (``GetArmInfo`` reports them); these are the
fixed points the station looks up by name on every arm.
"""

from __future__ import annotations

BASE_BODY = "base"
TOOL_BODY = "tool"
FLANGE_SITE = "flange"  # the mounting face of the last link
FT_SITE = "wrist_ft"  # force/torque sensor frame, on the tool body at the flange
TOOL_SITE = "tool_point"  # peg tip, z axis along the peg
FORCE_SENSOR = "wrist_force"
TORQUE_SENSOR = "wrist_torque"
HOME_KEY = "home"
# <custom><numeric name=...>: one bound per joint, in joint order (MJCF has no velocity limit)
MAX_VELOCITY_NUMERIC = "max_joint_velocity"  # rad/s
