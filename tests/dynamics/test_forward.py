"""Equations of motion and forward dynamics (issue 13): checked against the inverse
dynamics (an independent factoring of the same kinematics), Pinocchio's constraint
dynamics (shares only the URDF) and energy.

Tolerances: the identities are exact, so they hold to round-off (values ~1e3 N, ~1e1 m/s²;
1e-12 relative leaves three orders for ill-conditioned samples). Pinocchio's constraint
solver is a proximal iteration stopped at 1e-12: 1e-8 relative, the issue's bound.
"""

import re

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.dynamics.forward import (actuation_matrix, bias_forces,
                                             equations_of_motion, forward_dynamics,
                                             mass_matrix)
from problems import random_states


@pytest.fixture(scope="module")
def states(robot):
    q, qd, qdd = random_states(robot, 300, seed=101)
    return q, qd, qdd, oc.inverse_dynamics(robot, q, qd, qdd)


def test_mass_matrix_symmetric_positive_definite(robot, states):
    q = states[0]
    M = mass_matrix(robot, q)
    assert M.shape == (300, 9, 9)
    assert np.abs(M - np.swapaxes(M, 1, 2)).max() == 0.0
    assert np.linalg.eigvalsh(M).min() > 0.0


def test_equations_of_motion_reproduce_the_inverse_dynamics(robot, states):
    """M q̈ + h = A X with X from the fused Kane inverse dynamics."""
    q, qd, qdd, X = states
    eom = equations_of_motion(robot, q, qd)
    lhs = np.einsum("nij,nj->ni", eom.M, qdd) + eom.h
    rhs = np.einsum("nij,nj->ni", eom.A, X)
    assert np.abs(lhs - rhs).max() <= 1e-12 * np.abs(rhs).max()
    np.testing.assert_array_equal(eom.M, mass_matrix(robot, q))
    np.testing.assert_array_equal(eom.h, bias_forces(robot, q, qd))
    np.testing.assert_array_equal(eom.A, actuation_matrix(robot, q))


def test_mass_matrix_is_the_acceleration_part_of_the_inverse_dynamics(robot, states):
    """Column j of M is ID(q, 0, e_j) − ID(q, 0, 0) mapped by A: a finite-difference-free
    check of M against the fused inverse dynamics (zero gravity, zero rates)."""
    q = states[0][:20]
    zero = np.zeros_like(q)
    A = actuation_matrix(robot, q)
    M = mass_matrix(robot, q)
    base = oc.inverse_dynamics(robot, q, zero, zero, gravity=(0, 0, 0))
    for j in range(9):
        e = np.zeros_like(q)
        e[:, j] = 1.0
        col = np.einsum("nij,nj->ni", A, oc.inverse_dynamics(robot, q, zero, e,
                                                              gravity=(0, 0, 0)) - base)
        assert np.abs(col - M[:, :, j]).max() <= 1e-12 * np.abs(M).max()


def test_forward_inverse_round_trip(robot, states):
    q, qd, qdd, X = states
    qdd_fd = forward_dynamics(robot, q, qd, X)
    X_back = oc.inverse_dynamics(robot, q, qd, qdd_fd)
    assert np.abs(X_back - X).max() <= 1e-10 * np.abs(X).max()       # the bound
    assert np.abs(qdd_fd - qdd).max() <= 1e-10 * np.abs(qdd).max()


def test_single_sample_and_batch(robot, states):
    q, qd, qdd, X = states
    batch = forward_dynamics(robot, q[:5], qd[:5], X[:5])
    for k in range(5):
        one = forward_dynamics(robot, q[k], qd[k], X[k])
        assert one.shape == (9,)
        np.testing.assert_allclose(one, batch[k], rtol=0, atol=1e-13 * np.abs(batch).max())


def test_agrees_with_pinocchio_constraint_dynamics(robot, states):
    q, qd, _, X = states
    q, qd, X = q[:100], qd[:100], X[:100]
    ours = forward_dynamics(robot, q, qd, X)
    ref = forward_dynamics(robot, q, qd, X, method="pinocchio")
    scale = np.maximum(np.abs(ref).max(axis=1), 1.0)
    assert (np.abs(ours - ref).max(axis=1) / scale).max() <= 1e-8


def test_along_table1_against_pinocchio(robot, table1):
    _, q, qd, qdd = table1
    idx = slice(0, None, 60)
    X = oc.inverse_dynamics(robot, q[idx], qd[idx], qdd[idx])
    ours = forward_dynamics(robot, q[idx], qd[idx], X)
    ref = forward_dynamics(robot, q[idx], qd[idx], X, method="pinocchio")
    assert np.abs(ours - ref).max() <= 1e-8 * max(1.0, np.abs(ref).max())


def test_robot_without_arm(states):
    robot = oc.load_robot(with_arm=0)
    q, qd, qdd, _ = states
    X = oc.inverse_dynamics(robot, q[:30], qd[:30], qdd[:30])
    out = forward_dynamics(robot, q[:30], qd[:30], X)
    assert np.isnan(out[:, 6:]).all()
    assert np.abs(out[:, :6] - qdd[:30, :6]).max() <= 1e-10 * np.abs(qdd[:30, :6]).max()


def test_errors(robot, states):
    q, qd, _, X = states
    with pytest.raises(oc.InputError, match="unknown method 'euler'"):
        forward_dynamics(robot, q, qd, X, method="euler")
    bad = q[:3].copy()
    bad[1, 2] = np.nan
    with pytest.raises(oc.InputError, match=r"q\[1, 2\] is nan"):
        forward_dynamics(robot, bad, qd[:3], X[:3])
    pitched = q[:2].copy()
    pitched[1, 4] = np.pi / 2
    with pytest.raises(oc.SingularConfigurationError, match="attitude singularity"):
        forward_dynamics(robot, pitched, qd[:2], X[:2], limits=False)


def test_one_sample_fast_path_is_the_batch_kernel(robot, states):
    """A ``(9,)`` float64 state goes through one compiled call (``compiled.forward_one``):
    the same kernel as a batch, so the same numbers bit for bit; any other array (a
    strided row, another dtype) goes the general way and gives them too."""
    q, qd, _, X = states
    batch = forward_dynamics(robot, q[:6], qd[:6], X[:6])
    for k in range(6):
        np.testing.assert_array_equal(forward_dynamics(robot, q[k], qd[k], X[k]), batch[k])
    wide = np.zeros((9, 2))
    wide[:, 0] = q[0]                                   # a column: strides (16,)
    np.testing.assert_array_equal(forward_dynamics(robot, wide[:, 0], qd[0], X[0]), batch[0])
    np.testing.assert_array_equal(
        forward_dynamics(robot, q[0].astype(np.float32).astype(np.float64), qd[0],
                         X[0].tolist()),
        forward_dynamics(robot, q[0].astype(np.float32).astype(np.float64)[None],
                         qd[:1], X[:1])[0])


def test_one_sample_fast_path_reports_like_the_batch(robot, states):
    """What the one compiled call finds (a non-finite input, a pose out of the workspace,
    the attitude singularity) is reported by the general path: the same exception and
    message as the same sample given as a batch of one."""
    q, qd, _, X = states
    cases = {"inf": (2, np.inf), "pitched": (4, np.pi / 2), "high": (2, q[0, 2] + 5.0)}
    for name, (j, value) in cases.items():
        bad = q[0].copy()
        bad[j] = value
        with pytest.raises(oc.OffshoreCraneError) as batch:
            forward_dynamics(robot, bad[None], qd[:1], X[:1])
        with pytest.raises(type(batch.value), match=re.escape(str(batch.value))):
            forward_dynamics(robot, bad, qd[0], X[0])
