"""The compiled backend: the one text of the formulas, compiled by Numba.

Every function of :mod:`offshore_crane.robot.kinematics.formulas` and :mod:`.formulas` is
re-bound and wrapped in ``numba.njit`` (:func:`.backends.bind`); the drivers below loop
over samples, solve each 6x6 leg-force system by Gauss–Jordan elimination with partial
pivoting (which also gives the inverse for the 1-norm condition number) and apply the
checks inside the loop, writing a health record
(:mod:`offshore_crane.robot.kinematics.workspace`) instead of NumPy reductions.

Compilation happens on first call and is cached on disk (``cache=True``, beside the
package's files, or in ``NUMBA_CACHE_DIR``); the drivers close over a hash of the
formulas' source, so editing a formula recompiles what inlines it. The drivers release
the GIL (``nogil``), so ``threads=`` runs blocks of samples on several cores, with results
bit-identical to one thread (every sample is computed independently).
"""

from __future__ import annotations

import numpy as np
from offshore_crane.kernel_cache import njit

from offshore_crane.robot.kinematics import workspace as ws
from offshore_crane.dynamics import backends
from offshore_crane.dynamics.passes import (EXPLICIT, KANE, KANE_PULL,  # noqa: F401
                                           KANE_PULL2, call_explicit, call_kane,
                                           call_kane_pull, call_kane_pull2, explicit_sample,
                                           kane_constants_type, kane_pass, kane_pull_pass,
                                           kane_pull2_pass)
from offshore_crane.dynamics.constants import FIELDS
from offshore_crane.dynamics.formulas import KaneConstants
from offshore_crane.dynamics.linear import (actuation_minus_bias, cholesky_solve,  # noqa: F401
                                            kinetic_energy, leg_system, solve6,
                                            solve6_many)
from offshore_crane.dynamics.jit import JIT, LEAN  # noqa: F401  (LEAN: for its users)
from offshore_crane.dynamics.views import view_value
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic
from numba.np.arrayobj import make_array


def _jit_formula(f):
    """Compile a formula as a function of its own, typed and lowered once per argument
    types, which LLVM inlines into its callers where it pays (its optimiser sees the
    whole kernel). Inlined by Numba instead (``inline="always"``), each call site typed
    and lowered the formula again: the serial chain's kernels compiled in 9.7 s against
    3.1 s now, the whole set 83 s against 72 s, and no simulation or serial benchmark
    ran slower (measured one core, 2026-11-28). The Kane passes themselves are programs
    of their own (:mod:`.passes`)."""
    return njit(**JIT)(f)


K = backends.bind({}, _jit_formula)
#: The formulas compiled without inlining, each built once, for the paths that call a
#: formula now and then (the actuators' coordinates): ~2x the run time of the inlined
#: build.
KE = backends.bind({}, njit(**JIT))
STAMP = backends.source_stamp()

_BAD_INPUT, _VIOLATION, _BAD_OUTPUT, _KAPPA = ws.BAD_INPUT, ws.VIOLATION, ws.BAD_OUTPUT, ws.KAPPA
#: A clean health record, and the slots that hold the first sample of something found.
_EMPTY, _FIRST_SLOTS = ws.new_health(), ws.FIRST
_LENGTH, _COS, _HEIGHT, _DX, _DY, _DZ, _H = 0, 1, 2, 3, 4, 5, 6
_ujoint_angles = K.ujoint_angles
#: The U-joint angle check first compares tangents (no arctan2): it is trusted only well
#: inside a limit, by this relative margin; nearer, the angle itself is computed.
_TAN_MARGIN = 1e-12


assert FIELDS == ("plat_m", "plat_c", "plat_I", "arm_t", "arm_Ro", "arm_axis", "arm_m", "arm_c",
                  "arm_I", "leg_s", "leg_P", "leg_X", "leg_Y", "leg_Z", "lo_m", "lo_c", "up_m",
                  "up_c", "leg_I", "thin_It", "lo_cz", "up_cz", "L", "lim_arm", "lim_stroke",
                  "lim_ujoint"), "unpack() below follows constants.FIELDS"


#: :func:`unpack`'s fields in :class:`~.formulas.KaneConstants` order: ``("at", i)`` the
#: number ``flat[lay[i, 0]]``, ``("view", i, ndim)`` the view of layout row i, ``("n",)``
#: the arm's joints (``prism``'s length), ``("prism",)`` the joint types; then the
#: limits' views.
_FIELDS = (("at", 0), ("view", 1, 1), ("view", 2, 2), ("n",), ("view", 3, 2), ("view", 4, 3),
           ("view", 5, 2), ("prism",), ("view", 6, 1), ("view", 7, 2), ("view", 8, 3),
           ("view", 9, 2), ("view", 10, 2), ("view", 11, 2), ("view", 12, 2),
           ("view", 13, 2), ("view", 14, 1), ("view", 15, 2), ("view", 16, 1),
           ("view", 17, 2), ("view", 18, 3), ("view", 19, 1), ("view", 20, 1),
           ("view", 21, 1), ("at", 22))
_LIMITS = (("view", 23, 2), ("view", 24, 2), ("view", 25, 3))


@intrinsic
def _unpacked(typingctx, flat, lay, prism):
    """:func:`unpack`'s tuple, written in one piece: each view as :func:`~.views.c_view`
    writes it (no owner), ``prism`` without its owner (the kernel's argument). One call
    for Numba to type and lower where the views as inlined calls were 29 (a kernel's
    compile spent seconds on them, once per kernel that unpacks)."""
    if not (isinstance(flat, types.Array) and flat.ndim == 1 and flat.layout == "C"
            and isinstance(lay, types.Array) and lay.ndim == 2
            and isinstance(lay.dtype, types.Integer) and isinstance(prism, types.Array)):
        return None

    def of(spec):
        kind = spec[0]
        return (flat.dtype if kind == "at" else flat.copy(ndim=spec[2], layout="C")
                if kind == "view" else types.intp if kind == "n" else prism)

    named = types.NamedTuple([of(f) for f in _FIELDS], KaneConstants)
    limits = [of(f) for f in _LIMITS]
    sig = types.Tuple([named, *limits])(flat, lay, prism)

    def codegen(context, builder, signature, args):
        src = make_array(flat)(context, builder, args[0])
        table = make_array(lay)(context, builder, args[1])
        joints = make_array(prism)(context, builder, args[2])
        shape = cgutils.unpack_tuple(builder, table.shape)
        strides = cgutils.unpack_tuple(builder, table.strides)

        def row(i, j):
            at = cgutils.get_item_pointer2(context, builder, table.data, shape, strides,
                                           lay.layout, [context.get_constant(types.intp, i),
                                                        context.get_constant(types.intp, j)])
            return context.cast(builder, builder.load(at), lay.dtype, types.intp)

        def value(spec, typ):
            kind = spec[0]
            if kind == "at":
                return builder.load(builder.gep(src.data, [row(spec[1], 0)], inbounds=True))
            if kind == "view":
                return view_value(context, builder, typ, src, row(spec[1], 0),
                                  [row(spec[1], 1 + k) for k in range(spec[2])])
            if kind == "n":
                return cgutils.unpack_tuple(builder, joints.shape)[0]
            own = make_array(prism)(context, builder, value=args[2])
            own.meminfo = cgutils.get_null_value(own.meminfo.type)
            own.parent = cgutils.get_null_value(own.parent.type)
            return own._getvalue()

        C = context.make_tuple(builder, named, [value(f, t) for f, t in zip(
            _FIELDS, named.types)])
        return context.make_tuple(builder, signature.return_type, [C, *(
            value(f, t) for f, t in zip(_LIMITS, limits))])

    return sig, codegen


@njit(inline="always", **JIT)
def unpack(flat, lay, prism):
    """The constants' views from :attr:`~.constants.RobotArrays.flat`: ``(C, lim_arm,
    lim_stroke, lim_ujoint)`` (:data:`~.constants.FIELDS` order). Inlined, its views
    written directly (:func:`_unpacked`): called, with NumPy's reshape, it cost each
    kernel call 1.9 µs, what a one-sample call or a stage of a plant notices; ``prism``
    in C has no owner (it must outlive C, as ``flat`` must)."""
    return _unpacked(flat, lay, prism)


@njit(**JIT)
def _first(health, slot, k, a, b):
    if health[slot] < 0.0:
        health[slot] = k
        health[slot + 1] = a
        health[slot + 2] = b


@njit(**JIT)
def _kappa(health, kind, k, value, warn, error):
    s = _KAPPA + 4 * kind
    if value > health[s] or (np.isnan(value) and not np.isnan(health[s])):
        health[s] = value
        health[s + 1] = k
    if health[s + 2] < 0.0 and value > warn:
        health[s + 2] = k
    if health[s + 3] < 0.0 and not value <= error:
        health[s + 3] = k


@njit(**JIT)
def _finite_inputs(q, qd, qdd, k, health):
    """False (and the first one recorded) if sample k has a non-finite input. A finite
    sum of the 27 values (one pass, no branch) proves them all finite; only otherwise
    are they looked at one by one."""
    total = 0.0
    for j in range(9):
        total += q[k, j] + qd[k, j] + qdd[k, j]
    if np.isfinite(total):
        return True
    for which in range(3):
        arr = q if which == 0 else (qd if which == 1 else qdd)
        for j in range(9):
            if not np.isfinite(arr[k, j]):
                if health[_BAD_INPUT] < 0.0:
                    _first(health, _BAD_INPUT, k, j, which)
                return False
    return True          # finite values whose sum overflowed


@njit(**JIT)
def tangent_bounds(lim_ujoint):
    """``(6, 2, 2)`` tangents of the U-joint limits shrunk by :data:`_TAN_MARGIN`; inf
    (the test always defers to the angle) for a limit outside (−π/2, π/2)."""
    out = np.empty((6, 2, 2))
    for l in range(6):
        for a in range(2):
            lo, hi = lim_ujoint[l, a, 0], lim_ujoint[l, a, 1]
            if -0.5 * np.pi < lo <= hi < 0.5 * np.pi:
                tlo, thi = np.tan(lo), np.tan(hi)
                out[l, a, 0] = tlo + _TAN_MARGIN * (1.0 + abs(tlo))
                out[l, a, 1] = thi - _TAN_MARGIN * (1.0 + abs(thi))
            else:
                out[l, a, 0] = np.inf
                out[l, a, 1] = -np.inf
    return out


@njit(**JIT)
def _ujoint_inside(diag, l, tb):
    """True when both U-joint angles of leg l are surely inside their limits:
    θ1 = atan2(dx, dz) with dz > 0 and θ2 = atan2(−dy, h) with h > 0, compared through
    their tangents."""
    dx, dy, dz, h = diag[_DX, l], diag[_DY, l], diag[_DZ, l], diag[_H, l]
    return (dz > 0.0 and tb[l, 0, 0] * dz <= dx <= tb[l, 0, 1] * dz
            and h > 0.0 and tb[l, 1, 0] * h <= -dy <= tb[l, 1, 1] * h)


@njit(**JIT)
def _check(k, q, na, diag, cond, want_legs, want_cond, want_limits, warn, error, lim_arm,
           lim_stroke, lim_ujoint, tb, kappa, health):
    """Sample k's condition numbers (``cond``: the leg-force system's, NaN when none was
    solved) and workspace limits, into ``kappa`` and the health record."""
    if want_cond:
        att = 1.0 / abs(np.cos(q[k, 4]))
        kappa[2, k] = att
        _kappa(health, 2, k, att, warn, error)
        kappa[0, k] = cond
        if want_legs:
            if not np.isnan(cond):
                _kappa(health, 0, k, cond, warn, error)
            worst = diag[_COS, 0]
            for l in range(1, 6):
                worst = min(worst, diag[_COS, l])
            gim = 1.0 / worst if worst > 0.0 else np.inf
            kappa[1, k] = gim
            _kappa(health, 1, k, gim, warn, error)
        else:
            kappa[1, k] = np.nan
    if want_limits:
        s = _VIOLATION
        if health[s] < 0.0:
            for b in range(na):
                v = q[k, 6 + b]
                if v < lim_arm[b, 0] or v > lim_arm[b, 1]:
                    _first(health, s, k, b, v)
                    break
        if want_legs:
            if health[s + 3] < 0.0:
                for l in range(6):
                    if diag[_HEIGHT, l] <= 0.0:
                        _first(health, s + 3, k, l, diag[_HEIGHT, l])
                        break
            if health[s + 6] < 0.0:
                for l in range(6):
                    v = diag[_LENGTH, l]
                    if v < lim_stroke[l, 0] or v > lim_stroke[l, 1]:
                        _first(health, s + 6, k, l, v)
                        break
            if health[s + 9] < 0.0:
                for l in range(6):
                    if _ujoint_inside(diag, l, tb):
                        continue
                    th = _ujoint_angles(diag[_DX, l], diag[_DY, l], diag[_DZ, l], diag[_H, l])
                    hit = False
                    for a in range(2):
                        v = th[a]
                        if v < lim_ujoint[l, a, 0] or v > lim_ujoint[l, a, 1]:
                            _first(health, s + 9, k, 2 * l + a, v)
                            hit = True
                            break
                    if hit:
                        break


@njit(**JIT)
def _finite_outputs(k, out, columns_a, columns_b, health):
    """Record the first non-finite value of ``out[k]`` in columns [0, a) ∪ [3, b)."""
    if health[_BAD_OUTPUT] < 0.0:
        for j in range(columns_b):
            if (j < columns_a or j >= 3) and not np.isfinite(out[k, j]):
                health[_BAD_OUTPUT] = k
                health[_BAD_OUTPUT + 1] = j
                break


@njit(**JIT)
def _post(k, q, na, A, rhs, diag, want_legs, want_cond, want_limits, warn, error, lim_arm,
          lim_stroke, lim_ujoint, tb, X, kappa, health, x, M):
    """Sample k after the formulas: solve the legs, measure κ, check the limits and the
    result's finiteness (the arm columns of X are filled)."""
    for b in range(na, 3):
        X[k, b] = np.nan
    cond = 0.0
    if want_legs:
        cond = solve6(A, rhs, x, M, want_cond)
        for j in range(6):
            X[k, 3 + j] = x[j]
    else:
        for j in range(6):
            X[k, 3 + j] = np.nan
    _check(k, q, na, diag, cond, want_legs, want_cond, want_limits, warn, error, lim_arm,
           lim_stroke, lim_ujoint, tb, kappa, health)
    _finite_outputs(k, X, na, 9 if want_legs else na, health)


def _make(stamp):
    """The drivers, closed over the formulas' hash (it keys their disk cache)."""

    @njit(**JIT)
    def kane(flat, lay, prism, q, qd, qdd, g, static, leg_model, want_legs, want_cond,
             want_limits, warn, error, start, stop, X, kappa, health):
        """Samples ``start..stop-1`` of the fused Kane equations, checked."""
        if len(stamp) == 0:
            return
        C, lim_arm, lim_stroke, lim_ujoint = unpack(flat, lay, prism)
        tb = tangent_bounds(lim_ujoint)
        na = C.n_arm
        rows = np.zeros(3)
        A = np.empty((6, 6))
        rhs = np.empty(6)
        diag = np.zeros((7, 6))
        store = np.empty((max(na, 1), 27))
        x = np.empty(6)
        M = np.empty((6, 13))
        gt = (g[0], g[1], g[2])
        for k in range(start, stop):
            if not _finite_inputs(q, qd, qdd, k, health):
                for j in range(9):
                    X[k, j] = np.nan
                continue
            call_kane(C, q[k], qd[k], qdd[k], gt, static, leg_model, want_legs, rows, A, rhs,
                      diag, store)
            for b in range(na):
                X[k, b] = rows[b]
            _post(k, q, na, A, rhs, diag, want_legs, want_cond, want_limits, warn, error,
                  lim_arm, lim_stroke, lim_ujoint, tb, X, kappa, health, x, M)

    @njit(**JIT)
    def explicit(flat, lay, prism, q, qd, qdd, g, want_cond, want_limits, warn, error, start,
                 stop, X, kappa, health):
        """Samples ``start..stop-1`` of Kane's equations with explicit partials, checked:
        ``(T1, T2, Fs) = B[6:9]``, ``Jᵀ Fl = B[0:6]`` (rotation rows scaled by 1/L)."""
        if len(stamp) == 0:
            return
        C, lim_arm, lim_stroke, lim_ujoint = unpack(flat, lay, prism)
        tb = tangent_bounds(lim_ujoint)
        na = C.n_arm
        B = np.zeros(9)
        J = np.empty((6, 6))
        Mm = np.zeros((9, 9))
        A = np.empty((6, 6))
        rhs = np.empty(6)
        diag = np.zeros((7, 6))
        store = np.empty((max(na, 1), 27))
        Vw = np.empty((9, 3))
        Ww = np.empty((9, 3))
        Vs = np.empty((9, 3))
        mc = np.empty((1, 3))
        x = np.empty(6)
        M = np.empty((6, 13))
        gt = (g[0], g[1], g[2])
        iL = 1.0 / C.L
        for k in range(start, stop):
            if not _finite_inputs(q, qd, qdd, k, health):
                for j in range(9):
                    X[k, j] = np.nan
                continue
            B[:] = 0.0
            call_explicit(C, q[k], qd[k], qdd[k], gt, False, B, J, Mm, store, Vw, Ww, Vs,
                          diag, mc)
            for b in range(na):
                X[k, b] = B[6 + b]
            leg_system(B, J, iL, A, rhs)
            _post(k, q, na, A, rhs, diag, True, want_cond, want_limits, warn, error,
                  lim_arm, lim_stroke, lim_ujoint, tb, X, kappa, health, x, M)

    @njit(**JIT)
    def forward(flat, lay, prism, q, qd, X, g, want_qdd, want_M, want_h, want_A, want_cond,
                want_limits, warn, error, start, stop, qdd, Mout, hout, Aout, kappa, health):
        """Samples ``start..stop-1`` of the equations of motion ``M q̈ + h = A X`` in the
        independent coordinates (explicit partials, q̈ = 0 gives h): fills the requested
        of ``qdd`` (N, 9) (solved by Cholesky), ``Mout`` (N, 9, 9), ``hout`` (N, 9) and
        ``Aout`` (N, 9, 9); coordinates beyond 6 + n_arm are NaN in qdd, zero rows/columns
        in M, h, A."""
        if len(stamp) == 0:
            return
        C, lim_arm, lim_stroke, lim_ujoint = unpack(flat, lay, prism)
        tb = tangent_bounds(lim_ujoint)
        na = C.n_arm
        n = 6 + na
        B = np.zeros(9)
        J = np.empty((6, 6))
        Mm = np.zeros((9, 9))
        L = np.zeros((9, 9))
        diag = np.zeros((7, 6))
        store = np.empty((max(na, 1), 27))
        Vw = np.empty((9, 3))
        Ww = np.empty((9, 3))
        Vs = np.empty((9, 3))
        mc = np.empty((1, 3))
        rhs = np.empty(9)
        x = np.empty(9)
        zero = np.zeros(9)
        gt = (g[0], g[1], g[2])
        for k in range(start, stop):
            if not _finite_inputs(q, qd, X, k, health):
                if want_qdd:
                    for j in range(9):
                        qdd[k, j] = np.nan
                continue
            B[:] = 0.0
            Mm[:] = 0.0
            call_explicit(C, q[k], qd[k], zero, gt, want_M or want_qdd, B, J, Mm, store,
                          Vw, Ww, Vs, diag, mc)
            if want_h:
                for r in range(9):
                    hout[k, r] = B[r]
            if want_M:
                for r in range(9):
                    for c_ in range(r + 1):
                        Mout[k, r, c_] = Mm[r, c_]
                        Mout[k, c_, r] = Mm[r, c_]
            if want_A:
                for r in range(9):
                    for c_ in range(9):
                        Aout[k, r, c_] = 0.0
                for b in range(na):
                    Aout[k, 6 + b, b] = 1.0
                for r in range(6):
                    for l in range(6):
                        Aout[k, r, 3 + l] = J[l, r]
            if want_qdd:
                actuation_minus_bias(B, J, X[k], na, rhs)
                ok = cholesky_solve(Mm, rhs, n, x, L)
                for j in range(9):
                    qdd[k, j] = x[j] if j < n else np.nan
                if not ok and health[_KAPPA + 11] < 0.0:   # attitude: M singular
                    health[_KAPPA + 11] = k
                _finite_outputs(k, qdd, 3, n, health)
            _check(k, q, na, diag, np.nan, True, want_cond, want_limits, warn, error,
                   lim_arm, lim_stroke, lim_ujoint, tb, kappa, health)

    @njit(**JIT)
    def forward_one(flat, lay, prism, q, qd, X, g, warn, error, qdd):
        """:func:`forward` of one sample with q̈ wanted and every check on (condition
        numbers, workspace), for a per-step call from Python (a controller's, a user's):
        ``q, qd, X`` and ``qdd`` (9,), ten arguments where :func:`forward` has 23 (Numba's
        dispatch of a call: 1.1 against 1.5 µs, measured). Returns True when the health record
        holds nothing to report (:func:`~offshore_crane.robot.kinematics.workspace.
        is_clean`); otherwise ``qdd`` is not to be used: the caller runs the general
        path, which reports."""
        if len(stamp) == 0:
            return False
        kappa = np.empty((3, 1))
        health = _EMPTY.copy()
        forward(flat, lay, prism, q.reshape((1, 9)), qd.reshape((1, 9)), X.reshape((1, 9)),
                g, True, False, False, False, True, True, warn, error, 0, 1,
                qdd.reshape((1, 9)), np.empty((1, 9, 9)), np.empty((1, 9)),
                np.empty((1, 9, 9)), kappa, health)
        for s in _FIRST_SLOTS:
            if health[s] >= 0.0:
                return False
        return True

    return kane, explicit, forward, forward_one


kane, explicit, forward, forward_one = _make(STAMP)
