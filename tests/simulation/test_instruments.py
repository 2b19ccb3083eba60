"""Sensors and actuators between the law and the plant (issue 37 item 3): what the law
receives under delay, quantisation and seeded noise, the lag's and the rate limit's
effect on the applied forces, the same on every plant, and their refusals."""

from __future__ import annotations

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.errors import InputError
from offshore_crane.motion.trajectories import table1
from offshore_crane.simulation.control import Controller
from offshore_crane.simulation.instruments import Actuators, Sensors

STEP = 1e-3


@pytest.fixture(scope="module")
def robot():
    return oc.load_robot()


def recording_law(robot, seen):
    """Computed torque in Python that keeps the q it is given."""
    kp, kd = Controller().gains

    def law(t, q, qd, qr, qdr, qddr):
        seen.append((t, q.copy(), qd.copy()))
        cmd = qddr + kd * (qdr - qd) + kp * (qr - q)
        return oc.inverse_dynamics(robot, q[None], qd[None], cmd[None])[0]
    return law


def test_a_delayed_sensor_gives_the_state_that_many_steps_ago(robot):
    """Delay 3 ms at a 1 kHz control rate: the law at t receives q(t − 3 ms) exactly (the
    initial state before that), the state recorded at every step."""
    seen = []
    res = oc.simulate(robot, 0.05, table1, controller=Controller(
        function=recording_law(robot, seen), rate=1000.0), sensors=Sensors(delay=0.003))
    got = np.array([s[1] for s in seen])
    assert np.array_equal(got[3:], res.q[:-3]) and np.array_equal(got[:3], res.q[[0, 0, 0]])


def test_quantised_and_seeded_noise(robot):
    """Resolution 1e-4 m, rad: what the law receives is a multiple of it; noise of the
    same seed gives the same run, another seed another run."""
    seen = []
    oc.simulate(robot, 0.02, table1, controller=Controller(
        function=recording_law(robot, seen), rate=500.0),
        sensors=Sensors(resolution_q=1e-4))
    q = np.array([s[1] for s in seen])
    assert np.abs(q / 1e-4 - np.round(q / 1e-4)).max() < 1e-6
    runs = [oc.simulate(robot, 0.05, table1, controller=Controller(rate=500.0),
                        sensors=Sensors(noise_q=1e-4, seed=seed)) for seed in (1, 1, 2)]
    assert np.array_equal(runs[0].X, runs[1].X) and not np.allclose(runs[0].X, runs[2].X)


def test_the_controllers_noise_is_the_sensors_noise(robot):
    """``Controller(noise_q=...)`` (the shorthand) and ``Sensors(noise_q=...)`` draw the
    same noise: the same run to 1e-12 relative (measured 2e-15; the second run has a
    rate limit too large to act)."""
    a = oc.simulate(robot, 0.2, table1, controller=Controller(rate=250.0, noise_q=1e-5,
                                                              noise_qd=1e-4, seed=3))
    b = oc.simulate(robot, 0.2, table1, controller=Controller(rate=250.0),
                    sensors=Sensors(noise_q=1e-5, noise_qd=1e-4, seed=3),
                    actuators=Actuators(lag=None, rate_limit=1e30))
    assert a.info["plant"] == b.info["plant"] == "rigid"
    assert np.abs(a.X - b.X).max() <= 1e-12 * np.abs(a.X).max()


def test_a_first_order_lag_follows_a_step_of_the_command(robot):
    """A command that steps at 0.02 s, lag τ = 5 ms, law 'none'-like Python law: the
    applied force is X_a + (X_b − X_a)(1 − e^{−(t − 0.02)/τ}) to RK4's accuracy: at
    h/τ = 0.2 the RK4 polynomial misses e^{−h/τ} by (h/τ)⁵/120 = 2.7e-6 a step, which
    adds up over the first time constants; bound 2e-5 relative (measured 5.8e-6)."""
    Xa, Xb = np.zeros(9), np.r_[0.1, -0.1, 0.5, np.full(6, 2.0)]
    tau = 0.005

    def law(t, q, qd, qr, qdr, qddr):
        return Xa if t < 0.02 - 1e-12 else Xb

    res = oc.simulate(robot, 0.05, table1, controller=Controller(function=law, rate=1000.0,
                                                                 saturation=False),
                      actuators=Actuators(lag=tau), limits=False)
    t = res.t - res.t[0]
    after = t >= 0.02
    expect = Xa + (Xb - Xa) * (1.0 - np.exp(-(t[after, None] - 0.02) / tau))
    assert np.abs(res.X[after] - expect).max() <= 2e-5 * np.abs(Xb).max()
    assert np.array_equal(res.X[~after], np.zeros(((~after).sum(), 9)))


def test_a_rate_limit_bounds_the_applied_change(robot):
    """Rate limit 50 N/s on every actuator at 1 kHz: the applied forces change by at most
    0.05 N a step (they lag the unlimited command)."""
    res = oc.simulate(robot, 0.05, table1, controller=Controller(rate=1000.0),
                      actuators=Actuators(rate_limit=50.0), limits=False)
    assert np.abs(np.diff(res.X, axis=0)).max() <= 50.0 * STEP * (1 + 1e-12)


@pytest.mark.parametrize("overrides", [{}, {"payload.mass": 2.0, "payload.cable_length": 0.5}],
                         ids=["rigid", "hanging"])
def test_instruments_act_the_same_on_every_plant(overrides):
    """The same sensors and actuators on the rigid and the hanging plant: the rate limit
    (50 N/s at 1 kHz) bounds every applied change to 0.05 N a step, and the lag (2 ms)
    makes the applied forces depart from the commanded ones (by more than 1e-5 of their
    peak; measured 2.7e-4 on the rigid robot: an actuator model a plant dropped would
    leave them equal)."""
    robot = oc.load_robot(overrides=overrides)
    res = oc.simulate(robot, 0.05, table1, controller=Controller(rate=1000.0),
                      sensors=Sensors(noise_q=1e-5, delay=0.002),
                      actuators=Actuators(rate_limit=50.0), limits=False)
    assert res.info["plant"] == ("hanging" if overrides else "rigid")
    assert np.abs(np.diff(res.X, axis=0)).max() <= 50.0 * STEP * (1 + 1e-12)
    lag = oc.simulate(robot, 0.05, table1, controller=Controller(rate=1000.0),
                      actuators=Actuators(lag=0.002), limits=False)
    assert np.abs(lag.X - lag.X_cmd).max() > 1e-5 * np.abs(lag.X_cmd).max()


@pytest.mark.parametrize("make, match", [
    (lambda: Sensors(noise_q=-1e-3), r"noise_q\[0\] = -0.001 m, rad: must be finite and ≥ 0"),
    (lambda: Actuators(lag=0.0), r"lag\[0\] = 0.0 s: must be finite and > 0"),
    (lambda: Actuators(rate_limit=[1.0] * 8), r"rate_limit must be one number or 9"),
    (lambda: Sensors(delay=np.nan), r"sensor delay = nan s"),
])
def test_bad_instruments(make, match):
    with pytest.raises(InputError, match=match):
        make()


def test_refusals_at_the_run(robot):
    with pytest.raises(InputError, match=r"sensor delay = 0.0015 s is not a multiple of the "
                                         r"integration step 0.001 s"):
        oc.simulate(robot, 0.01, table1, controller=Controller(rate=500.0),
                    sensors=Sensors(delay=0.0015))
    with pytest.raises(InputError, match="sensor models act at the control instants"):
        oc.simulate(robot, 0.01, table1, sensors=Sensors(noise_q=1e-4))
    with pytest.raises(InputError, match="an actuator rate limit act"):
        oc.simulate(robot, 0.01, table1, actuators=Actuators(rate_limit=10.0))
