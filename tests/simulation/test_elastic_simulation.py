"""The forward simulation with the payload on an elastic cable (offshore_crane.simulation.
elastic, ``simulate --scene`` of a winch, an elastic cable or a compensation): checked
against the elastic cable's inverse dynamics integrating the same motion independently
(another integrator: the payload alone, 50 RK4 steps a period on the motion's samples),
the computed torque's exact tracking, and its refusals."""

from pathlib import Path

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.__main__ import main
from offshore_crane.dynamics import cable
from offshore_crane.dynamics.cable.tip import tip_positions
from offshore_crane.errors import InputError
from offshore_crane.motion.trajectories import table1
from offshore_crane.simulation.control import Controller
from offshore_crane.simulation.elastic import simulate_elastic

SCENES = Path(__file__).resolve().parents[2] / "scenes"
EA = 2e4


@pytest.fixture(scope="module")
def flown():
    """Table 1 for 2 s at 1 ms under computed torque, 2 kg on 1 m of EA 2e4 N, with a
    sway damping of 5 % of critical and 0.5 m² of drag area."""
    robot = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 1.0,
                                     "payload.sway_damping": 0.2 * 2.0 * np.sqrt(9.81),
                                     "payload.drag_area": 0.5})
    hoist = cable.hoist_profile([(0.2, 1.0), (1.6, 0.7)])
    res = simulate_elastic(robot, 2.0, table1, controller=Controller(law="computed-torque"),
                           ea=EA, damping=3.0, hoist=hoist, step=1e-3)
    return robot, hoist, res


def test_the_simulated_lift_is_the_elastic_inverse_dynamics_of_its_motion(flown):
    """The payload's path and X of the simulation equal the elastic cable's inverse
    dynamics of the simulated motion started from the same payload state (an independent
    integration of the payload on the prescribed motion): ≤ 1e-8 m and ≤ 1e-7 of the
    peak force (measured 1.3e-10 m and 6.9e-9 with the winch, the sway damping, up to
    0.54 N, and the drag, up to 0.77 N; 1.5e-10 m and 6.3e-9 without them); the computed
    torque with the measured pull tracks Table 1 to 1e-9 (round-off of the exact
    model)."""
    robot, hoist, res = flown
    assert np.abs(res.q - res.q_ref).max() <= 1e-9
    p, v = tip_positions(robot, res.q[:1], res.qd[:1])
    ref = cable.elastic_inverse_dynamics(
        robot, res.q, res.qd, res.qdd, t=res.t, ea=EA, damping=3.0, hoist=hoist,
        reference=table1, initial=res.info["payload"][0] - p[0],
        initial_velocity=res.info["payload_velocity"][0] - v[0])
    assert np.abs(ref.payload - res.info["payload"]).max() <= 1e-8
    assert np.abs(ref.X - res.X).max() <= 1e-7 * np.abs(res.X).max()
    assert np.abs(ref.sway_force).max() > 0.1 and np.abs(ref.drag).max() > 0.1
    assert np.array_equal(res.info["length"], hoist(res.t)[0])


def test_a_step_too_long_for_the_cable_and_other_refusals():
    robot = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 1.0})
    with pytest.raises(InputError, match=r"step = 0\.01 s is too long for the cable's "
                                         r"axial period 62\.8 ms"):
        simulate_elastic(robot, 1.0, table1, ea=EA, step=0.01)
    with pytest.raises(InputError, match="'anti-sway' does not run on the elastic plant"):
        simulate_elastic(robot, 1.0, table1, ea=EA,
                         controller=Controller(law="computed-torque", anti_sway=0.1))
    with pytest.raises(InputError, match=r"cable ea = -1\.0 N: give a finite number > 0"):
        simulate_elastic(robot, 1.0, table1, ea=-1.0)


def test_simulate_runs_the_compensated_lift(tmp_path, capsys):
    """simulate --scene scenes/compensated_lift.toml: the compensated arm's commands and
    the winch's length as the reference and profile, the load flying on its elastic
    cable (tension within 3 % of m g: the compensation holds it), a CSV with the
    payload, the tension and the length."""
    out = tmp_path / "sim.csv"
    assert main(["simulate", "--scene", str(SCENES / "compensated_lift.toml"), "--duration",
                 "1", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "payload on an elastic cable: tension" in text
    head = out.read_text().splitlines()[0].split(",")
    assert head[-5:] == ["payload_x_m", "payload_y_m", "payload_z_m", "tension_N", "L_m"]
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    assert np.abs(data[:, -2] / (2.5 * 9.81) - 1.0).max() <= 0.03


@pytest.mark.parametrize("scene, match", [
    ("deck_lift.toml", r"\[lift\]: simulate does not model the deck's contact"),
])
def test_simulate_refuses_what_it_does_not_run(tmp_path, capsys, scene, match):
    path = SCENES / scene
    assert main(["simulate", "--scene", str(path), "--duration", "1"]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1
    import re
    assert re.search(match, err)


def test_the_elastic_plants_energy_changes_by_the_actuators_work():
    """No axial or sway damping, no drag, no winch: the mechanical energy the plant records
    (the robot's, the payload's and the cable's strain energy) changes by the actuators'
    work (trapezoidal integral of the recorded power) under computed torque on Table 1
    for 2 s at 1 ms; bound 1e-5 of the work, 13.3 J (the trapezoid's error at 1 ms;
    measured 4.5e-7; RK4's own error is far smaller), the cable stretched throughout."""
    robot = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 1.0})
    res = simulate_elastic(robot, 2.0, table1, ea=EA, step=1e-3)
    work = np.concatenate([[0.0], np.cumsum(0.5 * (res.power[1:] + res.power[:-1])
                                            * np.diff(res.t))])
    assert (res.tension > 0).all() and np.abs(work).max() > 1.0
    assert np.abs(res.energy - res.energy[0] - work).max() <= 1e-5 * np.abs(work).max()


def test_the_law_and_the_plant_read_one_load_cell_a_stage_with_the_same_numbers():
    """The elastic plant measures the load cell once a stage (``prepare``); the built-in
    law's ``inverse`` and the plant's ``rhs`` read it there at that state, and give what
    each gives measuring its own, bit for bit (the same kernel on the same arrays). A
    cell changed after ``prepare`` changes the law's X: the shared cell is what it
    read; at another state (one ulp away) it measures its own."""
    from offshore_crane.simulation.plants import ElasticPlant

    robot = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 1.0})
    lengths = np.tile([1.0, 0.05, 0.0], (3, 1))
    plant = ElasticPlant(robot, robot, np.array(oc.GRAVITY), ea=EA, damping=3.0,
                         lengths=lengths)
    k = plant.kernels()
    q, qd, _ = table1(np.array([2.0]))
    p_tip, v_tip = (x[0] for x in tip_positions(plant.robot, q, qd))
    y = np.concatenate([q[0], p_tip + [0.01, -0.02, -1.0005], qd[0], v_tip])
    cmd, X = np.random.default_rng(3).normal(size=9), np.linspace(-20.0, 20.0, 9)
    aux = np.zeros(4)

    def run(share, cell_shift=0.0, at=y):
        P = plant.params()
        if share:
            k.prepare(P, 1, y, aux)
            P[8][0] += cell_shift
        Xc, dy = np.zeros(9), np.zeros(24)
        k.inverse(P, 1, at, cmd, Xc)
        k.rhs(P, 1, y, X, dy, aux)
        return Xc, dy

    shared, own = run(True), run(False)
    np.testing.assert_array_equal(shared[0], own[0])
    np.testing.assert_array_equal(shared[1], own[1])
    assert not np.array_equal(run(True, cell_shift=1.0)[0], own[0])
    y2 = y.copy()
    y2[3] = np.nextafter(y2[3], np.inf)
    np.testing.assert_array_equal(run(True, 1.0, at=y2)[0], run(False, at=y2)[0])


def test_a_stopped_run_keeps_its_per_sample_info_as_long_as_its_samples():
    """A lift that leaves the workspace (no law: the robot falls): the error's result
    holds the samples before the stop, and the payload's, the length's and the
    commanded winch's arrays in ``info`` are cut with them."""
    from offshore_crane.errors import SimulationError
    from offshore_crane.stops import StopCause

    robot = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 1.0,
                                     "actuators.winch.reflected_mass": 0.5})
    with pytest.raises(SimulationError, match="outside its limits") as info:
        simulate_elastic(robot, 2.0, table1, controller=Controller(law="none"), ea=EA,
                         step=1e-3)
    res = info.value.result
    assert info.value.stop_cause is StopCause.WORKSPACE and 0 < len(res) < 2000
    for key in ("payload", "payload_velocity", "length", "length_rate", "winch_force",
                "winch_power"):
        assert len(res.info[key]) == len(res), key
