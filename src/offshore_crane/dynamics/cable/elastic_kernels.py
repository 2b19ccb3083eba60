"""Compiled driver of the elastic cable (:mod:`offshore_crane.dynamics.cable.elastic`;
imports Numba).

The payload is a point mass whose position ``ρ`` from the tip and velocity ``ρ̇`` relative
to it (base axes) obey ``ρ̈ = g − a_tip − (T / m) u + (F_s + F_d) / m`` with the cable's
law :func:`~offshore_crane.dynamics.sway.cable_tension` clamped to a cable that only
pulls, the sway damping ``F_s`` (:func:`~offshore_crane.dynamics.sway.sway_damping_force`,
carried by the cable: while it is taut and pulling) and the air's drag ``F_d``
(:func:`~offshore_crane.dynamics.sway.drag_force`, at the payload's velocity
``v_tip + ρ̇``). Classical RK4 runs ``sub`` steps per sample interval; the tip's motion
(from :func:`~offshore_crane.dynamics.sway.tip_motion`: its acceleration, and what the
damping and the drag read, its attitude, angular velocity and velocity) and the winch's
length are given at the interval's ends and middle and interpolated quadratically
between (exact at those three points, so ``sub = 1`` is plain RK4 on the stage grid). A
step across which the cable goes slack or taut (the force's derivative jumps there,
RK4's order drops) is done again in ``refine`` steps.
"""

from __future__ import annotations

import hashlib
import inspect

import numpy as np

from offshore_crane.dynamics import compiled as c
from offshore_crane.stops import CODES
from offshore_crane.dynamics.cable import kernels as _ck
from offshore_crane.dynamics.cable.kernels import jit, tip
from offshore_crane.dynamics.integrator import rk4_combine, rk4_stage

#: What these kernels' disk cache is keyed by: the formulas' hash and the text of the
#: cable's kernels they link (``tip``: Numba's cache checks only a function's own file,
#: so a callee edited there was linked stale, calling an entry no longer registered).
STAMP = c.STAMP + hashlib.sha256(inspect.getsource(_ck).encode()).hexdigest()

cable_tension, sway_damping_force = c.K.cable_tension, c.K.sway_damping_force
drag_force = c.K.drag_force
unpack = c.unpack
#: Stop codes (``status[0]``, :class:`~offshore_crane.stops.StopCause`): none, a non-finite state (the payload at the tip), asked
#: to stop (the flag ``halt[0]`` set: a signal, :func:`offshore_crane.progress.run_polled`).
OK, _, _, DIVERGED, STOPPED, _ = CODES
#: Columns of the tip's state ``T`` (21,) (:func:`~.kernels.tip`): its attitude (by rows)
#: and angular velocity, its acceleration, its velocity.
_TURN, _ACC, _VEL = (0, 12), (15, 18), (18, 21)


def _helpers(stamp):
    """The step's pieces, closed over the formulas' hash only; the driver reaches them
    as module globals (a jitted closure variable would defeat the disk cache)."""

    @jit
    def quadratic(y0, ym, y1, theta):
        """The parabola through ``(0, y0), (½, ym), (1, y1)`` at ``theta``."""
        return (y0 * (1.0 - theta) * (1.0 - 2.0 * theta) + 4.0 * ym * theta * (1.0 - theta)
                + y1 * theta * (2.0 * theta - 1.0))

    @jit
    def forcing(A, Lr, theta, sway, drag, Tt, Lt):
        """The tip's state ``Tt`` (21,) and the winch's ``(L, L̇)`` ``Lt`` (2,) at the
        fraction ``theta`` of the interval: ``A`` (3, 21) and ``Lr`` (3, 3) hold them at
        its start, middle and end (rows). Only what is read is formed: the acceleration,
        the attitude and angular velocity with a sway damping (``sway`` (2,) not zero),
        the velocity with a drag ``drag`` > 0."""
        if len(stamp) == 0:
            return
        for j in range(_ACC[0], _ACC[1]):
            Tt[j] = quadratic(A[0, j], A[1, j], A[2, j], theta)
        if sway[0] + sway[1] > 0.0:
            for j in range(_TURN[0], _TURN[1]):
                Tt[j] = quadratic(A[0, j], A[1, j], A[2, j], theta)
        if drag > 0.0:
            for j in range(_VEL[0], _VEL[1]):
                Tt[j] = quadratic(A[0, j], A[1, j], A[2, j], theta)
        for j in range(2):
            Lt[j] = quadratic(Lr[0, j], Lr[1, j], Lr[2, j], theta)

    @jit
    def rhs(Tt, g, y, Lt, EA, damping, sway, drag, m, out, fs):
        """``out = (ρ̇, ρ̈)`` and ``fs`` (3,) the sway damping's force [N]; returns the
        tension [N] (0 slack)."""
        if len(stamp) == 0:
            return 0.0
        rho, rhod = (y[0], y[1], y[2]), (y[3], y[4], y[5])
        T, s, u = cable_tension(rho, rhod, Lt[0], Lt[1], EA, damping)
        if not (s > 0.0 and T > 0.0):
            T = 0.0
        f = (0.0, 0.0, 0.0)
        if sway[0] + sway[1] > 0.0 and T > 0.0:      # carried by the cable: while it pulls
            R = ((Tt[0], Tt[1], Tt[2]), (Tt[3], Tt[4], Tt[5]), (Tt[6], Tt[7], Tt[8]))
            f = sway_damping_force(R, (Tt[9], Tt[10], Tt[11]), rho, rhod, sway[0], sway[1])
        for j in range(3):
            fs[j] = f[j]
        if drag > 0.0:
            d = drag_force((Tt[18] + y[3], Tt[19] + y[4], Tt[20] + y[5]), drag)
            f = (f[0] + d[0], f[1] + d[1], f[2] + d[2])
        for j in range(3):
            out[j] = y[3 + j]
            out[3 + j] = g[j] - Tt[_ACC[0] + j] - T / m * u[j] + f[j] / m
        return T

    @jit
    def steps(A, Lr, g, y, theta0, dtheta, n, dt, EA, damping, sway, drag, m, w, Tt, Lt, fs):
        """``n`` RK4 steps of ``dtheta`` (fractions of the interval ``dt`` [s]) from
        ``theta0``, in place; ``w`` (6, 6), ``Tt`` (21,), ``Lt`` (2,), ``fs`` (3,)
        workspaces. Returns True when the cable's state (taut or slack) flipped in one
        of them (with ``n = 1``: in the step)."""
        if len(stamp) == 0:
            return False
        k1, k2, k3, k4, ys = w[0], w[1], w[2], w[3], w[4]
        h = dtheta * dt
        flipped = False
        for i in range(n):
            th = theta0 + i * dtheta
            forcing(A, Lr, th, sway, drag, Tt, Lt)
            before = rhs(Tt, g, y, Lt, EA, damping, sway, drag, m, k1, fs) > 0.0
            forcing(A, Lr, th + 0.5 * dtheta, sway, drag, Tt, Lt)
            rk4_stage(y, k1, 0.5 * h, ys)
            rhs(Tt, g, ys, Lt, EA, damping, sway, drag, m, k2, fs)
            rk4_stage(y, k2, 0.5 * h, ys)
            rhs(Tt, g, ys, Lt, EA, damping, sway, drag, m, k3, fs)
            forcing(A, Lr, th + dtheta, sway, drag, Tt, Lt)
            rk4_stage(y, k3, h, ys)
            rhs(Tt, g, ys, Lt, EA, damping, sway, drag, m, k4, fs)
            rk4_combine(y, h, k1, k2, k3, k4)
            after = rhs(Tt, g, y, Lt, EA, damping, sway, drag, m, w[5], fs) > 0.0
            flipped = flipped or (before != after)
        return flipped

    return quadratic, forcing, rhs, steps


quadratic, forcing, rhs, steps = _helpers(STAMP)


def _make(stamp):

    @jit
    def integrate(flat, lay, prism, Qh, Qdh, Qddh, Lh, g, sub, refine, dt, EA, damping, sway,
                  drag, m, y0, Y, status, halt):
        """RK4 of the payload from ``y0`` (6,) = ρ [m], ρ̇ [m/s] (base axes, relative to
        the tip) along the samples ``dt`` [s] apart, ``sub`` steps an interval (a step
        that flips the cable's state redone in ``refine``); ``Qh, Qdh, Qddh``
        ``(2 N − 1, 9)`` the robot's motion at the samples and midpoints, ``Lh`` the
        winch's ``(L, L̇, L̈)`` there ``(2 N − 1, 3)`` (or ``(1, 3)``: fixed); ``sway`` (2,)
        the sway angles' damping [N·m·s/rad], ``drag`` the payload's ``½ ρ C_d A`` [kg/m].
        Writes
        ``Y`` ``(N, 11)``: ρ, ρ̇, the tension [N], the stretch [m] and the sway damping's
        force on the payload [N]; ``status`` (3,): stop code, the sample of the stop, the
        count of refined steps. Ends before a sample when ``halt[0]`` (1,) is not zero."""
        if len(stamp) == 0:
            return
        C = unpack(flat, lay, prism)[0]
        gt = np.array([g[0], g[1], g[2]])
        q = np.empty(9)
        qd = np.empty(9)
        qdd = np.empty(9)
        T = np.zeros((3, 21))
        Lr = np.empty((3, 3))
        w = np.empty((6, 6))
        Tt = np.zeros(21)
        Lt = np.empty(2)
        fs = np.zeros(3)
        y = y0.copy()
        keep = np.empty(6)
        N = Y.shape[0]
        want_v = drag > 0.0
        status[0] = OK
        status[1] = -1
        status[2] = 0.0
        dtheta = 1.0 / sub
        for k in range(N):
            if halt[0] != 0:
                status[0] = STOPPED
                status[1] = k
                return
            tip(C, Qh, Qdh, Qddh, 2 * k, q, qd, qdd, T[0], want_v)
            r = 2 * k if Lh.shape[0] > 1 else 0
            Lt[0] = Lh[r, 0]
            Lt[1] = Lh[r, 1]
            tension = rhs(T[0], gt, y, Lt, EA, damping, sway, drag, m, w[5], fs)
            finite = True
            for j in range(6):
                Y[k, j] = y[j]
                finite = finite and np.isfinite(y[j])
            Y[k, 6] = tension
            Y[k, 7] = np.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]) - Lt[0]
            for j in range(3):
                Y[k, 8 + j] = fs[j]
            if not finite or not np.isfinite(tension):
                status[0] = DIVERGED
                status[1] = k
                return
            if k == N - 1:
                break
            tip(C, Qh, Qdh, Qddh, 2 * k + 1, q, qd, qdd, T[1], want_v)
            tip(C, Qh, Qdh, Qddh, 2 * k + 2, q, qd, qdd, T[2], want_v)
            for i in range(3):
                ri = 2 * k + i if Lh.shape[0] > 1 else 0
                for j in range(3):
                    Lr[i, j] = Lh[ri, j]
            for i in range(sub):
                for j in range(6):
                    keep[j] = y[j]
                if steps(T, Lr, gt, y, i * dtheta, dtheta, 1, dt, EA, damping, sway, drag,
                         m, w, Tt, Lt, fs):
                    for j in range(6):
                        y[j] = keep[j]
                    steps(T, Lr, gt, y, i * dtheta, dtheta / refine, refine, dt, EA,
                          damping, sway, drag, m, w, Tt, Lt, fs)
                    status[2] += 1.0

    return integrate


integrate = _make(STAMP)
