"""Lift-off and set-down (offshore_crane.dynamics.cable.liftoff): the instant the load
leaves a deck against the quasi-static closed form, a re-hit by a heaving deck, the
landing speed of a lowered load.

References: the static stretch at which the cable carries the weight
(``s = m g L / EA``), the hoisting profile's own speed, the samples themselves (a re-hit
is where the load is at or below the deck).
"""

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.dynamics import cable
from offshore_crane.dynamics.cable.tip import tip_positions
from offshore_crane.errors import InputError
from problems import held_at_home
from offshore_crane.motion.trajectories import Trajectory

G = 9.81
MASS, EA = 2.0, 2e4


@pytest.fixture(scope="module")
def held():
    """A frozen crane for 4 s at 1 kHz, its tip height, and its robot."""
    robot = oc.load_robot(overrides={"payload.mass": MASS, "payload.cable_length": 1.0})
    t, q, qd, qdd = held_at_home(robot, 4.0, 1000.0)
    tip = tip_positions(robot, q[:1])[0][0]
    return robot, Trajectory("held", t, q, qd, qdd), float(tip[2])


def still(z):
    return lambda t: (np.full(len(t), z), 0 * t, 0 * t)


def test_the_load_leaves_a_still_deck_when_the_cable_carries_its_weight(held):
    """The winch hauls in from 1.02 to 0.98 m over 3 s; the load rests 1 m below the tip:
    it lifts off when the stretch carries m g, ``L = d / (1 + m g / EA)``, within one
    sample (1 ms) of that instant, and rises without touching again."""
    robot, traj, z_tip = held
    hoist = cable.hoist_profile([(0.5, 1.02), (3.5, 0.98)])
    res = cable.lift_off(robot, traj, still(z_tip - 1.0), ea=EA, hoist=hoist)
    fine = np.linspace(0.5, 3.5, 300_001)
    when = fine[np.argmax(hoist(fine)[0] <= 1.0 / (1.0 + MASS * G / EA))]
    assert abs(res.t_liftoff - when) <= 1e-3 + 1e-9
    assert not res.rehit and res.clearance_min > 0.0
    assert res.flight.payload[0, 2] == pytest.approx(z_tip - 1.0, abs=1e-12)


def test_a_heaving_deck_catches_the_load_again(held):
    """A deck heaving 30 mm at 1 Hz under a cable of fixed length: the load leaves as the
    deck drops away (t ≈ 0.5 s), flies, and the rising deck catches it (measured at
    1.007 s, closing at 0.158 m/s): the re-hit is the first sample where the load is at
    or below the deck."""
    robot, traj, z_tip = held
    A, w = 0.03, 2 * np.pi

    def deck(t):
        return (z_tip - 1.0 + A * np.sin(w * t), A * w * np.cos(w * t),
                -A * w * w * np.sin(w * t))
    res = cable.lift_off(robot, traj, deck, ea=EA)
    assert 0.25 < res.t_liftoff < 0.75
    assert res.rehit and res.rehit_speed < 0.0 and res.clearance_min <= 0.0
    k = int(np.argmin(np.abs(res.flight.t - res.t_rehit)))
    z_deck = deck(res.flight.t)[0]
    assert res.flight.payload[k, 2] <= z_deck[k]
    assert (res.flight.payload[1:k, 2] > z_deck[1:k]).all()


def test_a_lowered_load_lands_at_the_winchs_speed(held):
    """Paid out from 0.9 to 1.1 m over 2 s onto a still deck 1.05 m below the tip: the
    first contact comes when the stretched cable reaches the deck, and the landing speed
    relative to the deck is the winch's pay-out speed there (the load hangs with its
    static stretch; within 1 mm/s: the axial ringing the profile's start excites)."""
    robot, traj, z_tip = held
    hoist = cable.hoist_profile([(0.5, 0.9), (2.5, 1.1)])
    t_land, speed, res = cable.set_down(robot, traj, still(z_tip - 1.05), ea=EA,
                                        hoist=hoist)
    assert 0.5 < t_land < 2.5
    assert speed == pytest.approx(-hoist(np.array([t_land]))[1][0], abs=1e-3)
    assert speed < -0.05


def test_no_lift_when_the_cable_never_carries_the_load(held):
    robot, traj, z_tip = held
    res = cable.lift_off(robot, traj, still(z_tip - 0.5), ea=EA)       # cable too long
    assert np.isnan(res.t_liftoff) and not res.rehit and res.flight is None


@pytest.mark.parametrize("deck, match", [
    (lambda t: (np.full(len(t), 10.0), 0 * t, 0 * t), r"the deck at 10 m is not below the tip"),
    (lambda t: (np.zeros(3), 0 * t, 0 * t), r"deck\(t\) must return three arrays"),
    (lambda t: (np.full(len(t), np.nan), 0 * t, 0 * t), "non-finite"),
])
def test_bad_decks(held, deck, match):
    robot, traj, _ = held
    with pytest.raises(InputError, match=match):
        cable.lift_off(robot, traj, deck, ea=EA)
