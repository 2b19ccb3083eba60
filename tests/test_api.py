"""Public API: shapes, single samples, validation messages."""

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.motion import trajectories


def test_single_sample_shape(robot):
    q, qd, qdd = trajectories.table1(1.0)
    X = oc.inverse_dynamics(robot, q, qd, qdd)
    assert X.shape == (9,)
    Xb = oc.inverse_dynamics(robot, q[None], qd[None], qdd[None])
    np.testing.assert_array_equal(X, Xb[0])


@pytest.mark.parametrize("bad, match", [
    (lambda q: q[:, :8], r"q has shape \(5, 8\); expected \(9,\) or \(N, 9\)"),
    (lambda q: np.where(np.arange(9) == 4, np.nan, q), r"q\[0, 4\] is nan \(sample 0, column 5\)"),
    (lambda q: np.vstack([q[:3], np.full((1, 9), np.inf), q[4:]]), r"q\[3, 0\] is inf \(sample 3"),
    (lambda q: q.astype(str).astype(object) + "x", "q must be an array of numbers"),
    (lambda q: q[:0], "q has no samples"),
])
def test_bad_q(robot, bad, match):
    q, qd, qdd = trajectories.table1(np.linspace(0, 1, 5))
    with pytest.raises(oc.InputError, match=match):
        oc.inverse_dynamics(robot, bad(q), qd, qdd)


def test_mismatched_lengths(robot):
    q, qd, qdd = trajectories.table1(np.linspace(0, 1, 5))
    with pytest.raises(oc.InputError, match="sample counts differ: q has 5, qd has 4"):
        oc.inverse_dynamics(robot, q, qd[:4], qdd)


def test_unknown_method_and_bad_gravity(robot):
    q, qd, qdd = trajectories.table1(0.0)
    with pytest.raises(oc.InputError, match="unknown method 'newton'"):
        oc.inverse_dynamics(robot, q, qd, qdd, method="newton")
    with pytest.raises(oc.InputError, match="gravity must be 3 finite numbers"):
        oc.inverse_dynamics(robot, q, qd, qdd, gravity=(0, 0))


def test_exception_tree():
    for exc in (oc.InputError, oc.TrajectoryError, oc.ModelError, oc.WorkspaceError,
                oc.SingularConfigurationError, oc.BackendMissingError):
        assert issubclass(exc, oc.OffshoreCraneError)
