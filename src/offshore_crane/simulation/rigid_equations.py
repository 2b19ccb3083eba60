"""The rigid robot's equations of motion and its built-in laws, compiled (imports Numba):
the kernels of the RK4 driver's rigid plant (:mod:`.plants._rigid_kernels`) and of the
DOP853 reference path (:mod:`.rigid`).

The functions reach the compiled formulas as module globals (the explicit pass by
address, :data:`~offshore_crane.dynamics.compiled.call_explicit`) and close over the
formulas' hash only (see :func:`_helpers`). The work arrays are views without an owner of
one zeroed buffer (:func:`carve`): handed from call to call, owned arrays cost the loop
their reference counts (a real-time factor of 67.3 against 63.5, one core, one session).
The law is called by address (:data:`LAW`): its code is not linked into each loop and
optimised again there.
"""

from __future__ import annotations

import numpy as np
from offshore_crane import kernel_calls
from offshore_crane.kernel_cache import njit
from offshore_crane.simulation.laws import codes

from offshore_crane.dynamics import compiled as c
from offshore_crane.dynamics.views import c_view

explicit_sample, actuator_coordinates = c.call_explicit, c.KE.actuator_coordinates
solve6, cholesky_solve, unpack = c.solve6, c.cholesky_solve, c.unpack
actuation_minus_bias, leg_system = c.actuation_minus_bias, c.leg_system
kinetic_energy = c.kinetic_energy
STAMP = c.STAMP
jit = njit(**c.JIT)
inline = njit(inline="always", **c.JIT)
#: The laws' codes (:mod:`offshore_crane.simulation.laws.codes`, one enumeration).
COMPUTED_TORQUE, PD_GRAVITY, PD, NONE = (codes.COMPUTED_TORQUE, codes.PD_GRAVITY, codes.PD,
                                         codes.NONE)


def _helpers(stamp):
    """The control law and the accelerations, closed over the formulas' hash ``stamp``
    only: it keys their disk cache, so that editing a formula (whose compiled code they
    link) rebuilds them. (A closure over a dispatcher would defeat the cache: the rigid
    plant's kernels reach these as module globals.)"""

    @njit(inline="always", **c.JIT)
    def command(kp, kd, q, qd, qr, qdr, qddr, qdd_c):
        """Computed torque's commanded accelerations ``q̈_r + Kd (q̇_r − q̇) + Kp (q_r −
        q)`` into ``qdd_c`` (9,)."""
        if len(stamp) == 0:
            return
        for j in range(9):
            qdd_c[j] = qddr[j] + kd[j] * (qdr[j] - qd[j]) + kp[j] * (qr[j] - q[j])

    @njit(inline="always", **c.JIT)
    def forces(n_arm, inv_L, B, J, A, rhs, x, M13, Xout):
        """Actuator forces of the generalized forces ``B`` (9,) of a robot with ``n_arm``
        arm joints and mean anchor distance ``1 / inv_L`` [m]: ``(T1, T2, Fs) =
        B[6:9]``, ``Jᵀ Fl = B[0:6]`` solved as inverse dynamics solves it
        (:func:`~offshore_crane.dynamics.compiled.leg_system`, rotation rows scaled; a
        singular system gives NaN forces); the other entries of ``Xout`` untouched.
        (This and :func:`command` are inlined: calls cost the loop ~5 %.)"""
        if len(stamp) == 0:
            return
        for b in range(n_arm):
            Xout[b] = B[6 + b]
        leg_system(B, J, inv_L, A, rhs)
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
            forces(Cc.n_arm, 1.0 / Cc.L, B, J, A, rhs, x, M13, Xout)
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
    def ct_from(n, inv_L, qdd_c, Xout, ws, wl):
        """Computed torque on the plant's own model from the pass already in ``ws`` (the
        one the accelerations use) at the commanded accelerations ``qdd_c`` (9,): ``B = M
        q̈_cmd + h`` (M's lower triangle), ``(T1, T2, Fs) = B[6:9]``, ``Jᵀ Fl = B[0:6]``
        (:func:`forces`, as :func:`law`). Equal to :func:`law`'s computed torque to
        round-off (its own explicit pass at q̈_cmd gives the same ``M q̈_cmd + h``),
        without that pass. ``n``: the coordinates (6 + arm joints); ``inv_L`` [1/m] as
        :func:`forces`."""
        if len(stamp) == 0:
            return
        h, J, Mm = ws[0], ws[1], ws[2]
        Bc, A, rhs, x, M13 = wl[0], wl[9], wl[10], wl[11], wl[12]
        for r in range(9):
            Xout[r] = 0.0
            f = h[r]
            if r < n:
                for c_ in range(n):
                    f += (Mm[r, c_] if c_ <= r else Mm[c_, r]) * qdd_c[c_]
            Bc[r] = f
        forces(n - 6, inv_L, Bc, J, A, rhs, x, M13, Xout)

    @inline
    def energy(Mm, mc, qd, n, g):
        """The robot's energy [J] from an explicit pass at (q, q̇): kinetic ``½ q̇ᵀ M q̇``
        (M's lower triangle ``Mm``) and gravitational ``−g · Σ m c`` (``mc`` (1, 3))."""
        if len(stamp) == 0:
            return 0.0
        return kinetic_energy(Mm, qd, n) - (g[0] * mc[0, 0] + g[1] * mc[0, 1]
                                            + g[2] * mc[0, 2])

    return law, accel, equations, solve, ct_from, energy


law, accel, equations, solve, ct_from, energy = _helpers(STAMP)


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


#: :func:`law` called by address (:mod:`offshore_crane.kernel_calls`) by the rigid plant's
#: kernels: its code (the explicit pass's call, the actuators' coordinates) is not linked
#: into each driver loop and optimised again there.
LAW = kernel_calls.Entry.typed("rigid_law", lambda: law,
                               "none(C, T3, int64, V, V, V, V, V, V, V, V, WL)", STAMP,
                               C=c.kane_constants_type(), WL=_work_type(_WL))
call_law = LAW.call


#: Each work array's element count, in :data:`_WS` then :data:`_WL` order (0: the arm
#: workspace, 27 per joint): the one layout :func:`work_size` and :func:`carve` share.
_COUNTS = tuple(0 if s == "S" else int(np.prod(s)) for s in _WS + _WL)


def work_size(na: int) -> int:
    """The length of the ``work`` buffer :func:`carve` lays out for an arm of ``na``
    joints."""
    return sum(c or max(na, 1) * 27 for c in _COUNTS)


def _carve_text(name: str, both: bool) -> str:
    """The text of :func:`carve` (``both``: ``ws`` and ``wl``) or :func:`carve_ws`, written
    from :data:`_WS` and :data:`_WL` (their one source): each view's start a constant plus
    the arm workspaces before it (a multiple of ``27 r``), no offsets array allocated at
    each call."""
    views, fixed, arms = [], 0, 0
    for s in _WS + _WL:
        shape = "(r, 27)" if s == "S" else repr(tuple(s))
        views.append(f"c_view(w, {fixed} + {arms} * r27, {shape})")
        if s == "S":
            arms += 1
        else:
            fixed += int(np.prod(s))
    ws, wl = views[:len(_WS)], views[len(_WS):]
    out = f"({', '.join(ws)},), ({', '.join(wl)},)" if both else f"({', '.join(ws)},)"
    return f"def {name}(w, na):\n    r = max(na, 1)\n    r27 = r * 27\n    return {out}\n"


def _carver(name: str, both: bool, doc: str):
    """:func:`carve` or :func:`carve_ws` made from :func:`_carve_text` (inlined where it
    is called: not cached on its own, its callers are)."""
    scope = {"c_view": c_view}
    exec(compile(_carve_text(name, both), f"<{__name__}.{name}>", "exec"),  # noqa: S102
         scope)                                                           # (our text)
    fn = scope[name]
    fn.__doc__ = (f"{doc} as views of the zeroed buffer ``w`` (:func:`work_size`), without "
                  "an owner (:mod:`offshore_crane.dynamics.views`: handed from call to "
                  "call, owned arrays cost the loop their reference counts).")
    return njit(inline="always", **{**c.JIT, "cache": False})(fn)


carve = _carver("carve", True, ":func:`workspaces`'s two tuples")
#: ``carve(w, na)[0]`` alone: a kernel that needs only the equations' arrays types and
#: lowers 13 views, not 32 (what a driver loop's compile spends its time on).
carve_ws = _carver("carve_ws", False, ":func:`workspaces`'s first tuple (``ws``)")
