"""Issue 10, family 7 / issue 11: one path for every robot override.

Scene ``[robot]``, ``[payload]``, ``[subsystems] arm``, ``--robot`` and ``--set`` all reach
the robot through :mod:`offshore_crane.robot.overrides` and the description's checks; a
``--set`` that contradicts the scene is an error (exit status 2, one line), never a silent
choice.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane import scenes
from offshore_crane.__main__ import main
from offshore_crane.errors import SceneError

ROOT = Path(__file__).resolve().parents[2]
PLATFORM_ONLY = str(ROOT / "scenes" / "platform_only.toml")
HS_DESCRIPTION = str(ROOT / "models" / "descriptions" / "harib_srinivasan_2003.toml")
HS_SCENE = str(ROOT / "scenes" / "harib_srinivasan_2003.toml")


def _run(argv, capsys):
    status = main(argv)
    out, err = capsys.readouterr()
    return status, out, err


@pytest.mark.parametrize("argv, match", [
    (["--scene", PLATFORM_ONLY, "--set", "with_arm=1"],
     "--set arm.enabled = true contradicts the scene's [subsystems] arm = false"),
    (["--scene", PLATFORM_ONLY, "--set", "payload_mass=100"],
     "payload.mass: 100 kg: the payload hangs from the arm tip, but the robot has no arm"),
    (["--set", "with_arm=2"], "with_arm (arm.enabled)=2 must be true or false (1 or 0)"),
    (["--set", "with_arm=0.5"], "must be true or false"),
    (["--set", "platform_mass=1e308"], "exceeds the magnitude limit 1e+100"),
    (["--set", "legs.lower.mass=nan"], "is not finite"),
    (["--set", "legs.lower.mas=3"], "legs.lower has no 'mas'; did you mean 'legs.lower.mass'"),
    (["--set", "platform_mass=3", "--set", "platform.mass=4"],
     "platform_mass and platform.mass name the same field platform.mass"),
    (["--scene", HS_SCENE, "--robot", str(ROOT / "models" / "descriptions" / "lab.toml")],
     "contradicts the scene's [robot] description"),
    (["--robot", "nowhere.toml"], "--robot nowhere.toml: no such file"),
])
def test_contradictions_and_bad_overrides_are_one_line_exit_2(argv, match, capsys):
    status, out, err = _run(["id", *argv], capsys)
    assert status == 2 and out == ""
    assert err.startswith("offshore-crane: error: ") and err.count("\n") == 1
    assert match in err


def test_set_reaches_the_robot_and_the_report(tmp_path, capsys):
    """--set payload_mass=2 changes the arm torques exactly as the same [payload] in a
    scene file does, and the report says the payload is there."""
    out_set, out_scene = tmp_path / "set.csv", tmp_path / "scene.csv"
    status, report, _ = _run(["id", "--duration", "2", "--set", "payload_mass=2",
                              "--set", "payload_z=-0.05", "--out", str(out_set)], capsys)
    assert status == 0 and "payload 2 kg at (0, 0, -0.05) m from arm_tip" in report
    scene = tmp_path / "payload.toml"
    scene.write_text("[payload]\nmass = 2\noffset = [0, 0, -0.05]\n[trajectory]\n"
                     "duration = 2\n", encoding="utf-8")
    assert _run(["id", "--scene", str(scene), "--out", str(out_scene)], capsys)[0] == 0
    a = np.loadtxt(out_set, delimiter=",", skiprows=1)
    b = np.loadtxt(out_scene, delimiter=",", skiprows=1)
    np.testing.assert_array_equal(a, b)                 # the same path: bit for bit
    plain = tmp_path / "plain.csv"
    assert _run(["id", "--duration", "2", "--out", str(plain)], capsys)[0] == 0
    assert not np.array_equal(np.loadtxt(plain, delimiter=",", skiprows=1), a)


def test_set_without_contradiction_is_applied_on_top_of_the_scene(capsys):
    """--set with_arm=0 on a scene that does not set the arm removes it (the report and the
    actuators follow); the same value as the scene's is no contradiction."""
    status, report, _ = _run(["id", "--duration", "1", "--set", "with_arm=0"], capsys)
    assert status == 0 and "no arm" in report and "T1" not in report
    status, report, _ = _run(["id", "--scene", PLATFORM_ONLY, "--duration", "1",
                              "--set", "with_arm=false"], capsys)
    assert status == 0 and "no arm" in report


def test_robot_option_loads_another_description(capsys):
    csv = str(ROOT / "scenes" / "harib_srinivasan_2003_motion.csv")
    status, report, _ = _run(["id", "--robot", HS_DESCRIPTION, "--trajectory", csv,
                              "--method", "both"], capsys)
    assert status == 0 and "Kane vs RNEA" in report and "OK" in report
    status, report2, _ = _run(["id", "--scene", HS_SCENE], capsys)
    assert status == 0 and "OK" in report2


def test_library_scene_overrides_match_load_robot():
    """The scene's robot is load_robot(description, overrides): same object (memoised)."""
    scene = scenes.Scene(robot={"leg_lower_mass": 0.5}, payload=scenes.Payload(1.0))
    assert scene.robot == {"legs.lower.mass": 0.5, "payload.mass": 1.0,
                           "payload.com": [0.0, 0.0, 0.0],
                           "payload.inertia": dict.fromkeys(
                               ("ixx", "iyy", "izz", "ixy", "ixz", "iyz"), 0.0),
                           "payload.cable_length": 0.0, "payload.sway_damping": 0.0,
                           "payload.drag_area": 0.0, "payload.air_density": 1.225}
    robot = scenes.load_robot(scene)
    assert robot is oc.load_robot(overrides=scene.robot)
    assert robot.hybrid.lower_mass.tolist() == [0.5] * 6


def test_with_robot_overrides_refuses_a_contradiction():
    scene = scenes.Scene(robot={"platform_mass": 10.0})
    with pytest.raises(SceneError, match=r"--set platform\.mass = 11 contradicts the "
                       r"scene's \[robot\] platform\.mass = 10"):
        scenes.with_robot_overrides(scene, {"platform.mass": 11.0})
    same = scenes.with_robot_overrides(scene, {"platform.mass": 10.0})
    assert same.robot["platform.mass"] == 10.0


def test_actuators_section_is_a_description_override(tmp_path, capsys):
    """[actuators] sets actuators.* through the same path: a bad key or value is named,
    and a --set contradicting it is an error."""
    good = tmp_path / "good.toml"
    good.write_text("[actuators]\nFl.push_max = 3000.0\n", encoding="utf-8")
    scene = scenes.load_scene(good)
    assert scene.robot == {"actuators.Fl.push_max": 3000.0}
    assert scenes.load_robot(scene).capacities.push_max[3:].tolist() == [3000.0] * 6
    status, _, err = _run(["id", "--scene", str(good), "--set", "leg_force_limit=10"], capsys)
    assert status == 2 and ("--set actuators.Fl.push_max = 10 contradicts the scene's "
                            "[actuators] Fl.push_max = 3000") in err
    bad = tmp_path / "bad.toml"
    bad.write_text("[actuators]\nFl.push = 3000.0\n", encoding="utf-8")
    with pytest.raises(SceneError, match=r"\[actuators\] unknown field 'actuators\.Fl\.push'"):
        scenes.load_scene(bad)
    bad.write_text("[actuators]\nFl.push_max = -1.0\n", encoding="utf-8")
    with pytest.raises(SceneError, match=r"actuators\.Fl\.push_max"):
        scenes.load_scene(bad)


def test_describe_writes_the_yaml_the_xacro_reads(tmp_path, capsys):
    """`describe` prints the resolved description; expanding the xacro with it gives the
    URDF load_robot builds (same overrides)."""
    import yaml
    from offshore_crane.robot.xacro_cache import run_xacro

    out = tmp_path / "lab.yaml"
    assert main(["describe", "--set", "platform_mass=55", "--out", str(out)]) == 0
    data = yaml.safe_load(out.read_text(encoding="utf-8"))
    assert data["platform"]["mass"] == 55.0
    urdf = run_xacro(out.read_text(encoding="utf-8"))
    robot = oc.load_robot(platform_mass=55)
    assert urdf.split("\n", 3)[3] == robot.urdf.split("\n", 3)[3]   # past xacro's header
    status, _, err = _run(["describe", "--set", "platform_mass=-1"], capsys)
    assert status == 2 and "platform.mass: -1 kg is negative" in err
