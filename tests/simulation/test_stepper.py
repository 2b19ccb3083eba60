"""A simulation you step (:mod:`offshore_crane.simulation.stepper`): a law stepped from
outside gives ``simulate``'s run of the same law sampled at the control period, on the
rigid robot, a hanging load and an elastic cable, with sensor models; bad input is
refused in one line."""

from __future__ import annotations

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.conventions import QD_COLUMNS, Q_COLUMNS
from offshore_crane.errors import InputError
from offshore_crane.motion.trajectories import table1
from offshore_crane.simulation.control import Controller
from offshore_crane.simulation.instruments import Sensors
from offshore_crane.simulation.stepper import Stepper
from problems import computed_torque_law, simulated_on_scene

PERIOD = 0.01          # [s]: 100 Hz, ten 1 ms steps
SECONDS = 0.3


def _stepped(sim, law, seed=5):
    """Run ``sim`` to its end with ``law`` on its observations (the sensors' noise seeded
    with ``seed``; None: their own seed): its record."""
    names = sim.observation_names
    iq, iqd = ([names.index(c) for c in cols] for cols in (Q_COLUMNS, QD_COLUMNS))
    y = sim.reset(seed=seed)
    while not (sim.terminated or sim.truncated):
        t, qr, qdr, qddr = sim.reference_now
        y = sim.step(law(t, y[iq], y[iqd], qr, qdr, qddr))
    return sim.record()


def _robots():
    rigid = oc.load_robot()
    hanging = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 0.5})
    lift = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 1.0})
    return {"rigid": (rigid, {}), "hanging": (hanging, {"initial": (0.05, -0.02)}),
            "elastic": (lift, {"ea": 2e4})}


@pytest.mark.parametrize("plant", ["rigid", "hanging", "elastic"])
@pytest.mark.parametrize("sensed", [False, True])
def test_a_law_stepped_from_outside_is_simulates_sampled_law(plant, sensed):
    """The same law, sampled at 100 Hz: through ``simulate`` (a Python law at that
    rate) and through the stepper: the same q, q̇, q̈ and forces bit for bit (the same
    loop, the same sensor model), but the last sample's forces and accelerations (the
    stepper holds its last action there). With sensors: noise, a 2 ms delay and
    quantisation, seeded."""
    from offshore_crane.simulation.elastic import simulate_elastic

    robot, options = _robots()[plant]
    sensors = Sensors(noise_q=1e-5, noise_qd=1e-4, delay=2e-3, resolution_q=1e-6,
                      seed=5) if sensed else None
    law = computed_torque_law(robot)
    run = simulate_elastic if "ea" in options else oc.simulate
    want = run(robot, SECONDS, table1, controller=Controller(function=law, rate=1 / PERIOD),
               sensors=sensors, **options)
    got = _stepped(Stepper(robot, SECONDS, table1, control_period=PERIOD, sensors=sensors,
                           **options), law)
    assert len(got) == len(want) == round(SECONDS / 1e-3) + 1
    for name in ("t", "q", "qd", "q_ref"):
        np.testing.assert_array_equal(getattr(got, name), getattr(want, name), err_msg=name)
    for name in ("qdd", "X_cmd", "X", "power"):     # the last: the last action held
        np.testing.assert_array_equal(getattr(got, name)[:-1], getattr(want, name)[:-1],
                                      err_msg=name)
    if plant == "hanging":
        np.testing.assert_array_equal(got.sway, want.sway)
    if plant == "elastic":
        np.testing.assert_array_equal(got.info["payload"], want.info["payload"])


def test_the_observation_is_the_measured_state_and_reset_starts_again():
    """Without sensors the observation is the state; with a seed, noise of that seed:
    two resets with one seed give one run, another seed another."""
    robot = oc.load_robot()
    sim = Stepper(robot, 0.05, table1, control_period=PERIOD)
    y = sim.reset()
    np.testing.assert_array_equal(y[:18], sim.state)
    assert sim.observation_names[:3] == ("q1_m", "q2_m", "q3_m") and len(y) == 36
    assert sim.observation_names[18:20] == ("q1_ref_m", "q2_ref_m")
    assert sim.observation_names[-1] == "qd9_ref_m_s"
    for _ in range(3):          # the reference at the instant: Table 1's own numbers
        q, qd, _ = table1(np.array([sim.time]))
        np.testing.assert_allclose(y[18:], np.r_[q[0], qd[0]], rtol=0, atol=1e-15)
        y = sim.step(oc.inverse_dynamics(robot, y[:9], y[9:18], np.zeros(9)))
    assert sim.action_names == ("T1", "T2", "Fs", "Fl1", "Fl2", "Fl3", "Fl4", "Fl5", "Fl6")
    noisy = Stepper(robot, 0.05, table1, control_period=PERIOD,
                    sensors=Sensors(noise_q=1e-4, seed=1))
    a, b, c = noisy.reset(seed=3), noisy.reset(seed=3), noisy.reset(seed=4)
    np.testing.assert_array_equal(a, b)
    assert np.abs(a[:9] - noisy.state[:9]).max() > 0 and not np.array_equal(a, c)


def test_bad_actions_and_calls_are_refused_in_one_line():
    robot = oc.load_robot()
    sim = Stepper(robot, 0.02, table1, control_period=PERIOD, saturation=False)
    assert sim.time == 0.0 and not (sim.terminated or sim.truncated)
    with pytest.raises(InputError, match=r"step\(\) before reset\(\)"):
        sim.step(np.zeros(9))
    for before in (lambda: sim.state, sim.record):
        with pytest.raises(InputError, match=r"no run yet: call reset\(\) first"):
            before()
    y = sim.reset()
    X = oc.inverse_dynamics(robot, y[:9], y[9:18], np.zeros(9))
    with pytest.raises(InputError, match=r"action of shape \(8,\): give 9 forces \(T1, "):
        sim.step(X[:8])
    with pytest.raises(InputError, match=r"action 'nine' is not numbers: give 9 of them"):
        sim.step("nine")
    bad = X.copy()
    bad[4] = np.nan
    with pytest.raises(InputError, match="action Fl2 = nan at t = 0 s: give finite numbers"):
        sim.step(bad)
    bad[4] = 1e9
    with pytest.raises(InputError, match=r"action Fl2 = 1e\+09 at t = 0 s is beyond its "
                                         r"capacity \[.*\]: .*saturation=True"):
        sim.step(bad)
    sim.step(X)
    sim.step(X)
    assert sim.truncated and not sim.terminated and sim.time == pytest.approx(0.02)
    with pytest.raises(InputError, match=r"step\(\) after the run reached its duration at "
                                         r"t = 0.02 s: call reset\(\)"):
        sim.step(X)
    assert len(sim.record()) == 21
    with pytest.raises(InputError, match=r"control_period = 0.00333333 s is not a whole "
                                         r"number of integration steps of 0.001 s"):
        Stepper(robot, 0.02, table1, control_period=1 / 300)
    with pytest.raises(InputError, match="duration = 0.025 s is not a whole number of "
                                         "control periods"):
        Stepper(robot, 0.025, table1, control_period=PERIOD)


def test_a_run_that_leaves_the_workspace_is_terminated_and_its_record_says_why():
    """Forces that throw the platform out: ``terminated``, further steps refused, and
    the record ends with its stop."""
    robot = oc.load_robot()
    sim = Stepper(robot, 2.0, table1, control_period=PERIOD)
    y = sim.reset()
    X = oc.inverse_dynamics(robot, y[:9], y[9:18], np.zeros(9))
    push = X + np.r_[0, 0, 0, [400.0] * 6]
    while not sim.terminated:
        sim.step(push)
        assert not sim.truncated
    res = sim.record()
    assert res.stop is not None and "outside its limits" in res.stop
    with pytest.raises(InputError, match=r"step\(\) after the run stopped"):
        sim.step(push)


def test_the_modules_example_runs():
    """The example in :mod:`offshore_crane.simulation.stepper`'s docstring, as written."""
    import doctest

    from offshore_crane.simulation import stepper

    assert doctest.testmod(stepper).failed == 0


@pytest.mark.parametrize("scene", ["compensated_lift.toml", "hanging_load.toml"])
def test_a_stepper_on_a_scene_is_its_simulations_run(scene):
    """``scenes.stepper`` sets the run up as ``simulate --scene`` does
    (``scenes.plant_options``: the compensated reference, the elastic cable and winch, or
    the hanging load's sway; the sensors, actuators, step and gravity): a Python law
    stepped on it gives the same law's ``simulate`` run on the scene's inputs, bit for
    bit (but the last sample's forces)."""
    from pathlib import Path

    from offshore_crane import scenes

    path = Path(__file__).parents[2] / "scenes" / scene
    law = computed_torque_law(scenes.load_robot(scenes.load_scene(path)))
    want = simulated_on_scene(path, law, 0.2, PERIOD)[0]
    sim = scenes.stepper(path, control_period=PERIOD, duration=0.2)
    got = _stepped(sim, law, seed=None)             # the scene's own seed
    for name in ("t", "q", "qd", "q_ref"):
        np.testing.assert_array_equal(getattr(got, name), getattr(want, name), err_msg=name)
    np.testing.assert_array_equal(got.X[:-1], want.X[:-1])
    for name in ("payload_x_m", "tension_N", "L_m"):      # a hanging load's, an elastic's
        assert name in sim.observation_names
    with pytest.raises(InputError, match="is longer than the scene's reference"):
        scenes.stepper(path, control_period=PERIOD, duration=1e6)


def test_what_the_plant_forms_of_the_state_is_the_records():
    """The hanging load's position and the elastic cable's tension observed at each
    control instant are the record's at that sample, the cable's length its own (the payload from the tip's and the
    sway's formulas on NumPy arrays, :func:`~offshore_crane.dynamics.cable.tip.
    payload_positions`; the tension as the loop recorded it). Without sensors the
    measured state is the state, so they agree to round-off (1e-12 m: the compiled and
    the NumPy kernels order their sums apart)."""
    from offshore_crane.dynamics.cable.tip import payload_positions

    robots = _robots()
    for plant, name, cols in (("hanging", "payload_x_m", 3), ("elastic", "tension_N", 1)):
        robot, options = robots[plant]
        sim = Stepper(robot, 0.1, table1, control_period=PERIOD, **options)
        law, names = computed_torque_law(robot), sim.observation_names
        j, jl = names.index(name), names.index("L_m")
        iq, iqd = ([names.index(c) for c in c_] for c_ in (Q_COLUMNS, QD_COLUMNS))
        y, seen, lengths = sim.reset(), [], []
        while not sim.truncated:
            seen.append(y[j:j + cols])
            lengths.append(y[jl])
            t, qr, qdr, qddr = sim.reference_now
            y = sim.step(law(t, y[iq], y[iqd], qr, qdr, qddr))
        res = sim.record()
        k = np.arange(len(seen)) * round(PERIOD / 1e-3)
        if plant == "hanging":
            from types import SimpleNamespace

            cable = SimpleNamespace(q=res.q, qd=res.qd, qdd=res.qdd, sway=res.sway,
                                    length=0.5, hoist=None)      # a CableResult's fields
            want, atol = payload_positions(sim._run.plant.robot, cable)[k], 1e-12
        else:
            want, atol = res.tension[k, None], 1e-9 * float(np.abs(res.tension).max())
        np.testing.assert_allclose(np.array(seen), want, rtol=0, atol=atol)
        profile = (np.full(len(k), 0.5) if plant == "hanging"      # the fixed length
                   else sim.plant.Lg[2 * k, 0])                    # the winch's profile
        np.testing.assert_array_equal(lengths, profile)


def test_a_reference_as_the_action_is_simulates_run_of_that_reference():
    """``action="reference"``: (q_ref, q̇_ref) given each period, held as a first-order
    hold, for the built-in computed torque: the run ``simulate`` makes of the same law at
    the control rate on that piecewise reference (≤ 1e-12 relative: the hold's times
    are formed apart, an ulp of t). The actions: Table 1 at the control instants,
    offset so they differ from the scene's own reference."""
    robot = oc.load_robot()
    seconds, n = 0.2, 20
    tk = np.arange(n + 1) * PERIOD
    q, qd, _ = table1(tk)
    q = q + 0.01 * np.sin(7 * tk)[:, None]
    sim = Stepper(robot, seconds, table1, control_period=PERIOD, action="reference")
    assert sim.action_names[0] == "q1_cmd_m" and len(sim.action_names) == 18
    assert np.isinf(sim.action_bounds[0]).all()
    sim.reset()
    for k in range(n):
        sim.step(np.r_[q[k], qd[k]])
    got = sim.record()

    def held(t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        k = np.minimum(np.floor(t / PERIOD + 1e-9).astype(int), n - 1)
        return (q[k] + (t - tk[k])[:, None] * qd[k], qd[k].copy(), np.zeros((len(t), 9)))
    want = oc.simulate(robot, seconds, held, table1(np.zeros(1))[0][0],
                       table1(np.zeros(1))[1][0], Controller(rate=1 / PERIOD))
    for name in ("q", "qd", "q_ref"):
        a, b = getattr(got, name), getattr(want, name)
        assert np.abs(a - b).max() <= 1e-12 * np.abs(b).max(), name
    assert np.abs(got.q - table1(got.t)[0]).max() > 1e-3     # the action's, not Table 1's
    with pytest.raises(InputError, match=r"action of shape \(9,\): give 18 reference "):
        sim.reset()
        sim.step(np.zeros(9))


def test_the_reference_action_is_refused_where_it_cannot_be():
    robot = oc.load_robot()
    with pytest.raises(InputError, match="action = 'torques': give 'forces' or"):
        Stepper(robot, 0.1, table1, control_period=PERIOD, action="torques")
    with pytest.raises(InputError, match="a controller drives the run only with action="):
        Stepper(robot, 0.1, table1, control_period=PERIOD, controller=Controller())
    with pytest.raises(InputError, match="'arm-compensation' forms its reference once"):
        Stepper(_robots()["hanging"][0], 0.1, table1, control_period=PERIOD,
                action="reference", controller=Controller(law="arm-compensation"))


def test_a_cable_below_its_slack_tension_terminates_the_run():
    """A hanging load whose description asks ``T ≥ 0.9 m g``: the platform dropped by
    pulling every leg in (20 N below holding it) takes part of the load's weight off
    (T ≈ 0.58 m g), the run is terminated after its first period, whose record holds
    those tensions."""
    robot = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 0.5,
                                     "payload.limits.tension_ratio_min": 0.9})
    sim = Stepper(robot, 1.0, table1, control_period=PERIOD)
    assert sim.slack_tension == pytest.approx(0.9 * 2.0 * 9.81, rel=1e-3)
    y = sim.reset()
    X = oc.inverse_dynamics(robot.without_hanging_payload(), y[:9], np.zeros(9),
                            np.zeros(9))
    while not sim.terminated:
        y = sim.step(X - np.r_[0, 0, 0, [20.0] * 6])
        assert not sim.truncated
    res = sim.record()          # taut still (no stop of the model's): the criterion's end
    assert res.stop is None and len(res) == 10 and sim.time == pytest.approx(PERIOD)
    assert 0.0 < res.tension.min() < sim.slack_tension


@pytest.mark.parametrize("case", ["fixed", "winch", "drag"])
def test_a_rigid_cables_observed_tension_is_the_records_under_the_same_forces(case):
    """A rigid cable's tension at a control instant is the pendulum's pull under the
    forces acting there (the last period's): held the same over every period, the
    record's tension at that sample (formed under the same forces by the next piece) is
    the observed one, on a cable of a fixed length (the Kane pass's force), hoisted by
    a winch (the hoisted pendulum's pull) and with the payload's air drag (its share
    along the cable). 1e-12 relative: the same formulas on the same numbers."""
    from offshore_crane.dynamics import cable

    over = {"payload.mass": 2.0, "payload.cable_length": 0.5}
    if case == "drag":
        over["payload.drag_area"] = 0.5
    robot = oc.load_robot(overrides=over)
    plant = {"initial": (0.05, -0.02)}
    if case == "winch":
        plant["hoist"] = cable.hoist_profile([(0.02, 0.5), (0.2, 0.48)])
    sim = Stepper(robot, 0.1, table1, control_period=PERIOD, **plant)
    j = sim.observation_names.index("tension_N")
    y = sim.reset()
    X = sim.holding()
    seen = [y[j]]
    while not sim.truncated:
        seen.append(sim.step(X)[j])
    res = sim.record()
    k = np.arange(1, len(seen) - 1) * round(PERIOD / 1e-3)    # the instants a step began
    np.testing.assert_allclose(seen[1:-1], res.tension[k], rtol=1e-12)
    assert np.all(np.isfinite(seen)) and np.ptp(seen) > 0          # it moves, it is read


def test_a_hoisted_rigid_cable_that_goes_slack_terminates_the_run():
    """A winch hauling 5 cm in 60 ms takes the load's weight off the cable: its tension,
    formed by the record after the run (not in the loop), is judged at each control
    instant, and the run is terminated at the first instant after the record's stop."""
    from offshore_crane.dynamics import cable

    robot = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 0.5})
    sim = Stepper(robot, 0.2, table1, control_period=PERIOD, initial=(0.05, -0.02),
                  hoist=cable.hoist_profile([(0.02, 0.5), (0.08, 0.45)]))
    sim.reset()
    X = sim.holding()
    while not (sim.terminated or sim.truncated):
        sim.step(X)
    res = sim.record()
    assert sim.terminated and "slack" in res.stop
    assert sim.time - PERIOD <= res.t[-1] + 1e-3 <= sim.time
