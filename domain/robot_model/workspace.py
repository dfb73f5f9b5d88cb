"""Layout of the simulated work cell around the PUMA 560 (world frame = robot base frame 0).

The robot stands at the origin facing +x. With q1 = 0 its forearm plane sits at
y = -SHOULDER_OFFSET, so the fixture is placed there, straight below the ``home`` tool tip.
All lengths in metres.
"""

from __future__ import annotations

from domain.robot_model.puma560 import SHOULDER_OFFSET

# Table: a solid block standing on the floor. Its top is low enough that the peg reaches it with
# the tool pointing down (wrist centre 0.35 m high, 0.32 m below the shoulder).
TABLE_TOP_Z = 0.25
TABLE_CENTER_XY = (0.60, 0.0)
TABLE_HALF_SIZE_XY = (0.25, 0.40)

# Peg-in-hole fixture: a square block with a square through-hole, built from four boxes.
FIXTURE_CENTER_XY = (0.645, -SHOULDER_OFFSET)
FIXTURE_HALF_WIDTH = 0.06  # outer block half side
FIXTURE_HEIGHT = 0.04
HOLE_HALF_WIDTH = 0.013  # 26 mm square hole for the 20 mm peg: 3 mm of play on each side

# Stereo camera rig in front of the table looking back at the fixture, parallel optical axes.
CAMERA_RIG_CENTER = (1.40, -SHOULDER_OFFSET, 0.90)
CAMERA_TARGET = (0.645, -SHOULDER_OFFSET, 0.40)
STEREO_BASELINE = 0.12
CAMERA_FOVY_DEG = 45.0
LEFT_CAMERA = "left_eye"
RIGHT_CAMERA = "right_eye"

# Named sites on the fixture, for the world and tests.
HOLE_ENTRY_SITE = "hole_entry"  # centre of the hole mouth, fixture top
HOLE_BOTTOM_SITE = "hole_bottom"  # centre of the hole floor (the table top)
