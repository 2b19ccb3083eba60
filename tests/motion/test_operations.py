"""Crane operations (issue 12): quintic rest-to-rest moves of q7..q9 through waypoints."""

from __future__ import annotations

import numpy as np
import pytest

from offshore_crane.errors import SeaStateError
from offshore_crane.motion.operations import Operation, operation

WAYPOINTS = [[1.0, 0.0, 0.0, 0.0],
             [4.0, 1.5, -0.5, 0.1],     # slew out, telescope
             [6.0, 1.5, -0.5, 0.1],     # dwell
             [9.0, -1.0, 0.3, -0.15]]


def test_passes_through_waypoints_at_rest_and_holds_outside():
    w = np.array(WAYPOINTS)
    q, qd, qdd = operation(w[:, 0], WAYPOINTS)
    np.testing.assert_array_equal(q, w[:, 1:])
    assert np.abs(qd).max() == 0.0 and np.abs(qdd).max() == 0.0
    q, qd, qdd = operation([-5.0, 0.5, 20.0], WAYPOINTS)        # before, before, after
    np.testing.assert_array_equal(q, w[[0, 0, -1], 1:])
    assert np.abs(qd).max() == 0.0 and np.abs(qdd).max() == 0.0
    dwell = operation(np.linspace(4.0, 6.0, 11), WAYPOINTS)
    np.testing.assert_array_equal(dwell[0], np.tile(w[1, 1:], (11, 1)))
    assert np.abs(dwell[1]).max() == 0.0


def test_continuous_acceleration_across_waypoints():
    """Position, velocity and acceleration are continuous at every waypoint: their jumps
    over ±1e-7 s are bounded by the next derivative times 2e-7 s (+ round-off)."""
    op = Operation.from_waypoints(WAYPOINTS)
    for tk in np.array(WAYPOINTS)[:, 0]:
        sides = op(np.array([tk - 1e-7, tk + 1e-7]))
        # bounds: max |qd|, |qdd|, |jerk| here are below 1, 1, 6 (per unit), times 2e-7 s
        for x, bound in zip(sides, (1e-6, 1e-5, 1e-4)):
            assert np.abs(x[0] - x[1]).max() < bound


def test_analytic_derivatives_match_finite_differences():
    """6th-order central differences at h = 1e-3 s: truncation (h/T)⁶ ~ 1e-17 times the
    sixth derivative of the quintic's jerk-free parts; 1e-7 of the peak is generous."""
    op = Operation.from_waypoints(WAYPOINTS)
    t = np.linspace(1.05, 8.95, 300)
    t = t[np.min(np.abs(t[:, None] - np.array(WAYPOINTS)[:, 0]), axis=1) > 0.01]
    h = 1e-3
    d1 = np.array([-1 / 60, 3 / 20, -3 / 4, 0, 3 / 4, -3 / 20, 1 / 60])
    d2 = np.array([1 / 90, -3 / 20, 3 / 2, -49 / 18, 3 / 2, -3 / 20, 1 / 90])
    x = np.stack([op(t + k * h)[0] for k in range(-3, 4)])
    _, qd, qdd = op(t)
    np.testing.assert_allclose(np.tensordot(d1, x, 1) / h, qd, rtol=0,
                               atol=1e-7 * np.abs(qd).max())
    np.testing.assert_allclose(np.tensordot(d2, x, 1) / h**2, qdd, rtol=0,
                               atol=1e-6 * np.abs(qdd).max())


def test_peak_speed_and_acceleration_of_a_move():
    """Closed forms of the quintic: peak speed 1.875 Δq/T at mid-move, peak acceleration
    (10/√3) Δq/T² at s = 1/2 − √3/6."""
    op = Operation.from_waypoints([[0.0, 0.0, 0.0, 0.0], [2.0, 1.0, 0.0, 0.0]])
    assert op(1.0)[1][0] == pytest.approx(1.875 * 1.0 / 2.0, rel=1e-14)
    s = 0.5 - np.sqrt(3) / 6
    assert op(2.0 * s)[2][0] == pytest.approx(10 / np.sqrt(3) / 4.0, rel=1e-12)


def test_any_order_of_times_and_scalar():
    op = Operation.from_waypoints(WAYPOINTS)
    t = np.array([7.3, 2.2, 5.0, 0.0, 3.9])
    q = op(t)[0]
    for k, tk in enumerate(t):
        np.testing.assert_array_equal(op(tk)[0], q[k])
    assert op(2.0)[0].shape == (3,)


def test_limits_checked_against_the_robot(robot):
    Operation.from_waypoints(WAYPOINTS, robot)
    with pytest.raises(SeaStateError, match=r"waypoint 1: q9 \(arm_slide\) = 0.5 m is "
                       r"outside the joint's limits \[-0.2, 0.2\] m") as info:
        operation([0.0], [[0.0, 0, 0, 0], [1.0, 0, 0, 0.5]], robot)
    assert info.value.index == 1


@pytest.mark.parametrize("waypoints,match", [
    ([[0.0, 0, 0, 0], [0.0, 1, 0, 0]], r"waypoint 1: time 0.0 s does not increase after 0.0"),
    ([[0.0, 0, 0]], r"shape \(K, 4\)"),
    ([], r"shape \(K, 4\)"),
    ([[0.0, 0, float("nan"), 0]], r"waypoint 0: q8 = nan is not finite"),
    ("slew", r"rows \[t, q7, q8, q9\] of numbers"),
])
def test_bad_waypoints(waypoints, match):
    with pytest.raises(SeaStateError, match=match):
        Operation.from_waypoints(waypoints)


def test_bad_times():
    op = Operation.from_waypoints(WAYPOINTS)
    with pytest.raises(SeaStateError, match=r"t\[1\] = inf is not finite"):
        op([0.0, np.inf])
    with pytest.raises(SeaStateError, match=r"scalar or a 1-D array"):
        op(np.zeros((2, 2)))
