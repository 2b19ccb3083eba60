"""Compiled one-sample kernels of the plant of the simulation on an elastic cable
(:mod:`offshore_crane.simulation.elastic`; imports Numba).

The plant is the robot without its hanging payload, pulled at the tip by the cable, and
the payload a point mass; its state ``y`` (24,) = ``[q (9), p (3), q̇ (9), v (3)]`` (``p``,
``v`` the payload's position and velocity, base frame). :func:`derivative` is
:class:`offshore_crane.simulation.plants.ElasticPlant`'s ``derivative``, compiled: the
cable's law :func:`~offshore_crane.dynamics.sway.cable_tension` clamped to pulling only;
the pull ``P = T ρ̂ − F_s`` on the robot at the payload's place (``F_s``:
:func:`~offshore_crane.dynamics.sway.sway_damping_force` while the cable pulls); the
robot's accelerations from its equations of motion (the explicit Kane pass,
``formulas.explicit_sample``, solved by Cholesky) under ``X − ΔX(P)``, with ``ΔX(P)`` the
Kane pass with the pull at rest (``formulas.kane_sample_pull`` at ``q̈ = 0``) less the same
with ``0 × P`` (the pull's share of X: X is affine in the pull, its share the same at any
accelerations); the payload's acceleration ``g + (F_d − P) / m`` (``F_d``:
:func:`~offshore_crane.dynamics.sway.drag_force`). :func:`computed_torque` is the built-in
law's X: the Kane pass with the measured pull at the commanded accelerations, and
:func:`measure` the pull (the load cell) it reads. :func:`computed_torque_share` is the
law's X and ``ΔX(P)`` from one program: the law's pass less the same with ``0 × P``, at
the commanded accelerations (the two share all but the pull's terms; each gives its own
numbers bit for bit), which :func:`derivative` then reads (``fused``) instead of making
its two passes at rest. The share differs from those two passes' by round-off only
(tested). On the driver's built-in law at the plant's own state: 3.3 → 1.5 µs for the
plant's rates (2026-11-28), and the law 1.14 → 0.93 µs when its program went from three
passes (the share at rest) to two (measured one core, the same day).

Every formula is the compiled text of :mod:`offshore_crane.dynamics.formulas` and
:mod:`offshore_crane.dynamics.sway` (:data:`offshore_crane.dynamics.compiled.K`, ``KE``);
every constant (the payload's mass included) comes from the robot's packed arrays
(:func:`~offshore_crane.dynamics.constants.cable_arrays` of the robot with its payload,
:func:`~offshore_crane.dynamics.constants.robot_arrays` of the robot without it). The
kernels allocate nothing: their scratch is one buffer ``work`` (:data:`WORK` floats) cut
into views. :class:`ElasticPlant` holds the arrays and buffers for calls from Python (an
RK4 loop). Like the drivers of :mod:`.kernels`, they close over the formulas' hash only.
"""

from __future__ import annotations

import numpy as np
from offshore_crane import kernel_calls

from offshore_crane.conventions import GRAVITY
from offshore_crane.dynamics import compiled as c
from offshore_crane.dynamics import views
from offshore_crane.dynamics.cable.work import NA
from offshore_crane.dynamics.cable.kernels import jit, tip_frame
from offshore_crane.kernel_cache import njit
from offshore_crane.dynamics.formulas import STORE_WIDTH

#: The kernels a stage runs (the load cell, the law, the plant's rates and their pieces):
#: compiled without Numba's reference counting (:data:`~offshore_crane.kernel_cache.
#: LEAN`: they allocate nothing and return numbers), whose calls on each array argument
#: at entry and exit were a tenth of the elastic lift's time (62 -> 69 real-time).
lean = njit(**c.LEAN)
dot = c.K.dot
cable_tension, sway_damping_force = c.K.cable_tension, c.K.sway_damping_force
drag_force = c.K.drag_force
#: The Kane pass with the pull and the explicit pass: each compiled once and called by
#: address (``compiled.call_kane_pull``, ``compiled.call_explicit``:
#: :mod:`offshore_crane.dynamics.passes`), as the plant's own passes are by its loops
#: (:data:`DERIVATIVE` below): linked, each loop (one per law) compiled them again.
kane_sample_pull, explicit_sample = c.call_kane_pull, c.call_explicit
kane_sample_pull2 = c.call_kane_pull2
solve6, solve6_many, cholesky_solve, unpack = (c.solve6, c.solve6_many, c.cholesky_solve,
                                               c.unpack)
c_view = views.c_view
actuation_minus_bias = c.actuation_minus_bias
#: :func:`derivative`'s ``status[0]``: the mass matrix positive definite, or singular (the
#: robot's accelerations are NaN: the attitude singularity q5 = ±π/2, or a state not
#: finite).
OK, SINGULAR = 0, 1
#: The layout of ``par`` (:func:`parameters`): gravity (3) [m/s²], EA [N], the axial
#: damping [N·s/m], the sway damping c1, c2 [N·m·s/rad], the drag ``½ ρ C_d A`` [kg/m].
_EA, _DAMPING, _C1, _C2, _DRAG = 3, 4, 5, 6, 7
#: The load cell ``cell`` (:data:`CELL`,): the pull on the robot P (3) [N], where it acts
#: ρ (3) [m, from the tip] and the force on the payload ``F_d − P`` (3) [N], base axes,
#: and the tension [N].
CELL = 10
#: The most bodies of the chain with the sway joints (an arm of 3 joints, the 2 sway
#: joints): the work buffer's arm rows (the hanging load's scratch's, one constant).
_MAX_ARM = NA
#: The work buffer's views, in order, by their sizes: the chain's q, q̇, q̈ (6 + its
#: bodies), the Kane pass's rows, Stewart matrix, right-hand side, diagnostics, arm store,
#: leg forces and Gauss–Jordan scratch, the forces with and without the pull and the
#: shifted X, then the equations of motion's B, J, M, its Cholesky factor, the partials
#: Vw, Ww, Vs, Σ m c, the right-hand side and q̈ (9 coordinates: the sizes of the compiled
#: forward pass, whose loops read the partials' row count).
_SIZES = (6 + _MAX_ARM, 6 + _MAX_ARM, 6 + _MAX_ARM, _MAX_ARM, 36, 6, 42,
          _MAX_ARM * STORE_WIDTH, 6, 78, 9, 9, 9, 9, 36, 81, 81, 27, 27, 27, 3, 9, 9)
(_Q, _QD, _QDD, _ROWS, _A, _RHS6, _DIAG, _STORE, _X6, _M13, _XP, _X0, _XS, _B, _J, _MM,
 _L, _VW, _WW, _VS, _MC, _RHS, _ACC, WORK) = (sum(_SIZES[:i]) for i in range(len(_SIZES) + 1))
#: Where :func:`_carve`'s tuple holds the mass matrix and the mass moments Σ m c (what
#: the plant's energy reads after a pass): the views are in :data:`_SIZES` order.
VIEW_MM, VIEW_MC = 15, 20


#: The scratch of :func:`computed_torque_share` (:data:`SHARE`,), after the work buffer:
#: the two passes' arm rows and right-hand sides, their leg forces and the Gauss–Jordan
#: workspace (:func:`_carve_share`).
_SHARE_SIZES = (2 * _MAX_ARM, 12, 12, 6 * 8)
_ROWS2, _RHS2, _X2, _M8, SHARE = (sum(_SHARE_SIZES[:i])
                                  for i in range(len(_SHARE_SIZES) + 1))


@jit
def _carve_share(w):
    """The views of :func:`computed_torque_share`'s scratch ``w`` (:data:`SHARE`,)."""
    return (c_view(w, _ROWS2, (2, _MAX_ARM)), c_view(w, _RHS2, (2, 6)),
            c_view(w, _X2, (2, 6)), c_view(w, _M8, (6, 8)))


@jit
def _carve_pass(w):
    """The first ten views of :func:`_carve`, what a Kane pass with the pull reads and
    writes (the law's and the load cell's calls carve these only: each view a kernel
    returns is counted in and out, measured)."""
    return (c_view(w, _Q, (_QD - _Q,)), c_view(w, _QD, (_QDD - _QD,)),
            c_view(w, _QDD, (_ROWS - _QDD,)), c_view(w, _ROWS, (_A - _ROWS,)),
            c_view(w, _A, (6, 6)), c_view(w, _RHS6, (_DIAG - _RHS6,)),
            c_view(w, _DIAG, (7, 6)), c_view(w, _STORE, (_MAX_ARM, STORE_WIDTH)),
            c_view(w, _X6, (_M13 - _X6,)), c_view(w, _M13, (6, 13)))


@jit
def _carve(w):
    """The views of the work buffer ``w`` (:data:`WORK`,), each up to the next's start
    (written directly, :func:`~offshore_crane.dynamics.views.c_view`)."""
    return _carve_pass(w) + (
        c_view(w, _XP, (_X0 - _XP,)), c_view(w, _X0, (_XS - _X0,)),
        c_view(w, _XS, (_B - _XS,)), c_view(w, _B, (_J - _B,)), c_view(w, _J, (6, 6)),
        c_view(w, _MM, (9, 9)), c_view(w, _L, (9, 9)), c_view(w, _VW, (9, 3)),
        c_view(w, _WW, (9, 3)), c_view(w, _VS, (9, 3)), c_view(w, _MC, (1, 3)),
        c_view(w, _RHS, (_ACC - _RHS,)), c_view(w, _ACC, (WORK - _ACC,)))


def _helpers(stamp):
    """The pieces, closed over the formulas' hash (their disk cache key); the kernels
    reach them as module globals (a jitted closure variable would defeat the cache)."""

    @lean
    def load(y, q, qd, qdd, n):
        """The chain's ``q, q̇`` (first ``n`` of 11) from the state y, the sway joints' at
        zero; ``q̈`` zero."""
        if len(stamp) == 0:
            return
        for j in range(n):
            q[j] = y[j] if j < 9 else 0.0
            qd[j] = y[12 + j] if j < 9 else 0.0
            qdd[j] = 0.0

    @lean
    def cable(C, par, L, Ld, y, q, qd, cell):
        """The cable at the state y (``q, qd`` the chain's): fills
        ``cell`` (:data:`CELL`,) and returns the tension [N] (0 slack)."""
        if len(stamp) == 0:
            return 0.0
        pt, vt, Rt, w = tip_frame(C, q, qd)
        rho = (y[9] - pt[0], y[10] - pt[1], y[11] - pt[2])
        rhod = (y[21] - vt[0], y[22] - vt[1], y[23] - vt[2])
        T, s, _ = cable_tension(rho, rhod, L, Ld, par[_EA], par[_DAMPING])
        if not (s > 0.0 and T > 0.0):
            T = 0.0
        d = np.sqrt(dot(rho, rho))
        pull = (T * rho[0] / d, T * rho[1] / d, T * rho[2] / d)
        c1, c2 = par[_C1], par[_C2]
        if T > 0.0 and c1 + c2 > 0.0:          # the sway damping, carried by the cable
            fs = sway_damping_force(Rt, w, rho, rhod, c1, c2)
            pull = (pull[0] - fs[0], pull[1] - fs[1], pull[2] - fs[2])
        f = (0.0, 0.0, 0.0)
        if par[_DRAG] != 0.0:
            f = drag_force((y[21], y[22], y[23]), par[_DRAG])
        for j in range(3):
            cell[j] = pull[j]
            cell[3 + j] = rho[j]
            cell[6 + j] = f[j] - pull[j]
        cell[9] = T
        return T

    @lean
    def pulled(C, q, qd, qdd, g, pull, at, X, rows, A, rhs6, diag, store, x6, M13):
        """X (9,) of the robot moving at ``qdd`` with ``pull`` [N] on it at ``at`` [m]
        from the tip (the Kane pass; :func:`.kernels.kane_pulled`'s sample)."""
        if len(stamp) == 0:
            return
        kane_sample_pull(C, q, qd, qdd, g, pull, at, rows, A, rhs6, diag, store)
        for b in range(3):
            X[b] = rows[b] if b < C.n_arm else np.nan
        solve6(A, rhs6, x6, M13, False)
        for l in range(6):
            X[3 + l] = x6[l]

    @lean
    def accelerate(E, q, qd, X, g, a, B, J, Mm, L, store, Vw, Ww, Vs, diag, mc, rhs, zero):
        """``a`` (9,): q̈ of ``M q̈ + h = A X`` of the robot ``E`` (the explicit Kane pass,
        Cholesky; :func:`offshore_crane.dynamics.compiled.forward`'s sample; NaN past its
        coordinates). False when M is not positive definite (``a`` NaN)."""
        if len(stamp) == 0:
            return False
        B[:] = 0.0
        Mm[:] = 0.0
        explicit_sample(E, q, qd, zero, g, True, B, J, Mm, store, Vw, Ww, Vs, diag, mc)
        n = 6 + E.n_arm
        actuation_minus_bias(B, J, X, E.n_arm, rhs)
        ok = cholesky_solve(Mm, rhs, n, a, L)
        for j in range(n, 9):
            a[j] = np.nan
        return ok

    @lean
    def pulled_share(C, q, qd, qdd, g, pull, at, X, D, rows2, A, rhs2, diag, store, x2,
                     M8):
        """X (9,) of :func:`pulled` at ``qdd`` and D (9,) the pull's share of X: X less
        :func:`pulled` at ``qdd`` with ``0 × pull``, each pass bit for bit its own call's
        (one program, one elimination for the two right-hand sides:
        :func:`~offshore_crane.dynamics.linear.solve6_many`)."""
        if len(stamp) == 0:
            return
        pz = (0.0 * pull[0], 0.0 * pull[1], 0.0 * pull[2])
        kane_sample_pull2(C, q, qd, qdd, g, pull, pz, at, rows2, A, rhs2, diag, store)
        solve6_many(A, rhs2, x2, M8)
        for b in range(3):
            X[b] = rows2[0, b] if b < C.n_arm else np.nan
            x0 = rows2[1, b] if b < C.n_arm else np.nan
            D[b] = X[b] - x0
        for l in range(6):
            X[3 + l] = x2[0, l]
            D[3 + l] = x2[0, l] - x2[1, l]

    return load, cable, pulled, accelerate, pulled_share


load, cable_kernel, pulled_kernel, accelerate, pulled_share = _helpers(c.STAMP)


#: :func:`pulled` and :func:`cable` called by address (:mod:`offshore_crane.
#: kernel_calls`): compiled once each (the Kane pass with the pull inlined, the cable's
#: model), not again in :func:`measure`, :func:`computed_torque` and :func:`derivative`,
#: which run them.
PULLED = kernel_calls.Entry.typed(
    "elastic_pulled", lambda: pulled_kernel,
    "none(C, V, V, V, T3, T3, T3, V, V, M, V, M, M, V, M)", c.STAMP,
    C=c.kane_constants_type())
CABLE = kernel_calls.Entry.typed(
    "elastic_cable", lambda: cable_kernel, "float64(C, V, float64, float64, V, V, V, V)",
    c.STAMP, C=c.kane_constants_type())
pulled, cable = PULLED.call, CABLE.call


def _make(stamp):

    @lean
    def measure(flat, lay, prism, par, L, Ld, y, cell, work):
        """The load cell at the state ``y`` (24,) on a cable of length ``L`` [m] paid out
        at ``Ld`` [m/s]: fills ``cell`` (:data:`CELL`,) and returns the tension [N]
        (0 slack). ``flat, lay, prism``: the robot with its payload
        (:func:`~offshore_crane.dynamics.constants.cable_arrays`); ``par``
        (:func:`parameters`); ``work`` (:data:`WORK`,) scratch."""
        if len(stamp) == 0:
            return 0.0
        C = unpack(flat, lay, prism)[0]
        q, qd, qdd = _carve_pass(work)[:3]
        load(y, q, qd, qdd, 6 + C.n_arm)
        return cable(C, par, L, Ld, y, q, qd, cell)

    @lean
    def computed_torque(flat, lay, prism, par, y, qdd_cmd, cell, X, work):
        """The built-in law's actuator forces ``X`` (9,): the Kane pass of the model
        (``flat, lay, prism``: the controller's model with its payload, as
        :func:`~offshore_crane.dynamics.constants.cable_arrays` packs it) at the state
        ``y`` (24,) moving at ``qdd_cmd`` (9,), with the measured pull ``cell[0:3]`` [N]
        acting at ``cell[3:6]`` [m] from the tip (:func:`measure`)."""
        if len(stamp) == 0:
            return
        C = unpack(flat, lay, prism)[0]
        (q, qd, qdd, rows, A, rhs6, diag, store, x6, M13) = _carve_pass(work)
        load(y, q, qd, qdd, 6 + C.n_arm)
        for j in range(9):
            qdd[j] = qdd_cmd[j]
        pulled(C, q, qd, qdd, (par[0], par[1], par[2]), (cell[0], cell[1], cell[2]),
               (cell[3], cell[4], cell[5]), X, rows, A, rhs6, diag, store, x6, M13)

    @lean
    def computed_torque_share(flat, lay, prism, par, y, qdd_cmd, cell, X, D, work, share):
        """:func:`computed_torque` and, from the same program, the pull's share ``D``
        (9,) of the actuator forces that :func:`derivative` subtracts (``fused``): the
        law's Kane pass less the same with ``0 × P``, on one model (the plant's), each
        bit for bit its own call's. ``share`` (:data:`SHARE`,) scratch."""
        if len(stamp) == 0:
            return
        C = unpack(flat, lay, prism)[0]
        q, qd, qdd, _, A, _, diag, store = _carve_pass(work)[:8]
        rows2, rhs2, x2, M8 = _carve_share(share)
        load(y, q, qd, qdd, 6 + C.n_arm)
        for j in range(9):
            qdd[j] = qdd_cmd[j]
        pulled_share(C, q, qd, qdd, (par[0], par[1], par[2]), (cell[0], cell[1], cell[2]),
                     (cell[3], cell[4], cell[5]), X, D, rows2, A, rhs2, diag, store, x2,
                     M8)

    @lean
    def derivative(flat, lay, prism, eflat, elay, eprism, par, L, Ld, y, X, ydot, cell, work,
                   status, measured, D, fused):
        """``ydot`` (24,) at the state ``y`` (24,) under the applied actuator forces X
        (9,) on a cable of length ``L`` [m] paid out at ``Ld`` [m/s]; returns the tension
        [N] (0 slack). ``flat, lay, prism``: the robot with its payload
        (:func:`~offshore_crane.dynamics.constants.cable_arrays`), ``eflat, elay,
        eprism``: without it (:func:`~offshore_crane.dynamics.constants.robot_arrays` of
        ``robot.without_hanging_payload()``); ``par`` (:func:`parameters`); ``cell``
        (:data:`CELL`,) receives the load cell (:func:`measure`), ``status[0]``
        :data:`OK` or :data:`SINGULAR` (the mass matrix; the robot's accelerations then
        NaN); ``work`` (:data:`WORK`,) scratch. ``measured``: ``cell`` holds the load
        cell at this state and length already (:func:`measure`'s, the same numbers),
        which is then not measured again; ``fused``: ``D`` (9,) holds the pull's share
        of X at this state (:func:`computed_torque_share`'s), which is then not formed
        again (unfused, it is formed at rest: the same up to round-off)."""
        if len(stamp) == 0:
            return 0.0
        C = unpack(flat, lay, prism)[0]
        E = unpack(eflat, elay, eprism)[0]
        (q, qd, qdd, rows, A, rhs6, diag, store, x6, M13, Xp, X0, Xs, B, J, Mm, Lc, Vw, Ww,
         Vs, mc, rhs, a) = _carve(work)
        na = C.n_arm
        load(y, q, qd, qdd, 6 + na)
        T = cell[9] if measured else cable(C, par, L, Ld, y, q, qd, cell)
        g = (par[0], par[1], par[2])
        pull = (cell[0], cell[1], cell[2])
        at = (cell[3], cell[4], cell[5])
        if fused:
            for j in range(9):
                Xs[j] = X[j] - D[j]
        else:
            pulled(C, q, qd, qdd, g, pull, at, Xp, rows, A, rhs6, diag, store, x6, M13)
            pulled(C, q, qd, qdd, g, (0.0 * pull[0], 0.0 * pull[1], 0.0 * pull[2]), at, X0,
                   rows, A, rhs6, diag, store, x6, M13)
            for j in range(9):
                Xs[j] = X[j] - (Xp[j] - X0[j])
        ok = accelerate(E, q, qd, Xs, g, a, B, J, Mm, Lc, store, Vw, Ww, Vs, diag, mc, rhs,
                        qdd)
        m = C.arm_m[na - 1]
        for j in range(9):
            ydot[j] = y[12 + j]
            ydot[12 + j] = a[j]
        for j in range(3):
            ydot[9 + j] = y[21 + j]
            ydot[21 + j] = g[j] + cell[6 + j] / m
        status[0] = OK if ok else SINGULAR
        return T

    return measure, computed_torque, computed_torque_share, derivative


measure, computed_torque, computed_torque_share, derivative = _make(c.STAMP)

#: :func:`measure`, :func:`computed_torque` and :func:`derivative` called by address
#: (:mod:`offshore_crane.kernel_calls`): the elastic plant's loops, one per law, call
#: them without compiling their Kane passes again.
MEASURE = kernel_calls.Entry.typed(
    "elastic_measure", lambda: measure, "float64(*PACKED, V, float64, float64, V, V, V)",
    c.STAMP)
COMPUTED_TORQUE = kernel_calls.Entry.typed(
    "elastic_computed_torque", lambda: computed_torque, "none(*PACKED, V, V, V, V, V, V)",
    c.STAMP)
COMPUTED_TORQUE_SHARE = kernel_calls.Entry.typed(
    "elastic_computed_torque_share", lambda: computed_torque_share,
    "none(*PACKED, V, V, V, V, V, V, V, V)", c.STAMP)
DERIVATIVE = kernel_calls.Entry.typed(
    "elastic_derivative", lambda: derivative,
    "float64(*PACKED, *PACKED, V, float64, float64, V, V, V, V, V, int64[::1], boolean, V, "
    "boolean)", c.STAMP)


def parameters(gravity, ea: float, damping: float, sway, drag: float) -> np.ndarray:
    """The kernels' ``par`` (8,): gravity (3,) [m/s²], the cable's EA [N] and axial
    damping [N·s/m], the sway damping ``(c1, c2)`` [N·m·s/rad] and the payload's drag
    ``½ ρ C_d A`` [kg/m] (``robot.hybrid.sway_damping``, ``robot.hybrid.drag``)."""
    return np.array([*np.asarray(gravity, dtype=float).reshape(3), ea, damping,
                     *np.asarray(sway, dtype=float).reshape(2), drag], dtype=float)


class ElasticPlant:
    """The kernels with their arrays and buffers, for one-sample calls from Python.

    Args:
        robot: With its payload on a cable.
        ea, damping: The cable's EA [N] and axial damping [N·s/m].
        gravity: ``(3,)`` [m/s²], base frame.
        empty: ``robot.without_hanging_payload()`` if already built (it reloads the
            description).
        model: The controller's model (with its payload on a cable) for
            :meth:`computed_torque`; None: ``robot``.

    The state ``y`` (24,), the forces ``X`` (9,), the commanded ``qdd`` (9,) and ``out``
    must be float64 and contiguous (anything else makes Numba compile another
    specialisation; nothing is checked, to keep a call at the kernel's cost).

    Raises:
        InputError: ``ea`` or ``damping`` out of bounds
            (:func:`~offshore_crane.dynamics.cable.elastic.check_cable`).
        ModelError: the robot has no payload on a cable.
    """

    def __init__(self, robot, ea: float, damping: float = 0.0, gravity=GRAVITY, *,
                 empty=None, model=None):
        from offshore_crane.dynamics.cable.elastic import check_cable
        from offshore_crane.dynamics.constants import cable_arrays, robot_arrays
        from offshore_crane.validation import as_gravity

        arrays = cable_arrays(robot)
        check_cable(ea, damping, float(arrays.kane.arm_m[arrays.kane.n_arm - 1]))
        empty = robot_arrays(robot.without_hanging_payload() if empty is None else empty)
        if arrays.kane.n_arm > _MAX_ARM or empty.kane.n_arm + 2 != arrays.kane.n_arm:
            from offshore_crane.errors import ModelError

            raise ModelError(f"the elastic plant takes an arm of at most {_MAX_ARM - 2} "
                             "joints, with and without its payload alike",
                             element="arm")
        mod = arrays if model is None else cable_arrays(model)
        self.par = parameters(as_gravity(gravity), float(ea), float(damping),
                              robot.hybrid.sway_damping, float(robot.hybrid.drag))
        self.cell = np.zeros(CELL)
        self.work = np.zeros(WORK)
        self.status = np.zeros(1, dtype=np.int64)
        self._share = np.zeros(9)               # (not read: derivative's D, unfused)
        self._plant = (arrays.flat, arrays.layout, arrays.prismatic, empty.flat,
                       empty.layout, empty.prismatic, self.par)
        self._cell = (arrays.flat, arrays.layout, arrays.prismatic, self.par)
        self._model = (mod.flat, mod.layout, mod.prismatic, self.par)

    def derivative(self, y, X, L: float, Ld: float, out) -> float:
        """``out`` (24,) = ẏ at ``y`` under the applied X on a cable of length ``L`` [m]
        paid out at ``Ld`` [m/s]; returns the tension [N] (0 slack). :attr:`singular`
        tells whether the mass matrix was singular (the accelerations then NaN);
        :attr:`cell` holds the pull (3) [N], where it acts (3) [m], the force on the
        payload (3) [N] and the tension [N]."""
        return derivative(*self._plant, L, Ld, y, X, out, self.cell, self.work,
                          self.status, False, self._share, False)

    def measure(self, y, L: float, Ld: float) -> float:
        """The load cell at ``y`` into :attr:`cell`; returns the tension [N]."""
        return measure(*self._cell, L, Ld, y, self.cell, self.work)

    def computed_torque(self, y, qdd_cmd, out):
        """``out`` (9,) = the built-in law's X at ``y`` for the commanded accelerations
        ``qdd_cmd`` (9,), with the pull in :attr:`cell` (:meth:`measure` first); returns
        ``out``."""
        computed_torque(*self._model, y, qdd_cmd, self.cell, out, self.work)
        return out

    @property
    def singular(self) -> bool:
        """Whether the last :meth:`derivative` met a singular mass matrix."""
        return bool(self.status[0] == SINGULAR)


def warm_up(robot=None) -> list[tuple[str, float]]:
    """Compile (or load from the cache) the plant's kernels: ``[(name, seconds)]``."""
    import time

    from offshore_crane.dynamics.cable.grid import cable_robot
    from offshore_crane.robot import load_robot

    t0 = time.perf_counter()
    robot = robot or load_robot()
    if robot.hybrid.cable is None:
        robot = cable_robot(robot, length=1.0, mass=1.0)
    plant = ElasticPlant(robot, ea=1e4)
    y = np.zeros(24)
    y[:9] = robot.home_pose()
    y[11] = -1.0
    plant.measure(y, 1.0, 0.0)
    X = plant.computed_torque(y, np.zeros(9), np.empty(9))
    plant.derivative(y, X, 1.0, 0.0, np.empty(24))
    return [("elastic-cable plant kernels", time.perf_counter() - t0)]
