"""Extremes an engineer can sign (offshore_crane.scenes.exposure, studies.sizing, size,
sweep, compensate): every figure from the record the run executed, stationary records as
long as the exposure, warnings on lightly damped modes.

References independent of what is checked: the compensated motion's own arm rates and
positions (not the envelope's kinematics), the medians of many full-length records'
maxima (not the Gumbel fit), a second run from another start (stationarity), the
scene's operation evaluated a cycle later (repetition).
"""

import json
import math
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from offshore_crane import scenes
from offshore_crane.cli import main
from offshore_crane.errors import SceneError
from offshore_crane.scenes import exposure
from offshore_crane.studies import sizing, sweep

SCENES = Path(__file__).resolve().parents[2] / "scenes"


def _size_json(argv, capsys) -> tuple[int, dict]:
    status = main(["size", *argv, "--json"])
    return status, json.loads(capsys.readouterr().out)


# --------------------------------------------------------------------------- the motion that runs
def test_the_compensated_lift_is_judged_on_the_motion_that_runs(tmp_path, capsys):
    """On the compensated lift (arm + winch), size's envelope and a sweep's row take the
    arm's speeds and strokes from the compensated motion — its own rates and positions
    over the judged window, to 1e-12 — not from the uncompensated record (which holds the
    arm still: 0 rad/s); compensate, size and the sweep report the same sway for the same
    seed (bit for bit: one record, one definition). Exposure 0.1 h to stay cheap."""
    from offshore_crane.simulation.compensation import compensated_motion

    path = SCENES / "compensated_lift.toml"
    scene = scenes.with_overrides(scenes.load_scene(path), "test",
                                  extremes={"exposure": 0.1})
    status, doc = _size_json(["--scene", str(path), "--exposure", "0.1", "--seeds", "1"],
                             capsys)
    env = doc["envelopes"][0]
    robot = scenes.load_robot(scene)
    plan = exposure.exposure_plan(scene, robot)
    comp = compensated_motion(robot, scenes.load_trajectory(plan.scene, robot),
                              "arm+winch", scene.control["delay"], None, scene.gravity)
    t = comp.trajectory.t
    window = (t >= plan.start - 1e-9) & (t <= plan.start + plan.length + 1e-9)
    q, qd = comp.trajectory.q[window, 6:9], comp.trajectory.qd[window, 6:9]
    row = sweep.run(scene, {"seed": [1]}).iloc[0]
    for k, a in enumerate(("T1", "T2", "Fs")):
        for value in (env[f"{a}_peak_speed"], row[f"{a}_peak_speed"]):
            assert value == pytest.approx(np.abs(qd[:, k]).max(), rel=1e-12)
        for value in (env[f"{a}_stroke_min"], row[f"{a}_stroke_min"]):
            assert value == pytest.approx(q[:, k].min(), rel=1e-12)
        for value in (env[f"{a}_stroke_max"], row[f"{a}_stroke_max"]):
            assert value == pytest.approx(q[:, k].max(), rel=1e-12)
    assert env["T1_peak_speed"] > 0.1                  # the compensating arm moves
    assert env["T1_stroke_max"] - env["T1_stroke_min"] > 0.05
    from offshore_crane.studies.compensation import compare_compensation

    run = compare_compensation(scene, modes=("arm+winch",))[0]
    assert env["sway_max"] == row["sway_max"]
    assert math.degrees(env["sway_max"]) == run.sway_max_deg


def test_the_sway_is_measured_from_the_tips_vertical():
    """One sway figure for both cables: the angle between the cable and the arm_tip
    frame's −z axis; on the elastic cable from the payload's position and the tip's
    attitude, checked against a rigid-body rotation written out here (Rz(q6) Ry(q5)
    Rx(q4) of the platform, the arm's revolute joints about its z: the tip's z axis is
    the platform's)."""
    from offshore_crane.dynamics.cable.tip import sway_angle

    scene = replace(scenes.load_scene(SCENES / "compensated_lift.toml"),
                    extremes={"record": "scene"})
    robot = scenes.load_robot(scene)
    res = scenes.run_swing(scene, robot, scenes.load_trajectory(scene, robot), "kane").cable
    q = res.q
    r, p, y = q[:, 3], q[:, 4], q[:, 5]
    z = np.stack([np.cos(y) * np.sin(p) * np.cos(r) + np.sin(y) * np.sin(r),
                  np.sin(y) * np.sin(p) * np.cos(r) - np.cos(y) * np.sin(r),
                  np.cos(p) * np.cos(r)], axis=-1)                 # R[:, 2]
    rho = res.position / np.linalg.norm(res.position, axis=1)[:, None]
    expected = np.arccos(np.clip(-(rho * z).sum(axis=1), -1, 1))
    assert np.abs(sway_angle(robot, res) - expected).max() <= 1e-12


# --------------------------------------------------------------------------- exposure records
def test_an_exposure_record_repeats_the_operation_after_a_spin_up():
    """The hanging-load scene's record: a spin-up of whole 60 s cycles covering 5 decay
    times of its sway mode (ζ 2 %, ω = √(g/L)), then the exposure at model scale; the
    operation at t and at t + 60 s is the same pose; the judged window starts after the
    spin-up; an operation that does not end where it starts cannot repeat."""
    scene = scenes.load_scene(SCENES / "hanging_load.toml")
    robot = scenes.load_robot(scene)
    plan = exposure.exposure_plan(scene, robot)
    assert [m.name for m in plan.modes] == ["sway phi1", "sway phi2"]
    mode = plan.modes[0]
    assert mode.omega == pytest.approx(math.sqrt(9.81 / 1.0))
    assert mode.zeta == pytest.approx(0.02, rel=1e-3)   # the scene's 2 ζ m L² √(g/L)
    assert plan.spin_up == 120.0 >= 5 * mode.decay_time > 60.0
    assert plan.length == pytest.approx(3 * 3600 / math.sqrt(20.0), rel=1e-15)
    assert plan.scene.duration == pytest.approx(plan.spin_up + plan.length, rel=1e-15)
    from offshore_crane.motion.operations import Operation

    op = Operation.from_waypoints(plan.scene.operation)
    once = Operation.from_waypoints(scene.operation)
    t = np.linspace(0.0, 60.0, 601)
    for k in (0, 1, 7, 40):
        for a, b in zip(op(t + 60.0 * k), once(t)):
            assert np.abs(a - b).max() <= 1e-12
    opened = replace(scene, operation=scene.operation[:-1])
    with pytest.raises(SceneError, match=r"\[operation\] ends at \[1\.2, -0\.6, 0\.18\] but "
                       r"starts at \[0\.0, 0\.0, 0\.0\]: an exposure record repeats"):
        exposure.exposure_plan(opened, robot)


def test_the_judged_window_has_forgotten_the_start():
    """Two records of the hanging load from different initial sways (0.05 and 0.3 rad):
    after the 120 s spin-up (7.5 decay times of the sway mode) the judged window's sway
    differs by less than 1e-3 of the start's difference (linear decay: e^-7.5 = 5.5e-4)."""
    base = scenes.with_overrides(scenes.load_scene(SCENES / "hanging_load.toml"), "test",
                                 extremes={"exposure": 0.02})
    other = replace(base, cable={**base.cable, "initial": [0.3, 0.0]})
    a, b = (sweep.record(s).result.cable for s in (base, other))
    assert a.t[0] == pytest.approx(120.0)
    assert np.abs(a.sway - b.sway).max() <= 1e-3 * 0.25


def test_the_lightly_damped_warning_fires_on_an_undamped_cable_only():
    """No shipped scene has a mode damped below 1 %; the compensated lift with its sway
    damping removed (an undamped elastic cable's swing) warns, naming the mode."""
    for path in sorted(SCENES.glob("*.toml")):
        scene = scenes.load_scene(path)
        robot = scenes.load_robot(scene)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            exposure.warn_light_damping(exposure.scene_modes(scene, robot), str(path))
        assert not [w for w in caught if w.category is exposure.LightlyDampedWarning], path
    scene = scenes.load_scene(SCENES / "compensated_lift.toml")
    undamped = replace(scene, robot={**scene.robot, "payload.sway_damping": 0.0},
                       payload=None, arm=None)
    with pytest.warns(exposure.LightlyDampedWarning, match=r"sway phi1 and sway phi2 are "
                      r"lightly damped \(ω 3\.13 rad/s, ζ 0 %, decay time ∞, below 1 % of "
                      r"critical\): no record of it is stationary"):
        exposure.exposure_plan(undamped, scenes.load_robot(undamped))


def test_a_scenes_own_short_record_warns():
    """The hanging-load scene judged on its own 60 s record: shorter than 5 decay times
    of its sway mode (80 s): a ShortRecordWarning, and an observed verdict."""
    scene = replace(scenes.load_scene(SCENES / "hanging_load.toml"),
                    extremes={"record": "scene"})
    with pytest.warns(exposure.ShortRecordWarning, match=r"the record \(60 s\) is shorter "
                      r"than 5 decay times of the sway mode"):
        run = sweep.record(scene)
    assert run.exposure is None and run.t[0] == 0.0
    assert sizing.verdict([run.envelope] * 5, scale=20.0).basis == "observed"


@pytest.mark.parametrize("text, match", [
    ("[extremes]\nrecord = \"all\"\n", r"\[extremes\] record = \"all\": must be one of "
     r"exposure, scene"),
    ("[extremes]\nexposure = -1\n", r"\[extremes\] exposure = -1: must be > 0 h"),
    ("[extremes]\nseeds = 0\n", r"\[extremes\] seeds = 0: must be an integer ≥ 1"),
    ("[extremes]\nspin_up = -5\n", r"\[extremes\] spin_up = -5: must be ≥ 0 s"),
    ("[extremes]\nlength = 5\n", r"\[extremes\] unknown key 'length'"),
])
def test_bad_extremes_are_named(tmp_path, text, match):
    path = tmp_path / "s.toml"
    path.write_text((SCENES / "hanging_load.toml").read_text() + text)
    with pytest.raises(SceneError, match=match):
        scenes.load_scene(path)


def test_extremes_need_a_sea():
    with pytest.raises(SceneError, match=r"\[extremes\] judges a random sea's extremes"):
        scenes.Scene(extremes={"exposure": 1.0})


# --------------------------------------------------------------------------- 3-hour extremes
#: The quantities the acceptance names: sway, the smallest tension ratio, every leg's
#: force and the winch's speed (row column, +1 for a maximum, −1 for a minimum).
QUANTITIES = (("sway_max", 1.0), ("tension_ratio_min", -1.0),
              *((f"Fl{k}_peak_push", 1.0) for k in range(1, 7)), ("winch_speed", 1.0))


@pytest.mark.slow
@pytest.mark.parametrize("name", ["hanging_load"])
def test_the_default_3_hour_extreme_is_that_of_full_length_records(name):
    """The default verdict (size's: the Gumbel mode of the maxima of the scene's 5 seeds,
    each a stationary 3-hour record) of the sway, the smallest tension ratio, each leg's
    peak force and the winch's speed lies within 5 % (the issue's bound) of the median of
    the maxima of 20 other full-length stationary 3-hour records (seeds 6..25; the
    median of 20 carries ~2.5 % of sampling error itself for the sway, whose 3-hour
    maximum varies by ~9 % from record to record). The elastic compensated lift's 25
    records (64 s of CI) are heavy statistics: ``benchmarks/extremes.py`` runs them, with
    3 more groups of 5 seeds, and docs/sizing.md gives its deviations (within 4.0 % on
    2026-11-27)."""
    scene = scenes.load_scene(SCENES / f"{name}.toml")
    rows = sweep.run(scene, {"seed": list(range(1, 26))}, workers=2)
    assert (rows["status"] == "ok").all()
    default, other = rows[rows["seed"] <= 5], rows[rows["seed"] > 5]
    record = float(default["duration_s"].iloc[0]) * math.sqrt(20.0)
    verdict = sweep.verdicts(default, scene).iloc[0]
    assert verdict["basis"] == "gumbel" and verdict["record_s"] == record
    for column, sign in QUANTITIES:
        if other[column].isna().all():
            continue                                       # no winch on this scene
        mpm = sizing.most_probable_extreme(default[column], record, 3 * 3600.0, True, sign)
        median = float(other[column].median())
        assert mpm == pytest.approx(median, rel=0.05), column
