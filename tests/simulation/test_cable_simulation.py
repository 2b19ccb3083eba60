"""The forward simulation with the hanging load (offshore_crane.simulation.swing): the
11 coordinates' equations of motion against the swing of the inverse dynamics (another
formulation: the pendulum's own equations on the tip's motion), energy, the anti-sway law
against the damping ratio it promises, stops and bad input."""

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.dynamics import cable
from offshore_crane.simulation.control import Controller
from offshore_crane.errors import InputError, SimulationError
from offshore_crane.motion.trajectories import table1, time_grid

MASS, LENGTH, G = 2.0, 0.5, 9.81


@pytest.fixture(scope="module")
def crane():
    return oc.load_robot(overrides={"payload.mass": MASS, "payload.cable_length": LENGTH})


def hold_home(robot):
    """A reference that holds the home pose."""
    home = np.zeros(9)
    home[2] = robot.home_height

    def reference(t):
        n = len(np.atleast_1d(t))
        return np.tile(home, (n, 1)), np.zeros((n, 9)), np.zeros((n, 9))

    return reference


def test_computed_torque_tracks_and_swings_as_the_inverse_dynamics(crane):
    """Computed torque that reads the sway, exact model, Table 1 for 10 s at 1 ms from a
    sway of 0.1 rad: the robot tracks to RK4's accuracy (≤ 1e-6; measured 3.8e-12) and the
    simulated swing (11-coordinate M from the explicit Kane pass) equals the inverse
    dynamics' swing (the pendulum's equations on the tip's motion) to 1e-9 rad (measured
    8.7e-12), its X to 1e-9 relative (7.6e-11) and its tension to 1e-7 N (6e-9)."""
    res = oc.simulate(crane, 10.0, table1, step=1e-3, initial=(0.1, 0.0))
    assert np.abs(res.error).max() <= 1e-6
    t = time_grid(10.0, 1000.0)
    ref = cable.inverse_dynamics(crane, *table1(t), reference=table1, initial=(0.1, 0.0), t=t)
    assert np.abs(res.sway - ref.sway).max() <= 1e-9
    assert np.abs(res.X - ref.X).max() <= 1e-9 * np.abs(ref.X).max()
    assert np.abs(res.tension - ref.tension).max() <= 1e-7
    assert np.abs(res.sway).max() > 0.1                  # Table 1 does shake the load


def test_the_simulated_swing_with_drag_is_the_inverse_dynamics(crane):
    """With the sway damping (5 % of critical) and 0.5 m² of drag area, Table 1 for 2 s at
    1 ms from a sway of (0.3, 0.2) rad: the simulated swing (the drag's ``Jᵀ f`` on the
    11 coordinates) equals the inverse dynamics' (the pendulum with the drag, X with the
    pull at the payload) to 1e-9 rad (measured 6.6e-12), X to 1e-9 relative (7.0e-11) and
    the tension to 1e-7 N (5.7e-9 N); the drag moves the swing by 0.06 rad."""
    c = 2 * 0.05 * MASS * LENGTH ** 2 * np.sqrt(G / LENGTH)
    over = {"payload.mass": MASS, "payload.cable_length": LENGTH, "payload.sway_damping": c}
    robot = oc.load_robot(overrides={**over, "payload.drag_area": 0.5})
    res = oc.simulate(robot, 2.0, table1, step=1e-3, initial=(0.3, 0.2))
    t = time_grid(2.0, 1000.0)
    ref = cable.inverse_dynamics(robot, *table1(t), reference=table1, initial=(0.3, 0.2),
                                 t=t)
    assert np.abs(res.error).max() <= 1e-6
    assert np.abs(res.sway - ref.sway).max() <= 1e-9
    assert np.abs(res.X - ref.X).max() <= 1e-9 * np.abs(ref.X).max()
    assert np.abs(res.tension - ref.tension).max() <= 1e-7
    still = cable.inverse_dynamics(oc.load_robot(overrides=over), *table1(t),
                                   reference=table1, initial=(0.3, 0.2), t=t)
    assert np.abs(still.sway - ref.sway).max() > 0.01


def test_free_motion_conserves_energy(crane):
    """No gravity, no actuator force (law 'none'): robot and load move freely from Table 1's
    initial speeds and a swinging start; T is conserved to RK4's error over 1 s at 1 ms
    (bound 1e-9 relative; the motion stays in the workspace)."""
    res = oc.simulate(crane, 1.0, table1, step=1e-3, gravity=(0, 0, 0),
                      controller=Controller("none"), initial=(0.3, 0.1),
                      initial_rate=(1.0, -0.5))
    assert np.abs(res.energy - res.energy[0]).max() <= 1e-9 * res.energy[0]


def test_energy_change_equals_the_actuators_work(crane):
    """Under gravity and computed torque, the energy change equals the actuators' work
    (trapezoidal rule at 1 ms, O(h²): 1e-5 of the work done)."""
    res = oc.simulate(crane, 3.0, table1, step=1e-3, initial=(0.2, 0.0))
    work = np.concatenate([[0.0], np.cumsum(0.5 * (res.power[1:] + res.power[:-1])
                                            * np.diff(res.t))])
    assert np.abs(res.energy - res.energy[0] - work).max() <= 1e-5 * np.abs(work).max()


def test_anti_sway_damps_the_swing_at_its_ratio(crane):
    """The robot holds home, the load starts 0.1 rad off. Without the law the swing keeps
    its amplitude; with anti_sway = ζ = 0.3 it decays like e^{−ζ ω0 t} (ω0 = √(g/L)):
    the log of the swing's peaks (while above 2e-3 rad) falls at ζ ω0 to within 25 %
    (the centring of the platform's reference shift and the nonlinear swing perturb the
    ideal oscillator), over the last two of 8 s the sway is below 1 % of the free
    swing's, and the platform, which gave way, comes back."""
    ref = hold_home(crane)
    free = oc.simulate(crane, 8.0, ref, step=2e-3, initial=(0.1, 0.0))
    damped = oc.simulate(crane, 8.0, ref, step=2e-3, initial=(0.1, 0.0),
                         controller=Controller(anti_sway=0.3))
    late = free.t >= 6.0
    assert np.abs(free.sway[late, 0]).max() > 0.09
    assert np.abs(damped.sway[late, 0]).max() < 0.01 * np.abs(free.sway[late, 0]).max()
    phi, rate_, t = damped.sway[:, 0], damped.sway_rate[:, 0], damped.t
    turns = np.flatnonzero(np.sign(rate_[1:]) != np.sign(rate_[:-1]))   # |φ| peaks
    turns = turns[np.abs(phi[turns]) > 2e-3]          # above the centring's own motion
    decay = -np.polyfit(t[turns], np.log(np.abs(phi[turns])), 1)[0]
    assert len(turns) >= 3
    assert decay == pytest.approx(0.3 * np.sqrt(G / LENGTH), rel=0.25)
    # the platform gives way (0.11 m here) and the centring (ω_c = ω0/10, critically
    # damped: (1 + ω_c t) e^{−ω_c t} = 0.27 at 6 s after the swing) brings it back
    shift = np.abs(damped.q[:, 1] - free.q[:, 1])
    assert 0.05 < shift.max() < 0.15 and shift[-1] < 0.3 * shift.max()


def test_a_slack_cable_stops_the_run_and_keeps_the_samples(crane):
    """Gravity upwards: the load would have to be pushed, so the run stops at once with
    the cause named; the samples before are kept (none here)."""
    with pytest.raises(SimulationError, match="the cable went slack") as info:
        oc.simulate(crane, 0.1, hold_home(crane), step=1e-3, gravity=(0, 0, 9.81))
    assert info.value.result is not None and info.value.time == pytest.approx(0.0)
    assert len(info.value.result) == 0
    assert "no sample was computed before it" in str(info.value)


def test_the_first_cause_wins(crane):
    """An initial sway next to cos φ2 = 0 (1/cos φ2 = 3.8e6): the cable is already slack at
    t = 0 (the load falls along the cable), which is named, not the divergence the next
    step meets (once an unpacking ValueError)."""
    with pytest.raises(SimulationError, match=r"at t = 0 s: the cable went slack") as info:
        oc.simulate(crane, 0.1, table1, step=1e-3, initial=(0.0, 1.570796))
    assert len(info.value.result) == 0


@pytest.mark.parametrize("kwargs, match", [
    (dict(controller=Controller(noise_q=0.001)), "control instants of a sampled law"),
    (dict(controller=Controller(noise_q=0.001, rate=500.0),
          sensors=oc.simulation.instruments.Sensors(noise_q=1e-4)), "noise given twice"),
    (dict(integrator="dop853"), "runs RK4"),
    (dict(initial=(0.0, np.nan)), "initial must be two finite numbers"),
])
def test_bad_arguments(crane, kwargs, match):
    with pytest.raises(InputError, match=match):
        oc.simulate(crane, 0.01, table1, step=1e-3, **kwargs)


def test_anti_sway_needs_a_cable_and_computed_torque():
    with pytest.raises(InputError, match="works through the computed-torque law"):
        Controller("pd", anti_sway=0.3)
    with pytest.raises(InputError, match=r"anti_sway = -0.1"):
        Controller(anti_sway=-0.1)
    with pytest.raises(InputError, match="payload is welded"):
        oc.simulate(oc.load_robot(), 0.01, table1, controller=Controller(anti_sway=0.3))


def test_cli_simulate_with_a_cable(tmp_path, capsys):
    from offshore_crane.cli import main

    out = tmp_path / "sim.csv"
    assert main(["simulate", "--set", "payload.mass=2", "--set", "payload.cable_length=0.5",
                 "--duration", "2", "--initial-sway", "0.1", "0", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "hanging load: max sway" in text and "cable tension" in text
    header = out.read_text().splitlines()[0]
    assert header.endswith(",phi1_rad,phi2_rad,tension_N")
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    assert data[0, -3] == 0.1 and (data[:, -1] > 0).all()
    assert main(["simulate", "--duration", "1", "--initial-sway", "0.1", "0"]) == 2
    assert "--initial-sway: applies to a payload on a cable" in capsys.readouterr().err
    assert main(["simulate", "--set", "payload.mass=2", "--set", "payload.cable_length=0.5",
                 "--duration", "1", "--anti-sway", "0.3", "--controller", "pd"]) == 2
    assert "works through the computed-torque law" in capsys.readouterr().err


def test_cli_angles_in_degrees_and_the_anti_sway_departure_labelled(tmp_path, capsys):
    """Human-facing sway angles are in degrees (the CSV keeps radians, named in its
    header); with --anti-sway the platform's departure from its reference is labelled as
    the law's command, not as a tracking error."""
    from offshore_crane.cli import main

    from pathlib import Path

    scene = Path(__file__).resolve().parents[2] / "scenes" / "hanging_load.toml"
    out = tmp_path / "sim.csv"
    assert main(["simulate", "--scene", str(scene), "--duration", "2", "--anti-sway", "0.3",
                 "--out", str(out)]) == 0
    text = capsys.readouterr().out
    line = next(ln for ln in text.splitlines() if ln.startswith("hanging load: max sway"))
    assert "°" in line and " rad" not in line
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    phi1, phi2 = data[:, -3], data[:, -2]                  # [rad] in the CSV
    worst = np.degrees(np.arccos(np.cos(phi1) * np.cos(phi2)).max())
    assert float(line.split("max sway ")[1].split("°")[0]) == pytest.approx(worst, rel=1e-3)
    assert "anti-sway (zeta = 0.3): the law moves the platform on purpose" in text
    assert "RMS departure" in text and "RMS error" not in text
    assert out.read_text().splitlines()[0].endswith(",phi1_rad,phi2_rad,tension_N")
    assert main(["id", "--set", "payload.mass=2", "--set", "payload.cable_length=0.5",
                 "--duration", "1"]) == 0
    text = capsys.readouterr().out
    assert "max sway" in text and "° from the tip's vertical" in text
