"""A commanded winch on the elastic cable (``actuators.winch.reflected_mass`` > 0): its
length and rate in the plant's state, ``m_w L̈ = T − Fw``, its line pull the 10th force,
from its drive or from the law. Checked by the drive's exact tracking (the error equation
``ë + kd ė + kp e = 0`` from zero), the work–energy balance with the winch's work, a
Python law that commands the pull against the built-in drive, and the refusals."""

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.dynamics.cable import hoist_profile
from offshore_crane.errors import DescriptionError, InputError
from offshore_crane.motion.trajectories import table1
from offshore_crane.simulation.control import CT_OMEGA, Controller
from offshore_crane.simulation.elastic import simulate_elastic

EA = 2e4
#: The winch's reflected mass [kg]: a quarter of the payload's.
M_W = 0.5
HOIST = hoist_profile([(0.2, 1.0), (1.6, 0.7)])


def _robot(**more):
    return oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 1.0,
                                    "actuators.winch.reflected_mass": M_W, **more})


@pytest.fixture(scope="module")
def hoisted():
    """Table 1 for 2 s at 1 ms under computed torque, 2 kg on 1 m of EA 2e4 N with axial
    damping, the winch's drive hauling 1.0 → 0.7 m."""
    robot = _robot()
    return robot, simulate_elastic(robot, 2.0, table1, ea=EA, damping=3.0, hoist=HOIST,
                                   step=1e-3)


def test_the_drive_follows_the_profile_and_the_robot_its_reference(hoisted):
    """The drive's pull ``T − m_w (L̈_r + kd ė + kp e)`` from the measured tension makes
    the length's error obey ``ë + kd ė + kp e = 0``; started on the profile, it stays
    there to the integration's round-off: ≤ 1e-9 m (measured 4.5e-12 m) while the winch
    hauls in 0.3 m, the robot on Table 1 to 1e-9 (computed torque with the load cell).
    The pull is recorded apart (X stays the robot's 9 forces) and held the load at the
    start (m g)."""
    robot, res = hoisted
    L, Ld = res.info["length"], res.info["length_rate"]
    assert np.abs(L - HOIST(res.t)[0]).max() <= 1e-9
    assert np.abs(Ld - HOIST(res.t)[1]).max() <= 1e-8
    assert np.ptp(L) > 0.29
    assert np.abs(res.q - res.q_ref).max() <= 1e-9
    assert res.X.shape == (len(res), 9) and res.info["winch_force"].shape == (len(res),)
    assert res.info["winch_force"][0] == pytest.approx(2.0 * 9.81, rel=1e-9)
    assert np.array_equal(res.info["winch_power"], -res.info["winch_force"] * Ld)


def test_the_energy_changes_by_the_actuators_and_the_winchs_work():
    """No damping or drag: the energy the plant records (robot, payload, the cable's
    strain ``½ EA s² / L``, the drum's ``½ m_w L̇²``) changes by the robot's actuators'
    work, the winch's ``−∫ Fw L̇ dt`` and ``−∫ ½ T² / EA · L̇ dt``: the strain energy the
    cable's unstretched length takes along as it grows (the line on the drum holds none
    in this model; it is what the balance misses without it: 3.0e-3 J here, 1.6e-4 of
    the work). Trapezoids of the recorded power at 1 ms: bound 1e-5 of the work (the
    trapezoid's error), the winch's own share well above that bound."""
    res = simulate_elastic(_robot(), 2.0, table1, ea=EA, hoist=HOIST, step=1e-3)
    Ld = res.info["length_rate"]
    power = res.power + res.info["winch_power"] - 0.5 * res.tension ** 2 / EA * Ld
    work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1])
                                            * np.diff(res.t))])
    winch = np.cumsum(res.info["winch_power"]) * 1e-3
    assert (res.tension > 0).all() and np.abs(winch).max() > 1e-3 * np.abs(work).max()
    assert np.abs(res.energy - res.energy[0] - work).max() <= 1e-5 * np.abs(work).max()


@pytest.mark.parametrize("rate", [None, 500.0])
def test_a_python_law_commanding_the_pull_is_the_built_in_drive(rate):
    """A Python law returning 10 forces: computed torque from the load cell and the
    drive's pull from the measured tension, length and rate, gives the built-in law and
    drive's run, continuous and sampled at 500 Hz (bound 1e-12 relative)."""
    from offshore_crane.dynamics.cable.forces import kane_forces
    from offshore_crane.robot.kinematics.workspace import Thresholds

    robot = _robot()
    kp, kd = Controller().gains
    g = np.array(oc.GRAVITY)
    wp, wd = CT_OMEGA ** 2, 2.0 * CT_OMEGA

    def law(t, q, qd, qr, qdr, qddr, *, pull, pull_at, tension, length, length_rate):
        cmd = qddr + kd * (qdr - qd) + kp * (qr - q)
        X = kane_forces(robot, np.zeros(1), q[None], qd[None], cmd[None], np.zeros((1, 6)),
                        g, False, False, Thresholds(), P=pull[None], at=pull_at[None])[0][0]
        Lr, Ldr, Lddr = (float(x[0]) for x in HOIST(np.array([t])))
        pull_w = tension - M_W * (Lddr + wd * (Ldr - length_rate) + wp * (Lr - length))
        return np.append(X, pull_w)

    kw = dict(ea=EA, damping=3.0, hoist=HOIST, step=1e-3)
    a = simulate_elastic(robot, 0.4, table1, controller=Controller(rate=rate), **kw)
    b = simulate_elastic(robot, 0.4, table1, controller=Controller(function=law, rate=rate),
                         **kw)
    for x, y in ((a.q, b.q), (a.X, b.X), (a.tension, b.tension),
                 (a.info["length"], b.info["length"]),
                 (a.info["winch_force"], b.info["winch_force"])):
        assert np.abs(x - y).max() <= 1e-12 * np.abs(x).max()


def test_a_law_that_lets_the_winch_go_drops_the_load():
    """A Python law that leaves the robot to computed torque's 9 forces and commands no
    pull (0 N): the drum runs free, ``m_w L̈ = T`` (the recorded rate against the
    trapezoids of the recorded tension: ≤ 1e-2 of the peak rate, the trapezoids' error
    on the drum's fast axial swing of ~200 rad/s; measured 1.1e-3), the line pays out
    0.37 m in 0.3 s and the payload falls with it, the tension settling about
    ``g / (1/m + 1/m_w)``, where drum and payload accelerate alike (3.9 N for the 19.6
    N held; the last 0.1 s's mean within 20 %: the axial swing has not died out)."""
    from offshore_crane.dynamics.cable.forces import kane_forces
    from offshore_crane.robot.kinematics.workspace import Thresholds

    robot = _robot()
    kp, kd = Controller().gains

    def law(t, q, qd, qr, qdr, qddr, *, pull, pull_at):
        cmd = qddr + kd * (qdr - qd) + kp * (qr - q)
        X = kane_forces(robot, np.zeros(1), q[None], qd[None], cmd[None], np.zeros((1, 6)),
                        np.array(oc.GRAVITY), False, False, Thresholds(), P=pull[None],
                        at=pull_at[None])[0][0]
        return np.append(X, 0.0)

    res = simulate_elastic(robot, 0.3, table1, controller=law, ea=EA, damping=3.0,
                           step=1e-3)
    Ld, T = res.info["length_rate"], res.tension
    assert (res.info["winch_force"] == 0.0).all()
    pushed = np.concatenate([[0.0], np.cumsum(0.5 * (T[1:] + T[:-1]) * 1e-3)]) / M_W
    assert np.abs(Ld - Ld[0] - pushed).max() <= 1e-2 * np.abs(Ld).max()
    assert res.info["length"][-1] > 1.3
    g_share = 9.81 / (1 / 2.0 + 1 / M_W)
    assert abs(T[-100:].mean() - g_share) <= 0.2 * g_share


def test_refusals():
    robot = _robot()
    with pytest.raises(InputError, match=r"reflected_mass = 0\.5 kg makes the winch a "
                                         r"commanded actuator, which runs on an elastic "
                                         r"cable only"):
        oc.simulate(robot, 0.01, table1, hoist=HOIST)
    plain = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 1.0})
    with pytest.raises(InputError, match=r"X returned by the controller has shape \(10,\); "
                                         r"expected \(9,\)"):
        simulate_elastic(plain, 0.01, table1, ea=EA, controller=lambda *a: np.zeros(10))
    with pytest.raises(InputError, match=r"must be 9 numbers \(10 with the commanded "
                                         r"winch's line pull last\), got \(11,\)"):
        simulate_elastic(robot, 0.01, table1, ea=EA, controller=lambda *a: np.zeros(11))
    with pytest.raises(InputError, match=r"X returned by the controller at t = 0 s is not "
                                         r"finite"):
        simulate_elastic(robot, 0.01, table1, ea=EA,
                         controller=lambda *a: np.append(np.zeros(9), np.nan))
    with pytest.raises(DescriptionError, match=r"actuators\.winch\.reflected_mass: -1 kg must be "
                                         r"finite and >= 0"):
        _robot(**{"actuators.winch.reflected_mass": -1.0})


def test_the_compiled_right_hand_side_is_the_python_plants():
    """The compiled ``rhs`` with a commanded winch (26 states, 10 forces) against the
    plant's NumPy ``derivative`` (the vectorised public pieces) at 20 seeded random
    states: ≤ 1e-10 relative to each rate's scale (the two sum the Kane pass in other
    orders), the drum's ``L̈ = (T − Fw) / m_w`` included; and the drive's pull from the
    measured tension."""
    from offshore_crane.dynamics.cable.tip import tip_positions
    from offshore_crane.simulation.plants import ElasticPlant

    robot = _robot()
    lengths = np.tile([1.0, 0.05, 0.3], (3, 1))
    plant = ElasticPlant(robot, robot, np.array(oc.GRAVITY), ea=EA, damping=3.0,
                         lengths=lengths, winch_mass=M_W, winch_gains=(400.0, 40.0))
    k, P = plant.kernels(), plant.params()
    rng = np.random.default_rng(11)
    for t in rng.uniform(0.0, 20.0, 20):
        q, qd, _ = table1(np.array([t]))
        p_tip, v_tip = (x[0] for x in tip_positions(plant.robot, q, qd))
        L = 1.0 + rng.uniform(-0.1, 0.1)
        y = np.concatenate([q[0], p_tip + [0.0, 0.0, -L] + rng.normal(0, 0.01, 3), qd[0],
                            v_tip + rng.normal(0, 0.1, 3), [L, rng.normal(0, 0.2)]])
        X = np.append(rng.normal(0, 20.0, 9), rng.uniform(10.0, 30.0))
        dy, aux = np.zeros(26), np.zeros(4)
        assert k.rhs(P, 1, y, X, dy, aux)
        ref, info = plant.derivative(1, y, X)
        scale = np.maximum(np.abs(ref), 1.0)
        assert np.abs(dy - ref).max() <= 1e-10 * scale.max()
        assert dy[24] == y[25] and dy[25] == (aux[1] - X[9]) / M_W
        assert abs(aux[1] - info["tension"]) <= 1e-10 * max(abs(info["tension"]), 1.0)
        Xd = np.zeros(10)
        k.winch(P, 1, y, Xd)
        want = aux[1] - M_W * (0.3 + 40.0 * (0.05 - y[25]) + 400.0 * (1.0 - y[24]))
        assert Xd[9] == pytest.approx(want, rel=1e-12, abs=1e-12)


def test_the_actuator_models_take_the_winchs_pull():
    """One lag for all: the winch's applied pull lags its command, ``τ Ẋ_a = X_cmd −
    X_a`` (the recorded applied pull against the trapezoids of that equation on the
    recorded command: ≤ 1e-3 of the pull's range, the trapezoids' error at 1 ms with τ =
    10 ms; measured 3.5e-5); 9 lags leave the pull unlagged (applied = commanded); 10
    without a commanded winch are refused."""
    from offshore_crane.simulation.instruments import Actuators

    robot = _robot()
    kw = dict(ea=EA, damping=3.0, hoist=HOIST, step=1e-3)
    tau = 0.01
    res = simulate_elastic(robot, 1.0, table1, actuators=Actuators(lag=tau), **kw)
    F, Fc = res.info["winch_force"], res.info["winch_force_cmd"]
    pred = np.empty_like(F)
    pred[0] = F[0]
    a = 1e-3 / (2 * tau)
    for k in range(1, len(F)):           # trapezoids of τ Ẋ_a = X_cmd − X_a
        pred[k] = ((1 - a) * pred[k - 1] + a * (Fc[k] + Fc[k - 1])) / (1 + a)
    assert np.ptp(F) > 1.0 and np.abs(F - Fc).max() > 1e-3
    assert np.abs(F - pred).max() <= 1e-3 * np.ptp(F)
    nine = simulate_elastic(robot, 0.2, table1, actuators=Actuators(lag=[tau] * 9), **kw)
    assert np.array_equal(nine.info["winch_force"], nine.info["winch_force_cmd"])
    plain = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 1.0})
    with pytest.raises(InputError, match=r"actuators lag: 10 numbers given, but the plant "
                                         r"has no commanded winch"):
        simulate_elastic(plain, 0.01, table1, ea=EA, actuators=Actuators(lag=[tau] * 10))

