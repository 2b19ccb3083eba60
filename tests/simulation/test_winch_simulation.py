"""The rigid cable on a winch in the forward simulation (the hanging plant with the
cable's length ``L(t)``, offshore_crane.simulation.plants.HangingPlant): against the
hoisted pendulum's inverse dynamics of the simulated motion (another formulation: the
pendulum's own equations on the tip's motion with L, L̇, L̈ given), against its own
fixed-length run, by the work the actuators and the winch do, a Python law reading the
winch, and ``simulate`` of a scene with a winch or a compensation on a rigid cable."""

from pathlib import Path

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.dynamics import cable
from offshore_crane.dynamics.cable import hoist_profile
from offshore_crane.motion.trajectories import table1, time_grid
from offshore_crane.simulation.control import Controller
from offshore_crane.simulation.swing import simulate_swing

ROOT = Path(__file__).resolve().parents[2]

MASS, LENGTH = 2.0, 0.5
#: Pay out from 0.5 m to 0.9 m in 1 s, haul in to 0.35 m in the next (quintic moves).
HOIST = hoist_profile([(0.0, 0.5), (1.0, 0.9), (2.0, 0.35)])


def crane(**over):
    return oc.load_robot(overrides={"payload.mass": MASS, "payload.cable_length": LENGTH,
                                    **over})


@pytest.mark.parametrize("over", [{}, {"payload.drag_area": 0.5,
                                       "payload.sway_damping": 0.05}],
                         ids=["plain", "drag+damping"])
def test_the_hoisted_swing_is_the_hoisted_pendulums_inverse_dynamics(over):
    """Computed torque on Table 1 for 2 s at 1 ms while the winch pays out and hauls in,
    from a sway of (0.1, 0.05) rad: the robot tracks to RK4's accuracy (≤ 1e-6; measured
    3.8e-12) and the swing of the 11 coordinates (the winch's ``−m Jᵀ (L̈ e + 2 L̇ ė)`` on
    the explicit Kane pass) is the inverse dynamics' with the same winch (the hoisted
    pendulum's equations on the tip's motion, X from the pull at the payload) to 1e-9 rad
    (measured 7.6e-12), X to 1e-9 relative (7.1e-11) and the tension to 1e-7 N (5.3e-9 N
    of 28 N); the bounds are the ones the fixed cable meets (test_cable_simulation.py)."""
    robot = crane(**over)
    res = simulate_swing(robot, 2.0, table1, step=1e-3, initial=(0.1, 0.05), hoist=HOIST)
    t = time_grid(2.0, 1000.0)
    ref = cable.inverse_dynamics(robot, *table1(t), reference=table1, initial=(0.1, 0.05),
                                 t=t, hoist=HOIST)
    assert np.abs(res.error).max() <= 1e-6
    assert np.abs(res.sway - ref.sway).max() <= 1e-9
    assert np.abs(res.X - ref.X).max() <= 1e-9 * np.abs(ref.X).max()
    assert np.abs(res.tension - ref.tension).max() <= 1e-7
    assert np.array_equal(res.info["length"], HOIST(res.t)[0])
    still = oc.simulate(robot, 2.0, table1, step=1e-3, initial=(0.1, 0.05))
    assert np.abs(still.sway - res.sway).max() > 0.01          # the winch does matter


def test_a_winch_holding_the_length_is_the_fixed_cable():
    """A winch that holds the description's length (L̇ = L̈ = 0 at every stage) gives the
    fixed cable's run: q, the sway and X bit for bit (the same arithmetic), the tension
    (there from the hoisted pendulum on NumPy arrays, here from the Kane pass) to 1e-12
    relative."""
    robot = crane()
    held = lambda t: (np.full(len(t), LENGTH), 0.0 * t, 0.0 * t)   # noqa: E731
    a = oc.simulate(robot, 0.5, table1, initial=(0.1, 0.0))
    b = oc.simulate(robot, 0.5, table1, initial=(0.1, 0.0), hoist=held)
    for x, y in ((a.q, b.q), (a.sway, b.sway), (a.X, b.X)):
        assert np.array_equal(x, y)
    assert np.abs(a.tension - b.tension).max() <= 1e-12 * np.abs(a.tension).max()


def test_the_energy_changes_by_the_actuators_and_the_winchs_work():
    """No damping, no drag: the energy the plant records (with the winch's share of the
    payload's kinetic energy, ``m L̇ e·v + ½ m L̇²``) changes by the actuators' work and
    the winch's, ``−∫ T L̇ dt`` (Simpson's rule on the 1 ms record), Table 1 for 2 s while
    hoisting: bound 1e-8 of the work done through the run, ``∫ |P| dt`` = 23 J (Simpson's
    error at 1 ms; measured 4e-10 of it: 1.0e-8 J on a 16.5 J change)."""
    from scipy.integrate import cumulative_simpson

    res = simulate_swing(crane(), 2.0, table1, step=1e-3, initial=(0.1, 0.05), hoist=HOIST)
    power = res.power - res.tension * HOIST(res.t)[1]
    work = cumulative_simpson(power, x=res.t, initial=0.0)
    total = np.sum(np.abs(power[1:]) * np.diff(res.t))
    assert total > 10.0 and (res.tension > 0).all()
    assert np.abs(res.energy - res.energy[0] - work).max() <= 1e-8 * total


def test_a_python_law_reading_the_winch_is_the_built_in_one():
    """A Python computed torque that reads the sway and the winch (``length``,
    ``length_rate``; L̈ from the profile) and calls the cable's kernel on arrays set to
    that length gives the built-in law's run to 1e-12 relative."""
    from offshore_crane.dynamics.cable import kernels as ck
    from offshore_crane.dynamics.constants import cable_arrays

    robot = crane()
    a_ = cable_arrays(robot)
    flat = a_.flat.copy()
    kp, kd = Controller().gains
    g = np.array(oc.GRAVITY)

    def law(t, q, qd, qr, qdr, qddr, sway, sway_rate, length, length_rate):
        cmd = qddr + kd * (qdr - qd) + kp * (qr - q)
        ck.set_length(flat, a_.layout, a_.prismatic, length)
        X = np.empty(9)
        ck.computed_torque(flat, a_.layout, a_.prismatic, robot.hybrid.sway_damping, 0.0,
                           np.concatenate([q, sway]), np.concatenate([qd, sway_rate]), cmd,
                           g, length_rate, float(HOIST(np.array([t]))[2][0]), X,
                           np.zeros(ck.WORK))
        return X

    a = simulate_swing(robot, 0.5, table1, initial=(0.1, -0.05), hoist=HOIST)
    b = simulate_swing(robot, 0.5, table1, initial=(0.1, -0.05), hoist=HOIST, controller=law)
    for x, y in ((a.q, b.q), (a.sway, b.sway), (a.X, b.X), (a.tension, b.tension)):
        assert np.abs(x - y).max() <= 1e-12 * np.abs(x).max()


def _rigid(tmp_path, name):
    """The shipped scene ``name`` with its elastic cable made rigid (no ``ea``)."""
    text = (ROOT / "scenes" / name).read_text()
    path = tmp_path / f"rigid_{name}"
    path.write_text("\n".join(line for line in text.splitlines()
                              if not line.startswith(("ea ", "damping "))))
    return path


@pytest.mark.parametrize("name", ["winch_lift.toml", "compensated_lift.toml"])
def test_simulate_runs_a_winch_and_a_compensation_on_a_rigid_cable(tmp_path, capsys, name):
    """``simulate`` of a rigid cable with a winch (the hoist column) or an arm + winch
    compensation: no longer refused; its CSV carries the sway, the tension and the
    cable's length; the load hangs near its weight (tension within 30 % of m g over the
    first 2 s of the lift, which slews the arm)."""
    from offshore_crane.cli import main

    out = tmp_path / "sim.csv"
    assert main(["simulate", "--scene", str(_rigid(tmp_path, name)), "--duration", "2",
                 "--out", str(out)]) == 0
    assert "hanging load: max sway" in capsys.readouterr().out
    head = out.read_text().splitlines()[0].split(",")
    assert head[-4:] == ["phi1_rad", "phi2_rad", "tension_N", "L_m"]
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    assert np.abs(data[:, -2] / (2.5 * 9.81) - 1.0).max() <= 0.3
    assert data[:, -1].min() > 0.0


def test_the_compensated_rigid_lift_swings_as_the_inverse_dynamics_says(tmp_path):
    """The rigid cable under arm + winch compensation in a beam sea, 5 s: the simulated
    swing (the robot tracking the compensated commands to 1e-9) is the one ``id``
    integrates on the commanded motion (the scene's inverse dynamics) to 1e-8 rad
    (measured 1.1e-9: the two integrate on different grids, 1 ms against the record's
    10 ms with substeps)."""
    from offshore_crane import scenes

    scene = scenes.load_scene(_rigid(tmp_path, "compensated_lift.toml"))
    robot = scenes.load_robot(scene)
    traj = scenes.load_trajectory(scene, robot)
    reference, options = scenes.cable_simulation(scene, robot, traj)
    res = simulate_swing(robot, 5.0, reference.reference, gravity=scene.gravity, step=1e-3,
                         t0=float(reference.t[0]), **options)
    swing = scenes.run(scene, robot, traj).results["kane"].cable
    n = len(res.t[::10])
    assert np.abs(swing.t[:n] - res.t[::10]).max() <= 1e-12
    assert np.abs(res.error).max() <= 1e-9
    assert np.abs(swing.sway[:n] - res.sway[::10]).max() <= 1e-8
