"""The hanging load by Pinocchio: an independent check of :mod:`offshore_crane.dynamics.cable`.

It shares only the URDF with the Kane path. The pendulum is the two sway joints
``cable_joint1``, ``cable_joint2`` of Pinocchio's model of the equivalent tree, the payload
the mass below them; the robot's motion is prescribed, so this is hybrid dynamics:

- sway accelerations: with the tree at the robot's state (the platform's virtual joints
  take q1..q6 and their rates directly, the arm joints q7..q9; the legs are other
  branches and do not act on the sway rows) and the sway at ``(φ, φ̇)``,
  ``b = RNEA(q, v, a with φ̈ = 0)`` on the sway rows and ``M_φφ`` from CRBA give
  ``φ̈ = −M_φφ⁻¹ b``, integrated by the same classical RK4 (in Python: a reference, not a
  fast path);
- actuator forces: the RNEA reference's loop-closing tree states
  (:func:`offshore_crane.reference.rnea.tree_state`) with the sway joints' rows set,
  ``pin.rneaInParallel`` and the RNEA reference's projection on the independent speeds
  (:func:`offshore_crane.reference.rnea.rnea_projected`); the residual torque on the sway
  joints (zero when φ̈ solves the sway equations) and the cable's pull on the tip,
  ``m (g − a_payload)`` from Pinocchio's frame acceleration.

A winch (``hoist``): the payload's point mass moves from the last sway joint's body to
a prismatic joint ``cable_hoist`` appended after it, along the cable (−z of
``cable_link2``), whose coordinate is the cable's length L(t), prescribed like the
robot's; the sway rows see its rate and acceleration through RNEA and CRBA, the winch's
line pull is minus the RNEA force on that joint, and X is the projection of the tree's
torques (the appended joint is the last speed, so the tree's rows keep their places).

The payload's air drag (the URDF's ``<drag area air_density>`` of the link ``payload``):
``f = −½ ρ C_d A |v| v`` at the payload frame's velocity v from Pinocchio's kinematics of
the tree state, entering every joint as ``Jᵀ f`` (J the frame's Jacobian, world axes):
subtracted from RNEA's torques on the sway rows and before the projection on X, added
to the pull.

Everything it needs of the robot it reads from ``robot.pinocchio_model`` (the payload's
mass, the sway joints' damping) and ``robot.urdf`` (the drag); it checks nothing: the
caller (``offshore_crane.dynamics.cable``) applies the workspace limits and the
singularity policy to the diagnostics it returns.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from offshore_crane.conventions import ARM_JOINTS, CABLE_JOINTS, N_LEGS, PLATFORM_JOINTS
from offshore_crane.errors import require
from offshore_crane.reference.rnea import Forces, rnea_projected, tree_state
from offshore_crane.reference.rnea.projection import project, read_tree
from offshore_crane.stops import CODES

#: The prismatic joint a winch adds along the cable (the payload its body).
#: The integration's stop codes (:class:`~offshore_crane.stops.StopCause`).
_, _, SINGULAR, DIVERGED, _, _ = CODES
HOIST_JOINT = "cable_hoist"


def _drag(urdf: str) -> float:
    """``½ ρ C_d A`` [kg/m] of the URDF's ``<drag area air_density/>`` in the link
    ``payload`` (0 without one)."""
    import xml.etree.ElementTree as ET

    link = ET.fromstring(urdf).find("link[@name='payload']")
    el = None if link is None else link.find("drag")
    return 0.0 if el is None else 0.5 * float(el.get("air_density")) * float(el.get("area"))


class _Pendulum:
    """Pinocchio's model of the robot with the sway joints, and its indices."""

    def __init__(self, robot, g, hoisted: bool = False):
        pin = self.pin = require("pinocchio", "pin", "The hanging load's Pinocchio reference")
        model = robot.pinocchio_model.copy()
        model.gravity.linear = np.asarray(g, dtype=float)
        jid = model.getJointId
        self.hoist = None
        if hoisted:                 # the payload on a prismatic joint along the cable
            last = jid(CABLE_JOINTS[-1])
            mass = model.inertias[last].mass            # the sway links are massless
            model.inertias[last] = pin.Inertia.Zero()
            joint = model.addJoint(last, pin.JointModelPrismaticUnaligned(
                np.array([0.0, 0.0, -1.0])), pin.SE3.Identity(), HOIST_JOINT)
            model.appendBodyToJoint(joint, pin.Inertia(mass, np.zeros(3), np.zeros((3, 3))),
                                    pin.SE3.Identity())
            model.addFrame(pin.Frame("hoisted_payload", joint, 0, pin.SE3.Identity(),
                                     pin.FrameType.OP_FRAME))
            self.hoist = (model.idx_qs[joint], model.idx_vs[joint])
        self.model, self.data = model, model.createData()
        self.coords = [(model.idx_qs[jid(n)], model.idx_vs[jid(n)], k)
                       for k, n in enumerate(PLATFORM_JOINTS + ARM_JOINTS)
                       if model.existJointName(n)]
        self.sway_q = np.array([model.idx_qs[jid(n)] for n in CABLE_JOINTS])
        self.sway_v = np.array([model.idx_vs[jid(n)] for n in CABLE_JOINTS])
        self.payload = model.getFrameId("hoisted_payload" if hoisted else "payload")
        self.mass = float(sum(model.inertias[j].mass for j in range(model.njoints)
                              if j >= jid(CABLE_JOINTS[0])))
        self.g = np.asarray(g, dtype=float)
        self.damping = np.asarray(model.damping)[self.sway_v]      # URDF <dynamics damping>
        self.drag = _drag(robot.urdf)                              # URDF <drag>

    def drag_torques(self, x, v):
        """``(Jᵀ f (nv,), f (3,))``: the payload's drag ``f = −drag |v| v`` [N] (world
        axes) at the tree's state ``x, v`` and its generalized forces."""
        pin, model, data = self.pin, self.model, self.data
        frame = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
        pin.forwardKinematics(model, data, x, v)
        pin.computeJointJacobians(model, data, x)
        pin.updateFramePlacements(model, data)
        vel = np.asarray(pin.getFrameVelocity(model, data, self.payload, frame).linear)
        f = -self.drag * np.linalg.norm(vel) * vel
        J = pin.getFrameJacobian(model, data, self.payload, frame)[:3]
        return J.T @ f, f

    def state(self, q9, qd9, qdd9, y, phidd=(0.0, 0.0), L=None):
        """Pinocchio's ``(q, v, a)`` at the robot's state, the sway ``y`` and its
        accelerations ``phidd``, and the hoisted length, rate, acceleration ``L`` (3,)."""
        m = self.model
        x, v, a = np.zeros(m.nq), np.zeros(m.nv), np.zeros(m.nv)
        for iq, iv, k in self.coords:
            x[iq], v[iv], a[iv] = q9[k], qd9[k], qdd9[k]
        x[self.sway_q] = y[0:2]
        v[self.sway_v] = y[2:4]
        a[self.sway_v] = phidd
        if self.hoist is not None:
            x[self.hoist[0]], v[self.hoist[1]], a[self.hoist[1]] = L
        return x, v, a

    def rhs(self, q9, qd9, qdd9, y, out, L=None):
        """``out = (φ̇, φ̈)``; returns ``det M_φφ / M44²``."""
        pin = self.pin
        x, v, a = self.state(q9, qd9, qdd9, y, L=L)
        tau = pin.rnea(self.model, self.data, x, v, a)
        if self.drag > 0.0:
            tau = tau - self.drag_torques(x, v)[0]
        M = pin.crba(self.model, self.data, x)
        i, j = self.sway_v
        m11, m12, m22 = M[i, i], M[min(i, j), max(i, j)], M[j, j]
        b1, b2 = tau[[i, j]] + self.damping * y[2:4]
        det = m11 * m22 - m12 * m12
        out[0:2] = y[2:4]
        out[2] = (m12 * b2 - m22 * b1) / det
        out[3] = (m12 * b1 - m11 * b2) / det
        return det / (m22 * m22)


def integrate(robot: Any, Q: np.ndarray, Qd: np.ndarray, Qdd: np.ndarray, g: np.ndarray,
              h: float, sub: int, y0: np.ndarray, rel_min: float,
              hoist: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """RK4 of the sway with Pinocchio's right-hand side; same contract as the compiled
    :func:`offshore_crane.dynamics.cable.kernels.integrate`.

    Args:
        Q, Qd, Qdd: ``(2 n + 1, 9)`` the robot's motion at the steps and half steps.
        g: ``(3,)`` gravity [m/s²]; ``h``: the step [s]; ``sub``: steps per output sample.
        y0: ``(4,)`` initial sway ``(φ1, φ2)`` [rad] and rates [rad/s].
        rel_min: the smallest ``det M_φφ / M44²`` accepted (1 / the error threshold).
        hoist: ``(2 n + 1, 3)`` a winch's cable length [m], rate, acceleration at the
            same points, or None (the URDF's fixed length).

    Returns:
        ``(Y, status)``: ``Y`` ``(n // sub + 1, 6)`` sway, rates, accelerations at the
        output samples (NaN after a stop); ``status`` ``(3,)``: stop code (0 none, 1
        singular, 2 non-finite), the output sample of the stop, worst ``1/rel``.
    """
    P = _Pendulum(robot, g, hoisted=hoist is not None)
    n_steps = (Q.shape[0] - 1) // 2

    def L(i):
        return None if hoist is None else hoist[i]

    Y = np.full((n_steps // sub + 1, 6), np.nan)
    status = np.array([0.0, -1.0, 0.0])
    y = np.array(y0, dtype=float)
    k1, k2, k3, k4 = (np.empty(4) for _ in range(4))
    for s in range(n_steps + 1):
        rel = P.rhs(Q[2 * s], Qd[2 * s], Qdd[2 * s], y, k1, L(2 * s))
        if s % sub == 0:
            k = s // sub
            Y[k, 0:4] = y
            Y[k, 4:6] = k1[2:4]
            worst = 1.0 / rel if rel > 0 else np.inf
            finite = bool(np.isfinite(Y[k]).all())
            status[2] = max(status[2], worst) if finite else np.inf
            if not finite or not rel >= rel_min:
                status[0], status[1] = (DIVERGED if not finite else SINGULAR), k
                return Y, status
        if s == n_steps:
            break
        P.rhs(Q[2 * s + 1], Qd[2 * s + 1], Qdd[2 * s + 1], y + 0.5 * h * k1, k2,
              L(2 * s + 1))
        P.rhs(Q[2 * s + 1], Qd[2 * s + 1], Qdd[2 * s + 1], y + 0.5 * h * k2, k3,
              L(2 * s + 1))
        P.rhs(Q[2 * s + 2], Qd[2 * s + 2], Qdd[2 * s + 2], y + h * k3, k4, L(2 * s + 2))
        y = y + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    return Y, status


def forces(robot: Any, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray, Y: np.ndarray,
           g: np.ndarray, *, conditioning: bool = False,
           hoist: np.ndarray | None = None) -> tuple[Forces, np.ndarray]:
    """The actuator forces and the cable's pull at the integrated sway, unchecked.

    Args:
        q, qd, qdd: ``(n, 9)`` the robot's motion [m, rad], rates, accelerations.
        Y: ``(n, 6)`` the sway ``(φ1, φ2)`` [rad], its rates and accelerations.
        g: ``(3,)`` gravity in the base frame [m/s²].
        conditioning: Measure the leg-force systems' condition numbers.
        hoist: ``(n, 3)`` a winch's cable length [m], rate [m/s], acceleration [m/s²],
            or None.

    Returns:
        ``(forces, F)``: :class:`~offshore_crane.reference.rnea.Forces` (X from the RNEA
        reference with the sway rows set, its condition numbers and leg diagnostics, for
        the caller's checks) and ``F`` ``(n, 6)``: the cable's pull on the tip (3) [N],
        the tension [N] (with a winch: minus the RNEA force on the hoist joint, the line
        pull the winch holds), the RNEA torques left on the sway joints (2) [N·m].
    """
    pin = require("pinocchio", "pin", "The hanging load's Pinocchio reference")
    P = _Pendulum(robot, g, hoisted=hoist is not None)
    n = len(q)
    F = np.empty((n, 6))
    if n == 0:
        return Forces(np.empty((0, 9)), np.empty(0), *(np.empty((0, N_LEGS)),) * 3,
                      np.empty((0, N_LEGS, 2))), F
    Qt, Vt, At, G, diag = tree_state(robot, q, qd, qdd)
    for arr, col in ((Qt, 0), (Vt, 2), (At, 4)):
        arr[P.sway_v] = Y[:, col:col + 2].T
    drag = np.zeros((n, 3))
    if hoist is None and P.drag == 0.0:
        X, cond, tau = rnea_projected(robot, Qt, Vt, At, G, g, conditioning=conditioning)
    else:                          # with a winch: the tree with the hoist joint appended,
        ext = [np.asfortranarray(arr if hoist is None else      # one more row
                                 np.vstack([arr, hoist[:, col][None, :]]))
               for arr, col in ((Qt, 0), (Vt, 1), (At, 2))]
        tau = np.empty_like(ext[0], order="F")
        pin.rneaInParallel(1, pin.ModelPool(P.model, 1), *ext, tau)
        if P.drag > 0.0:           # the payload's drag enters every joint as Jᵀ f
            for k in range(n):
                jf, drag[k] = P.drag_torques(ext[0][:, k], ext[1][:, k])
                tau[:, k] -= jf
        T = read_tree(robot)
        X, cond = np.empty((n, 9)), np.empty(n)
        project(np.ascontiguousarray((tau if hoist is None else tau[:-1]).T), G, T.plat_v,
                T.legs.v_index, T.arm_v, 1.0 / T.L, conditioning, X, cond)
    F[:, 4:6] = tau[P.sway_v].T + P.damping * Y[:, 2:4]
    model, data = P.model, P.data
    for k in range(n):
        x, v, a = P.state(q[k], qd[k], qdd[k], Y[k, 0:4], Y[k, 4:6],
                          None if hoist is None else hoist[k])
        pin.forwardKinematics(model, data, x, v, a)
        acc = pin.getFrameClassicalAcceleration(model, data, P.payload,
                                                pin.ReferenceFrame.LOCAL_WORLD_ALIGNED).linear
        f = P.mass * (P.g - np.asarray(acc)) + drag[k]
        pin.updateFramePlacement(model, data, P.payload)
        tip = data.oMi[model.getJointId(CABLE_JOINTS[0])].translation
        e = data.oMf[P.payload].translation - tip
        F[k, 0:3] = f
        F[k, 3] = f @ e / np.linalg.norm(e) if hoist is None else -tau[P.hoist[1], k]
    return Forces(X, cond, diag[0], diag[1], diag[2], np.stack([diag[3], diag[4]], -1)), F
