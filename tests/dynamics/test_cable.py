"""The hanging load (offshore_crane.dynamics.cable): physics checks, Kane against Pinocchio, errors.

References that share nothing with the code under test: the small-oscillation solution of
a pendulum, its energy, the equilibrium of a pendulum in a uniformly accelerated frame,
the rigid robot with the payload welded at the cable's end, and Pinocchio's model of the
URDF's sway joints (offshore_crane.reference.cable).
"""

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.dynamics import cable
from offshore_crane.errors import (InputError, ModelError, SingularConfigurationError,
                                   SlackCableError)
from offshore_crane.robot.kinematics.workspace import OffshoreCraneWarning, Thresholds
from offshore_crane.motion.trajectories import table1, time_grid

G = 9.81
MASS, LENGTH = 2.0, 0.5


@pytest.fixture(scope="module")
def crane():
    return oc.load_robot(overrides={"payload.mass": MASS, "payload.cable_length": LENGTH})


def at_rest(robot, duration, rate):
    """The robot held at home: ``t, q, qd, qdd``."""
    t = time_grid(duration, rate)
    q = np.zeros((len(t), 9))
    q[:, 2] = robot.home_height
    return t, q, np.zeros_like(q), np.zeros_like(q)


def test_small_oscillation_has_the_pendulum_period(crane):
    """Robot at rest, φ1(0) = φ0 = 1e-3 rad: φ1 = φ0 cos(ω' t) with the pendulum's
    ω = √(g/L) corrected for amplitude, ω' = ω (1 − φ0²/16) (Lindstedt; without it the
    phase drifts 2.8e-6 rad in 10 s, 2.7e-9 rad of φ1: measured). Left: the third
    harmonic φ0³/192 = 5e-12 rad and RK4's error at 1 ms (~1e-13): bound 5e-11 rad."""
    t, q, qd, qdd = at_rest(crane, 10.0, 1000.0)
    phi0 = 1e-3
    res = cable.inverse_dynamics(crane, q, qd, qdd, initial=(phi0, 0.0), t=t)
    w = np.sqrt(G / LENGTH) * (1 - phi0 ** 2 / 16)
    assert np.abs(res.sway[:, 0] - phi0 * np.cos(w * t)).max() <= 5e-11
    assert np.abs(res.sway[:, 1]).max() == 0.0          # no φ2 motion is excited


def test_energy_is_conserved_at_rest(crane):
    """Robot at rest, a large swing (0.6, 0.3 rad): T + V of the payload is conserved to
    RK4's error (10 s at 1 ms: measured 8.2e-13 relative; bound 1e-10)."""
    t, q, qd, qdd = at_rest(crane, 10.0, 1000.0)
    res = cable.inverse_dynamics(crane, q, qd, qdd, initial=(0.6, 0.3), t=t)
    (p1, p2), (r1, r2) = res.sway.T, res.sway_rate.T
    energy = (0.5 * MASS * LENGTH ** 2 * (r1 ** 2 * np.cos(p2) ** 2 + r2 ** 2)
              + MASS * G * LENGTH * (1 - np.cos(p1) * np.cos(p2)))
    assert np.abs(energy - energy[0]).max() <= 1e-10 * energy[0]


def test_constant_horizontal_acceleration_tilts_the_pendulum(crane):
    """The platform accelerates along +x at a = 0.2 m/s² from rest, the payload hanging
    still: in the accelerated frame the payload swings about the tilt atan(a/g) (φ2 > 0:
    the payload lags), from 0 to twice it. The first turning point, from the samples' φ,
    φ̇, φ̈ (Taylor, error O(Δt³)), is 2 atan(a/g) to 1e-6 relative; φ1 stays zero."""
    a = 0.2
    t, q, qd, qdd = at_rest(crane, 1.5, 1000.0)
    x0 = q[0, 0]

    def motion(tt):
        n = len(tt)
        Q, Qd, Qdd = np.zeros((n, 9)), np.zeros((n, 9)), np.zeros((n, 9))
        Q[:, 2] = crane.home_height
        Q[:, 0] = x0 + 0.5 * a * tt ** 2
        Qd[:, 0] = a * tt
        Qdd[:, 0] = a
        return Q, Qd, Qdd

    res = cable.inverse_dynamics(crane, *motion(t), reference=motion, t=t)
    p, r, acc = res.sway[:, 1], res.sway_rate[:, 1], res.sway_accel[:, 1]
    k = int(np.argmax((r[:-1] > 0) & (r[1:] <= 0)))
    turning = p[k] + r[k] ** 2 / (2 * -acc[k])
    assert turning == pytest.approx(2 * np.arctan(a / G), rel=1e-6)
    assert np.abs(res.sway[:, 0]).max() <= 1e-15


def test_damping_decays_the_swing_at_its_rate():
    """payload.sway_damping c = 2 ζ m L² ω with ζ = 0.05: a small swing (φ0 = 1e-4 rad)
    follows the damped oscillator φ0 e^{−ζωt} (cos ω_d t + ζ/√(1−ζ²) sin ω_d t) to
    1e-12 rad over 5 s at 1 ms (nonlinear terms ~φ0³ = 1e-12; RK4 ~1e-15)."""
    zeta, w = 0.05, np.sqrt(G / LENGTH)
    c = 2 * zeta * MASS * LENGTH ** 2 * w
    robot = oc.load_robot(overrides={"payload.mass": MASS, "payload.cable_length": LENGTH,
                                     "payload.sway_damping": c})
    t, q, qd, qdd = at_rest(robot, 5.0, 1000.0)
    res = cable.inverse_dynamics(robot, q, qd, qdd, initial=(0.0, 1e-4), t=t)
    wd = w * np.sqrt(1 - zeta ** 2)
    ref = 1e-4 * np.exp(-zeta * w * t) * (np.cos(wd * t) + zeta / np.sqrt(1 - zeta ** 2)
                                          * np.sin(wd * t))
    assert np.abs(res.sway[:, 1] - ref).max() <= 1e-12
    p = cable.inverse_dynamics(robot, q[:500], qd[:500], qdd[:500],
                               initial=(0.3, 0.2), method="pinocchio", t=t[:500])
    k = cable.inverse_dynamics(robot, q[:500], qd[:500], qdd[:500], initial=(0.3, 0.2), t=t[:500])
    assert np.abs(k.sway - p.sway).max() <= 1e-12          # both read <dynamics damping>
    assert np.abs(k.X - p.X).max() <= 1e-12 * np.abs(p.X).max()


def test_damped_swing_settles_at_the_tilt_of_the_acceleration():
    """With damping (ζ = 0.5, L = 0.1 m: decay rate ζω = 4.95 /s), under a constant
    horizontal acceleration a = 0.05 m/s² for 3 s (the platform moves 0.225 m, inside the
    workspace) the sway settles at atan(a/g): to 1e-5 relative (e^{−ζωt} = 4e-7)."""
    a, zeta, L = 0.05, 0.5, 0.1
    c = 2 * zeta * MASS * L ** 2 * np.sqrt(G / L)
    robot = oc.load_robot(overrides={"payload.mass": MASS, "payload.cable_length": L,
                                     "payload.sway_damping": c})
    t, q, qd, qdd = at_rest(robot, 3.0, 1000.0)
    q[:, 0] = -0.1125 + 0.5 * a * t ** 2
    qd[:, 0] = a * t
    qdd[:, 0] = a
    res = cable.inverse_dynamics(robot, q, qd, qdd, t=t)
    assert res.sway[-1, 1] == pytest.approx(np.arctan(a / G), rel=1e-5)
    assert abs(res.sway_rate[-1, 1]) <= 1e-5 * np.arctan(a / G) * np.sqrt(G / L)
    assert np.abs(res.sway[:, 0]).max() <= 1e-15


def test_at_rest_the_cable_pulls_mg_like_a_welded_payload(crane):
    """Hanging still under a robot at rest: tension m g, and X equal to the rigid robot's
    with the same mass welded at the cable's end (measured: identical to the last bit)."""
    t, q, qd, qdd = at_rest(crane, 0.2, 100.0)
    res = cable.inverse_dynamics(crane, q, qd, qdd, t=t)
    welded = oc.load_robot(overrides={"payload.mass": MASS, "payload.com": [0, 0, -LENGTH]})
    X = oc.inverse_dynamics(welded, q, qd, qdd)
    assert np.abs(res.X - X).max() <= 1e-12 * np.abs(X).max()
    assert res.tension == pytest.approx(np.full(len(t), MASS * G), rel=1e-14)
    assert np.allclose(res.force_tip, [0.0, 0.0, -MASS * G], rtol=0, atol=1e-12)


def _random_states(robot, n, seed):
    rng = np.random.default_rng(seed)
    t = rng.uniform(0, 10 * np.pi, n)
    q, qd, qdd = table1(t)
    sway = rng.uniform(-1.0, 1.0, (n, 2))
    rate = rng.uniform(-2.0, 2.0, (n, 2))
    return q, qd, qdd, sway, rate


def test_right_hand_side_equals_pinocchios(crane):
    """At 200 random states (Table 1 poses, sway up to 1 rad, rates up to 2 rad/s): the
    sway accelerations of the Kane formula equal Pinocchio's RNEA/CRBA on the URDF's
    sway joints to 1e-12 relative (measured ~1e-15)."""
    from offshore_crane.reference.cable import _Pendulum

    q, qd, qdd, sway, rate = _random_states(crane, 200, 7)
    ours = cable.sway_accelerations(crane, q, qd, qdd, sway, rate)
    P = _Pendulum(crane, oc.GRAVITY)
    out = np.empty(4)
    ref = np.empty_like(ours)
    for k in range(len(q)):
        P.rhs(q[k], qd[k], qdd[k], np.concatenate([sway[k], rate[k]]), out)
        ref[k] = out[2:]
    assert np.abs(ours - ref).max() <= 1e-12 * np.abs(ref).max()
    one = cable.sway_accelerations(crane, q[3], qd[3], qdd[3], sway[3], rate[3])
    assert one.shape == (2,) and np.array_equal(one, ours[3])     # single = batch row


def test_kane_equals_pinocchio_along_table1(crane):
    """Table 1 (31.4 s at 100 Hz, analytic motion at RK4's stages) from a sway of
    (0.05, −0.03) rad: the two paths integrate the same swing (Kane compiled, Pinocchio
    in Python) and give the same sway and X. Bounds: the issue's 1e-6 (measured: sway
    1.6e-14 rad, X 2.4e-15 relative; round-off grows slowly along the undamped swing)."""
    t = time_grid(10 * np.pi, 100.0)
    q, qd, qdd = table1(t)
    args = dict(reference=table1, initial=(0.05, -0.03))
    k = cable.inverse_dynamics(crane, q, qd, qdd, **args, t=t)
    p = cable.inverse_dynamics(crane, q, qd, qdd, method="pinocchio", **args, t=t)
    assert np.abs(k.sway - p.sway).max() <= 1e-6
    assert np.abs(k.X - p.X).max() <= 1e-6 * np.abs(p.X).max()
    assert np.abs(k.tension - p.tension).max() <= 1e-6 * np.abs(p.tension).max()
    assert np.abs(k.force_tip - p.force_tip).max() <= 1e-6 * np.abs(p.force_tip).max()
    # each path's sway equations hold at its own result (round-off: m g L ~ 10 N·m)
    assert np.abs(k.residual).max() <= 1e-12 * MASS * G * LENGTH
    assert np.abs(p.residual).max() <= 1e-12 * MASS * G * LENGTH
    # the swing matters: the forces differ from the payload welded at the cable's end
    welded = oc.load_robot(overrides={"payload.mass": MASS, "payload.com": [0, 0, -LENGTH]})
    assert np.abs(k.X - oc.inverse_dynamics(welded, q, qd, qdd)).max() > 1.0


def test_sampled_motion_is_interpolated_to_rk4s_accuracy(crane):
    """Without the analytic reference, RK4's half-step stages come from the quintic
    Hermite interpolant of q, q̇, q̈: at 100 Hz along Table 1 the sway differs from the
    analytic-stage run by ≤ 1e-7 rad (measured 4.3e-14; the interpolant's error is O(h⁶),
    and Table 1's sines are smooth at 100 Hz)."""
    t = time_grid(10.0, 100.0)
    q, qd, qdd = table1(t)
    a = cable.inverse_dynamics(crane, q, qd, qdd, reference=table1, initial=(0.1, 0.0), t=t)
    b = cable.inverse_dynamics(crane, q, qd, qdd, initial=(0.1, 0.0), t=t)
    assert 0 < np.abs(a.sway - b.sway).max() <= 1e-7


def test_substeps_converge_at_fourth_order(crane):
    """Halving RK4's step divides the sway error by ~16 (reference: 8 substeps)."""
    t = time_grid(5.0, 100.0)
    q, qd, qdd = table1(t)
    run = [cable.inverse_dynamics(crane, q, qd, qdd, reference=table1, substeps=s,
                                  initial=(0.2, 0.1), t=t).sway for s in (1, 2, 8)]
    e1, e2 = (np.abs(r - run[2]).max() for r in run[:2])
    assert 12.0 <= e1 / e2 <= 20.0


def sea_scene(**cable):
    """The shipped sea-state scene with its 2 kg payload on a 0.3 m cable, 10 s."""
    import tomllib
    from pathlib import Path

    from offshore_crane import scenes

    path = Path(__file__).resolve().parents[2] / "scenes" / "sea_state_crane.toml"
    data = tomllib.loads(path.read_text())
    data["payload"] = {"mass": 2.0, "cable_length": 0.3}
    data["trajectory"]["duration"] = 10.0
    data["cable"] = cable
    return scenes.scene_from_dict(data, str(path), path.parent)


def test_sea_state_run_is_reproducible_bit_for_bit():
    """A seeded sea-state scene with a cable, run twice: identical to the last bit."""
    from offshore_crane import scenes

    scene = sea_scene(initial=[0.02, 0.0])
    runs = []
    for _ in range(2):
        robot = scenes.load_robot(scene)
        runs.append(cable.swing(robot, scenes.load_trajectory(scene, robot),
                                **scene.cable))
    for name in ("X", "sway", "sway_rate", "tension", "force_tip"):
        assert np.array_equal(getattr(runs[0], name), getattr(runs[1], name)), name
    assert np.abs(runs[0].sway).max() > 1e-3            # it does swing


def test_threads_split_the_kane_pass_bit_for_bit():
    """The Kane pass over the integrated sway in two threads: the same numbers as one
    (each sample is computed alone; only the blocks differ)."""
    from offshore_crane import scenes

    scene = sea_scene(initial=[0.02, 0.0])
    robot = scenes.load_robot(scene)
    traj = scenes.load_trajectory(scene, robot)
    one, two = (cable.swing(robot, traj, **scene.cable, threads=n) for n in (1, 2))
    for name in ("X", "sway", "tension", "force_tip", "residual", "condition"):
        assert np.array_equal(getattr(one, name), getattr(two, name)), name


def test_substeps_of_a_sea_state_evaluate_its_synthesis_per_stage_offset():
    """With substeps = 3 the sea's motion is wanted at 5 stage offsets between samples:
    each offset is a uniform set of times, so the synthesis stays on its FFT path (all
    of them as one non-uniform set fell back to the direct sum: on 3 h with substeps = 2,
    unfinished after 2 min, against 3.1 s).
    Reference: the direct sum at the first 200 intervals' stage points (one non-uniform
    set); equal to 1e-12 of each column's peak (the two summations' round-off on ~2·10⁴
    components, measured 3.3e-15)."""
    from offshore_crane import scenes

    scene = sea_scene()
    robot = scenes.load_robot(scene)
    traj = scenes.load_trajectory(scene, robot)
    tt, *grid = cable.stage_grid(traj.t, traj.q, traj.qd, traj.qdd, traj.reference, 3)
    src = traj.source
    fft = src.ship.side_by_side(tt[1::6] * np.sqrt(src.scale), method="fft")
    assert fft.shape == (len(traj.t) - 1, 18)          # an offset's times are a grid
    for g, given in zip(grid, (traj.q, traj.qd, traj.qdd)):
        assert np.array_equal(g[::6], given)           # the samples' own rows
    inner = np.arange(1200) % 6 != 0
    ref = src(tt[:1200][inner])                        # not a grid: the direct sum
    for g, r in zip(grid, ref):
        scale = np.abs(r).max(axis=0) + 1e-300
        assert (np.abs(g[:1200][inner] - r) / scale).max() <= 1e-12


def test_slack_cable_is_an_error_or_marked(crane):
    """The platform dropping faster than gravity (q̈3 = −15 m/s² for 0.1 s) would need a
    pushing cable: SlackCableError names the time and keeps the samples before it; with
    slack='warn' they are marked and a warning is given."""
    t, q, qd, qdd = at_rest(crane, 0.3, 100.0)
    drop = (t >= 0.1) & (t < 0.2)
    qdd[drop, 2] = -15.0
    with pytest.raises(SlackCableError, match=r"slack at sample 10 \(t = 0.1 s\)") as info:
        cable.inverse_dynamics(crane, q, qd, qdd, limits=False, t=t)
    assert len(info.value.result) == 10 and info.value.tension < 0
    with pytest.warns(OffshoreCraneWarning, match="slack at 10 samples"):
        res = cable.inverse_dynamics(crane, q, qd, qdd, limits=False, slack="warn", t=t)
    assert res.slack.sum() == 10 and res.slack[10] and not res.slack[9]


@pytest.mark.parametrize("threads", [1, 2])
def test_singular_sway_stops_with_the_time_and_keeps_the_samples(crane, threads, monkeypatch):
    """A swing driven towards cos φ2 = 0 with an error threshold of 50 on 1/cos²φ2:
    SingularConfigurationError (kind 'sway') naming the sample; the samples before it
    kept (6 of them). In two threads (the Kane pass alongside the integration, chunks of
    2 samples here so that several wait on it) the same stop and the same numbers."""
    from offshore_crane.dynamics.cable import forces

    monkeypatch.setattr(forces, "CHUNK", 2)
    t, q, qd, qdd = at_rest(crane, 1.0, 100.0)
    results = []
    for n in sorted({1, threads}):
        with pytest.raises(SingularConfigurationError, match="singular set") as info:
            cable.inverse_dynamics(crane, q, qd, qdd, initial=(0.0, 1.3),
                                   initial_rate=(0.0, 3.0), thresholds=Thresholds(10.0, 50.0),
                                   t=t, threads=n)
        exc = info.value
        assert exc.kind == "sway" and exc.index > 2 and len(exc.result) == exc.index
        assert (1 / np.cos(exc.result.sway[:, 1]) ** 2).max() <= 50.0
        results.append(exc.result)
    for name in ("X", "sway", "tension", "condition"):
        assert np.array_equal(getattr(results[0], name), getattr(results[-1], name)), name


def test_kane_alongside_the_integration_waits_for_its_rows(crane, monkeypatch):
    """Table 1 with the swing in two threads, in chunks of 16 samples that wait for the
    integration: every output equal to one thread's to the bit."""
    from offshore_crane.dynamics.cable import forces

    monkeypatch.setattr(forces, "CHUNK", 16)
    t = time_grid(5.0, 100.0)
    q, qd, qdd = table1(t)
    one, two = (cable.inverse_dynamics(crane, q, qd, qdd, reference=table1, t=t,
                                       initial=(0.1, 0.05), threads=n) for n in (1, 2))
    for name in ("X", "sway", "sway_rate", "sway_accel", "tension", "force_tip", "residual",
                 "condition"):
        assert np.array_equal(getattr(one, name), getattr(two, name)), name


def test_an_integration_that_raises_is_not_masked_by_the_kane_pass(crane, monkeypatch):
    """The integration raising in its thread (here a stand-in that writes 5 rows, then
    fails): the Kane pass alongside stops waiting and computes nothing more, and the
    integration's own exception reaches the caller."""
    from offshore_crane.dynamics.cable import kernels as ck

    def failing(*args):
        Y = args[-2]
        Y[:5] = 0.0
        raise RuntimeError("integration failed")

    monkeypatch.setattr(ck, "integrate", failing)
    t, q, qd, qdd = at_rest(crane, 1.0, 100.0)
    with pytest.raises(RuntimeError, match="integration failed"):
        cable.inverse_dynamics(crane, q, qd, qdd, t=t, threads=2)


@pytest.mark.parametrize("kwargs, error, match", [
    (dict(length=0.0, mass=2.0), InputError, r"length = 0.0 m: the cable needs a finite"),
    (dict(length=-1.0, mass=2.0), InputError, r"length = -1.0 m"),
    (dict(length=1.0, mass=-2.0), InputError, r"mass = -2.0 kg"),
    (dict(length=float("nan"), mass=2.0), InputError, r"length = nan"),
    (dict(initial=(0.0, np.pi / 2)), InputError, r"singular set cos\(phi2\) = 0"),
    (dict(initial=(0.0, np.nan)), InputError, r"initial must be two finite numbers"),
    (dict(substeps=0), InputError, r"substeps = 0 must be an integer >= 1"),
    (dict(slack="ignore"), InputError, r"slack = 'ignore'"),
    (dict(method="rnea"), InputError, r"unknown method 'rnea'"),
    (dict(threads=0), InputError, r"threads must be a positive integer, got 0"),
])
def test_bad_arguments(crane, kwargs, error, match):
    t, q, qd, qdd = at_rest(crane, 0.1, 100.0)
    with pytest.raises(error, match=match):
        cable.inverse_dynamics(crane, q, qd, qdd, **kwargs, t=t)


def test_bad_samples(crane):
    t, q, qd, qdd = at_rest(crane, 0.1, 100.0)
    q[3, 4] = np.nan
    with pytest.raises(InputError, match=r"q\[3, 4\] is nan"):
        cable.inverse_dynamics(crane, q, qd, qdd, t=t)
    t2 = t.copy()
    t2[5] += 0.003
    with pytest.raises(InputError, match=r"time axis is not uniform: step 4 .* resample the motion"):
        cable.inverse_dynamics(crane, *at_rest(crane, 0.1, 100.0)[1:], t=t2)


def test_rigid_solvers_refuse_a_hanging_payload(crane):
    """The rigid-robot paths cannot know the sway: an error, never a silent result."""
    q = np.zeros(9)
    q[2] = crane.home_height
    for call in (lambda: oc.inverse_dynamics(crane, q, q * 0, q * 0),
                 lambda: oc.forward_dynamics(crane, q, q * 0, q * 0),
                 lambda: oc.forward_dynamics(crane, q, q * 0, q * 0, method="pinocchio")):
        with pytest.raises(ModelError, match="hangs on a cable"):
            call()
    with pytest.raises(ModelError, match="payload is welded"):
        t, q, qd, qdd = at_rest(crane, 0.1, 100.0)
        cable.inverse_dynamics(oc.load_robot(), q, qd, qdd, t=t)


@pytest.mark.parametrize("overrides, match", [
    ({"payload.cable_length": -1.0}, "must not be negative"),
    ({"payload.cable_length": 1.0}, "needs a payload to hang from it"),
    ({"payload.cable_length": 1.0, "payload.mass": 2.0, "payload.com": [0, 0, -0.1]},
     "point mass at the cable's end"),
    ({"payload.sway_damping": 0.1}, "damps the swing of a payload on a cable"),
    ({"payload.cable_length": 1.0, "payload.mass": 2.0, "payload.sway_damping": -0.1},
     "must not be negative"),
])
def test_description_checks_the_cable(overrides, match):
    from offshore_crane.errors import DescriptionError

    with pytest.raises(DescriptionError, match=match):
        oc.load_robot(overrides=overrides)


# ------------------------------------------------------------------- command line
CABLE_SET = ["--set", "payload.mass=2", "--set", "payload.cable_length=0.5"]


def test_cli_id_with_a_cable(tmp_path, capsys):
    """The summary gives the sway and the tension; the CSV gains phi1, phi2, tension,
    equal to the library's result; --method both compares the two paths."""
    from offshore_crane.cli import main

    out = tmp_path / "x.csv"
    assert main(["id", *CABLE_SET, "--duration", "5", "--initial-sway", "0.05", "0",
                 "--method", "both", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "hanging on a 0.5 m cable" in text and "max sway" in text
    assert "cable tension: min" in text and "max |Δsway|" in text
    header = out.read_text().splitlines()[0]
    assert header.endswith("Fl6_N,phi1_rad,phi2_rad,tension_N")
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    robot = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 0.5})
    t = data[:, 0]
    lib = cable.inverse_dynamics(robot, *table1(t), reference=table1, initial=(0.05, 0.0), t=t)
    assert np.array_equal(data[:, 10:12], lib.sway)
    assert np.array_equal(data[:, 12], lib.tension)


@pytest.mark.parametrize("argv, match", [
    (["--set", "payload.cable_length=-1"], "must not be negative"),
    (["--initial-sway", "0.1", "0"], "--initial-sway: applies to a payload on a cable"),
    ([*CABLE_SET, "--initial-sway", "0", "1.5707963267948966"], "singular set"),
    ([*CABLE_SET, "--substeps", "0"], "--substeps 0: give an integer >= 1"),
    ([*CABLE_SET, "--method", "kane-explicit"], "the methods are kane and rnea"),
    ([*CABLE_SET, "--compare-fidelity"], "hangs on a cable"),
    ([*CABLE_SET, "--gravity", "0", "0", "9.81"], "the cable goes slack at sample 0"),
])
def test_cli_bad_input_one_line_no_file(tmp_path, capsys, argv, match):
    from offshore_crane.cli import main

    out = tmp_path / "x.csv"
    assert main(["id", "--duration", "1", *argv, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and match in err, err
    assert not out.exists() and list(tmp_path.iterdir()) == []
