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


def _rnea_per_sample(robot, q, qd, qdd, gravity):
    """The RNEA path written out plainly, sample by sample, with Pinocchio's kinematics
    instead of the compiled closure: tree positions and rates from the constrained
    reference's Newton on frame placements and Jacobians; passive accelerations from the
    loops' relative classical accelerations, ``J_p a_p = −(J_i a_i + γ)``; ``τ = pin.rnea``;
    ``G = −J_p⁻¹ J_i``, ``B = τ_indep + Gᵀ τ_passive`` and the leg forces from
    ``Jlᵀ Fl = B[0:6]`` (rotation rows scaled by 1/L, L the mean anchor distance from O2)
    by ``np.linalg.solve``. Returns X ``(n, 9)``, the 1-norm condition number of that
    system and the worst 1/|cos θ2| (``(n,)`` each)."""
    import pinocchio as pin

    from offshore_crane.reference.constrained import loop_tree, tree_states as closed

    tree = loop_tree(robot)                 # indices and loop Jacobians only
    model = robot.pinocchio_model.copy()
    model.gravity.linear = np.asarray(gravity, dtype=float)
    data = model.createData()
    frame = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    L = np.mean([np.linalg.norm(model.frames[f].placement.translation) for f in tree.anchors])
    states = closed(robot, q, qd)
    n, m = len(q), len(tree.indep)
    X, cond, gimbal = np.empty((n, 9)), np.empty(n), np.empty(n)
    for k in range(n):
        x, v = states.q[k], states.v[k]
        _, J = tree.loop_residual(x)
        Jp, Ji = J[:, tree.passive], J[:, tree.indep]
        a = np.zeros(model.nv)
        a[tree.indep] = qdd[k, :m]
        pin.forwardKinematics(model, data, x, v, a)
        gap = np.concatenate([pin.getFrameClassicalAcceleration(model, data, t, frame).linear
                              - pin.getFrameClassicalAcceleration(model, data, s, frame).linear
                              for t, s in zip(tree.tips, tree.anchors)])
        a[tree.passive] = -np.linalg.solve(Jp, gap)
        tau = pin.rnea(model, data, x, v, a)
        G = -np.linalg.solve(Jp, Ji)[:, :6]             # ∂(passive rates)/∂(q̇1..q̇6)
        B = tau[tree.indep[:6]] + G.T @ tau[tree.passive]
        scale = np.array([1.0] * 3 + [1.0 / L] * 3)[:, None]
        A = G[2::3].T * scale                           # Jlᵀ: the slide rows of G
        X[k, :3] = tau[tree.indep[6:]] if m == 9 else np.nan
        X[k, 3:] = np.linalg.solve(A, B * scale[:, 0])
        cond[k] = np.linalg.cond(A, 1)
        gimbal[k] = 1.0 / np.abs(np.cos(x[tree.passive][1::3])).min()
    return X, cond, gimbal


@pytest.mark.parametrize("gravity", [oc.GRAVITY, (1.0, -2.0, -9.81)])
def test_rnea_path_equals_a_per_sample_pinocchio_evaluation(robot, gravity):
    """The compiled RNEA path (Numba loop closure, batched ``rneaInParallel``, QR
    projection) against the same mechanics evaluated sample by sample with Pinocchio's own
    frame kinematics and NumPy's LAPACK solves (no code in common but Pinocchio's RNEA):
    X to 1e-12 relative (the two closures stop at different Newton tolerances, 1e-13 m
    and round-off; measured 7e-14), the leg-force systems' condition numbers (7 to 32
    here) and the gimbal measure to 1e-11 relative (measured 1.1e-13, 3e-14). Both
    registry backends of ``method="rnea"`` run this one path."""
    from offshore_crane.dynamics import REGISTRY, solve

    assert REGISTRY[("rnea", "numpy")] is REGISTRY[("rnea", "numba")]
    q, qd, qdd = random_states(robot, 300, seed=17)
    ours = solve(robot, q, qd, qdd, method="rnea", gravity=gravity)
    X, cond, gimbal = _rnea_per_sample(robot, q, qd, qdd, gravity)
    assert relative_error(ours.X, X) <= 1e-12
    np.testing.assert_allclose(ours.condition, cond, rtol=1e-11)
    np.testing.assert_allclose(ours.gimbal, gimbal, rtol=1e-11)
