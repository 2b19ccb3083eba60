"""Issue 12 at the user's end: the ``[sea]``/``[operation]`` scene sections, the
``motion`` command, ``id`` on its CSV, Welch against SciPy, and the bad inputs the issue
lists (one line, exit status 2, no partial file)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane import scenes
from offshore_crane.motion import sea
from offshore_crane.motion import trajectories
from offshore_crane.__main__ import main
from offshore_crane.errors import SceneError

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "scenes" / "sea_state_crane.toml"
SEA = ["--hs", "2.5", "--tp", "8", "--heading", "90", "--scale", "20"]
#: Kane against RNEA (docs/conventions.md, AGREEMENT_RTOL).
AGREEMENT = 1e-9


def _run(argv, capsys):
    status = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return status, out, err


def test_example_scene_runs_kane_equals_rnea(capsys):
    status, out, err = _run(["id", "--scene", SCENE, "--method", "both", "--duration", "20"],
                            capsys)
    assert status == 0 and err == ""
    assert "trajectory sea Hs 2.5 m Tp 8 s heading 90° at scale 20, 2001 samples" in out
    assert "Kane vs RNEA" in out and "(OK, limit 1e-09)" in out


def test_scene_trajectory_is_the_library_record():
    """The scene's record is sea.platform_trajectory with the same arguments, and the
    operation drives q7..q9 with its waypoints' positions."""
    scene = scenes.load_scene(SCENE)
    robot = scenes.load_robot(scene)
    traj = scenes.load_trajectory(scene, robot)
    ref = sea.platform_trajectory(60.0, 100.0, 2.5, 8.0, 90.0, 20.0, robot, seed=1,
                                  highpass=0.2, operation=[list(r) for r in scene.operation])
    for a, b in ((traj.q, ref.q), (traj.qd, ref.qd), (traj.qdd, ref.qdd)):
        np.testing.assert_array_equal(a, b)
    k = np.searchsorted(traj.t, 30.0)
    np.testing.assert_allclose(traj.q[k, 6:], (1.2, -0.6, 0.18), atol=1e-12)
    q, qd, qdd = traj.reference(np.array([12.3456]))      # analytic at any time
    np.testing.assert_array_equal(q, traj.source(np.array([12.3456]))[0])


def test_motion_csv_round_trips_through_id(tmp_path, capsys):
    """motion --out writes the analytic rates; id --trajectory reads them instead of
    differencing: the forces equal those of the scene itself, bit for bit."""
    csv, forces_csv, forces_scene = (tmp_path / n for n in ("m.csv", "a.csv", "b.csv"))
    status, out, _ = _run(["motion", "--scene", SCENE, "--duration", "10", "--out", csv],
                          capsys)
    assert status == 0 and "every sample inside the workspace" in out
    t, q, qd, qdd = trajectories.read_csv(csv, derivatives=True)
    assert qd is not None and q.shape == (1001, 9)
    assert _run(["id", "--scene", SCENE, "--trajectory", csv, "--out", forces_csv],
                capsys)[0] == 0                       # the scene's robot and payload
    assert _run(["id", "--scene", SCENE, "--duration", "10", "--out", forces_scene],
                capsys)[0] == 0
    np.testing.assert_array_equal(np.loadtxt(forces_csv, delimiter=",", skiprows=1),
                                  np.loadtxt(forces_scene, delimiter=",", skiprows=1))
    assert _run(["motion", *SEA, "--duration", "5", "--no-derivatives", "--out", csv],
                capsys)[0] == 0
    assert trajectories.read_csv(csv, derivatives=True)[2] is None


def test_motion_plot_and_stdout(tmp_path, capsys):
    plot = tmp_path / "m.png"
    status, out, err = _run(["motion", *SEA, "--duration", "30", "--out", "-", "--plot", plot],
                            capsys)
    assert status == 0 and out.startswith("t_s,q1_m,") and "coordinate unit" in err
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_welch_equals_scipy():
    """The NumPy Welch estimate (what the plot shows) is SciPy's density per Hz / 2π."""
    from scipy import signal
    rng = np.random.default_rng(7)
    x = rng.standard_normal((5000, 2)).cumsum(axis=0)
    omega, S = sea.welch(x, 50.0, 512)
    f, P = signal.welch(x, fs=50.0, nperseg=512, axis=0)
    np.testing.assert_allclose(omega, 2 * np.pi * f, rtol=1e-15)
    np.testing.assert_allclose(S, P / (2 * np.pi), rtol=1e-12, atol=0)


def _bad_rao(tmp_path, kind):
    """RAO files with the defects the issue lists."""
    head = "omega_rad_s,heading_deg,dof,amplitude,phase_rad"
    rows = [f"{w},{h},{d},1.0,0.0" for h in (0.0, 90.0, 180.0, 270.0) for w in (0.3, 1.0, 2.0)
            for d in sea.DOFS]
    if kind == "missing-dof":
        rows = [r for r in rows if not r.startswith("1.0,90.0,roll")]
    elif kind == "negative":
        rows[5] = rows[5].replace(",1.0,0.0", ",-1.0,0.0")
    elif kind == "omega-order":
        rows[0], rows[6] = rows[6], rows[0]
    elif kind == "duplicate":
        rows.append(rows[3])
    elif kind == "text":
        rows[4] = rows[4].replace(",1.0,0.0", ",one,0.0")
    elif kind == "half-circle":
        rows = [r for r in rows if r.split(",")[1] in ("0.0", "90.0")]
    path = tmp_path / f"{kind}.csv"
    path.write_text("\n".join([head, *rows]) + "\n", encoding="utf-8")
    return path


@pytest.mark.parametrize("extra, match", [
    (["--hs", "0"], "hs = 0.0 m must be > 0"),
    (["--hs", "-2"], "hs = -2.0 m must be > 0"),
    (["--tp", "0"], "tp = 0.0 s must be > 0"),
    (["--gamma", "0.5"], "gamma = 0.5 - must be >= 1"),
    (["--hs", "nan"], "hs = nan is not finite"),
    (["--scale", "-20"], "scale = -20.0 - must be > 0"),
    (["--scale", "nan"], "scale = nan is not finite"),
    (["--vessel", "missing-dof"], "missing dof roll"),
    (["--vessel", "negative"], "is negative"),
    (["--vessel", "omega-order"], "does not increase"),
    (["--vessel", "duplicate"], "duplicate row"),
    (["--vessel", "text"], "'one' is not a number"),
    (["--vessel", "half-circle", "--heading", "200"], "heading 200 deg is not covered"),
    (["--vessel", "tanker"], "unknown vessel 'tanker'"),
])
def test_bad_motion_inputs_are_one_line_exit_2(tmp_path, capsys, extra, match):
    argv = list(SEA)
    for i in range(0, len(extra), 2):
        flag, value = extra[i], extra[i + 1]
        if flag == "--vessel" and value != "tanker":
            value = str(_bad_rao(tmp_path, value))
        if flag in argv:
            argv[argv.index(flag) + 1] = value
        else:
            argv += [flag, value]
    out = tmp_path / "motion.csv"
    status, stdout, err = _run(["motion", *argv, "--duration", "10", "--out", out], capsys)
    assert status == 2 and stdout == "" and err.count("\n") == 1, err
    assert err.startswith("offshore-crane: error: ") and match in err
    assert not out.exists() and list(tmp_path.glob(".oc-*")) == []


def test_operation_outside_the_arm_limits(tmp_path):
    """The waypoints' limits are the robot's: checked when the record is built."""
    path = tmp_path / "op.toml"
    path.write_text('[trajectory]\nsource = "sea"\n[sea]\nhs = 2\ntp = 8\nheading = 90\n'
                    "scale = 20\n[operation]\nwaypoints = [[0, 0, 0, 0], [1, 0, 0, 0.5]]\n",
                    encoding="utf-8")
    scene = scenes.load_scene(path)
    with pytest.raises(SceneError, match=r"\[operation\] waypoint 1: q9 \(arm_slide\) = 0\.5 m "
                       r"is outside the joint's limits \[-0\.2, 0\.2\] m") as info:
        scenes.load_trajectory(scene, scenes.load_robot(scene))
    assert info.value.name == "operation.waypoints"


def test_workspace_error_names_the_smallest_scale(tmp_path, capsys):
    out = tmp_path / "m.csv"
    status, _, err = _run(["motion", "--hs", "4", "--tp", "9", "--heading", "180", "--scale",
                           "5", "--duration", "60", "--out", out], capsys)
    assert status == 2 and not out.exists()
    assert "leaves the workspace" in err and "fits from scale 8.0" in err


def test_id_on_a_sea_scene_names_the_smallest_scale_too(tmp_path, capsys):
    """id leaves the record's workspace check to Kane's (limits on: computed once); its
    error becomes the record's own, the same line as the motion command's, naming the
    smallest scale that fits. With --no-limits the record is checked when loaded, as
    before."""
    path = tmp_path / "small.toml"
    path.write_text('[trajectory]\nsource = "sea"\nduration = 60\n[sea]\nhs = 4\ntp = 9\n'
                    "heading = 180\nscale = 5\n", encoding="utf-8")
    lines = []
    for extra in ([], ["--no-limits"]):
        status, _, err = _run(["id", "--scene", path, *extra], capsys)
        assert status == 2 and "leaves the workspace" in err and "fits from scale 8.0" in err
        lines.append(err)
    status, _, err = _run(["motion", "--hs", "4", "--tp", "9", "--heading", "180", "--scale",
                           "5", "--duration", "60", "--out", tmp_path / "m.csv"], capsys)
    assert lines == [err, err]


@pytest.mark.parametrize("text, key, match", [
    ('[trajectory]\nsource = "sea"\n', "sea", 'needs [sea] hs, tp, heading, scale'),
    ("[sea]\nhs = 2\n", "sea", '[sea] applies to [trajectory] source = "sea"'),
    ('[trajectory]\nsource = "sea"\n[sea]\nhs = 2\ntp = 8\nheading = 90\nscale = 20\n'
     "gamma = 0.5\n", "sea.gamma", "[sea] gamma = 0.5 - must be >= 1"),
    ('[trajectory]\nsource = "sea"\n[sea]\nhs = 2\ntp = 8\nheading = 90\nscale = 20\n'
     'vessel = "nowhere.csv"\n', "sea.vessel", "neither a shipped vessel (supply) nor a file"),
    ('[trajectory]\nsource = "sea"\nfd_order = 4\n[sea]\nhs = 2\ntp = 8\nheading = 90\n'
     "scale = 20\n", "trajectory.fd_order", "a sea state has analytic derivatives"),
    ('[trajectory]\nsource = "sea"\n[sea]\nhs = 2\ntp = 8\nheading = 90\nscale = 20\n'
     "[operation]\nwaypoints = [[0, 0, 0]]\n", "operation.waypoints",
     "must be a list of [t, q7, q8, q9] rows"),
    ('[trajectory]\nsource = "sea"\n[subsystems]\nplatform = false\n[sea]\nhs = 2\ntp = 8\n'
     "heading = 90\nscale = 20\n", "sea", "[sea] moves the platform"),
    ("[sea]\nheigth = 2\n", "sea.heigth", "[sea] unknown key 'heigth'"),
])
def test_bad_sea_scenes(tmp_path, text, key, match):
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(SceneError, match=None) as info:
        scenes.load_scene(path)
    assert match in str(info.value), str(info.value)
    assert info.value.name == key and str(info.value).startswith(str(path))


def test_motion_imports_nothing_heavy(tmp_path):
    """A short record on a warm URDF cache: neither Numba (~1.2 s to load), Pinocchio,
    matplotlib nor SciPy is imported (the workspace check runs the NumPy kernels)."""
    import subprocess
    import sys

    out = tmp_path / "m.csv"
    code = ("import sys; from offshore_crane.__main__ import main; "
            f"assert main(['motion', '--hs', '2.5', '--tp', '8', '--heading', '90', "
            f"'--scale', '20', '--duration', '5', '--out', {str(out)!r}]) == 0; "
            "bad = [m for m in ('numba', 'pinocchio', 'matplotlib', 'scipy', 'yourdfpy') "
            "if m in sys.modules]; assert not bad, bad")
    oc.load_robot()                                       # warm the URDF cache
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
