"""Envelopes, Gumbel most probable maxima and verdicts (offshore_crane.studies.sizing), and the
``size`` command.

References are independent of the code under test: the forces come from ``id --out``'s
CSV, the arm speeds from Table 1's analytic rates, the leg lengths from the description's
anchors (|O2 + R s_i − P_i|, written out here) and the leg rates from central differences
of those lengths, the Gumbel fit from SciPy's ``gumbel_r.fit``.
"""

import json
import math

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.studies import sizing
from offshore_crane.motion import trajectories
from offshore_crane.cli import main
from offshore_crane.errors import InputError, InsufficientSeedsError

SEA_SCENE = """
name = "small sea"
[payload]
mass = 2.0
offset = [0.0, 0.0, -0.05]
[trajectory]
source = "sea"
duration = 5.0
rate = 50.0
[sea]
hs = 2.5
tp = 8.0
heading = 90.0
scale = 20.0
seed = 3
highpass = 0.2
"""


def _rot(q):
    """R_base_platform = Rz(q6) Ry(q5) Rx(q4), (N, 3, 3), written out independently."""
    r, p, y = q[:, 3], q[:, 4], q[:, 5]
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    return np.stack([np.stack([cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr], -1),
                     np.stack([sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr], -1),
                     np.stack([-sp, cp * sr, cp * cr], -1)], -2)


def _leg_lengths(robot, q):
    S = robot.spec.p_platform_S                      # (6, 3) platform frame [m]
    P = robot.spec.p_base_P                          # (6, 3) base frame [m]
    p_S = q[:, None, :3] + np.einsum("nij,lj->nli", _rot(q), S)
    return np.linalg.norm(p_S - P[None], axis=-1)    # (N, 6) [m]


def _size_json(argv, capsys):
    status = main(["size", *argv, "--json"])
    out = capsys.readouterr().out
    return status, json.loads(out)


def test_size_equals_what_id_out_csv_gives(tmp_path, capsys):
    """Peaks (push and pull apart, with times), RMS, speeds, powers and strokes of
    ``size --json`` recomputed from ``id --out``'s CSV and independent kinematics."""
    csv = tmp_path / "x.csv"
    # one backend for both: id's default takes NumPy in a process that has not loaded
    # Numba (dynamics.quick_backend), whose forces differ from Numba's in the last bits
    backend = ["--backend", "numba"]
    assert main(["id", "--duration", "3", "--rate", "100", "--out", str(csv), *backend]) == 0
    capsys.readouterr()
    status, doc = _size_json(["--duration", "3", "--rate", "100", *backend], capsys)
    env = doc["envelopes"][0]
    data = np.loadtxt(csv, delimiter=",", skiprows=1)
    t, X = data[:, 0], data[:, 1:]
    robot = oc.load_robot()
    q, qd, _ = trajectories.table1(t)
    h = 1e-6                                         # central difference of lengths [s]
    rate = (_leg_lengths(robot, trajectories.table1(t + h)[0])
            - _leg_lengths(robot, trajectories.table1(t - h)[0])) / (2 * h)
    v = np.column_stack([qd[:, 6:9], rate])
    pos = np.column_stack([q[:, 6:9], _leg_lengths(robot, q)])
    caps = robot.capacities
    for k, a in enumerate(oc.ACTUATORS):
        x = X[:, k]
        # CSV holds 17 significant digits: the forces round-trip exactly
        assert env[f"{a}_peak_push"] == max(x.max(), 0.0)
        assert env[f"{a}_peak_pull"] == max((-x).max(), 0.0)
        if x.max() > 0:
            assert env[f"{a}_t_push"] == t[np.argmax(x)]
        if x.min() < 0:
            assert env[f"{a}_t_pull"] == t[np.argmin(x)]
        # same sum in another order: a few ulps
        assert env[f"{a}_rms"] == pytest.approx(np.sqrt(np.mean(x ** 2)), rel=1e-13)
        # leg rates by differences (h = 1e-6 s: truncation ~1e-12, rounding ~1e-10 m/s)
        assert env[f"{a}_peak_speed"] == pytest.approx(np.abs(v[:, k]).max(), rel=1e-8)
        assert env[f"{a}_peak_power"] == pytest.approx(np.abs(x * v[:, k]).max(), rel=1e-8)
        assert env[f"{a}_mean_abs_power"] == pytest.approx(np.abs(x * v[:, k]).mean(),
                                                           rel=1e-8)
        assert env[f"{a}_stroke_min"] == pytest.approx(pos[:, k].min(), rel=1e-13)
        assert env[f"{a}_stroke_max"] == pytest.approx(pos[:, k].max(), rel=1e-13)
        assert env[f"{a}_util_push"] == pytest.approx(env[f"{a}_peak_push"]
                                                      / caps.push_max[k], rel=1e-15)
        assert env[f"{a}_util_speed"] == pytest.approx(env[f"{a}_peak_speed"]
                                                       / caps.speed_max[k], rel=1e-15)
        assert env[f"{a}_util_power"] is None       # lab.toml gives no power limit
    assert status == 0 and doc["verdict"]["exceeded"] is False
    assert doc["verdict"]["basis"] == "observed"


def test_size_exit_1_when_a_capacity_is_exceeded(capsys):
    """A scene override of one leg's push capacity below its peak: exit 1, that leg named
    as governing; a power limit shows up as a utilisation."""
    status, doc = _size_json(["--duration", "2", "--set", "actuators.Fl3.push_max=10",
                              "--set", "actuators.T1.power_max=4"], capsys)
    assert status == 1
    w = doc["verdict"]["worst"]
    assert (w["actuator"], w["capacity"]) == ("Fl3", "push") and w["utilisation"] > 1
    env = doc["envelopes"][0]
    assert env["T1_util_power"] == pytest.approx(env["T1_peak_power"] / 4, rel=1e-15)
    status = main(["size", "--duration", "2", "--set", "actuators.Fl3.push_max=10"])
    out = capsys.readouterr().out
    assert status == 1 and "Fl3" in out and "EXCEEDED" in out


def test_size_seeds_gumbel(tmp_path, capsys):
    """Five seeds of a sea, each a stationary record as long as the exposure (here 0.25 h
    full scale, to stay cheap): the verdict is the mode of the Gumbel fit of the five
    records' maxima (no extrapolation: one record per exposure), and says so; the
    records are the judged windows (the exposure at model scale, to one sample)."""
    scene = tmp_path / "sea.toml"
    scene.write_text(SEA_SCENE)
    status, doc = _size_json(["--scene", str(scene), "--exposure", "0.25"], capsys)
    v = doc["verdict"]
    assert v["basis"] == "gumbel" and v["seeds"] == 5 and doc["seeds"] == [3, 4, 5, 6, 7]
    exposure = 0.25 * 3600.0
    # the judged window ends on the last sample within the exposure (50 Hz: 0.02 s model)
    assert exposure - 0.02 * math.sqrt(20.0) <= v["record_s"] <= exposure
    assert doc["records"]["judged_s"] == pytest.approx(exposure / math.sqrt(20.0), rel=1e-15)
    assert doc["records"]["modes"] == [] and doc["records"]["spin_up_s"] == 0.0
    peaks = [e["Fl6_peak_push"] for e in doc["envelopes"]]
    mu, beta = sizing.gumbel_fit(peaks)
    assert v["peaks"]["push"][8] == pytest.approx(
        mu + beta * math.log(exposure / v["record_s"]), rel=1e-15)
    assert v["peaks"]["push"][8] == pytest.approx(mu, rel=1e-5)     # ln n ~ 2e-5
    assert "mode of the Gumbel fit (maximum likelihood) of the maxima of 5 records" in \
        v["describe"]
    # the scene's own 5 s records: observed, not extrapolated to the exposure
    status, doc = _size_json(["--scene", str(scene), "--record", "scene"], capsys)
    v = doc["verdict"]
    assert v["basis"] == "observed" and doc["records"] is None
    assert v["record_s"] == pytest.approx(5.0 * math.sqrt(20.0), rel=1e-15)
    assert v["peaks"]["push"][8] == max(e["Fl6_peak_push"] for e in doc["envelopes"])
    assert "shorter than the 3 h exposure: observed, not extrapolated" in v["describe"]


def test_gumbel_fit_matches_scipy():
    from scipy import stats as st
    rng = np.random.default_rng(7)
    for n, loc, scale in ((5, 3.0, 0.5), (12, -40.0, 7.0), (200, 1e4, 3e2)):
        x = st.gumbel_r.rvs(loc=loc, scale=scale, size=n, random_state=rng)
        mu, beta = sizing.gumbel_fit(x)
        mu_ref, beta_ref = st.gumbel_r.fit(x)
        # both maximum likelihood; SciPy solves the same equation to ~1e-10
        assert mu == pytest.approx(mu_ref, rel=1e-8, abs=1e-8 * scale)
        assert beta == pytest.approx(beta_ref, rel=1e-8)
        n_rec = 3 * 3600.0 / 120.0
        assert sizing.most_probable_maximum(x, 120.0) == pytest.approx(
            mu_ref + beta_ref * math.log(n_rec), rel=1e-8)


def test_gumbel_mode_of_the_exposure_maximum():
    """The most probable maximum of n records is the mode of their maximum, where a
    Gumbel's distribution function is exp(-1): simulated exposures (n = 50 records of
    Gumbel(0, 1)) stay below it e^-1 of the time."""
    rng = np.random.default_rng(11)
    x = rng.gumbel(size=20000)
    mpm = sizing.most_probable_maximum(x, 1.0, 50.0)
    assert mpm == pytest.approx(math.log(50.0), abs=0.03)   # fit error ~1/sqrt(20000)
    exposures = rng.gumbel(size=(20000, 50)).max(axis=1)
    below = float((exposures <= mpm).mean())
    # binomial noise sqrt(p (1 - p) / 20000) = 0.0034, fit error ~0.03 * density 0.37
    assert below == pytest.approx(math.exp(-1.0), abs=0.02)


def test_too_few_seeds_and_bad_exposure():
    with pytest.raises(InsufficientSeedsError, match="at least 5 per-record maxima"):
        sizing.gumbel_fit([1.0, 2.0, 3.0, 4.0])
    with pytest.raises(InputError, match="exposure 10 s is shorter than one record"):
        sizing.most_probable_maximum([1.0, 2.0, 3.0, 4.0, 5.0], 20.0, 10.0)
    with pytest.raises(InputError, match="maxima\\[2\\] = nan"):
        sizing.gumbel_fit([1.0, 2.0, math.nan, 4.0, 5.0])
    assert sizing.gumbel_fit([2.0] * 6) == (2.0, 0.0)


def test_verdict_falls_back_to_observed_below_min_seeds(robot):
    """Fewer than 5 records that cover the exposure, or 5 records shorter than it: the
    largest observed peak, and the verdict says which; 5 covering records: Gumbel."""
    t = np.linspace(0.0, 2.0, 101)
    q, qd, qdd = trajectories.table1(t)
    X = oc.inverse_dynamics(robot, q, qd, qdd)
    envs = [sizing.envelope(robot, t, q, qd, X * s) for s in (1.0, 1.5, 1.2, 1.1, 1.3)]
    # 2 s at 1:20 is 8.94 s full scale: an exposure of 8.9 s is covered, 3 h is not
    v = sizing.verdict(envs[:3], scale=20.0, exposure=8.9)
    assert v.basis == "observed" and v.seeds == 3 and v.covered
    assert "fewer than 5 records for a Gumbel fit" in v.describe()
    np.testing.assert_array_equal(v.peaks["push"], envs[1].peak_push)
    v = sizing.verdict(envs, scale=20.0)
    assert v.basis == "observed" and v.covered is False
    assert "shorter than the 3 h exposure: observed, not extrapolated" in v.describe()
    np.testing.assert_array_equal(v.peaks["push"], envs[1].peak_push)
    assert sizing.verdict(envs, scale=20.0, exposure=8.9).basis == "gumbel"
    # covered within one sample interval (0.02 s model), not beyond
    full = 2.0 * math.sqrt(20.0)
    assert sizing.covers_exposure(2.0, 101, 20.0, full + 0.02 * math.sqrt(20.0))
    assert not sizing.covers_exposure(2.0, 101, 20.0, full + 0.021 * math.sqrt(20.0))


def test_envelope_absent_actuators_and_conditions(robot):
    """Arm columns NaN (no arm evaluated): the arm rows are NaN, never 0; worst
    condition numbers with their times."""
    t = np.linspace(0.0, 1.0, 51)
    q, qd, qdd = trajectories.table1(t)
    res = oc.dynamics.solve(robot, q, qd, qdd)
    X = res.X.copy()
    X[:, :3] = np.nan
    env = sizing.envelope(robot, t, q, qd, X, sizing.conditions(res))
    assert np.isnan(env.utilisation[:3]).all() and not np.isnan(env.utilisation[3:]).all()
    k = int(np.argmax(res.condition))
    assert env.kappa["leg"] == res.condition[k] and env.t_kappa["leg"] == t[k]
    assert env.row()["T1_rms"] != env.row()["T1_rms"]        # NaN


@pytest.mark.parametrize("change, match", [
    (lambda t, q, qd, X: (t, q[:-1], qd, X), r"q has shape \(50, 9\); expected \(51, 9\)"),
    (lambda t, q, qd, X: (t, np.where(np.arange(51)[:, None] == 7, np.nan, q), qd, X),
     r"q\[7, 0\] = nan is not finite"),
    (lambda t, q, qd, X: (t, q, qd, np.where(np.arange(51)[:, None] == 4, np.inf, X)),
     r"X\[4, 0\] \(T1\) = inf is not finite"),
])
def test_envelope_bad_inputs(robot, change, match):
    t = np.linspace(0.0, 1.0, 51)
    q, qd, qdd = trajectories.table1(t)
    X = oc.inverse_dynamics(robot, q, qd, qdd)
    with pytest.raises(InputError, match=match):
        sizing.envelope(robot, *change(t, q, qd, X))


def test_size_with_a_cable_equals_id_out(tmp_path, capsys):
    """A payload on a cable: size runs the swing; its envelope (peaks, sway, tension)
    equals what id --out's CSV of the same run gives (phi1, phi2, tension columns)."""
    argv = ["--duration", "3", "--set", "payload.mass=2", "--set", "payload.cable_length=0.5",
            "--initial-sway", "0.1", "0"]
    out = tmp_path / "id.csv"
    assert main(["id", *argv, "--out", str(out)]) == 0
    capsys.readouterr()
    status, doc = _size_json(argv, capsys)
    assert status == 0
    env = doc["envelopes"][0]
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    sway = np.arccos(np.clip(np.cos(data[:, 10]) * np.cos(data[:, 11]), -1, 1))
    assert env["sway_max"] == sway.max() > 0.09
    assert (env["tension_min"], env["tension_max"]) == (data[:, 12].min(), data[:, 12].max())
    assert env["Fl1_peak_push"] == max(data[:, 4].max(), 0.0)


def test_size_bad_flags(tmp_path, capsys):
    for argv, match in ((["--seeds", "3"], "deterministic"), (["--seeds", "0"], "≥ 1"),
                        (["--exposure", "-1"], "positive number of hours")):
        assert main(["size", "--duration", "1", *argv]) == 2
        err = capsys.readouterr().err
        assert match in err and err.count("\n") == 1


def test_actuator_motion_equals_kinematics_legs(robot):
    """The envelope's lean leg evaluation (lengths and rates only) gives exactly what the
    full leg kinematics gives, on perturbed Table 1 states."""
    from offshore_crane.robot import kinematics

    t = np.linspace(0.0, 5.0, 301)
    q, qd, _ = trajectories.table1(t)
    rng = np.random.default_rng(5)
    q = q + 0.01 * rng.standard_normal(q.shape)
    qd = qd + 0.1 * rng.standard_normal(qd.shape)
    p, v = sizing.actuator_motion(robot, q, qd)
    legs = kinematics.legs(robot, q, qd)
    np.testing.assert_array_equal(p[:, 3:], legs.length)
    np.testing.assert_array_equal(v[:, 3:], legs.rate)
    np.testing.assert_array_equal(p[:, :3], q[:, 6:])
    np.testing.assert_array_equal(v[:, :3], qd[:, 6:])


def test_zero_capacity_is_no_headroom_not_no_limit():
    """A capacity of 0 is a limit (issue 21): a zero demand uses all of it (100 %, printed
    as such, not as the '—' of a missing capacity) and any demand exceeds it."""
    from offshore_crane.studies.sizing.envelopes import utilisation

    u = utilisation(np.array([0.0, 2.0, 0.0, np.nan]), np.array([0.0, 0.0, np.inf, 0.0]))
    assert u[0] == 1.0 and u[1] == np.inf and np.isnan(u[2]) and np.isnan(u[3])
    robot = oc.load_robot(overrides={"actuators.T2.push_max": 0.0})
    t = trajectories.time_grid(2.0, 50.0)
    q, qd, qdd = trajectories.table1(t)
    q[:, 7], qd[:, 7], qdd[:, 7] = 0.0, 0.0, 0.0          # T2's joint held still
    X = oc.inverse_dynamics(robot, q, qd, qdd)
    X[:, 1] = np.minimum(X[:, 1], 0.0)                   # and pulling only: no push
    env = sizing.envelope(robot, t, q, qd, X)
    k = oc.ACTUATORS.index("T2")
    assert env.utilisation[k, sizing.CAPACITIES.index("push")] == 1.0
    table = sizing.format_verdict(sizing.verdict([env]), robot.hybrid.actuators).splitlines()
    assert table[2 + k].split()[:2] == ["T2", "100.0"]      # not "—" (no capacity)
    assert table[-1] == "worst: T2 push at 100.0 % (within capacity)"


# --------------------------------------------------------------------------- the hanging load
def test_size_judges_the_hanging_load_over_its_exposure(tmp_path, capsys):
    """scenes/hanging_load.toml, 5 seeds of stationary records over an exposure of 0.5 h
    (to stay cheap): the sway and tension verdict rests on the same Gumbel fit as the
    forces, each value beside its limit, degrees for angles; the records' spin-up comes
    from the sway mode; a sway limit below the sway makes the verdict fail (exit 1, and
    in --json)."""
    from pathlib import Path

    scene = Path(__file__).resolve().parents[2] / "scenes" / "hanging_load.toml"
    assert main(["size", "--scene", str(scene), "--exposure", "0.5"]) == 0
    out = capsys.readouterr().out
    assert "most probable maximum over 0.5 h full scale: the mode of the Gumbel" in out
    assert ("each after a 120 s spin-up (5 decay times of the sway mode, 16 s each, "
            "rounded up to whole 60 s cycles), discarded") in out
    assert "limit 45°:" in out and "limit ≥ 0.1:" in out
    assert "hanging load: max sway" in out and "°" in out.split("hanging load: max sway")[1]
    tight = tmp_path / "tight.toml"
    tight.write_text(scene.read_text().replace("sway_max_deg = 45.0", "sway_max_deg = 20.0"))
    status, doc = _size_json(["--scene", str(tight), "--exposure", "0.5"], capsys)
    load = doc["verdict"]["load"]
    assert status == 1 and load["exceeded"] and doc["verdict"]["exceeded"]
    assert load["limits"]["sway_max_deg"] == pytest.approx(20.0)
    assert load["utilisation"]["sway"] == pytest.approx(load["sway_max_deg"] / 20.0)
    assert load["sway_max_deg"] > 20.0 and load["tension_ratio_min"] > 0.1
    assert main(["size", "--scene", str(tight), "--exposure", "0.5", "--seeds", "1"]) == 1
    assert "the hanging load EXCEEDS its limits: sway" in capsys.readouterr().out


def test_load_verdict_extremes_and_the_slack_criterion():
    """The load verdict from envelopes alone: the most probable maximum of the maxima,
    the most probable minimum of the minima (the negated maxima's fit), the slack
    utilisation = limit ratio / ratio, inf once the cable goes slack (ratio <= 0)."""
    from offshore_crane.robot.description import LoadLimits
    from offshore_crane.studies.sizing.envelopes import Envelope
    from offshore_crane.studies.sizing.extremes import most_probable_maximum
    from offshore_crane.studies.sizing.verdicts import load_verdict

    rng = np.random.default_rng(21)
    sway = 0.3 + 0.02 * rng.random(6)
    t_min = 8.0 + rng.random(6)
    t_max = 30.0 + rng.random(6)
    nan9 = np.full(9, np.nan)

    def env(k, limits):
        return Envelope(duration=60.0, samples=10, peak_push=nan9, t_push=nan9,
                        peak_pull=nan9, t_pull=nan9, rms=nan9, peak_speed=nan9,
                        peak_power=nan9, mean_abs_power=nan9, stroke_min=nan9,
                        stroke_max=nan9, stroke_range=np.full((9, 2), np.nan),
                        capacities={}, utilisation=np.full((9, 5), np.nan),
                        sway_max=sway[k], tension_min=t_min[k], tension_max=t_max[k],
                        static_tension=19.62, load_limits=limits)

    limits = LoadLimits(sway_max=math.radians(20.0), tension_ratio_min=0.1, tension_max=40.0)
    v = load_verdict([env(k, limits) for k in range(6)], 268.0, 10800.0, True)
    assert v.sway == pytest.approx(most_probable_maximum(sway, 268.0, 10800.0), rel=1e-12)
    assert v.tension_min == pytest.approx(-most_probable_maximum(-t_min, 268.0, 10800.0),
                                          rel=1e-12)
    assert v.tension_max == pytest.approx(most_probable_maximum(t_max, 268.0, 10800.0),
                                          rel=1e-12)
    assert v.tension_min < t_min.min()
    assert v.utilisation["slack"] == pytest.approx(0.1 / (v.tension_min / 19.62))
    assert v.utilisation["sway"] == pytest.approx(v.sway / math.radians(20.0))
    assert v.utilisation["tension"] == pytest.approx(v.tension_max / 40.0)
    observed = load_verdict([env(k, limits) for k in range(6)], 268.0, 10800.0, False)
    assert observed.sway == sway.max() and observed.tension_min == t_min.min()
    t_min[:] = -1.0                                      # the cable goes slack
    slack = load_verdict([env(k, limits) for k in range(6)], 268.0, 10800.0, False)
    assert math.isinf(slack.utilisation["slack"]) and slack.exceeded
    none = load_verdict([env(k, LoadLimits()) for k in range(6)], 268.0, 10800.0, False)
    assert all(math.isnan(x) for x in none.utilisation.values()) and not none.exceeded
