"""Layout of the simulated work cell around an arm (world frame = the arm's base frame).

Every arm gets the same cell, placed under its home pose: a table, the peg-in-hole fixture
straight below the home tool tip, and a stereo camera rig in front looking back at the fixture.
The PUMA 560's cell is the papers' own, with its numbers kept as they were measured; every other
arm's is built around its home tip by ``cell_below``. All lengths in metres.
"""

from __future__ import annotations

from dataclasses import dataclass

from domain.robot_model import fr3, ur5e
from domain.robot_model.puma560 import SHOULDER_OFFSET, TOOL
from domain.robot_model.serial_chain import SerialChain, forward_kinematics

FIXTURE_HALF_WIDTH = 0.06  # outer block half side
FIXTURE_HEIGHT = 0.04
HOLE_HALF_WIDTH = 0.013  # 26 mm square hole for the 20 mm peg: 3 mm of play on each side
STEREO_BASELINE = 0.12
CAMERA_FOVY_DEG = 45.0
LEFT_CAMERA = "left_eye"
RIGHT_CAMERA = "right_eye"

# Named sites on the fixture, for the world and tests.
HOLE_ENTRY_SITE = "hole_entry"  # centre of the hole mouth, fixture top
HOLE_BOTTOM_SITE = "hole_bottom"  # centre of the hole floor (the table top)

HOME_TIP_ABOVE_HOLE = 0.21  # m, the home tool tip above the hole mouth
RIG_FROM_FIXTURE = (0.755, 0.0, 0.65)  # m, rig centre from the fixture's foot
TARGET_ABOVE_FIXTURE = 0.15  # m, where the rig looks, above the fixture's foot


@dataclass(frozen=True)
class WorkCell:
    """Where the table, the fixture and the cameras stand."""

    table_top_z: float
    table_center_xy: tuple[float, float]
    table_half_size_xy: tuple[float, float]
    fixture_center_xy: tuple[float, float]
    camera_rig_center: tuple[float, float, float]
    camera_target: tuple[float, float, float]


# The PUMA 560: its forearm plane sits at y = -SHOULDER_OFFSET with q1 = 0, and the table top is
# low enough that the peg reaches it pointing down (wrist centre 0.35 m high).
PUMA560_CELL = WorkCell(
    table_top_z=0.25,
    table_center_xy=(0.60, 0.0),
    table_half_size_xy=(0.25, 0.40),
    fixture_center_xy=(0.645, -SHOULDER_OFFSET),
    camera_rig_center=(1.40, -SHOULDER_OFFSET, 0.90),
    camera_target=(0.645, -SHOULDER_OFFSET, 0.40),
)


def cell_for(arm: str) -> WorkCell:
    """The cell of an arm the project describes, by name (KeyError for another)."""
    if arm == "puma560":
        return PUMA560_CELL
    chain = {chain.name: chain for chain in (fr3.CHAIN, ur5e.CHAIN)}[arm]
    return cell_below(home_tip(chain))


def home_tip(chain: SerialChain) -> tuple[float, float, float]:
    """Where a chain's tool tip is at home (the peg runs along the flange's z axis)."""
    flange = forward_kinematics(chain, chain.home_q)
    tip = flange[:3, 3] + flange[:3, 2] * TOOL.length
    return (float(tip[0]), float(tip[1]), float(tip[2]))


def cell_below(home_tip: tuple[float, float, float]) -> WorkCell:
    """The cell for an arm whose home tool tip (pointing down) is at ``home_tip``."""
    x, y, z = home_tip
    table_top = z - HOME_TIP_ABOVE_HOLE - FIXTURE_HEIGHT
    dx, dy, dz = RIG_FROM_FIXTURE
    return WorkCell(
        table_top_z=table_top,
        table_center_xy=(x, 0.0),
        table_half_size_xy=(0.25, max(0.40, abs(y) + 0.25)),
        fixture_center_xy=(x, y),
        camera_rig_center=(x + dx, y + dy, table_top + dz),
        camera_target=(x, y, table_top + TARGET_ABOVE_FIXTURE),
    )


# The default arm's cell, by name, for code that works on the PUMA 560's task.
TABLE_TOP_Z = PUMA560_CELL.table_top_z
TABLE_CENTER_XY = PUMA560_CELL.table_center_xy
TABLE_HALF_SIZE_XY = PUMA560_CELL.table_half_size_xy
FIXTURE_CENTER_XY = PUMA560_CELL.fixture_center_xy
CAMERA_RIG_CENTER = PUMA560_CELL.camera_rig_center
CAMERA_TARGET = PUMA560_CELL.camera_target
