"""The compiled RK4 loop of :mod:`offshore_crane.simulation.rigid` (imports Numba).

The functions reach the compiled formulas as module globals (the explicit pass by
address, :data:`~offshore_crane.dynamics.compiled.call_explicit`) and close over the
formulas' hash only (see :func:`_helpers`). The equations, their solve and the shared
computed torque are inlined into :func:`stage`: called, each was passed the two work
tuples (32 arrays) again, and the loop ran at a real-time factor of 47.3 against 50.1
inlined (Table 1, 20 s, one core, measured in one session); inlining everything into the
loop (the law too, at three stage sites) ran at 53.9 but compiled in 47 s instead of 22 s.
The work arrays are views without an owner of a buffer the caller passes (:func:`carve`):
a real-time factor of 67.3 against 63.5 with owned arrays (their reference counts; one
core, one session). :func:`stage` is handed the packed arrays and that buffer and makes
its views itself: handed the views (the two robots' constants and the two work tuples,
about 80 array structures copied at each of its three calls a step), the loop ran at
68.2 against 77.2; inlined into the loop, at 81.0, but the loop's compile took 27.5 s
against 22.6 s (one core, one session). It is called by address (:data:`STAGE`), so a
first ``simulate`` compiles it in a helper process while this one compiles the loop; and
the loop writes its (9,) copies out and copies q into a (1, 9) array for the checks
instead of ``reshape``: their shape checks brought Numba's error-message formatting into
the loop's compile. The loop's own cold compile went 16.8 → 11.7 s with the two
(Numba's compile events, one process), a first ``simulate`` of the rigid robot 23.0 →
16.4 s (the real-time factor within 1 %, interleaved A/B, one core).
"""

from __future__ import annotations

import numpy as np
from offshore_crane import kernel_calls
from offshore_crane.kernel_cache import njit
from offshore_crane.stops import CODES
from offshore_crane.simulation.laws import codes

from offshore_crane.dynamics import compiled as c
from offshore_crane.dynamics.integrator import rk4_combine, rk4_stage
from offshore_crane.dynamics.views import c_view

explicit_sample, actuator_coordinates = c.call_explicit, c.KE.actuator_coordinates
solve6, cholesky_solve, unpack, check = c.solve6, c.cholesky_solve, c.unpack, c._check
actuation_minus_bias, leg_system = c.actuation_minus_bias, c.leg_system
kinetic_energy = c.kinetic_energy
tangent_bounds = c.tangent_bounds
STAMP = c.STAMP
jit = njit(**c.JIT)
inline = njit(inline="always", **c.JIT)
#: Stop codes (:class:`~offshore_crane.stops.StopCause`); STOPPED: asked to (the flag set
#: by :func:`offshore_crane.progress.run_polled` on a signal, which the caller raises).
OK, WORKSPACE, SINGULAR, DIVERGED, STOPPED, _ = CODES
_VIOLATION = 3
#: The laws' codes (:mod:`offshore_crane.simulation.laws.codes`, one enumeration). SHARED:
#: computed torque on the plant's own model with the law applied at every stage
#: (:func:`offshore_crane.simulation.rigid.simulate` chooses it): one explicit pass a stage
#: serves the law and the accelerations (:func:`_helpers`' ``ct``).
COMPUTED_TORQUE, PD_GRAVITY, PD, NONE, SHARED = (
    codes.COMPUTED_TORQUE, codes.PD_GRAVITY, codes.PD, codes.NONE, codes.SHARED)


def _helpers(stamp):
    """The control law and the accelerations, closed over the formulas' hash ``stamp``
    only: it keys their disk cache, so that editing a formula (whose compiled code they
    link) rebuilds them. (A closure over a dispatcher would defeat the cache: the loop
    below reaches these two as module globals.)"""

    @njit(inline="always", **c.JIT)
    def command(kp, kd, q, qd, qr, qdr, qddr, qdd_c):
        """Computed torque's commanded accelerations ``q̈_r + Kd (q̇_r − q̇) + Kp (q_r −
        q)`` into ``qdd_c`` (9,)."""
        if len(stamp) == 0:
            return
        for j in range(9):
            qdd_c[j] = qddr[j] + kd[j] * (qdr[j] - qd[j]) + kp[j] * (qr[j] - q[j])

    @njit(inline="always", **c.JIT)
    def forces(C, B, J, A, rhs, x, M13, Xout):
        """Actuator forces of the generalized forces ``B`` (9,): ``(T1, T2, Fs) =
        B[6:9]``, ``Jᵀ Fl = B[0:6]`` solved as inverse dynamics solves it
        (:func:`~offshore_crane.dynamics.compiled.leg_system`, rotation rows scaled; a
        singular system gives NaN forces); the other entries of ``Xout`` untouched.
        (This and :func:`command` are inlined: calls cost the loop ~5 %.)"""
        if len(stamp) == 0:
            return
        for b in range(C.n_arm):
            Xout[b] = B[6 + b]
        leg_system(B, J, 1.0 / C.L, A, rhs)
        solve6(A, rhs, x, M13, False)
        for l in range(6):
            Xout[3 + l] = x[l]

    @jit
    def law(Cc, g, kind, kp, kd, q, qd, qr, qdr, qddr, Xout, w):
        """The control law at one state, with the controller's model ``Cc`` (``w``: the
        workspace tuple). The model's inverse dynamics comes from its equations of motion:
        ``B = M q̈_cmd + h``, turned into actuator forces by :func:`forces` (a singular
        leg system gives NaN forces, and the run stops as diverged)."""
        if len(stamp) == 0:
            return
        B, J, Mm, store, Vw, Ww, Vs, diag, mc, A, rhs, x, M13, zero, qdd_c, pos, rate, posr, \
            rater = w
        if kind == NONE:
            for j in range(9):
                Xout[j] = 0.0
            return
        for j in range(9):
            Xout[j] = 0.0
        if kind == COMPUTED_TORQUE or kind == PD_GRAVITY:
            B[:] = 0.0
            Mm[:] = 0.0
            if kind == COMPUTED_TORQUE:
                command(kp, kd, q, qd, qr, qdr, qddr, qdd_c)
                explicit_sample(Cc, q, qd, qdd_c, g, False, B, J, Mm, store, Vw, Ww, Vs,
                                diag, mc)
            else:
                explicit_sample(Cc, q, zero, zero, g, False, B, J, Mm, store, Vw, Ww, Vs,
                                diag, mc)
            forces(Cc, B, J, A, rhs, x, M13, Xout)
        if kind == PD_GRAVITY or kind == PD:
            actuator_coordinates(Cc, q, qd, pos, rate)
            actuator_coordinates(Cc, qr, qdr, posr, rater)
            for j in range(9):
                Xout[j] += kp[j] * (posr[j] - pos[j]) + kd[j] * (rater[j] - rate[j])

    @inline
    def equations(C, g, q, qd, ws):
        """The explicit pass at ``q, q̇`` and q̈ = 0 into ``ws``: M (lower triangle), h,
        the leg Jacobian J, the checks' record and the mass moments."""
        if len(stamp) == 0:
            return
        B, J, Mm, L, store, Vw, Ww, Vs, diag, mc, rhs, x, zero = ws
        B[:] = 0.0
        Mm[:] = 0.0
        explicit_sample(C, q, qd, zero, g, True, B, J, Mm, store, Vw, Ww, Vs, diag, mc)

    @inline
    def solve(n, X, qdd, ws):
        """q̈ of ``M q̈ + h = A X`` from the pass in ``ws`` into ``qdd``; False when M is
        singular."""
        if len(stamp) == 0:
            return False
        B, J, Mm, L, store, Vw, Ww, Vs, diag, mc, rhs, x, zero = ws
        actuation_minus_bias(B, J, X, n - 6, rhs)
        ok = cholesky_solve(Mm, rhs, n, x, L)
        for j in range(9):
            qdd[j] = x[j] if j < n else 0.0
        return ok

    @jit
    def accel(C, g, n, q, qd, X, qdd, ws):
        """q̈ from the equations of motion into ``qdd``; False when M is singular."""
        if len(stamp) == 0:
            return False
        equations(C, g, q, qd, ws)
        return solve(n, X, qdd, ws)

    @inline
    def ct(C, n, kp, kd, q, qd, qr, qdr, qddr, Xout, ws, wl):
        """Computed torque on the plant's own model from the pass already in ``ws`` (the
        one the accelerations use): ``B = M q̈_cmd + h`` (M's lower triangle), ``(T1, T2,
        Fs) = B[6:9]``, ``Jᵀ Fl = B[0:6]`` (:func:`forces`, as :func:`law`). Equal to
        :func:`law`'s computed torque to round-off (its own explicit pass at q̈_cmd gives
        the same ``M q̈_cmd + h``), without that pass."""
        if len(stamp) == 0:
            return
        h, J, Mm = ws[0], ws[1], ws[2]
        Bc, A, rhs, x, M13, qdd_c = wl[0], wl[9], wl[10], wl[11], wl[12], wl[14]
        command(kp, kd, q, qd, qr, qdr, qddr, qdd_c)
        for r in range(9):
            Xout[r] = 0.0
            f = h[r]
            if r < n:
                for c_ in range(n):
                    f += (Mm[r, c_] if c_ <= r else Mm[c_, r]) * qdd_c[c_]
            Bc[r] = f
        forces(C, Bc, J, A, rhs, x, M13, Xout)

    @inline
    def energy(Mm, mc, qd, n, g):
        """The robot's energy [J] from an explicit pass at (q, q̇): kinetic ``½ q̇ᵀ M q̇``
        (M's lower triangle ``Mm``) and gravitational ``−g · Σ m c`` (``mc`` (1, 3))."""
        if len(stamp) == 0:
            return 0.0
        return kinetic_energy(Mm, qd, n) - (g[0] * mc[0, 0] + g[1] * mc[0, 1]
                                            + g[2] * mc[0, 2])

    @jit
    def stage(shared, plant, model, g, n, kind, kp, kd, hold, q, qd, qr, qdr, qddr, lo, hi,
              Xc, Xa, qdd, work):
        """One RK4 stage after the first: the law at every stage (``hold`` 0: with the
        pass shared when ``shared``, :data:`SHARED`) or the held forces, clamped into
        ``Xa``, and q̈ into ``qdd``; False when M is singular."""
        if len(stamp) == 0:
            return False
        C = unpack(plant[0], plant[1], plant[2])[0]
        Cc = unpack(model[0], model[1], model[2])[0]
        ws, wl = carve(work, max(C.n_arm, Cc.n_arm))
        if shared:
            equations(C, g, q, qd, ws)
            ct(C, n, kp, kd, q, qd, qr, qdr, qddr, Xc, ws, wl)
        elif hold == 0:
            call_law(Cc, g, kind, kp, kd, q, qd, qr, qdr, qddr, Xc, wl)
        if shared or hold == 0:
            for j in range(9):
                Xa[j] = min(max(Xc[j], lo[j]), hi[j])
        if shared:
            return solve(n, Xa, qdd, ws)
        return accel(C, g, n, q, qd, Xa, qdd, ws)

    return law, accel, equations, solve, ct, energy, stage


law, accel, equations, solve, ct, energy, stage = _helpers(STAMP)


def _packed_type():
    """The Numba type of :class:`~offshore_crane.simulation.record.Packed`."""
    from numba import types

    from offshore_crane.simulation.record import Packed

    return types.NamedTuple(list(kernel_calls.short_names()["PACKED"]), Packed)


#: :func:`stage` called by address (:mod:`offshore_crane.kernel_calls`) by :func:`run`:
#: compiled in its own library, in a helper process while a first ``simulate`` compiles
#: the loop (:mod:`offshore_crane.compile_beside`), not again inside the loop.
STAGE = kernel_calls.Entry.typed(
    "rigid_stage", lambda: stage,
    "boolean(boolean, P, P, T3, int64, int64, V, V, int64, V, V, V, V, V, V, V, V, V, V, V)",
    STAMP, P=_packed_type())
call_stage = STAGE.call


def workspaces(na: int) -> tuple:
    """The equations' (``ws``) and the law's (``wl``) work tuples of :func:`accel`,
    :func:`law` for an arm of ``na`` joints, as owned zeroed arrays (:data:`_WS`,
    :data:`_WL`): for the DOP853 path, which calls them from Python. The compiled loops
    carve the same arrays from one buffer (:func:`carve`)."""
    def made(shapes):
        return tuple(np.zeros((max(na, 1), 27) if s == "S" else s) for s in shapes)

    return made(_WS), made(_WL)


#: The work arrays of :func:`workspaces`, in order: ``ws``'s, then ``wl``'s (``S``: the
#: arm workspace, ``(max(na, 1), 27)``); :func:`carve` lays them out by :data:`_COUNTS`.
_WS = ((9,), (6, 6), (9, 9), (9, 9), "S", (9, 3), (9, 3), (9, 3), (7, 6), (1, 3), (9,), (9,),
       (9,))
_WL = ((9,), (6, 6), (9, 9), "S", (9, 3), (9, 3), (9, 3), (7, 6), (1, 3), (6, 6), (6,), (6,),
       (6, 13), (9,), (9,), (9,), (9,), (9,), (9,))


def _work_type(shapes):
    """The Numba type of a work tuple laid out as ``shapes`` (:data:`_WL`)."""
    from numba import types

    return types.Tuple([types.Array(types.float64, 2 if s == "S" else len(s), "C")
                        for s in shapes])


#: :func:`law` called by address (:mod:`offshore_crane.kernel_calls`) by the loop and its
#: stages: its code (the explicit pass's call, the actuators' coordinates) is not linked
#: into :func:`run` and optimised again there.
LAW = kernel_calls.Entry.typed("rigid_law", lambda: law,
                               "none(C, T3, int64, V, V, V, V, V, V, V, V, WL)", STAMP,
                               C=c.kane_constants_type(), WL=_work_type(_WL))
call_law = LAW.call


#: Each work array's element count, in :data:`_WS` then :data:`_WL` order (0: the arm
#: workspace, 27 per joint): the one layout :func:`work_size` and :func:`carve` share.
_COUNTS = tuple(0 if s == "S" else int(np.prod(s)) for s in _WS + _WL)


def work_size(na: int) -> int:
    """The length of :func:`run`'s ``work`` buffer for an arm of ``na`` joints."""
    return sum(c or max(na, 1) * 27 for c in _COUNTS)


@inline
def carve(w, na):
    """:func:`workspaces`'s two tuples as views of the zeroed buffer ``w``
    (:func:`work_size`), without an owner (:mod:`offshore_crane.dynamics.views`: handed
    from call to call, owned arrays cost the loop their reference counts)."""
    r = max(na, 1)
    o = np.zeros(len(_COUNTS) + 1, dtype=np.int64)          # each array's start
    for i in range(len(_COUNTS)):
        o[i + 1] = o[i] + (_COUNTS[i] if _COUNTS[i] > 0 else r * 27)
    ws = (c_view(w, o[0], (9,)), c_view(w, o[1], (6, 6)), c_view(w, o[2], (9, 9)),
          c_view(w, o[3], (9, 9)), c_view(w, o[4], (r, 27)), c_view(w, o[5], (9, 3)),
          c_view(w, o[6], (9, 3)), c_view(w, o[7], (9, 3)), c_view(w, o[8], (7, 6)),
          c_view(w, o[9], (1, 3)), c_view(w, o[10], (9,)), c_view(w, o[11], (9,)),
          c_view(w, o[12], (9,)))
    wl = (c_view(w, o[13], (9,)), c_view(w, o[14], (6, 6)), c_view(w, o[15], (9, 9)),
          c_view(w, o[16], (r, 27)), c_view(w, o[17], (9, 3)), c_view(w, o[18], (9, 3)),
          c_view(w, o[19], (9, 3)), c_view(w, o[20], (7, 6)), c_view(w, o[21], (1, 3)),
          c_view(w, o[22], (6, 6)), c_view(w, o[23], (6,)), c_view(w, o[24], (6,)),
          c_view(w, o[25], (6, 13)), c_view(w, o[26], (9,)), c_view(w, o[27], (9,)),
          c_view(w, o[28], (9,)), c_view(w, o[29], (9,)), c_view(w, o[30], (9,)),
          c_view(w, o[31], (9,)))
    return ws, wl


@inline
def copy9(src, dst):
    """``dst[:] = src`` for the loop's (9,) arrays, written out: the slice assignment's
    shape check brings Numba's error-message formatting into the loop's compile (about
    5 s with the ``reshape`` the checks' (1, 9) view once came from, measured)."""
    for j in range(9):
        dst[j] = src[j]


def _runner(stamp):
    """The RK4 loop, closed over ``stamp`` only (see :func:`_helpers`)."""

    @jit
    def run(plant, model, g, h, n_steps, out_every, reference, gains, want_limits, q0, qd0,
            record, health, status, halt, work):
        """RK4 from (q0, qd0) of the robot ``plant`` under the law ``gains`` computed on
        ``model`` (:class:`~offshore_crane.simulation.record.Packed`, ``LawParameters``),
        tracking ``reference`` (``StageGrid``); writes every ``out_every``-th step to
        ``record`` (``Recording``); ``status`` receives (code, step) of a stop. Ends
        before a step when ``halt[0]`` (1,) is not zero (code STOPPED). ``work``: a zeroed
        buffer of :func:`work_size` (its work arrays, :func:`carve`)."""
        if len(stamp) == 0:
            return
        fp, lp, pp = plant
        fc, lc, pc = model
        qr, qdr, qddr = reference
        kind, kp, kd, hold, nq, nqd, lo, hi = gains
        shared = kind == SHARED                 # hold is 0 then (rigid.simulate)
        Q, QD, QDD, QR, QDR, XC, XA, SAT, E, P = record
        C, lim_arm, lim_stroke, lim_ujoint = unpack(fp, lp, pp)
        Cc = unpack(fc, lc, pc)[0]
        tb = tangent_bounds(lim_ujoint)
        na = C.n_arm
        n = 6 + na
        gt = (g[0], g[1], g[2])
        ws, wl = carve(work, max(na, Cc.n_arm))
        kap = np.empty((3, 1))
        q = q0.copy()
        qd = qd0.copy()
        Xc = np.zeros(9)
        Xa = np.zeros(9)
        qm = np.empty(9)
        qdm = np.empty(9)
        k1q = np.empty(9)
        k1v = np.empty(9)
        k2q = np.empty(9)
        k2v = np.empty(9)
        k3q = np.empty(9)
        k3v = np.empty(9)
        k4v = np.empty(9)
        qs = np.empty(9)
        q1 = np.empty((1, 9))                   # q as check reads it (no reshape)
        qds = np.empty(9)
        sat = np.zeros(9, dtype=np.bool_)
        ctrl = 0
        for step in range(n_steps + 1):
            if halt[0] != 0:
                status[0] = STOPPED
                status[1] = step
                return
            i0 = 2 * step
            # control at the step start (sample-and-hold) or at every stage
            if hold == 0 or step % hold == 0:
                for j in range(9):
                    qm[j] = q[j] + (nq[ctrl, j] if hold > 0 else 0.0)
                    qdm[j] = qd[j] + (nqd[ctrl, j] if hold > 0 else 0.0)
                if hold > 0:
                    ctrl += 1
                if shared:
                    equations(C, gt, q, qd, ws)
                    ct(C, n, kp, kd, q, qd, qr[i0], qdr[i0], qddr[i0], Xc, ws, wl)
                else:
                    call_law(Cc, gt, kind, kp, kd, qm, qdm, qr[i0], qdr[i0], qddr[i0], Xc,
                             wl)
                for j in range(9):
                    sat[j] = Xc[j] < lo[j] or Xc[j] > hi[j]
                    Xa[j] = min(max(Xc[j], lo[j]), hi[j])
            if shared:
                ok = solve(n, Xa, k1v, ws)
            else:
                ok = accel(C, gt, n, q, qd, Xa, k1v, ws)
            diag, mc, Mm, J = ws[8], ws[9], ws[2], ws[1]
            finite = ok
            for j in range(9):
                finite = finite and np.isfinite(q[j]) and np.isfinite(qd[j])
            if want_limits:
                copy9(q, q1[0])
                check(0, q1, na, diag, np.nan, True, False, True, np.inf,
                      np.inf, lim_arm, lim_stroke, lim_ujoint, tb, kap, health)
            stop = OK if finite else (SINGULAR if not ok else DIVERGED)
            if want_limits and stop == OK:
                for s in range(4):
                    if health[_VIOLATION + 3 * s] >= 0.0:
                        stop = WORKSPACE
            if step % out_every == 0 or stop != OK:
                o = step // out_every if stop == OK else (step + out_every - 1) // out_every
                if o < Q.shape[0]:
                    pw = 0.0
                    for b in range(na):
                        pw += Xa[b] * qd[6 + b]
                    for l in range(6):
                        ldot = 0.0
                        for r in range(6):
                            ldot += J[l, r] * qd[r]
                        pw += Xa[3 + l] * ldot
                    for j in range(9):
                        Q[o, j] = q[j]
                        QD[o, j] = qd[j]
                        QDD[o, j] = k1v[j]
                        QR[o, j] = qr[i0, j]
                        QDR[o, j] = qdr[i0, j]
                        XC[o, j] = Xc[j]
                        XA[o, j] = Xa[j]
                        SAT[o, j] = sat[j]
                    E[o] = energy(Mm, mc, qd, n, gt)
                    P[o] = pw
                    status[2] = o + 1
            if stop != OK:
                status[0] = stop
                status[1] = step
                return
            if step == n_steps:
                break
            # RK4 stages
            copy9(qd, k1q)
            rk4_stage(q, k1q, 0.5 * h, qs)
            rk4_stage(qd, k1v, 0.5 * h, qds)
            call_stage(shared, plant, model, gt, n, kind, kp, kd, hold, qs, qds, qr[i0 + 1],
                       qdr[i0 + 1], qddr[i0 + 1], lo, hi, Xc, Xa, k2v, work)
            copy9(qds, k2q)
            rk4_stage(q, k2q, 0.5 * h, qs)
            rk4_stage(qd, k2v, 0.5 * h, qds)
            call_stage(shared, plant, model, gt, n, kind, kp, kd, hold, qs, qds, qr[i0 + 1],
                       qdr[i0 + 1], qddr[i0 + 1], lo, hi, Xc, Xa, k3v, work)
            copy9(qds, k3q)
            rk4_stage(q, k3q, h, qs)
            rk4_stage(qd, k3v, h, qds)
            call_stage(shared, plant, model, gt, n, kind, kp, kd, hold, qs, qds, qr[i0 + 2],
                       qdr[i0 + 2], qddr[i0 + 2], lo, hi, Xc, Xa, k4v, work)
            rk4_combine(q, h, k1q, k2q, k3q, qds)              # k4 of q is the stage's q̇
            rk4_combine(qd, h, k1v, k2v, k3v, k4v)

    return run


run = _runner(STAMP)
