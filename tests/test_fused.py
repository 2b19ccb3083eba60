"""The fused Kane kernel: its code paths agree, and its prunings are exact.

Tolerance 1e-12 relative for "identical" results: the paths evaluate the same formulas
in a different order (chunks, Python floats vs arrays), so they differ by round-off only.
"""

import numpy as np
import pytest

import offshore_crane as oc
from conftest import relative_error
from offshore_crane.dynamics import solve
from offshore_crane.dynamics.fused import SCALAR_MAX, Options, fused_inverse_dynamics
from problems import random_states

G = np.array([0.0, 0.0, -9.81])
EXACT = 1e-12


@pytest.mark.parametrize("leg_model", ["full", "thin-rod", "massless"])
def test_scalar_path_equals_vector_path(robot, leg_model):
    q, qd, qdd = random_states(robot, 30, seed=21)
    opts = Options(leg_model=leg_model, conditioning=True, diagnostics=True)
    Xv, cv, dv = fused_inverse_dynamics(robot.fused, q, qd, qdd, G, opts, backend="numpy")
    for k in range(0, 30, 7):
        Xs, cs, ds = fused_inverse_dynamics(robot.fused, q[k:k + 1], qd[k:k + 1],
                                            qdd[k:k + 1], G, opts, backend="numpy")
        assert relative_error(Xs[0], Xv[k]) < EXACT
        assert cs[0] == pytest.approx(cv[k], rel=1e-10)
        for key in dv:
            np.testing.assert_allclose(ds[key][0], dv[key][k], rtol=1e-12, atol=1e-15)
    assert SCALAR_MAX >= 1


@pytest.mark.parametrize("chunk", [1, 9, 64, 5000])
def test_chunking_does_not_change_results(robot, chunk):
    q, qd, qdd = random_states(robot, 300, seed=4)
    ref, _, _ = fused_inverse_dynamics(robot.fused, q, qd, qdd, G, backend="numpy")
    X, _, _ = fused_inverse_dynamics(robot.fused, q, qd, qdd, G, chunk=chunk, backend="numpy")
    assert relative_error(X, ref) < EXACT


@pytest.mark.parametrize("opts", [
    Options(conditioning=True, diagnostics=True), Options(leg_model="thin-rod"),
    Options(leg_model="massless", diagnostics=True), Options(legs=False),
    Options(platform_static=True, conditioning=True)], ids=str)
def test_numba_kernel_equals_numpy_kernel(robot, opts):
    pytest.importorskip("numba")
    q, qd, qdd = random_states(robot, 500, seed=31)
    if opts.platform_static:
        q[:, :6] = q[0, :6]
        qd[:, :6] = qdd[:, :6] = 0.0
    Xp, cp, dp = fused_inverse_dynamics(robot.fused, q, qd, qdd, G, opts, backend="numpy")
    Xn, cn, dn = fused_inverse_dynamics(robot.fused, q, qd, qdd, G, opts, backend="numba")
    np.testing.assert_array_equal(np.isnan(Xn), np.isnan(Xp))
    finite = np.isfinite(Xp)
    assert relative_error(Xn[finite], Xp[finite]) < EXACT
    if cp is not None:
        np.testing.assert_allclose(cn, cp, rtol=1e-12)
    if dp is not None:
        for key in dp:
            np.testing.assert_allclose(dn[key], dp[key], rtol=1e-12, atol=1e-15)


def test_arm_only_pruning_is_exact(robot, table1):
    _, q, qd, qdd = table1
    full = solve(robot, q, qd, qdd)
    arm = solve(robot, q, qd, qdd, outputs=["T1", "T2", "Fs"])
    assert relative_error(arm.X[:, :3], full.X[:, :3]) < EXACT
    assert np.isnan(arm.X[:, 3:]).all() and arm.condition is None
    assert "leg kinematics and dynamics (no leg force wanted)" in arm.pruned


def test_static_platform_pruning_is_exact(robot, table1):
    _, q, qd, qdd = table1
    q = q.copy()
    q[:, :6] = q[100, :6]
    qd, qdd = qd.copy(), qdd.copy()
    qd[:, :6] = qdd[:, :6] = 0.0
    pruned, _, _ = fused_inverse_dynamics(robot.fused, q, qd, qdd, G,
                                          Options(platform_static=True))
    unpruned, _, _ = fused_inverse_dynamics(robot.fused, q, qd, qdd, G)
    assert relative_error(pruned, unpruned) < EXACT
    assert any("static platform" in p for p in solve(robot, q, qd, qdd).pruned)


def test_thin_rod_is_exact_without_axial_inertia():
    """Zero leg radii: no axial inertia, so dropping the leg spin changes nothing."""
    robot = oc.load_robot(leg_lower_radius=0.0, leg_upper_radius=0.0)
    q, qd, qdd = random_states(robot, 200, seed=8)
    full = oc.inverse_dynamics(robot, q, qd, qdd)
    thin = oc.inverse_dynamics(robot, q, qd, qdd, leg_model="thin-rod")
    assert relative_error(thin, full) < EXACT
    ref = oc.inverse_dynamics(robot, q, qd, qdd, method="rnea")
    assert relative_error(thin, ref) < 1e-9


def test_massless_model_matches_a_massless_robot():
    robot = oc.load_robot()
    light = oc.load_robot(leg_lower_mass=0.0, leg_upper_mass=0.0)
    q, qd, qdd = random_states(robot, 200, seed=12)
    approx = oc.inverse_dynamics(robot, q, qd, qdd, leg_model="massless")
    ref = oc.inverse_dynamics(light, q, qd, qdd, method="rnea")
    assert relative_error(approx, ref) < 1e-9


def test_approximations_differ_and_are_labelled(robot, table1):
    _, q, qd, qdd = table1
    full = solve(robot, q, qd, qdd)
    thin = solve(robot, q, qd, qdd, leg_model="thin-rod")
    assert full.approximations == ()
    assert thin.approximations and "thin-rod" in thin.approximations[0]
    assert 1e-12 < relative_error(thin.X, full.X) < 1e-3
    with pytest.raises(oc.InputError, match="leg model 'thin-rod' is an approximation"):
        solve(robot, q, qd, qdd, method="rnea", leg_model="thin-rod")


def test_twist_form_survives_the_attitude_singularity(robot):
    """At pitch q5 = π/2 the explicit form's Jᵀ is singular; the fused solve is not."""
    q, qd, qdd = random_states(robot, 20, seed=2)
    q[:, 4] = np.pi / 2
    q[:, 3] = q[:, 5] = 0.0
    res = solve(robot, q, qd, qdd, limits=False, checks=False)
    assert np.isfinite(res.X).all()
