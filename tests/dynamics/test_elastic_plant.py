"""The compiled plant of the simulation on an elastic cable
(:mod:`offshore_crane.dynamics.cable.elastic_plant`) against its Python reference
(:class:`offshore_crane.simulation.plants.ElasticPlant`, the Python plant
``simulate_elastic`` integrated): the same right-hand side and the same computed torque on seeded random
states, a singular mass matrix reported rather than raised, and no allocation a call."""

from __future__ import annotations

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.conventions import GRAVITY
from offshore_crane.dynamics.cable import elastic_plant as ep
from offshore_crane.dynamics.cable.tip import tip_positions
from offshore_crane.errors import SingularConfigurationError, WorkspaceError
from offshore_crane.simulation.plants import ElasticPlant as PyElastic


class PythonPlant:
    """The Python plant (:class:`~offshore_crane.simulation.plants.ElasticPlant`) at one
    cable length and rate, called as the kernels are."""

    def __init__(self, robot, empty, ea, damping, g):
        self.robot, self.ea, self.damping, self.g = robot, ea, damping, g
        self.m = float(robot.hybrid.cable.mass[-1])

    def _at(self, L, Ld):
        return PyElastic(self.robot, self.robot, self.g, ea=self.ea, damping=self.damping,
                         lengths=np.array([[float(L), float(Ld), 0.0]]))

    def derivative(self, y, X, L, Ld):
        dy, aux = self._at(L, Ld).derivative(0, y, X)
        return dy, aux["tension"]

    def cable(self, y, L, Ld):
        return self._at(L, Ld).cable(0, y)

    def pulled(self, q, qd, qdd, pull, at):
        return self._at(1.0, 0.0)._pulled(q, qd, qdd, pull, at)

EA, DAMPING = 2e4, 3.0
#: The bound of every comparison, relative to the largest magnitude of the compared part
#: (the issue's): both sides evaluate the same formula texts in float64 in the same order,
#: but the reference runs the tip's kinematics on NumPy arrays (NumPy's sin and cos, and
#: np.linalg.norm's BLAS dot for |ρ|) where the kernels use libm and a plain dot; one
#: rounding there reaches the accelerations through the Cholesky solve of M (condition
#: ~1e4 here), so agreement is to round-off times κ(M), not bitwise by construction.
#: Measured on this machine: ẏ's q̇, v, q̈ parts and the tension bitwise equal, the
#: payload's acceleration 1.4e-16, the load cell 2.1e-16, the computed torque 2.1e-16
#: (|ρ| by BLAS against a plain dot: one rounding of the pull).
RTOL = 1e-12
PARTS = {"qd": slice(0, 9), "v": slice(9, 12), "qdd": slice(12, 21),
         "a_payload": slice(21, 24)}


def _robot(damped: bool):
    over = {"payload.mass": 2.0, "payload.cable_length": 1.0}
    if damped:
        over |= {"payload.sway_damping": 0.2 * 2.0 * np.sqrt(9.81), "payload.drag_area": 0.5}
    return oc.load_robot(overrides=over)


@pytest.fixture(scope="module", params=[True, False], ids=["damped-drag", "plain"])
def plants(request):
    robot = _robot(request.param)
    empty = robot.without_hanging_payload()
    g = np.asarray(GRAVITY, dtype=float)
    return (robot, PythonPlant(robot, empty, EA, DAMPING, g),
            ep.ElasticPlant(robot, EA, DAMPING, g, empty=empty))


def _states(robot, n: int, seed: int):
    """``n`` seeded ``(y, X, L, L̇, qdd_cmd)``: poses near home, rates of a lift, the
    payload ~1 m below the tip stretched by −2..+2 mm (half slack, half taut, some of
    these pushing through the cable's damping at the winch rate L̇ of ±0.5 m/s), X and the
    commanded accelerations of a lift's size."""
    rng = np.random.default_rng(seed)
    out = []
    for k in range(n):
        q = robot.home_pose() + rng.uniform(-0.02, 0.02, 9)
        qd = rng.uniform(-0.3, 0.3, 9)
        p, v = (x[0] for x in tip_positions(robot, q[None], qd[None]))
        L = rng.uniform(0.8, 1.2)
        u = np.array([rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), -1.0])
        u /= np.linalg.norm(u)
        rho = u * (L + rng.uniform(-2e-3, 2e-3))
        y = np.concatenate([q, p + rho, qd, v + rng.uniform(-0.5, 0.5, 3)])
        X = np.concatenate([rng.uniform(-50, 50, 3), rng.uniform(-800, 800, 6)])
        out.append((y, X, L, rng.uniform(-0.5, 0.5), rng.uniform(-2.0, 2.0, 9)))
    return out


def _relative(got, want) -> float:
    scale = max(float(np.abs(want).max()), np.finfo(float).tiny)
    return float(np.abs(np.asarray(got) - want).max() / scale)


def test_the_derivative_is_the_python_plants(plants):
    """ẏ, the tension and the load cell (pull, where it acts, the payload's force) of
    the kernel equal the reference's within :data:`RTOL` of each part's largest magnitude
    (the tension: of the largest tension met), on 40 states, taut and slack, with a winch
    rate; the payload's mass the kernel reads from the packed arrays is the robot's."""
    from offshore_crane.dynamics.constants import cable_arrays

    robot, ref, plant = plants
    kane = cable_arrays(robot).kane
    assert float(kane.arm_m[kane.n_arm - 1]) == ref.m
    worst = dict.fromkeys([*PARTS, "T", "cell"], 0.0)
    got, want, T_got, T_want = [], [], [], []
    for y, X, L, Ld, _ in _states(robot, 40, seed=37):
        out = np.empty(24)
        T = plant.derivative(y, X, L, Ld, out)
        assert not plant.singular
        ydot, T_ref = ref.derivative(y, X, L, Ld)
        pull, at, _, force = ref.cable(y, L, Ld)
        worst["cell"] = max(worst["cell"], _relative(plant.cell[0:3], pull),
                            _relative(plant.cell[3:6], at), _relative(plant.cell[6:9], force))
        got.append(out)
        want.append(ydot)
        T_got.append(T)
        T_want.append(T_ref)
    got, want, T_got, T_want = map(np.array, (got, want, T_got, T_want))
    assert (T_want == 0.0).sum() >= 10 and (T_want > 0.0).sum() >= 10   # both cables met
    assert np.array_equal(T_got == 0.0, T_want == 0.0)
    for name, part in PARTS.items():
        worst[name] = _relative(got[:, part], want[:, part])
    worst["T"] = _relative(T_got, T_want)
    assert max(worst.values()) <= RTOL, worst


def test_the_computed_torque_is_the_python_law(plants):
    """X of the law (the Kane pass with the measured pull at the commanded accelerations)
    equals the reference's within :data:`RTOL` of its largest magnitude, on 40 states."""
    robot, ref, plant = plants
    got, want = [], []
    for y, _, L, Ld, cmd in _states(robot, 40, seed=38):
        plant.measure(y, L, Ld)
        got.append(plant.computed_torque(y, cmd, np.empty(9)).copy())
        pull, at = ref.cable(y, L, Ld)[:2]
        want.append(ref.pulled(y[:9], y[12:21], cmd, pull, at))
    assert _relative(np.array(got), np.array(want)) <= RTOL


def test_a_singular_mass_matrix_is_reported_not_raised(plants):
    """At the attitude singularity (q5 = π/2, outside the workspace: the reference's
    forward dynamics raises there) and at a state that is not finite, the kernel flags
    the mass matrix as singular and leaves the robot's accelerations NaN; the rest of ẏ
    is written."""
    robot, ref, plant = plants
    y, X, L, Ld, _ = _states(robot, 1, seed=39)[0]
    y[4] = np.pi / 2
    out = np.zeros(24)
    plant.derivative(y, X, L, Ld, out)
    assert plant.singular
    assert np.isnan(out[12:21]).all() and np.isfinite(out[:12]).all()
    with pytest.raises((SingularConfigurationError, WorkspaceError)):
        ref.derivative(y, X, L, Ld)
    y[4] = 0.0
    plant.derivative(y, X, L, Ld, out)
    assert not plant.singular
    y[0] = np.nan
    plant.derivative(y, X, L, Ld, out)
    assert plant.singular


def test_the_kernels_allocate_nothing_a_call(plants):
    """Called from compiled code (no boxing of the arguments), the three kernels make no
    allocation: 1 and 51 calls allocate alike (Numba's allocation counters)."""
    import numba
    from numba.core.runtime import _nrt_python, rtsys

    robot, _, plant = plants
    y, X, L, Ld, cmd = _states(robot, 1, seed=40)[0]

    @numba.njit
    def calls(n, head, cell_head, model_head, y, X, L, Ld, cmd, out, Xc, cell, work, status):
        for _ in range(n):
            ep.measure(*cell_head, L, Ld, y, cell, work)
            ep.computed_torque(*model_head, y, cmd, cell, Xc, work)
            ep.derivative(*head, L, Ld, y, X, out, cell, work, status, False, Xc, False)

    args = (plant._plant, plant._cell, plant._model, y, X, L, Ld, cmd, np.empty(24),
            np.empty(9), plant.cell, plant.work, plant.status)
    calls(1, *args)
    was = _nrt_python.memsys_stats_enabled()
    _nrt_python.memsys_enable_stats()
    try:
        counts = []
        for n in (1, 51):
            before = rtsys.get_allocation_stats()
            calls(n, *args)
            after = rtsys.get_allocation_stats()
            counts.append(after.alloc - before.alloc + after.mi_alloc - before.mi_alloc)
    finally:
        if not was:
            _nrt_python.memsys_disable_stats()
    assert counts[0] == counts[1], counts


def test_the_carved_views_named_for_the_energy_are_the_mass_matrix_and_moments():
    """``VIEW_MM`` and ``VIEW_MC`` pick the (9, 9) mass matrix and the (1, 3) mass moments
    out of the work buffer's views, where ``_SIZES`` lays them out."""
    import numba

    @numba.njit
    def views(w):                    # the views leave compiled code: w stays alive below
        return ep._carve(w)

    w = np.zeros(ep.WORK)
    carved = views(w)
    assert len(carved) == len(ep._SIZES)
    mm, mc = carved[ep.VIEW_MM], carved[ep.VIEW_MC]
    assert mm.shape == (9, 9) and mc.shape == (1, 3)
    assert (mm.ctypes.data - w.ctypes.data) // 8 == ep._MM
    assert (mc.ctypes.data - w.ctypes.data) // 8 == ep._MC


#: How far the pull's share at the commanded accelerations (:func:`~.elastic_plant.
#: computed_torque_share`) may lie from the share at rest (the unfused plant's two
#: passes), relative to the largest |X| of the law: X is affine in the pull, the two
#: differences of passes differ by the rounding of the passes' sums (a few ulps of X;
#: measured over 400 such states: at most 1.5e-15 of |X| for D, 1.8e-15 of |ẏ| for the
#: rates).
SHARE_ROUNDING = 1e-14


def test_the_law_and_the_pulls_share_from_one_program_are_the_separate_calls(plants):
    """:func:`~.elastic_plant.computed_torque_share` (the law's Kane pass and the same
    with ``0 × P``, one program) gives the law's X of
    :func:`~.elastic_plant.computed_torque` bit for bit, a pull's share D equal to the
    unfused plant's (at rest) to round-off, and :func:`~.elastic_plant.derivative`
    reading D (``fused``) gives the unfused call's rates to the same round-off carried
    through the solve, slack and taut, damped and not; with D at rest, bit for bit."""
    robot, _, plant = plants
    D, share, work = np.zeros(9), np.zeros(ep.SHARE), np.zeros(ep.WORK)
    taut = 0
    for y, X, L, Ld, cmd in _states(robot, 8, seed=41):
        plant.measure(y, L, Ld)
        X_law = plant.computed_torque(y, cmd, np.empty(9))
        X_fused = np.empty(9)
        ep.computed_torque_share(*plant._model, y, cmd, plant.cell, X_fused, D, work, share)
        np.testing.assert_array_equal(X_fused, X_law)
        want, got, exact = np.empty(24), np.empty(24), np.empty(24)
        T = ep.derivative(*plant._plant, L, Ld, y, X, want, plant.cell, plant.work,
                          plant.status, True, D, False)
        w = plant.work                          # the unfused call's two passes at rest
        rest = w[ep._XP:ep._XP + 9] - w[ep._X0:ep._X0 + 9]
        assert np.abs(D - rest).max() <= SHARE_ROUNDING * np.abs(X_law).max()
        taut += bool(np.any(plant.cell[:3] != 0.0))
        T_fused = ep.derivative(*plant._plant, L, Ld, y, X, got, plant.cell, plant.work,
                                plant.status, True, D, True)
        ep.derivative(*plant._plant, L, Ld, y, X, exact, plant.cell, plant.work,
                      plant.status, True, rest, True)
        np.testing.assert_array_equal(exact, want)
        np.testing.assert_allclose(got, want, rtol=0.0,
                                   atol=SHARE_ROUNDING * np.abs(want).max())
        assert T_fused == T
    assert taut >= 4


def test_the_stewart_solve_of_many_right_hand_sides_is_each_solve_bit_for_bit():
    """:func:`~offshore_crane.dynamics.linear.solve6_many` against :func:`solve6` per
    right-hand side (no tolerance: the same operations on each column), and NaN for a
    singular A."""
    from offshore_crane.dynamics.linear import solve6, solve6_many

    rng = np.random.default_rng(42)
    for _ in range(20):
        A, R = rng.normal(size=(6, 6)), rng.normal(size=(3, 6))
        X = np.empty((3, 6))
        assert solve6_many(A, R, X, np.empty((6, 9)))
        for j in range(3):
            x = np.empty(6)
            solve6(A, R[j], x, np.empty((6, 13)), False)
            np.testing.assert_array_equal(X[j], x)
    A[:, 2] = 0.0
    assert not solve6_many(A, R, X, np.empty((6, 9)))
    assert np.isnan(X).all()
