"""Compiled kernels of the rigid plant (:mod:`.rigid`) for the RK4 driver
(:mod:`offshore_crane.simulation.loop`; imports Numba), over the rigid robot's equations
of motion and laws (:mod:`offshore_crane.simulation.rigid_equations`). ``P``
(:func:`params`): the plant's and the model's packed arrays, gravity, the one zeroed work
buffer (:func:`~offshore_crane.simulation.rigid_equations.carve`: the equations' and the
law's work arrays, views made in each kernel rather than handed in P, which the driver
passes at every stage), q̈, zeros, the state the pass in the buffer was made at (NaN
before any: no state equals it), whether the model is the plant's own, the plant's
``1 / L`` [1/m] (its mean anchor distance from O2: the leg system's scale) and the
actuated joints' positions and rates (18,) that :func:`keep` forms the power from.

One explicit pass a stage serves both the law and the accelerations when a computed
torque runs on the plant's own model: :func:`prepare` makes the pass at the stage's
state before the law is evaluated, and :func:`inverse` finds it there (the state it was
made at equal to the law's, value for value) and forms ``M q̈_cmd + h`` from it
(:func:`~offshore_crane.simulation.rigid_equations.ct_from`) instead of a pass of its
own. A law sampled at other states (held, delayed, noisy) misses the memo and makes its
own pass, as a model other than the plant always does."""

from __future__ import annotations

import hashlib
import inspect

import numpy as np

from offshore_crane import kernel_calls
from offshore_crane.dynamics import compiled as c
from offshore_crane.kernel_cache import njit
from offshore_crane.simulation.plants import shared_kernels as shared
from offshore_crane.simulation import rigid_equations as eq
from offshore_crane.simulation.laws import codes

jit = njit(**c.LEAN)
equations, solve, law = eq.equations, eq.solve, eq.call_law
carve, carve_ws = eq.carve, eq.carve_ws
energy, ct_from = eq.energy, eq.ct_from
inline = njit(inline="always", **c.JIT)


@inline
def _work(P):
    """The equations' and the law's work tuples (``ws``, ``wl``), carved from ``P[7]``
    for the longer arm of the plant's and the model's (their ``prismatic`` flags)."""
    return carve(P[7], max(P[2].shape[0], P[5].shape[0]))


@inline
def _ws(P):
    """``_work(P)[0]`` alone (fewer views for the compiler to type and lower)."""
    return carve_ws(P[7], max(P[2].shape[0], P[5].shape[0]))


unpack = c.unpack
CT, PDG = codes.COMPUTED_TORQUE, codes.PD_GRAVITY


@inline
def _made_at(P, y):
    """True when the pass in the work buffer was made at ``y[:18]`` (value for value)."""
    at = P[10]
    for j in range(18):
        if at[j] != y[j]:
            return False
    return True


def _make(stamp):

    @inline
    def prepare(P, i, y, aux):
        """The explicit pass at ``y``'s (q, q̇) into the work buffer, remembered as made
        there (the module docstring)."""
        if len(stamp) == 0:
            return
        C = unpack(P[0], P[1], P[2])[0]
        equations(C, P[6], y[:9], y[9:18], _ws(P))
        at = P[10]
        for j in range(18):
            at[j] = y[j]

    @jit
    def prepare_called(P, y):
        """:func:`prepare` called by address (:data:`PREPARE`): for what finds no pass
        made at its state; its text is then typed and compiled once, beside the driver's
        loop, not inlined into its stage a second time."""
        if len(stamp) == 0:
            return
        prepare(P, 0, y, P[9])

    @inline
    def rhs(P, i, y, X, dy, aux):
        """(q̇, q̈) into ``dy[:18]``; ``aux[0]`` ok (False: M singular). The pass
        :func:`prepare` made at ``y``, else one made here."""
        if len(stamp) == 0:
            return False
        qdd = P[8]
        if not _made_at(P, y):
            call_prepare(P, y)
        ok = solve(6 + P[2].shape[0], X, qdd, _ws(P))
        for j in range(9):
            dy[j] = y[9 + j]
            dy[9 + j] = qdd[j]
        aux[0] = 1.0 if ok else 0.0
        return ok

    @jit
    def keep(P, EXTRA, k, y, dy, X, aux):
        """The energy [J] at ``y`` into ``EXTRA[k, 0]``: kinetic ``½ q̇ᵀ M q̇`` and
        gravitational ``−g · Σ m c``, from the explicit pass made at ``y`` (the step's
        first stage) in the work buffer; and the actuators' power [W] under the applied
        ``X`` into ``EXTRA[k, 1]``: ``Σ X_k ṡ_k`` over the arm joints, then over the legs
        (the actuated joints' rates, the kinematics' compiled text: the numbers of
        :func:`~offshore_crane.simulation.record.actuator_power` on NumPy, bit for bit,
        without its pass over the record after the run)."""
        if len(stamp) == 0:
            return
        ws = _ws(P)
        EXTRA[k, 0] = energy(ws[2], ws[9], y[9:18], 6 + P[2].shape[0], P[6])
        EXTRA[k, 1] = shared.power(P[0], P[1], P[2], y[:9], y[9:18], X, P[13])

    @jit
    def own_inverse(P, y, qdd, X):
        """The compiled law's computed torque with the model's own pass, zero gains at
        the reference (q, q̇, q̈), called by address (:data:`OWN_INVERSE`: compiled once,
        beside a law's template that calls it)."""
        if len(stamp) == 0:
            return
        Cc = unpack(P[3], P[4], P[5])[0]
        zero = P[9]
        law(Cc, P[6], CT, zero, zero, y[:9], y[9:18], y[:9], y[9:18], qdd, X, _work(P)[1])

    @inline
    def inverse(P, i, y, qdd, X):
        """The model's inverse dynamics at ``qdd``: from the plant's pass made at ``y``
        when the model is the plant's own (the module docstring), else
        :func:`own_inverse`."""
        if len(stamp) == 0:
            return
        if P[11] and _made_at(P, y):
            ws, wl = _work(P)
            ct_from(6 + P[2].shape[0], P[12], qdd, X, ws, wl)
            return
        call_own_inverse(P, y, qdd, X)

    @jit
    def gravity(P, i, y, X):
        if len(stamp) == 0:
            return
        Cc = unpack(P[3], P[4], P[5])[0]
        zero = P[9]
        wl = _work(P)[1]
        law(Cc, P[6], PDG, zero, zero, y[:9], zero, y[:9], zero, zero, X, wl)

    return prepare, rhs, keep, inverse, gravity, prepare_called, own_inverse


#: What these kernels' disk cache is keyed by: the formulas' hash and the text of the
#: rigid equations and shared kernels they call (Numba's cache checks only a function's
#: own file, so a callee edited elsewhere would otherwise be linked stale).
STAMP = c.STAMP + hashlib.sha256((inspect.getsource(eq) + inspect.getsource(shared)
                                  ).encode()).hexdigest()
prepare, rhs, keep, inverse, gravity, prepare_called, own_inverse = _make(STAMP)
#: ``P``'s Numba type (:func:`params`), in the entries' signatures.
_P = "Tuple((*PACKED, *PACKED, T3, V, V, V, V, boolean, float64, V))"
#: The pass and the model's own inverse dynamics called by address
#: (:mod:`offshore_crane.kernel_calls`): the paths the memo does not serve compile in a
#: helper process beside the driver's loop (measured, one process, Numba's compile
#: events: the rigid computed torque's loop 17.7 s when they were inlined, 10.5 s now).
PREPARE = kernel_calls.Entry.typed("rigid_prepare", lambda: prepare_called,
                                   f"none({_P}, V)", STAMP)
OWN_INVERSE = kernel_calls.Entry.typed("rigid_own_inverse", lambda: own_inverse,
                                       f"none({_P}, V, V, V)", STAMP)
call_prepare, call_own_inverse = PREPARE.call, OWN_INVERSE.call
check, coords, payload, arm_tip = shared.check, shared.coords, shared.payload, shared.arm_tip
winch, winch_to = shared.winch, shared.winch_to


def params(plant) -> tuple:
    """``P`` of a :class:`~offshore_crane.simulation.plants.RigidPlant`."""
    from offshore_crane.dynamics.constants import robot_arrays

    a, m = robot_arrays(plant.robot), robot_arrays(plant.model)
    work = np.zeros(eq.work_size(max(a.kane.n_arm, m.kane.n_arm)))
    own = all(np.array_equal(x, z) for x, z in ((a.flat, m.flat), (a.layout, m.layout),
                                                  (a.prismatic, m.prismatic)))
    return (a.flat, a.layout, a.prismatic, m.flat, m.layout, m.prismatic,
            tuple(float(x) for x in plant.g), work, np.zeros(9), np.zeros(9),
            np.full(18, np.nan), own, 1.0 / float(a.kane.L), np.zeros(18))
