"""The operator's master arm and its CAT functions (section II.4 of the full paper).

Domain code only: no gRPC here (the operator station couples it to ``clients.python``).

* ``model``     -- `MasterModel`: a 6R master arm built in Pinocchio; G_M(θ), Jacobian,
  D(q), C(q, q̇), G(q), IK
* ``sources``   -- joint readings: `SimulatedHand` (default), `ScriptedSource` (file format in
  its docstring), `SpaceMouseSource` (optional ``pyspacemouse``)
* ``cat``       -- increments ΔX, ΔM against the reference, and eq. 2's scaling
* ``impedance`` -- eq. 3/4 impedance control and force feedback τ_ff = Jᵀ F
* ``arm``       -- `MasterArm`: indexing (clutch), scaling, increments, motor torques
"""

from clients.master.arm import JointStateEstimator, MasterArm
from clients.master.cat import Increment, IncrementFrame, hand_increment, scale
from clients.master.impedance import (
    FULL_INERTIA,
    ImpedanceController,
    ImpedanceTorques,
    slave_wrench_to_master,
)
from clients.master.model import HAND_FRAME, MASTER_LINKS, LinkSpec, MasterModel
from clients.master.sources import (
    JointReading,
    JointSource,
    Script,
    ScriptedSource,
    SimulatedHand,
    SpaceMouseSource,
    SpaceMouseUnavailable,
    circle_path,
    line_path,
    load_script,
)

__all__ = [
    "FULL_INERTIA", "HAND_FRAME", "MASTER_LINKS", "ImpedanceController", "ImpedanceTorques",
    "Increment", "IncrementFrame", "JointReading", "JointSource", "JointStateEstimator",
    "LinkSpec", "MasterArm", "MasterModel", "Script", "ScriptedSource", "SimulatedHand",
    "SpaceMouseSource", "SpaceMouseUnavailable", "circle_path", "hand_increment", "line_path",
    "load_script", "scale", "slave_wrench_to_master",
]
