"""Compiled drivers of the hanging load (:mod:`offshore_crane.dynamics.cable`; imports Numba).

The formulas are those of :mod:`offshore_crane.dynamics.formulas` (``tip_motion``,
``pendulum``, ``cable_force``, ``kane_sample`` on the arm chain continued by the two sway
joints), compiled inlined (:data:`offshore_crane.dynamics.compiled.K`). Two drivers:

- :func:`integrate`: classical RK4 of the sway state ``y = (φ1, φ2, φ̇1, φ̇2)`` under the
  robot's prescribed motion, given on the grid of RK4's stage times (every half step):
  the tip's motion (``tip_motion``) drives the pendulum's equations (``pendulum``);
- :func:`kane`: Kane's inverse dynamics of the robot with the payload hanging at the
  integrated sway (the cable's pull enters X through the arm pass), with the cable force
  and the residual of the sway equations (zero up to round-off: a check);
- :func:`accelerations` and :func:`computed_torque`: the equations of motion of the 11
  coordinates (q1..q9, φ1, φ2) by the explicit Kane pass on the chain with the sway
  joints, ``M a + h = [A X; −c φ̇]``, and the computed-torque law that knows the sway
  (the forward simulation with the swing, :mod:`offshore_crane.simulation.swing`).

They close over the formulas' hash only (the disk cache keys on it, see
:mod:`offshore_crane.dynamics.compiled`).
"""

from __future__ import annotations

import hashlib
import inspect

import numpy as np
from offshore_crane.stops import CODES
from offshore_crane import kernel_calls
from offshore_crane.kernel_cache import njit

from offshore_crane.dynamics import compiled as c
from offshore_crane.dynamics.cable import work as _work
from offshore_crane.dynamics.cable.work import WORK, carve_accelerations, carve_law  # noqa: F401
from offshore_crane.dynamics.formulas import STORE_WIDTH
from offshore_crane.dynamics.integrator import rk4_combine, rk4_stage

#: The tip's motion and frame (:data:`~offshore_crane.dynamics.compiled.KE`'s), called
#: by address (:mod:`offshore_crane.kernel_calls`), not inlined: seven kernels here run
#: them, and each inlined copy of the arm's kinematics cost its kernel seconds of compile
#: (a first hanging-load ``simulate`` compiled them five times over); by address, a helper
#: process compiles them once beside the kernels that call them. A call a stage costs
#: the run little (the commit log measures both).
_V3 = "UniTuple(float64, 3)"
TIP_MOTION = kernel_calls.Entry.typed(
    "tip_motion", lambda: c.KE.tip_motion,
    f"Tuple((UniTuple({_V3}, 3), {_V3}, {_V3}, {_V3}))(C, V, V, V)", c.STAMP,
    C=c.kane_constants_type())
TIP_FRAME = kernel_calls.Entry.typed("tip_frame", lambda: c.KE.tip_frame,
                                     f"Tuple(({_V3}, {_V3}, UniTuple({_V3}, 3), {_V3}))"
                                     "(C, V, V)", c.STAMP, C=c.kane_constants_type())
tip_motion, tip_frame = TIP_MOTION.call, TIP_FRAME.call
pendulum, hoisted_pendulum, cable_force = c.K.pendulum, c.K.hoisted_pendulum, c.K.cable_force
sway_direction, mv, axpy, scale = c.K.sway_direction, c.K.mv, c.K.axpy, c.K.scale
hanging_velocity, drag_force = c.K.hanging_velocity, c.K.drag_force
explicit_sample, cholesky_solve, solve6 = c.call_explicit, c.cholesky_solve, c.solve6
kinetic_energy = c.kinetic_energy
actuation_minus_bias = c.actuation_minus_bias
#: The Kane passes, compiled once and called by address (:data:`offshore_crane.dynamics.
#: passes.KANE`, ``KANE_PULL``): :func:`kane`'s, the law's (:func:`computed_torque`) and
#: :func:`kane_pulled`'s.
kane_sample_call, kane_sample_pull_call = c.call_kane, c.call_kane_pull
finite_inputs = c._finite_inputs
unpack, post, tangent_bounds = c.unpack, c._post, c.tangent_bounds
jit = njit(**c.JIT)
#: Stop codes of :func:`integrate` (``status[0]``, :class:`~offshore_crane.stops.
#: StopCause`); STOPPED: asked to (its flag set by
#: :func:`offshore_crane.progress.run_polled` on a signal, which the caller raises).
OK, _, SINGULAR, DIVERGED, STOPPED, _ = CODES


def _helpers(stamp):
    """The right-hand side pieces, closed over the formulas' hash (their disk cache key;
    the drivers reach them as module globals, see
    :mod:`offshore_crane.simulation.rigid_equations`)."""

    @jit
    def tip(C, Qh, Qdh, Qddh, i, q, qd, qdd, out, want_v):
        """``out`` (21,) = R_base_tip (by rows), ω, α, a of the tip at stage point ``i``,
        and with ``want_v`` its velocity [m/s] (else ``out[18:21]`` is left as it was)."""
        if len(stamp) == 0:
            return
        for j in range(9):
            q[j] = Qh[i, j]
            qd[j] = Qdh[i, j]
            qdd[j] = Qddh[i, j]
        R, w, al, a = tip_motion(C, q, qd, qdd)
        for r in range(3):
            for j in range(3):
                out[3 * r + j] = R[r][j]
            out[9 + r] = w[r]
            out[12 + r] = al[r]
            out[15 + r] = a[r]
        if want_v:
            v = tip_frame(C, q, qd)[1]
            for r in range(3):
                out[18 + r] = v[r]

    @jit
    def rhs(C, g, damp, drag, T, y, L, i, out):
        """``out = (φ̇1, φ̇2, φ̈1, φ̈2)`` for the tip state ``T`` (21,) and sway ``y`` on a
        cable of length ``L[i, 0]`` [m] hoisted at ``L[i, 1]`` [m/s] (row 0 when ``L`` has
        one row: a fixed length), the payload's drag ``½ ρ C_d A`` = ``drag`` [kg/m] (the
        tip's velocity in ``T[18:21]`` when > 0); returns ``cos²φ2`` (0 on the singular
        set)."""
        if len(stamp) == 0:
            return 0.0
        j = i if L.shape[0] > 1 else 0
        R = ((T[0], T[1], T[2]), (T[3], T[4], T[5]), (T[6], T[7], T[8]))
        w = (T[9], T[10], T[11])
        f = (0.0, 0.0, 0.0)
        if drag > 0.0:
            f = drag_force(hanging_velocity(R, w, (T[18], T[19], T[20]), y[0], y[1], y[2],
                                            y[3], L[j, 0], L[j, 1]), drag)
        a1, a2, cos2, _, _ = hoisted_pendulum(
            C, R, w, (T[12], T[13], T[14]), (T[15], T[16], T[17]), g, y[0], y[1], y[2],
            y[3], damp[0], damp[1], f, L[j, 0], L[j, 1], L[j, 2])
        out[0] = y[2]
        out[1] = y[3]
        out[2] = a1
        out[3] = a2
        return cos2

    @jit
    def velocity(C, q, qd, zero):
        """The payload's velocity [m/s] (base axes) at the state ``q, qd`` (11,) of the
        chain with the sway joints (``zero``: zeros (11,), a workspace)."""
        if len(stamp) == 0:
            return (0.0, 0.0, 0.0)
        na = C.n_arm
        Rt, w, _, _ = tip_motion(C, q, qd, zero)
        return hanging_velocity(Rt, w, tip_frame(C, q, qd)[1], q[na + 4], q[na + 5],
                                qd[na + 4], qd[na + 5], -C.arm_c[na - 1, 2], 0.0)

    @jit
    def set_length(flat, lay, prism, L):
        """Put the payload of the arrays ``flat`` at ``L`` [m] below the sway joints (a
        winch's length: the chain's last centre of mass, ``(0, 0, −L)``; ``flat`` is
        written, so it must be the caller's own copy)."""
        if len(stamp) == 0:
            return
        C = unpack(flat, lay, prism)[0]
        C.arm_c[C.n_arm - 1, 2] = -L

    @jit
    def hoisting(C, q, qd, zero, v, Ld, Ldd):
        """``(e, a)``: the cable's direction (base axes) and the payload's acceleration
        that a winch adds to the fixed-length chain's, ``a = L̈ e + 2 L̇ ė`` [m/s²], at
        ``q, qd`` (11,) on a cable of the arrays' length paid out at ``Ld`` [m/s],
        ``Ldd`` [m/s²] (``ė = (v − v_tip) / L``, ``v`` the payload's velocity at the
        fixed length, :func:`velocity`)."""
        if len(stamp) == 0:
            return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
        na = C.n_arm
        L = -C.arm_c[na - 1, 2]
        e = mv(tip_motion(C, q, qd, zero)[0], sway_direction(q[na + 4], q[na + 5])[0])
        vt = tip_frame(C, q, qd)[1]
        k = 2.0 * Ld / L
        return e, (Ldd * e[0] + k * (v[0] - vt[0]), Ldd * e[1] + k * (v[1] - vt[1]),
                   Ldd * e[2] + k * (v[2] - vt[2]))

    @jit
    def tip_kinematics(flat, lay, prism, q, qd, qdd, out):
        """``out`` (9,): the tip's (``arm_tip`` origin's) position [m], velocity [m/s]
        and acceleration [m/s²], base frame, under the robot's ``q, q̇, q̈`` (9,) on the
        cable chain's arrays."""
        if len(stamp) == 0:
            return
        C = unpack(flat, lay, prism)[0]
        p, v = tip_frame(C, q, qd)[:2]
        a = tip_motion(C, q, qd, qdd)[3]
        for j in range(3):
            out[j] = p[j]
            out[3 + j] = v[j]
            out[6 + j] = a[j]

    return tip, rhs, velocity, set_length, hoisting, tip_kinematics


tip, rhs, velocity, set_length, hoisting, tip_kinematics = _helpers(c.STAMP)


def _make(stamp):

    @jit
    def integrate(flat, lay, prism, damp, drag, Qh, Qdh, Qddh, Lh, g, h, sub, y0, rel_min,
                  Y, status, halt):
        """RK4 of the sway from ``y0`` (4,) with step ``h`` [s], the sway joints'
        damping ``damp`` (2,) [N·m·s/rad] and the payload's drag ``½ ρ C_d A`` = ``drag``
        [kg/m] (against still air); ``Qh, Qdh, Qddh`` ``(2 n + 1, 9)`` the robot's
        motion at every half step (n steps; the tip's motion is formed once per point);
        ``Lh`` ``(2 n + 1, 3)`` the cable's length [m], rate, acceleration there (a
        winch), or ``(1, 3)`` for a fixed length;
        writes every ``sub``-th state to ``Y`` ``(n // sub + 1, 6)``: φ1, φ2 [rad], φ̇1,
        φ̇2 [rad/s], φ̈1, φ̈2 [rad/s²]. ``status`` (3,): stop code, sample index of the
        stop, and the worst ``1 / cos²φ2`` met (the sway inertia's condition); the run
        stops at the first output sample whose state is not finite or whose ``cos²φ2``
        falls below ``rel_min`` (``Y`` holds every sample before it), or before a step
        when ``halt[0]`` (1,) is not zero (code STOPPED, the step's index)."""
        if len(stamp) == 0:
            return
        C = unpack(flat, lay, prism)[0]
        gt = (g[0], g[1], g[2])
        q = np.empty(9)
        qd = np.empty(9)
        qdd = np.empty(9)
        T0 = np.zeros(21)
        Tm = np.zeros(21)
        T1 = np.zeros(21)
        want_v = drag > 0.0
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
        tip(C, Qh, Qdh, Qddh, 0, q, qd, qdd, T0, want_v)
        for s in range(n_steps + 1):
            if halt[0] != 0:
                status[0] = STOPPED
                status[1] = s
                return
            rel = rhs(C, gt, damp, drag, T0, y, Lh, 2 * s, k1)
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
            tip(C, Qh, Qdh, Qddh, 2 * s + 1, q, qd, qdd, Tm, want_v)
            tip(C, Qh, Qdh, Qddh, 2 * s + 2, q, qd, qdd, T1, want_v)
            rk4_stage(y, k1, 0.5 * h, ys)
            rhs(C, gt, damp, drag, Tm, ys, Lh, 2 * s + 1, k2)
            rk4_stage(y, k2, 0.5 * h, ys)
            rhs(C, gt, damp, drag, Tm, ys, Lh, 2 * s + 1, k3)
            rk4_stage(y, k3, h, ys)
            rhs(C, gt, damp, drag, T1, ys, Lh, 2 * s + 2, k4)
            rk4_combine(y, h, k1, k2, k3, k4)
            for j in range(21):
                T0[j] = T1[j]

    @jit
    def kane(flat, lay, prism, damp, q, qd, qdd, g, want_cond, want_limits, warn, error,
             start, stop, X, kappa, health, F):
        """Samples ``start..stop-1`` of the fused Kane equations of the robot with its
        hanging payload: ``q, qd, qdd`` ``(N, 11)`` (the sway's in columns 9, 10); fills
        X ``(N, 9)`` and ``F`` ``(N, 6)``: the cable's pull on the tip (3) [N, base
        axes], the tension [N], and the residual of the two sway equations [N·m]
        (Kane's rows of the sway speeds with the damping ``damp`` (2,) [N·m·s/rad], zero
        when φ̈ solves them)."""
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
            kane_sample_call(C, q[k], qd[k], qdd[k], gt, False, 0, True, rows, A, rhs6, diag,
                             store)
            for b in range(3):
                X[k, b] = rows[b]
            f, tension = cable_force(C, store)
            for j in range(3):
                F[k, j] = f[j]
            F[k, 3] = tension
            F[k, 4] = rows[na - 2] + damp[0] * qd[k, 4 + na]
            F[k, 5] = rows[na - 1] + damp[1] * qd[k, 5 + na]
            post(k, q, na, A, rhs6, diag, True, want_cond, want_limits, warn, error,
                 lim_arm, lim_stroke, lim_ujoint, tb, X, kappa, health, x, M)

    @jit
    def kane_pulled(flat, lay, prism, q, qd, qdd, P, AT, g, want_cond, want_limits, warn,
                    error, start, stop, X, kappa, health):
        """As :func:`kane` with the payload replaced by a given pull ``P`` ``(N, 3)`` [N]
        (base axes) on the tip, acting at the point ``AT`` ``(N, 3)`` [m] from it (the
        payload's place; ``formulas.kane_sample_pull``: a winch's hoisted pendulum, an
        elastic cable); fills X only (the sway columns are not read)."""
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
            kane_sample_pull_call(C, q[k], qd[k], qdd[k], gt, (P[k, 0], P[k, 1], P[k, 2]),
                                  (AT[k, 0], AT[k, 1], AT[k, 2]), rows, A, rhs6, diag,
                                  store)
            for b in range(3):
                X[k, b] = rows[b]
            post(k, q, na, A, rhs6, diag, True, want_cond, want_limits, warn, error,
                 lim_arm, lim_stroke, lim_ujoint, tb, X, kappa, health, x, M)

    @jit
    def accelerations(flat, lay, prism, damp, drag, q, qd, X, g, Ld, Ldd, a, energy, work):
        """One state ``q, qd`` (11,) [m, rad, /s] under actuator forces ``X`` (9,):
        ``a`` (11,) the accelerations of ``M a + h = [A X; −c φ̇] + Jᵀ (f − m a_w)``
        (Cholesky of the explicit Kane pass's M; NaN when M is singular; ``f`` the
        payload's drag with ``½ ρ C_d A`` = ``drag`` [kg/m], J its velocity's partials;
        ``a_w = L̈ e + 2 L̇ ė`` what a winch paying out at ``Ld`` [m/s], ``Ldd`` [m/s²]
        adds to the payload's acceleration on the arrays' cable length, :func:`hoisting`)
        and ``energy`` (2,): kinetic ``½ q̇ᵀ M q̇ + m L̇ e·J q̇ + ½ m L̇²`` and
        gravitational ``−g · Σ m c`` [J]. Returns False when M is not positive definite
        (the attitude singularity, or the sway's cos φ2 = 0). ``work``
        (:data:`~offshore_crane.dynamics.cable.work.WORK`,): scratch."""
        if len(stamp) == 0:
            return False
        C = unpack(flat, lay, prism)[0]
        na = C.n_arm
        n = 6 + na
        B, J, Mm, L, Vw, Ww, Vs, diag, store, mc, rhs, zero, unit = carve_accelerations(
            work, na)
        for i in range(n):
            B[i] = 0.0
            zero[i] = 0.0
            unit[i] = 0.0
            for j in range(n):
                Mm[i, j] = 0.0
                L[i, j] = 0.0
        diag[:] = 0.0
        gt = (g[0], g[1], g[2])
        explicit_sample(C, q, qd, zero, gt, True, B, J, Mm, store, Vw, Ww, Vs, diag, mc)
        actuation_minus_bias(B, J, X, na - 2, rhs)
        rhs[n - 2] = -damp[0] * qd[n - 2] - B[n - 2]
        rhs[n - 1] = -damp[1] * qd[n - 1] - B[n - 1]
        hoisted = Ld != 0.0 or Ldd != 0.0
        m = C.arm_m[na - 1]
        e, aw, v = (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
        if drag > 0.0 or hoisted:       # the generalized forces v_i · (f − m a_w)
            v = velocity(C, q, qd, zero)        # the payload's, at the arrays' length
            if hoisted:
                e, aw = hoisting(C, q, qd, zero, v, Ld, Ldd)
            f = (0.0, 0.0, 0.0)
            if drag > 0.0:
                f = drag_force(axpy(Ld, e, v), drag)
            f = axpy(-m, aw, f)
            for i in range(n):
                unit[i] = 1.0
                vi = velocity(C, q, unit, zero)
                rhs[i] += vi[0] * f[0] + vi[1] * f[1] + vi[2] * f[2]
                unit[i] = 0.0
        ok = cholesky_solve(Mm, rhs, n, a, L)
        energy[0] = kinetic_energy(Mm, qd, n)
        if hoisted:
            energy[0] += m * Ld * (e[0] * v[0] + e[1] * v[1] + e[2] * v[2]) + 0.5 * m * Ld * Ld
        energy[1] = -(g[0] * mc[0, 0] + g[1] * mc[0, 1] + g[2] * mc[0, 2])
        return ok

    @jit
    def computed_torque(flat, lay, prism, damp, drag, q, qd, qdd_cmd, g, Ld, Ldd, X, work):
        """The actuator forces ``X`` (9,) that give the robot the accelerations
        ``qdd_cmd`` (9,) at the measured state ``q, qd`` (11,) with its payload swinging
        on the arrays' cable length, paid out at ``Ld`` [m/s], ``Ldd`` [m/s²] (a winch;
        0, 0: a fixed length): the sway's accelerations from the pendulum's equations
        under that motion (the payload's drag with ``½ ρ C_d A`` = ``drag`` [kg/m]),
        then Kane's inverse dynamics of the chain with the sway joints (with drag or a
        winch: of the robot pulled at the payload's place, ``kane_sample_pull``).
        Returns the Stewart system's condition number (inf when singular). ``work``
        (:data:`~offshore_crane.dynamics.cable.work.WORK`,): scratch."""
        if len(stamp) == 0:
            return 0.0
        C = unpack(flat, lay, prism)[0]
        na = C.n_arm
        gt = (g[0], g[1], g[2])
        qdd, rows, A, rhs6, diag, store, x, M, zero = carve_law(work, na)
        for j in range(6 + na):
            zero[j] = 0.0
        for j in range(na):
            rows[j] = 0.0
        diag[:] = 0.0
        for j in range(9):
            qdd[j] = qdd_cmd[j]
        Rt, w, al, at = tip_motion(C, q, qd, qdd)
        hoisted = Ld != 0.0 or Ldd != 0.0
        L = -C.arm_c[na - 1, 2]
        p1, p2, r1, r2 = q[6 + na - 2], q[6 + na - 1], qd[6 + na - 2], qd[6 + na - 1]
        e_t = sway_direction(p1, p2)[0]
        e = mv(Rt, e_t)
        f = (0.0, 0.0, 0.0)
        if drag > 0.0:
            f = drag_force(axpy(Ld, e, velocity(C, q, qd, zero)), drag)
        pulled = drag > 0.0 or hoisted  # X from the pull at the payload (kane_sample_pull)
        pull = (0.0, 0.0, 0.0)
        if pulled:
            a1, a2, cos2, pull, _ = hoisted_pendulum(C, Rt, w, al, at, gt, p1, p2, r1, r2,
                                                     damp[0], damp[1], f, L, Ld, Ldd)
        if not hoisted:                 # the fixed length's own equations (bit for bit)
            a1, a2, cos2 = pendulum(C, Rt, w, al, at, gt, p1, p2, r1, r2, damp[0], damp[1],
                                    f)
        qdd[6 + na - 2] = a1
        qdd[6 + na - 1] = a2
        if pulled:
            kane_sample_pull_call(C, q, qd, qdd, gt, pull, mv(Rt, scale(e_t, L)), rows, A,
                                  rhs6, diag, store)
        else:
            kane_sample_call(C, q, qd, qdd, gt, False, 0, True, rows, A, rhs6, diag, store)
        for b in range(3):
            X[b] = rows[b] if b < na - 2 else 0.0
        cond = solve6(A, rhs6, x, M, True)
        for l in range(6):
            X[3 + l] = x[l]
        return cond

    @jit
    def payload(flat, lay, prism, q, qd, Ld, pay):
        """``pay`` (6,): the payload's velocity relative to the tip [m/s] (the sway
        rates' part and the winch's ``Ld`` [m/s] along the cable, base axes) and its
        position from the tip [m], at ``q, qd`` (11,)."""
        if len(stamp) == 0:
            return
        C = unpack(flat, lay, prism)[0]
        na = C.n_arm
        Rt = tip_motion(C, q, qd, np.zeros(6 + na))[0]
        L = -C.arm_c[na - 1, 2]
        e, e1, e2 = sway_direction(q[6 + na - 2], q[6 + na - 1])
        rate = mv(Rt, axpy(Ld, e, scale(axpy(qd[6 + na - 1], e2, scale(e1, qd[6 + na - 2])),
                                        L)))
        rho = mv(Rt, scale(e, L))
        for i in range(3):
            pay[i] = rate[i]
            pay[3 + i] = rho[i]

    return integrate, kane, kane_pulled, accelerations, computed_torque, payload


#: What the drivers' disk cache is keyed by: the formulas' hash and the text of the
#: scratch's layout they inline (Numba's cache checks only a function's own file).
STAMP = c.STAMP + hashlib.sha256(inspect.getsource(_work).encode()).hexdigest()
integrate, kane, kane_pulled, accelerations, computed_torque, payload = _make(STAMP)

#: :func:`accelerations`, :func:`computed_torque` and :func:`payload` called by address
#: (:mod:`offshore_crane.kernel_calls`): the hanging plant's loops, one per law, call
#: them without compiling their Kane passes and the tip's kinematics again.
ACCELERATIONS = kernel_calls.Entry.typed(
    "cable_accelerations", lambda: accelerations,
    "boolean(*PACKED, V, float64, V, V, V, V, float64, float64, V, V, V)", STAMP)
COMPUTED_TORQUE = kernel_calls.Entry.typed(
    "cable_computed_torque", lambda: computed_torque,
    "float64(*PACKED, V, float64, V, V, V, V, float64, float64, V, V)", STAMP)
PAYLOAD = kernel_calls.Entry.typed("cable_payload", lambda: payload,
                                   "none(*PACKED, V, V, float64, V)", STAMP)
