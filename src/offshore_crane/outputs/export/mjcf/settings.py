"""The exported model's settings (time step, integrator, solver, constraint softness) and the
:class:`MJCF` it is returned as.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


#: Integration step of the written model [s] (``<option timestep>``); MuJoCo's
#: soft-constraint time constant may not be shorter than two steps (its ``refsafe``).
TIMESTEP = 1e-3
#: ``<option integrator>``: implicit in the velocity-dependent forces, explicit in the
#: constraint forces (MuJoCo's recommended default since 3.0).
INTEGRATOR = "implicitfast"
#: Loop constraints' ``solref``: time constant [s] and damping ratio. The shortest time
#: constant MuJoCo accepts at :data:`TIMESTEP` (2 steps), critically damped.
SOLREF = (2 * TIMESTEP, 1.0)
#: Loop constraints' ``solimp`` (dmin, dmax, width [m], midpoint, power): impedance
#: 0.9999 at every violation, MuJoCo's largest (mjMAXIMP). The constraint force then
#: meets the exact one up to a regulariser of relative size (1 - d)/d = 1e-4.
SOLIMP = (0.9999, 0.9999, 0.001, 0.5, 2.0)
#: MuJoCo's accelerations at our exact states meet ours to this, per coordinate, relative
#: to the largest acceleration the loop constraints produce (:meth:`MujocoForward.agreement`):
#: MuJoCo's regulariser makes the constraint forces err by ~(1 - d)/d = 1e-4 of
#: themselves (MuJoCo scales the regulariser by weights computed at qpos0, so the written
#: pose matters): measured 6.4e-5 for the model written at home, up to 2.1e-4 written
#: off home (benchmarks/mjcf_agreement.py, docs/mjcf.md); the bound is 2.4x above the
#: worst. A 1 % error in the upper leg links' mass gives 1.7e-3.
AGREEMENT = 5e-4
#: Constraint solver: Newton to a tight tolerance (the loops are the only constraints).
SOLVER, SOLVER_TOLERANCE, SOLVER_ITERATIONS = "Newton", 1e-12, 200
#: Joints of the hanging load (docs/cable.md) in the arm_tip frame: phi1 about x, phi2
#: about y.
CABLE_JOINTS = ("cable_joint1", "cable_joint2")
#: A mass below this [kg] counts as none (MuJoCo's mjMINVAL is 1e-15).
MASSLESS = 1e-12
#: MuJoCo's compiler lower bound on a body's principal moments [kg·m²] (``boundinertia``):
#: it reaches only a point mass (the hanging payload, whose moments are zero); its effect
#: on the swing is 1e-12 / (m L²) relative (2e-12 for 2 kg on 0.5 m).
POINT_MASS_INERTIA = 1e-12


@dataclass(frozen=True)
class MJCF:
    """A MuJoCo model of the robot.

    Attributes:
        xml: The MJCF text.
        joints: Names of the model's joints in the order of ``qpos`` and ``qvel`` (all
            have one degree of freedom).
        actuators: Motor names in the order of ``ctrl`` (``T1, T2, Fs, Fl1..Fl6``, the
            arm's three absent for a Stewart platform alone).
        qpos0: ``(nq,)`` the written configuration [m, rad] (loops closed).
        hold: ``(nu,)`` static actuator forces holding ``qpos0`` [N·m, N] (the keyframe
            ``hold``'s ctrl), or None when not computed.
    """

    xml: str
    joints: tuple
    actuators: tuple
    qpos0: np.ndarray
    hold: np.ndarray | None = None
