"""The Time Domain Passivity Approach (TDPA) for the delayed master–slave channel. No gRPC.

The channel between the operator's hand and the slave's tool is a two-port: the master sends
motion (position increments), the slave sends back force (the wrench in the acks). With delay,
jitter or a stall, that channel can make energy: the slave pushes on for a whole round trip
before the operator feels anything, and the operator's reaction then arrives late too. TDPA
(Ryu, Kwon and Hannaford 2004; Artigas, Ryu, Preusche and Hirzinger 2010, as flown in KONTUR-2)
watches the energy through each port and dissipates, at the port, whatever the other side has
not put in.

Sign conventions. Energies are in joules, forces in newtons in the slave's base axes, and motions
in metres of the slave (the master's hand motion times eq. 2's scale). With force scaled by the
same factor (`slave_wrench_to_master`), the hand does the same work as the tool, so the two ports
are measured in one unit. Per control step k, the energy entering the channel is

    master port:  ΔE_m(k) = −F_d(k) · Δx_h(k)   the hand moving against the displayed force F_d
    slave port:   ΔE_s(k) =  F_e(k) · Δx_s(k)   the environment's force F_e on the tool along
                                                the tool's commanded motion Δx_s

and each port's observer splits it into what went in and what came out (Artigas' network
representation):

    E_in(k) = Σ max(ΔE, 0),   E_out(k) = Σ max(−ΔE, 0)

The channel is passive when neither side has taken out more than the other put in, as far as it
knows (the other side's E_in arrives in the messages, one delay late):

    W_s(k) = E_in_m(k − T_forward)  − E_out_s(k) ≥ 0      checked at the slave
    W_m(k) = E_in_s(k − T_backward) − E_out_m(k) ≥ 0      checked at the master

Passivity controllers keep each W at or above zero:

- at the slave (admittance type, its output is motion) the part of Δx_s that pushes into the
  environment beyond what W_s covers is removed along F_e:  Δx_s' = Δx_s + λ F̂_e with
  λ = (−F_e·Δx_s − W_s) / ‖F_e‖ when −F_e·Δx_s > W_s (Ryu et al. 2004, in increments);
- at the master (impedance type, its output is force) the part of F_d along the hand's motion
  that W_m does not cover is removed: F_d' = F_d − μ ĥ with μ = (F_d·Δx_h − W_m) / ‖Δx_h‖.

What the slave's controller removes is position drift: the slave is short of where the master
sent it. `SlavePassivity` keeps the drift and adds it back to later steps as far as the energy
allows (free motion costs none, so it returns at `drift_return_m` per step once out of contact).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from domain.geometry import vector_norm

# Forces under this are the sensor's noise and the peg's friction: their work is not counted, so
# free motion never starves for energy (a 0.5 N floor over a 40 mm stroke is 20 mJ).
FORCE_DEADBAND_N = 0.5
# How much of the drift goes back per step (slave metres): at 50 commands/s, 10 mm/s.
DRIFT_RETURN_M = 0.0002


@dataclass
class EnergyLedger:
    """A passivity observer: the energy through one port of the channel, split into what went
    in and what came out (joules, since the session began)."""

    energy_in_j: float = 0.0
    energy_out_j: float = 0.0

    def add(self, energy_j: float) -> None:
        """One step's energy into the channel (negative: out of it)."""
        if energy_j > 0.0:
            self.energy_in_j += energy_j
        else:
            self.energy_out_j -= energy_j


def bound_motion(step_m: np.ndarray, force_n: np.ndarray, available_j: float
                 ) -> tuple[np.ndarray, float]:
    """(step', dissipated J): `step_m` less the part that would push against `force_n` (the
    environment's force on the tool) with more energy than `available_j`. Motion across the
    force, or along it (the environment giving way), is never changed."""
    step = np.asarray(step_m, dtype=float)
    force = np.asarray(force_n, dtype=float)
    out_j = -float(force @ step)  # energy this step puts into the environment
    allowed_j = max(available_j, 0.0)
    if out_j <= allowed_j:
        return step, 0.0
    norm = vector_norm(force)
    return step + (out_j - allowed_j) / norm * (force / norm), out_j - allowed_j


def bound_force(force_n: np.ndarray, step_m: np.ndarray, available_j: float
                ) -> tuple[np.ndarray, float]:
    """(force', dissipated J): the displayed force `force_n` less the part along the hand's
    `step_m` that would give the hand more energy than `available_j`. A force the hand moves
    against (it takes energy from the hand) is never changed."""
    force = np.asarray(force_n, dtype=float)
    step = np.asarray(step_m, dtype=float)
    out_j = float(force @ step)  # energy this step gives the hand
    allowed_j = max(available_j, 0.0)
    if out_j <= allowed_j:
        return force, 0.0
    norm = vector_norm(step)
    return force - (out_j - allowed_j) / norm * (step / norm), out_j - allowed_j


def counted_force(force_n: np.ndarray, deadband_n: float = FORCE_DEADBAND_N) -> np.ndarray:
    """The force whose work the observers count: zero under the deadband."""
    force = np.asarray(force_n, dtype=float)
    return force if vector_norm(force) >= deadband_n else np.zeros_like(force)


@dataclass
class SlaveStep:
    step_m: np.ndarray  # what the slave is told to move
    dissipated_j: float  # energy the controller kept out of the environment this step
    drift_m: np.ndarray  # where the slave is short of the master, after this step


@dataclass
class SlavePassivity:
    """The slave port: its observer, the master's E_in as last received, its controller and
    the drift it leaves. Call `step` once per motion command, in order."""

    deadband_n: float = FORCE_DEADBAND_N
    drift_return_m: float = DRIFT_RETURN_M
    ledger: EnergyLedger = field(default_factory=EnergyLedger)
    master_in_j: float = 0.0  # the master's E_in, as last received
    dissipated_j: float = 0.0
    drift_m: np.ndarray = field(default_factory=lambda: np.zeros(3))
    limited_steps: int = 0

    def heard(self, master_energy_in_j: float) -> None:
        """The master's E_in, from a command or heartbeat. It only grows: an older message
        arriving late never lowers it."""
        self.master_in_j = max(self.master_in_j, float(master_energy_in_j))

    @property
    def available_j(self) -> float:
        """W_s: the energy the slave may still put into the environment."""
        return self.master_in_j - self.ledger.energy_out_j

    def step(self, step_m: np.ndarray, force_n: np.ndarray) -> SlaveStep:
        """The master's step (slave metres, base axes), with the drift it can take back, bounded
        by the energy the master has put in; `force_n` is the environment's force on the tool
        now (base axes)."""
        step = np.asarray(step_m, dtype=float)
        force = counted_force(force_n, self.deadband_n)
        wanted = step + _clipped(self.drift_m, self.drift_return_m)
        applied, dissipated = bound_motion(wanted, force, self.available_j)
        self.ledger.add(float(force @ applied))
        self.drift_m = self.drift_m + step - applied
        if dissipated > 0.0:
            self.dissipated_j += dissipated
            self.limited_steps += 1
        return SlaveStep(applied, dissipated, self.drift_m.copy())


@dataclass
class MasterPassivity:
    """The master port: its observer, the slave's E_in as last received, and the controller on
    the displayed force. Call `display` once per control step, in order."""

    deadband_n: float = FORCE_DEADBAND_N
    ledger: EnergyLedger = field(default_factory=EnergyLedger)
    slave_in_j: float = 0.0  # the slave's E_in, as last received
    dissipated_j: float = 0.0
    limited_steps: int = 0

    def heard(self, slave_energy_in_j: float) -> None:
        """The slave's E_in, from an ack. It only grows."""
        self.slave_in_j = max(self.slave_in_j, float(slave_energy_in_j))

    @property
    def available_j(self) -> float:
        """W_m: the energy the displayed force may still give the hand."""
        return self.slave_in_j - self.ledger.energy_out_j

    def display(self, force_n: np.ndarray, hand_step_m: np.ndarray) -> np.ndarray:
        """The force to display (slave newtons, base axes) for the slave's `force_n` while the
        hand moves `hand_step_m` (slave metres) this step; observes the step's energy."""
        force = np.asarray(force_n, dtype=float)
        if vector_norm(force) < self.deadband_n:
            return force  # shown as it is, its work not counted (see FORCE_DEADBAND_N)
        step = np.asarray(hand_step_m, dtype=float)
        shown, dissipated = bound_force(force, step, self.available_j)
        self.ledger.add(-float(shown @ step))
        if dissipated > 0.0:
            self.dissipated_j += dissipated
            self.limited_steps += 1
        return shown


def _clipped(vector: np.ndarray, length: float) -> np.ndarray:
    norm = vector_norm(vector)
    return vector if norm <= length else vector * (length / norm)
