"""Kane inverse dynamics of a general serial robot read from a URDF (paper §3.2).

The paper's Section 3.2 (Eqs. 27-31) writes Kane's equations for a serial chain: body
positions from the joint axes, partial velocities ``v_r`` of the centres of mass and
partial angular velocities ``w_r`` from the chain, and ``F_r + F*_r = 0`` solved for the
joint torques and forces. For a fixed base every generalized speed is a joint rate
(``u_r = q̇_r``), so the actuator's generalized force is alone on row ``r`` and

    τ_r = Σ_bodies [v_r · m (a − g) + w_r · (I α + ω × I ω)] − (v_r^P · F + w_r^P · M),

the last term for an external wrench ``(F, M)`` acting on the robot at the origin ``P``
of a tip frame. The sums are evaluated with the partial velocities factored, by the same
formulas as the hybrid robot's arm: the forward recursion
(:func:`~offshore_crane.dynamics.formulas.arm_forward`) gives each body's wrench and the
backward accumulation (:func:`~offshore_crane.dynamics.formulas.arm_backward`) projects
the wrenches beyond each joint on its axis.

Quick start::

    from offshore_crane import serial
    chain = serial.load_chain("panda.urdf", tip="panda_hand")   # fingers locked at 0
    q, qd, qdd = serial.random_states(chain, 100, seed=0)       # (100, 7) each
    tau = serial.inverse_dynamics(chain, q, qd, qdd)            # (100, 7) [N·m]

:mod:`offshore_crane.serial.reference` gives the same quantities from Pinocchio's RNEA
(cross-check); :mod:`offshore_crane.cli.serial_id` is ``offshore-crane serial-id``.
"""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr

from offshore_crane.robot.chain import SerialChain
from offshore_crane.serial.core import GRAVITY, inverse_dynamics, load_chain, random_states

__all__ = ["SerialChain", "GRAVITY", "load_chain", "inverse_dynamics", "random_states"]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
