"""Identification (offshore_crane.studies.identification): the closed-loop regressor
against Kane's and the RNEA reference's X, batch against per-sample, the friction
columns against their definition, the base parameters' rank and groupings, error paths.

References: Kane's inverse dynamics (shares nothing with the regressor but the URDF), the
RNEA reference (shares the projection), hand-written friction forces.
"""

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.errors import InputError
from offshore_crane.motion.trajectories import table1, time_grid
from offshore_crane.robot.kinematics import actuator_motion
from offshore_crane.studies import identification as ident
from problems import random_states


@pytest.fixture(scope="module")
def robot():
    return oc.load_robot()


def test_y_pi_is_kanes_x(robot):
    """``Y π`` equals Kane's X to 1e-12 of the peak force (the issue's bound; measured
    ~1e-15) on 50 random states and along Table 1 (one sample in ten of 100 Hz), and
    the RNEA reference's."""
    q, qd, qdd = random_states(robot, 50, seed=11)
    t = time_grid(31.4, 10.0)
    for a, b, c in ((q, qd, qdd), table1(t)):
        R = ident.regressor(robot, a, b, c)
        X = oc.inverse_dynamics(robot, a, b, c)
        assert np.abs(R.Y @ R.pi - X).max() <= 1e-12 * np.abs(X).max()
        Xr = oc.inverse_dynamics(robot, a, b, c, method="rnea")
        assert np.abs(R.Y @ R.pi - Xr).max() <= 1e-12 * np.abs(X).max()
    assert R.Y.shape == (len(t), 9, 160) and len(R.names) == 160
    assert R.names[:2] == ("leg1_lower.m", "leg1_lower.mcx") and R.units[4] == "kg·m²"


def test_batch_equals_per_sample(robot):
    """To round-off (1e-13 of the largest entry: the loop closure's Newton stops on the
    batch's worst residual, so a sample alone may take one iteration less)."""
    q, qd, qdd = random_states(robot, 6, seed=2)
    whole = ident.regressor(robot, q, qd, qdd).Y
    for k in range(6):
        one = ident.regressor(robot, q[k:k + 1], qd[k:k + 1], qdd[k:k + 1]).Y
        assert np.abs(one[0] - whole[k]).max() <= 1e-13 * np.abs(whole[k]).max()


def test_friction_columns_are_viscous_coulomb_and_offset(robot):
    q, qd, qdd = random_states(robot, 20, seed=5)
    R = ident.regressor(robot, q, qd, qdd, friction=True)
    assert R.Y.shape[-1] == 160 + 27 and R.names[160:163] == ("T1.fv", "T1.fc", "T1.f0")
    assert R.units[163:166] == ("N·m·s/rad", "N·m", "N·m") and R.units[-3] == "N·s/m"
    rng = np.random.default_rng(0)
    f = rng.normal(size=(9, 3))
    v = actuator_motion(robot, q, qd)[1]
    want = f[:, 0] * v + f[:, 1] * np.sign(v) + f[:, 2]
    assert np.allclose(R.Y[:, :, 160:] @ f.ravel(), want, rtol=0, atol=1e-14)


def test_base_parameters(robot):
    """Rank 100 of 160 with a clear gap (|R_ii| from ~7e-2 to ~1e-15 of |R_11|), the same
    from another seed; ``Y_b K π = Y π`` on other states to 1e-12; the U-joint pairs'
    grouping written out: ``leg{i}_lower.Izz + leg{i}_upper.Izz`` for every leg."""
    B = ident.base_parameters(robot, n=100, seed=0)
    assert B.rank == 100 == ident.base_parameters(robot, n=100, seed=1).rank
    d = B.diagonal / B.diagonal[0]
    assert d[B.rank - 1] > 1e-3 and d[B.rank] < 1e-12
    R = ident.regressor(robot, *random_states(robot, 30, seed=9))
    full = R.Y @ R.pi
    assert np.abs(B.base_regressor(R.Y) @ (B.K @ R.pi) - full).max() <= 1e-12 * np.abs(
        full).max()
    text = B.describe()
    for i in range(1, 7):
        assert any(line.endswith(f"= leg{i}_lower.Izz + leg{i}_upper.Izz") for line in text)


def test_errors(robot):
    q, qd, qdd = random_states(robot, 3, seed=1)
    hanging = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 1.0})
    with pytest.raises(InputError, match="the payload hangs on a cable"):
        ident.regressor(hanging, q, qd, qdd)
    with pytest.raises(InputError, match="qd has 2 samples and q 3"):
        ident.regressor(robot, q, qd[:2], qdd)
    bad = q.copy()
    bad[1, 4] = np.nan
    with pytest.raises(InputError, match=r"q\[1, 4\]"):
        ident.regressor(robot, bad, qd, qdd)
