"""Compiled kernels of the elastic plant (:mod:`.elastic`) for the RK4 driver
(:mod:`offshore_crane.simulation.loop`; imports Numba), over the plant's one-sample
kernels (:mod:`offshore_crane.dynamics.cable.elastic_plant`). ``P`` (:func:`params`): the
robot's arrays with and without its payload, the kernels' parameters, the winch's length
at every stage, the load cells and scratch of the plant and of the law, a still state and
zeros, the state and stage point the plant's cell was measured at (:func:`prepare`), the
winch's reflected mass [kg] (0: its length is the profile's; > 0: ``(L, L̇)`` are the
state's last two entries and its line pull the 10th force, :func:`winch`) and its drive's
gains ``(kp [1/s²], kd [1/s])``, then the pull's share of X at rest ``D`` (9,), the stage
point it was made at (1,: −1 none since :func:`prepare`) and its scratch.

The built-in law asked at the plant's state (:func:`inverse`) makes its Kane pass and,
less the same with ``0 × P``, the pull's share ``D`` the plant subtracts, in one program
(:func:`~offshore_crane.dynamics.cable.elastic_plant.computed_torque_share`), which
:func:`rhs` then reads: two passes where the plant alone makes two at rest, the share
the same up to round-off.

One load cell a stage: :func:`prepare` measures it before the law is evaluated, and the
built-in law's :func:`inverse` and the plant's :func:`rhs` read it when they are asked
about that state (a sampled, delayed or noisy measurement is another state: the law then
measures its own)."""

from __future__ import annotations

import hashlib
import inspect

import numpy as np

from offshore_crane.dynamics import compiled as c
from offshore_crane.dynamics.cable import elastic_plant as ep
from offshore_crane.dynamics.cable import kernels as ck
from offshore_crane.dynamics.linear import kinetic_energy
from offshore_crane.kernel_cache import njit
from offshore_crane.simulation.plants import shared_kernels as shared

jit = njit(**c.LEAN)
inline = njit(inline="always", **c.JIT)
#: The plant's passes, called by address: each loop (one per law) compiles its own code
#: only (:mod:`offshore_crane.kernel_calls`).
derivative, measure, computed_torque = (ep.DERIVATIVE.call, ep.MEASURE.call,
                                        ep.COMPUTED_TORQUE.call)
computed_torque_share = ep.COMPUTED_TORQUE_SHARE.call
carve, VIEW_MM, VIEW_MC = ep._carve, ep.VIEW_MM, ep.VIEW_MC
unpack = c.unpack
tip_kinematics = ck.tip_kinematics
_OK = ep.OK


def _make(stamp, commanded):
    """The kernels, closed over the formulas' hash and whether the winch is commanded (a
    constant of their code: a test of ``P[16]`` at run time cost the elastic lift 5 %,
    measured). The helpers that test it are made here too, one pair per variant. The
    commanded variant's functions have names of their own (:func:`_named`): one name and
    argument types for two texts made a library loaded from the disk cache call the other
    variant's code (a plain lift after a commanded one in one process: a heap overrun,
    a divergence or a segfault later)."""
    jit = _named(commanded)

    @inline
    def _length(P, i, y):
        """The cable's length L [m] and its rate L̇ [m/s]: the commanded winch's state,
        else the profile's at stage point ``i``."""
        if commanded:
            return y[24], y[25]
        return P[7][i, 0], P[7][i, 1]

    @inline
    def _made_at(P, i, y):
        """True when the plant's load cell ``P[8]`` was measured at stage point ``i`` and
        state ``y`` (value for value; ``P[15]``: that state and ``i`` last, NaN before
        any)."""
        at = P[15]
        if at[26] != i:
            return False
        for j in range(24):
            if at[j] != y[j]:
                return False
        if commanded:                   # the winch's (L, L̇)
            return at[24] == y[24] and at[25] == y[25]
        return True

    @inline
    def prepare(P, i, y, aux):
        """The load cell at ``y`` on the stage's length into the plant's cell ``P[8]``,
        remembered as measured there: the built-in law's measurement (the same kernel on
        the same arrays) and the plant's cable read it (one cable model a stage, not
        two; the numbers are the same)."""
        if len(stamp) == 0:
            return
        at = P[15]
        P[19][0] = -1.0                 # no pull's share made at this stage yet
        L, Ld = _length(P, i, y)
        measure(P[0], P[1], P[2], P[6], L, Ld, y, P[8], P[9])
        for j in range(24):
            at[j] = y[j]
        if commanded:
            at[24] = y[24]
            at[25] = y[25]
        at[26] = i

    @inline
    def rhs(P, i, y, X, dy, aux):
        """ẏ (24, or 26 with a commanded winch: ``m_w L̈ = T − X[9]``) into ``dy``;
        ``aux[0]`` ok, ``aux[1]`` the tension [N], ``aux[2]``, ``aux[3]`` the cable's
        length [m] and its rate [m/s]. The load cell :func:`prepare` measured at ``y``,
        else one measured here."""
        if len(stamp) == 0:
            return False
        status = P[10]
        L, Ld = _length(P, i, y)
        measured = _made_at(P, i, y)
        T = derivative(P[0], P[1], P[2], P[3], P[4], P[5], P[6], L, Ld, y, X,
                       dy, P[8], P[9], status, measured, P[18], measured and P[19][0] == i)
        if commanded:
            dy[24] = y[25]
            dy[25] = (T - X[9]) / P[16]
        ok = status[0] == _OK
        aux[0] = 1.0 if ok else 0.0
        aux[1] = T
        aux[2] = L
        aux[3] = Ld
        return ok

    @jit
    def keep(P, EXTRA, k, y, dy, X, aux):
        """The payload's position and velocity (3 each), the tension, the length, the
        mechanical energy [J] and the length's rate: the robot's ``T − g · Σ m c`` (the
        mass matrix and mass moments its equations of motion just formed at ``y``), the
        payload's ``½ m |v|² − m g · p``, the cable's strain energy ``½ EA s² / L`` while
        taut (``s = |ρ| − L``; the load cell's ρ) and a commanded winch's ``½ m_w L̇²``."""
        if len(stamp) == 0:
            return
        for j in range(3):
            EXTRA[k, j] = y[9 + j]
            EXTRA[k, 3 + j] = y[21 + j]
        EXTRA[k, 6] = aux[1]
        EXTRA[k, 7] = aux[2]
        par, cell, views = P[6], P[8], carve(P[9])
        Mm, mc = views[VIEW_MM], views[VIEW_MC]
        n = 6 + unpack(P[3], P[4], P[5])[0].n_arm
        E = kinetic_energy(Mm, y[12:21], n)
        C = unpack(P[0], P[1], P[2])[0]
        m = C.arm_m[C.n_arm - 1]                     # the payload, the chain's last body
        for j in range(3):
            E += -par[j] * mc[0, j] + 0.5 * m * y[21 + j] * y[21 + j] - m * par[j] * y[9 + j]
        stretch = np.sqrt(cell[3] ** 2 + cell[4] ** 2 + cell[5] ** 2) - aux[2]
        if stretch > 0.0:
            E += 0.5 * par[3] * stretch * stretch / aux[2]
        if commanded:
            E += 0.5 * P[16] * y[25] * y[25]
        EXTRA[k, 8] = E
        EXTRA[k, 9] = aux[3]

    @inline
    def inverse(P, i, y, qdd, X):
        """The Kane pass with the load cell's pull at ``qdd`` (the law's side): the
        plant's cell when :func:`prepare` measured it at ``y`` (the state the law reads
        is the plant's), else one measured into the law's own."""
        if len(stamp) == 0:
            return
        cell, work = P[11], P[12]
        if _made_at(P, i, y):
            computed_torque_share(P[0], P[1], P[2], P[6], y, qdd, P[8], X, P[18], work,
                                  P[20])
            P[19][0] = i
            return
        L, Ld = _length(P, i, y)
        measure(P[0], P[1], P[2], P[6], L, Ld, y, cell, work)
        computed_torque(P[0], P[1], P[2], P[6], y, qdd, cell, X, work)

    @jit
    def gravity(P, i, y, X):
        """The static forces with the measured pull (rates of the robot zero)."""
        if len(stamp) == 0:
            return
        cell, work, still = P[11], P[12], P[13]
        L, Ld = _length(P, i, y)
        measure(P[0], P[1], P[2], P[6], L, Ld, y, cell, work)
        for j in range(24):
            still[j] = y[j] if (j < 12 or j >= 21) else 0.0
        computed_torque(P[0], P[1], P[2], P[6], still, P[14], cell, X, work)

    @jit
    def arm_tip(P, q, qd, qdd, out):
        """The tip's position, velocity, acceleration (9,) under ``q, q̇, q̈`` (9,)."""
        if len(stamp) == 0:
            return
        tip_kinematics(P[0], P[1], P[2], q, qd, qdd, out)

    @jit
    def winch_to(P, i, y, Lr, Ldr, Lddr, X):
        """A commanded winch's drive (nothing on a plant without one): the line pull
        ``X[9] = T − m_w (L̈_r + kd (L̇_r − L̇) + kp (L_r − L))`` [N] that makes the length
        follow ``(L_r, L̇_r, L̈_r)`` [m, m/s, m/s²] with the error obeying ``ë + kd ė +
        kp e = 0``, the tension ``T`` measured at stage point ``i`` (the plant's load cell
        when :func:`prepare` measured it at ``y``)."""
        if len(stamp) == 0 or not commanded:
            return
        m, gains = P[16], P[17]
        if _made_at(P, i, y):
            T = P[8][9]
        else:
            T = measure(P[0], P[1], P[2], P[6], y[24], y[25], y, P[11], P[12])
        X[9] = T - m * (Lddr + gains[1] * (Ldr - y[25]) + gains[0] * (Lr - y[24]))

    @inline
    def winch(P, i, y, X):
        """The drive (:func:`winch_to`) following the winch's profile at stage point
        ``i``. Called before the law, which may overwrite ``X[9]`` (it commands the
        winch then); inlined: a plant without a commanded winch pays nothing."""
        if len(stamp) == 0:
            return
        if commanded:
            Lg = P[7]
            winch_to(P, i, y, Lg[i, 0], Lg[i, 1], Lg[i, 2], X)

    return prepare, rhs, keep, inverse, gravity, arm_tip, winch, winch_to


def _named(commanded):
    """The compiled kernels' decorator of a variant: the commanded winch's functions'
    qualified names end in ``_commanded`` (Numba names a symbol by module, qualified
    name and argument types, the same for both variants)."""
    if not commanded:
        return jit

    def named(f):
        f.__qualname__ += "_commanded"
        return jit(f)
    return named


#: What these kernels' disk cache is keyed by: the formulas' hash and the text of the
#: elastic plant's kernels they call (Numba's cache checks only a function's own file, so
#: a callee edited elsewhere would otherwise be linked stale).
STAMP = c.STAMP + hashlib.sha256((inspect.getsource(ep) + inspect.getsource(shared)
                                  + inspect.getsource(ck)).encode()).hexdigest()
_NAMES = ("prepare", "rhs", "keep", "inverse", "gravity", "arm_tip", "winch", "winch_to")
prepare, rhs, keep, inverse, gravity, arm_tip, winch, winch_to = _make(STAMP, False)
check, coords, payload = shared.check, shared.coords, shared.payload


def params(plant) -> tuple:
    """``P`` of an :class:`~offshore_crane.simulation.plants.ElasticPlant`."""
    from offshore_crane.dynamics.constants import cable_arrays, robot_arrays

    a, e = cable_arrays(plant.robot), robot_arrays(plant.empty)
    par = ep.parameters(plant.g, plant.ea, plant.damping, plant.robot.hybrid.sway_damping,
                        float(plant.robot.hybrid.drag))
    return (a.flat, a.layout, a.prismatic, e.flat, e.layout, e.prismatic, par,
            np.ascontiguousarray(plant.Lg), np.zeros(ep.CELL), np.zeros(ep.WORK),
            np.zeros(1, dtype=np.int64), np.zeros(ep.CELL), np.zeros(ep.WORK), np.zeros(24),
            np.zeros(9), np.full(27, np.nan), float(plant.winch_mass),
            np.array(plant.winch_gains, dtype=float), np.zeros(9), np.full(1, -1.0),
            np.zeros(ep.SHARE))


def _commanded():
    """The kernels of the plant with a commanded winch (its ``(L, L̇)`` in the state):
    the same text compiled with that constant, apart (made on first use), in the shape of
    this module for the driver."""
    if not _COMMANDED:
        import types

        _COMMANDED.append(types.SimpleNamespace(
            **dict(zip(_NAMES, _make(STAMP, True))), check=check, coords=coords,
            payload=payload, params=params, STAMP=STAMP + "commanded winch"))
    return _COMMANDED[0]


_COMMANDED: list = []
