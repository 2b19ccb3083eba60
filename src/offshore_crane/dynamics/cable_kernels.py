"""Compiled drivers of the hanging load (:mod:`offshore_crane.cable`; imports Numba).

The formulas are those of :mod:`.formulas` (``sway_accelerations``, ``cable_force``,
``kane_sample`` on the arm chain continued by the two sway joints), compiled without
inlining (:data:`.compiled.KE`). Two drivers:

- :func:`integrate`: classical RK4 of the sway state ``y = (φ1, φ2, φ̇1, φ̇2)`` under the
  robot's prescribed motion, given on the grid of RK4's stage times (every half step);
- :func:`kane`: Kane's inverse dynamics of the robot with the payload hanging at the
  integrated sway (the cable's pull enters X through the arm pass), with the cable force
  and the residual of the sway equations (zero up to round-off: a check).

They close over the formulas' hash only (the disk cache keys on it, see
:mod:`.compiled`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from . import compiled as c
from .formulas import STORE_WIDTH

sway_accelerations, cable_force = c.KE.sway_accelerations, c.KE.cable_force
sway_mass, finite_inputs = c.KE.sway_mass, c._finite_inputs
kane_sample, unpack, post, tangent_bounds = c.KE.kane_sample, c.unpack, c._post, c.tangent_bounds
jit = njit(**c.JIT)
#: Stop codes of :func:`integrate` (``status[0]``).
OK, SINGULAR, DIVERGED = 0, 1, 2


def _helpers(stamp):
    """The right-hand side, closed over the formulas' hash (its disk cache key; the
    drivers reach it as a module global, see :mod:`offshore_crane._rk4`)."""

    @jit
    def rhs(C, g, Qh, Qdh, Qddh, i, y, q, qd, qdd, rows, store, out):
        """``out = (φ̇1, φ̇2, φ̈1, φ̈2)`` at stage-grid point ``i`` and sway state ``y``;
        returns ``det M_φφ / M44²`` (``cos²φ2`` for the point mass; 0 on the singular
        set)."""
        if len(stamp) == 0:
            return 0.0
        for j in range(9):
            q[j] = Qh[i, j]
            qd[j] = Qdh[i, j]
            qdd[j] = Qddh[i, j]
        q[9] = y[0]
        q[10] = y[1]
        qd[9] = y[2]
        qd[10] = y[3]
        qdd[9] = 0.0
        qdd[10] = 0.0
        a1, a2, det = sway_accelerations(C, q, qd, qdd, g, rows, store)
        out[0] = y[2]
        out[1] = y[3]
        out[2] = a1
        out[3] = a2
        m44 = sway_mass(C, store)[2]
        return det / (m44 * m44)

    return rhs


rhs = _helpers(c.STAMP)


def _make(stamp):

    @jit
    def integrate(flat, lay, prism, Qh, Qdh, Qddh, g, h, sub, y0, rel_min, Y, status):
        """RK4 of the sway from ``y0`` (4,) with step ``h`` [s]; ``Qh, Qdh, Qddh``
        ``(2 n + 1, 9)`` the robot's motion at every half step (n steps); writes every
        ``sub``-th state to ``Y`` ``(n // sub + 1, 6)``: φ1, φ2 [rad], φ̇1, φ̇2 [rad/s],
        φ̈1, φ̈2 [rad/s²]. ``status`` (3,): stop code, sample index of the stop, and the
        worst ``1 / cos²φ2`` met (the sway inertia's condition); the run stops at the
        first output sample whose state is not finite or whose ``cos²φ2`` falls below
        ``rel_min`` (``Y`` holds every sample before it)."""
        if len(stamp) == 0:
            return
        C = unpack(flat, lay, prism)[0]
        gt = (g[0], g[1], g[2])
        q = np.empty(11)
        qd = np.empty(11)
        qdd = np.empty(11)
        rows = np.zeros(C.n_arm)
        store = np.empty((C.n_arm, STORE_WIDTH))
        y = y0.copy()
        ys = np.empty(4)
        k1 = np.empty(4)
        k2 = np.empty(4)
        k3 = np.empty(4)
        k4 = np.empty(4)
        n_steps = (Qh.shape[0] - 1) // 2
        status[0] = OK
        status[1] = -1
        status[2] = 0.0
        for s in range(n_steps + 1):
            rel = rhs(C, gt, Qh, Qdh, Qddh, 2 * s, y, q, qd, qdd, rows, store, k1)
            if s % sub == 0:
                k = s // sub
                finite = True
                for j in range(4):
                    Y[k, j] = y[j]
                    finite = finite and np.isfinite(y[j])
                Y[k, 4] = k1[2]
                Y[k, 5] = k1[3]
                finite = finite and np.isfinite(k1[2]) and np.isfinite(k1[3])
                worst = 1.0 / rel if rel > 0.0 else np.inf
                if worst > status[2] or not finite:
                    status[2] = worst
                if not finite:
                    status[0] = DIVERGED
                    status[1] = k
                    return
                if not rel >= rel_min:
                    status[0] = SINGULAR
                    status[1] = k
                    return
            if s == n_steps:
                break
            for j in range(4):
                ys[j] = y[j] + 0.5 * h * k1[j]
            rhs(C, gt, Qh, Qdh, Qddh, 2 * s + 1, ys, q, qd, qdd, rows, store, k2)
            for j in range(4):
                ys[j] = y[j] + 0.5 * h * k2[j]
            rhs(C, gt, Qh, Qdh, Qddh, 2 * s + 1, ys, q, qd, qdd, rows, store, k3)
            for j in range(4):
                ys[j] = y[j] + h * k3[j]
            rhs(C, gt, Qh, Qdh, Qddh, 2 * s + 2, ys, q, qd, qdd, rows, store, k4)
            for j in range(4):
                y[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])

    @jit
    def kane(flat, lay, prism, q, qd, qdd, g, want_cond, want_limits, warn, error, start,
             stop, X, kappa, health, F):
        """Samples ``start..stop-1`` of the fused Kane equations of the robot with its
        hanging payload: ``q, qd, qdd`` ``(N, 11)`` (the sway's in columns 9, 10); fills
        X ``(N, 9)`` and ``F`` ``(N, 6)``: the cable's pull on the tip (3) [N, base
        axes], the tension [N], and the residual of the two sway equations [N·m]
        (Kane's rows of the sway speeds, zero when φ̈ solves them)."""
        if len(stamp) == 0:
            return
        C, lim_arm, lim_stroke, lim_ujoint = unpack(flat, lay, prism)
        tb = tangent_bounds(lim_ujoint)
        na = C.n_arm
        rows = np.zeros(na)
        A = np.empty((6, 6))
        rhs6 = np.empty(6)
        diag = np.zeros((7, 6))
        store = np.empty((na, STORE_WIDTH))
        x = np.empty(6)
        M = np.empty((6, 13))
        gt = (g[0], g[1], g[2])
        for k in range(start, stop):
            if not finite_inputs(q, qd, qdd, k, health):
                for j in range(9):
                    X[k, j] = np.nan
                continue
            kane_sample(C, q[k], qd[k], qdd[k], gt, False, 0, True, rows, A, rhs6, diag,
                        store)
            for b in range(3):
                X[k, b] = rows[b]
            f, tension = cable_force(C, store)
            for j in range(3):
                F[k, j] = f[j]
            F[k, 3] = tension
            F[k, 4] = rows[na - 2]
            F[k, 5] = rows[na - 1]
            post(k, q, na, A, rhs6, diag, True, want_cond, want_limits, warn, error,
                 lim_arm, lim_stroke, lim_ujoint, tb, X, kappa, health, x, M)

    return integrate, kane


integrate, kane = _make(c.STAMP)
