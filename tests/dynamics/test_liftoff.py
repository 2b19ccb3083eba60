"""Lift-off and set-down (offshore_crane.dynamics.cable.liftoff): the instant the load
leaves a deck against the quasi-static closed form, a re-hit by a heaving deck, the
landing speed of a lowered load.

References: the static stretch at which the cable carries the weight
(``s = m g L / EA``), the hoisting profile's own speed, the samples themselves (a re-hit
is where the load is at or below the deck).
"""

from pathlib import Path

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


def _empty_X(robot, traj):
    """X of the crane with nothing on its cable (the reference for a slack cable)."""
    return oc.inverse_dynamics(robot.without_hanging_payload(), traj.q, traj.qd,
                               traj.qdd)


def test_the_whole_lift_off_record_rests_then_flies(held):
    """The lift's record: resting on the deck (slack cable: X is the empty crane's to
    1e-12 relative; taut: the pull of the stretch), then the flight from the same state
    (X continuous at the junction: its jump within twice the taut ramp's per-sample
    change just before), the
    lift figures judged from lift-off on (no slack while resting)."""
    robot, traj, z_tip = held
    hoist = cable.hoist_profile([(0.5, 1.02), (3.5, 0.98)])
    res = cable.lift_off(robot, traj, still(z_tip - 1.0), ea=EA, hoist=hoist)
    whole = res.result
    k = len(traj.t) - len(res.flight.t)
    assert len(whole.t) == len(traj.t) and whole.airborne == (k, None)
    assert np.array_equal(whole.X[k:], res.flight.X)
    slack = whole.tension[:k] == 0.0
    assert slack.sum() > 100 and (whole.tension[k - 10:k] > 0.0).all()
    empty = _empty_X(robot, traj)
    scale = np.abs(empty).max()
    assert np.abs(whole.X[:k][slack] - empty[:k][slack]).max() <= 1e-12 * scale
    before = np.abs(np.diff(whole.X[k - 10:k], axis=0)).max()   # the taut cable's ramp
    assert np.abs(whole.X[k] - whole.X[k - 1]).max() <= 2.0 * before
    assert cable.lift_metrics(whole).time_slack == 0.0


def test_a_landed_load_rests_and_its_record_goes_on(held):
    """Set-down's whole record: the flight up to the first contact, then the load resting
    where it landed while the winch pays out (slack: X the empty crane's to 1e-12), not
    lifted again; the lift's figures from before the contact."""
    robot, traj, z_tip = held
    hoist = cable.hoist_profile([(0.5, 0.9), (2.5, 1.1)])
    t_land, _, res = cable.set_down(robot, traj, still(z_tip - 1.05), ea=EA, hoist=hoist)
    k = int(np.searchsorted(traj.t, t_land))
    assert len(res.t) == len(traj.t) and res.airborne == (0, k)
    assert np.isnan(res.event.after.t_liftoff)
    late = np.flatnonzero(res.tension == 0.0)
    late = late[late > k]
    assert len(late) > 1000
    empty = _empty_X(robot, traj)
    assert np.abs(res.X[late] - empty[late]).max() <= 1e-12 * np.abs(empty).max()
    assert cable.lift_metrics(res).ratio_min > 0.5


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


# --------------------------------------------------------------------------- from a scene
DECK_LIFT = Path(__file__).resolve().parents[2] / "scenes" / "deck_lift.toml"


def test_a_lift_scene_runs_the_lift_off_and_reports_it(capsys):
    """scenes/deck_lift.toml through ``id``: its result is the library's lift-off on the
    scene's deck (the second vessel's heave under the load, the winch's profile) to the
    bit, and the report names the instant and the re-hit."""
    from offshore_crane import scenes
    from offshore_crane.__main__ import main

    scene = scenes.load_scene(DECK_LIFT)
    robot = scenes.load_robot(scene)
    traj = scenes.load_trajectory(scene, robot)
    run = scenes.run(scene, robot, traj)
    res = run.result.cable
    ref = cable.lift_off(robot, traj, scenes.lift_deck(scene), ea=1.25e4, damping=5.0,
                         hoist=cable.hoist_profile(scenes.hoist_waypoints(scene)))
    assert np.array_equal(res.X, ref.result.X) and res.event.t_liftoff == ref.t_liftoff
    assert 1.0 < ref.t_liftoff < 5.0 and ref.rehit
    assert main(["id", "--scene", str(DECK_LIFT)]) == 0
    out = capsys.readouterr().out
    assert f"lift-off at t = {ref.t_liftoff:.4g} s; RE-HIT" in out


@pytest.mark.parametrize("old, new, match", [
    ("ea = 1.25e4", "", r"\[lift\] lift-off needs an elastic cable: set \[cable\] ea"),
    ("deck_height = -0.12", "", r"\[lift\] lift-off needs deck_height \[m\]"),
    ('event = "lift-off"', 'event = "drop"', r"\[lift\] event = \"drop\": must be one of "
     r"lift-off, set-down"),
    ('event = "lift-off"', "", r"\[lift\] needs event = one of lift-off, set-down"),
    ("deck = { point = [10.0, 0.0, 2.0], seed = 7 }", "deck = { point = [10.0], seed = 7 }",
     r"\[lift\] deck: point = \[10\.0\] must be 3 finite numbers"),
    ("[lift]", "[lift]\nspeed = 3", r"\[lift\] unknown key"),
])
def test_bad_lift_sections_are_named(tmp_path, old, new, match):
    from offshore_crane import scenes
    from offshore_crane.errors import SceneError

    path = tmp_path / "s.toml"
    path.write_text(DECK_LIFT.read_text().replace(old, new, 1))
    with pytest.raises(SceneError, match=match):
        scenes.load_scene(path)
