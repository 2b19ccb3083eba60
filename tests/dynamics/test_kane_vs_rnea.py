"""Kane (hand-written) against Pinocchio RNEA on the equivalent tree.

Tolerance: docs/conventions.md asks max |X_kane − X_rnea| ≤ 1e-9 · max |X|. Both are exact
methods on the same URDF, so they differ by round-off only (observed ~1e-15).
"""

import numpy as np
import pytest

import offshore_crane as oc
from conftest import relative_error
from problems import random_states

LIMIT = 1e-9


@pytest.mark.parametrize("kane", ["kane", "kane-explicit"])
def test_table1_default_span(robot, table1, kane):
    t, q, qd, qdd = table1
    Xk = oc.inverse_dynamics(robot, q, qd, qdd, method=kane)
    Xr = oc.inverse_dynamics(robot, q, qd, qdd, method="rnea")
    assert Xk.shape == (3142, 9)
    assert relative_error(Xk, Xr) <= LIMIT


@pytest.mark.parametrize("kane", ["kane", "kane-explicit"])
def test_10000_random_states(robot, kane):
    q, qd, qdd = random_states(robot, 10_000, seed=20261122)
    Xk = oc.inverse_dynamics(robot, q, qd, qdd, method=kane)
    Xr = oc.inverse_dynamics(robot, q, qd, qdd, method="rnea")
    assert relative_error(Xk, Xr) <= LIMIT
    # per-sample too: no sample hides behind a large one elsewhere
    scale = np.abs(Xr).max(axis=1)
    assert np.all(np.abs(Xk - Xr).max(axis=1) <= LIMIT * scale)


@pytest.mark.parametrize("gravity", [(0.0, 0.0, 0.0), (1.0, -2.0, -9.81)])
def test_other_gravity(robot, gravity):
    q, qd, qdd = random_states(robot, 50, seed=7)
    Xk = oc.inverse_dynamics(robot, q, qd, qdd, gravity=gravity)
    Xr = oc.inverse_dynamics(robot, q, qd, qdd, method="rnea", gravity=gravity)
    assert relative_error(Xk, Xr) <= LIMIT


def test_overridden_robot(robot):
    heavy = oc.load_robot(platform_mass=120.0, link1_length=0.7, leg_upper_mass=2.5)
    q, qd, qdd = random_states(heavy, 200, seed=3)
    Xk = oc.inverse_dynamics(heavy, q, qd, qdd)
    Xr = oc.inverse_dynamics(heavy, q, qd, qdd, method="rnea")
    assert relative_error(Xk, Xr) <= LIMIT
    # and the override changes the answer
    assert relative_error(Xk, oc.inverse_dynamics(robot, q, qd, qdd)) > 1e-3


def test_batch_equals_single_samples(robot):
    q, qd, qdd = random_states(robot, 40, seed=11)
    X = oc.inverse_dynamics(robot, q, qd, qdd)
    loop = np.array([oc.inverse_dynamics(robot, q[i], qd[i], qdd[i]) for i in range(len(q))])
    assert loop.shape == X.shape
    # same arithmetic per sample; batched LAPACK may reorder a few operations: 1e-13
    assert relative_error(loop, X) <= 1e-13


def test_rnea_backends_agree(robot):
    """The compiled RNEA path (tree states, projection) equals the NumPy one, and both
    report the same leg diagnostics and condition numbers."""
    from offshore_crane.dynamics import solve

    q, qd, qdd = random_states(robot, 300, seed=17)
    a = solve(robot, q, qd, qdd, method="rnea", backend="numpy")
    b = solve(robot, q, qd, qdd, method="rnea", backend="numba")
    assert relative_error(b.X, a.X) <= 1e-13      # same formulas, different order
    np.testing.assert_allclose(b.condition, a.condition, rtol=1e-10)
    np.testing.assert_allclose(b.gimbal, a.gimbal, rtol=1e-12)
