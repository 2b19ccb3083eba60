"""Scenes (issue 4): TOML files, sub-systems, payload, exact pruning, fidelity report.

Tolerances:
- EXACT = 1e-12 relative: a pruned computation skips terms that are exact zeros (or
  columns the output does not depend on), so it differs from the unpruned one by
  round-off only (observed ≤ 1e-15).
- AGREE = 1e-9 relative: Kane against RNEA, as docs/conventions.md asks (observed ~1e-15).
"""

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import offshore_crane as oc
from conftest import relative_error
from offshore_crane import scenes
from offshore_crane.__main__ import main
from offshore_crane.dynamics import runtime
from offshore_crane.dynamics import REGISTRY, solve
from offshore_crane.dynamics.kernels import Options
from offshore_crane.robot.kinematics import legs as leg_kinematics
from offshore_crane.robot.kinematics.formulas import FULL, MASSLESS
from offshore_crane.errors import SceneError
from offshore_crane.validation import as_gravity
from problems import random_states

EXACT = 1e-12
AGREE = 1e-9
G = as_gravity((0.0, 0.0, -9.81))      # read-only, as the public functions hand it on
SCENES = Path(__file__).resolve().parents[2] / "scenes"
EXAMPLES = ("full_crane", "platform_only", "arm_fixed_deck", "crane_with_payload")
ARM = ["T1", "T2", "Fs"]


def example(name: str) -> scenes.Scene:
    return scenes.load_scene(SCENES / f"{name}.toml")


@pytest.fixture
def numpy_kernel(monkeypatch):
    """Make solve() use the NumPy backend (whose Python functions can be traced)."""
    monkeypatch.setattr(runtime, "numba_available", lambda: False)


# --------------------------------------------------------------------------- examples
@pytest.mark.parametrize("name", EXAMPLES)
def test_example_scene_loads_and_runs(name):
    scene = example(name)
    done = scenes.run(scene)
    res = done.result
    assert len(done.trajectory) == 3142                  # Table 1 default span
    assert res.outputs == scene.wanted()
    cols = [oc.ACTUATORS.index(n) for n in res.outputs]
    assert np.isfinite(res.X[:, cols]).all()
    others = [k for k in range(9) if k not in cols]
    assert np.isnan(res.X[:, others]).all()              # not computed, not invented
    for _, _, _, rel, _, _ in scenes.compare_methods(done):
        assert rel <= AGREE


@pytest.mark.parametrize("name", EXAMPLES)
def test_example_scene_runs_from_the_command_line(name, capsys):
    assert main(["id", "--scene", str(SCENES / f"{name}.toml"), "--duration", "2"]) == 0
    out = capsys.readouterr().out
    assert out.startswith(f"scene {example(name).name} (") and "201 samples" in out


def test_sub_systems_of_the_examples():
    assert example("full_crane").actuators() == tuple(oc.ACTUATORS)
    assert example("platform_only").actuators() == tuple(oc.ACTUATORS[3:])
    assert example("arm_fixed_deck").actuators() == tuple(ARM)
    payload = example("crane_with_payload").payload
    assert payload.mass == 2.0 and payload.offset == (0.0, 0.0, -0.05)


# --------------------------------------------------------------------------- robot variants
def test_robot_without_arm():
    robot = oc.load_robot(with_arm=0)
    names = set(robot.description.inertials)
    assert not names & {"arm_column", "arm_link1", "arm_link2", "arm_slider", "arm_tip",
                        "payload"}
    assert robot.hybrid.arm.n == 0 and robot.hybrid.actuators == tuple(oc.ACTUATORS[3:])
    assert robot.hybrid.platform_mass == pytest.approx(40.0, rel=1e-14)  # plate only
    q, qd, qdd = random_states(robot, 20, seed=5)
    res = solve(robot, q, qd, qdd)
    assert res.outputs == tuple(oc.ACTUATORS[3:]) and np.isnan(res.X[:, :3]).all()
    for method in ("kane", "rnea"):
        with pytest.raises(oc.InputError, match="outputs T1 do not exist: the robot has no arm"):
            solve(robot, q, qd, qdd, method=method, outputs=["T1", "Fl1"])
    # the kernels cope with 0 arm joints on every backend: arrays, Python floats
    # (N ≤ PYTHON_MAX) and compiled; same formulas, so round-off only
    for n, backend in ((20, "numpy"), (3, "numpy"), (20, "numba")):
        Xv = REGISTRY[("kane", backend)](robot, q[:n], qd[:n], qdd[:n], G, Options(), 1)[0]
        assert np.isnan(Xv[:, :3]).all()
        assert relative_error(Xv[:, 3:], res.X[:n, 3:]) < EXACT


def test_with_arm_override_is_a_boolean():
    robot = oc.load_robot(with_arm=1)                     # 0/1 or true/false only
    assert robot.overrides == {"arm.enabled": True}
    assert robot.urdf == oc.load_robot().urdf
    with pytest.raises(oc.ModelError, match=r"with_arm \(arm.enabled\)=0.5 must be true "
                       r"or false"):
        oc.load_robot(with_arm=0.5)


def test_payload_is_part_of_both_models():
    import pinocchio as pin
    base = oc.load_robot()
    robot = scenes.load_robot(example("crane_with_payload"))
    assert robot.hybrid.total_mass == pytest.approx(base.hybrid.total_mass + 2.0, rel=1e-14)
    model = robot.pinocchio_model
    data = model.createData()
    pin.computeTotalMass(model, data)
    assert data.mass[0] == pytest.approx(robot.hybrid.total_mass, rel=1e-14)
    # the slider carries it: its mass grows by 2 kg, its CoM moves towards the tip
    assert robot.hybrid.arm.mass[2] == pytest.approx(base.hybrid.arm.mass[2] + 2.0)
    assert robot.hybrid.arm.com[2, 0] > base.hybrid.arm.com[2, 0]


def test_payload_static_equilibrium():
    """Massless legs, everything at rest: the legs carry exactly the weight above them."""
    scene = scenes.Scene(robot={"leg_lower_mass": 0.0, "leg_upper_mass": 0.0},
                         payload=scenes.Payload(2.0, (0.01, 0.02, -0.05)))
    robot = scenes.load_robot(scene)
    rng = np.random.default_rng(9)
    q = np.zeros((5, 9))
    q[:, 2] = 0.5
    q[:, 6:] = rng.uniform([-3.0, -1.5, -0.15], [3.0, 1.5, 0.15], size=(5, 3))
    zero = np.zeros_like(q)
    u = leg_kinematics(robot, q).u                                    # (5, 6, 3)
    weight = robot.hybrid.total_mass * 9.81
    for method in ("kane", "kane-explicit", "rnea"):
        X = oc.inverse_dynamics(robot, q, zero, zero, method=method)
        lift = np.einsum("nl,nlk->nk", X[:, 3:], u)
        np.testing.assert_allclose(lift, np.tile([0.0, 0.0, weight], (5, 1)),
                                   rtol=0, atol=1e-10 * weight)
        # gravity along the arm's vertical joint axes, slider horizontal: no arm load
        np.testing.assert_allclose(X[:, :3], 0.0, atol=1e-10 * weight)


@pytest.mark.parametrize("name", ["crane_with_payload", "platform_only"])
def test_kane_agrees_with_rnea(name):
    """Both paths read the xacro's payload and with_arm the same way."""
    scene = example(name)
    robot = scenes.load_robot(scene)
    q, qd, qdd = random_states(robot, 500, seed=44)
    Xr = oc.inverse_dynamics(robot, q, qd, qdd, method="rnea")
    cols = [oc.ACTUATORS.index(n) for n in scene.wanted()]
    for method in ("kane", "kane-explicit"):
        Xk = oc.inverse_dynamics(robot, q, qd, qdd, method=method)
        assert relative_error(Xk[:, cols], Xr[:, cols]) <= AGREE
    done = scenes.run(scenes.with_overrides(scene, "test", methods=("kane", "rnea")))
    assert scenes.compare_methods(done)[0][3] <= AGREE


# --------------------------------------------------------------------------- pruning is exact
@pytest.mark.parametrize("backend", ["numba", "numpy"])
def test_arm_only_outputs_are_exact(robot, table1, backend, monkeypatch):
    _, q, qd, qdd = table1
    full = solve(robot, q, qd, qdd, backend=backend)
    arm = solve(robot, q, qd, qdd, outputs=ARM, backend=backend)
    assert relative_error(arm.X[:, :3], full.X[:, :3]) < EXACT
    assert any("leg kinematics" in p for p in arm.pruned)


def test_fixed_deck_equals_the_full_robot_held_still():
    """The fixed-deck scene (legs skipped, static platform) against the unpruned kernel
    on the full robot with q1..q6 held at the deck pose."""
    scene = example("arm_fixed_deck")
    done = scenes.run(scene)
    res, traj = done.result, done.trajectory
    assert any("static platform" in p for p in res.pruned)
    assert any("leg kinematics" in p for p in res.pruned)
    np.testing.assert_array_equal(traj.q[:, :6], np.tile(scenes.deck_pose(scene, done.robot),
                                                         (len(traj), 1)))
    for backend in ("numpy", "numba"):
        ref = REGISTRY[("kane", backend)](done.robot, traj.q, traj.qd, traj.qdd, G,
                                          Options(legs=True, static=False), 1)[0]
        assert relative_error(res.X[:, :3], ref[:, :3]) < EXACT
    Xr = oc.inverse_dynamics(done.robot, traj.q, traj.qd, traj.qdd, method="rnea")
    assert relative_error(res.X[:, :3], Xr[:, :3]) <= AGREE


def test_massless_leg_robot_skips_leg_inertia_exactly(table1):
    light = oc.load_robot(leg_lower_mass=0.0, leg_upper_mass=0.0)
    _, q, qd, qdd = table1
    res = solve(light, q, qd, qdd)
    assert any("the legs have no mass" in p for p in res.pruned)
    assert res.approximations == ()                       # exact for this robot
    for backend in ("numpy", "numba"):
        ref = REGISTRY[("kane", backend)](light, q, qd, qdd, G, Options(leg_model=FULL), 1)[0]
        assert relative_error(res.X, ref) < EXACT
    assert not any("no mass" in p for p in solve(oc.load_robot(), q, qd, qdd).pruned)


# --------------------------------------------------------------------------- skips happen
def test_legs_not_evaluated_for_arm_outputs(robot, numpy_kernel, monkeypatch):
    from offshore_crane.dynamics import formulas

    calls = []
    legs = formulas.leg_force

    def counting(*args, **kwargs):
        calls.append(1)
        return legs(*args, **kwargs)

    monkeypatch.setattr(formulas, "leg_force", counting)
    q, qd, qdd = random_states(robot, 100, seed=3)
    solve(robot, q, qd, qdd, outputs=ARM)
    assert calls == []
    solve(robot, q, qd, qdd)
    assert calls                                           # the counter does count


def test_options_passed_to_the_kernel(robot, monkeypatch):
    seen = []
    for key in (("kane", "numpy"), ("kane", "numba")):
        def spy(robot, q, qd, qdd, g, opts, threads, entry=REGISTRY[key]):
            seen.append(opts)
            return entry(robot, q, qd, qdd, g, opts, threads)

        monkeypatch.setitem(REGISTRY, key, spy)
    deck = scenes.run(example("arm_fixed_deck"))
    assert not seen[-1].legs and seen[-1].static and deck.result.condition is None
    light = scenes.Scene(robot={"leg_lower_mass": 0.0, "leg_upper_mass": 0.0},
                         trajectory="table1", duration=1.0)
    scenes.run(light)
    assert seen[-1].leg_model == MASSLESS and seen[-1].legs


@pytest.mark.parametrize("name", ["platform_only", "arm_fixed_deck"])
def test_kane_scene_imports_nothing_heavy(name, tmp_path, monkeypatch):
    """Warm URDF cache, Kane only, no --plot: neither Pinocchio, matplotlib, yourdfpy nor
    xacro is imported."""
    from offshore_crane.robot import description, xacro_cache

    monkeypatch.setenv("OFFSHORE_CRANE_CACHE", str(tmp_path))
    path = SCENES / f"{name}.toml"
    scene = scenes.load_scene(path)
    xacro_cache.expand(description.resolve(scene.robot_description,
                                           scene.robot_overrides()).xacro_data())
    code = ("import sys; from offshore_crane.__main__ import main; "
            f"assert main(['id', '--scene', {str(path)!r}, '--duration', '1']) == 0; "
            "bad = [m for m in ('pinocchio', 'matplotlib', 'yourdfpy', 'xacro') "
            "if m in sys.modules]; assert not bad, bad")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env={**os.environ, "OFFSHORE_CRANE_CACHE": str(tmp_path)})
    assert proc.returncode == 0, proc.stderr


# --------------------------------------------------------------------------- fidelity
def test_fidelity_report(capsys):
    scene = scenes.with_overrides(example("full_crane"), "test", methods=("kane",),
                                  duration=2.0)
    names, scale, rows = scenes.compare_fidelity(scene, repeat=1)
    assert [r.leg_model for r in rows] == ["full", "thin-rod", "massless"]
    assert rows[0].approximations == () and not rows[0].deviation.any()
    assert all(r.approximations for r in rows[1:])
    assert np.all(rows[1].deviation[:3] == 0.0)            # arm forces: legs irrelevant
    assert 0 < rows[1].relative.max() < rows[2].relative.max() < 0.5
    assert main(["id", "--scene", str(SCENES / "full_crane.toml"), "--method", "kane",
                 "--duration", "2", "--compare-fidelity"]) == 0
    out = capsys.readouterr().out
    assert "fidelity of the leg models against 'full'" in out
    for model in ("full", "thin-rod", "massless"):
        assert re.search(rf"^{model} +\d+\.\d+ +\d+\.\d+ ", out, re.M)
    assert re.search(r"^Fl6 +N +[\d.]+ +[\d.e+-]+ +[\d.e+-]+ +[\d.e+-]+ +[\d.e+-]+$", out,
                     re.M)


# --------------------------------------------------------------------------- bad scenes
BAD = [
    ("[payload]\nmass = -1\n", "payload.mass",
     "with payload.mass = -1: payload.mass: -1 kg is negative"),
    ("[payload]\nmass = 1\ninertia = { ixx = 1, iyy = 1, izz = -1 }\n", "payload.inertia",
     "payload.inertia: not positive definite"),
    ("[payload]\nmass = 1\ninertia = { ixx = 1, iyy = 1, izz = 3 }\n", "payload.inertia",
     "break the triangle inequality"),
    ("[payload]\ninertia = { ixx = 1, iyy = 1, izz = 1 }\n", "payload.inertia",
     "an inertia without mass"),
    ("[payload]\nmass = 1\ninertia = { ixx = 1, iyy = 1, izz = 1, iyx = 0 }\n",
     "payload.inertia.iyx", "[payload.inertia] unknown key 'iyx'"),
    ("[payload]\nmass = 2\noffset = [0, 0]\n", "payload.com",
     "payload.com: [0, 0] must be a list of 3 numbers [m]"),
    ("[payload]\nmas = 2\n", "payload.mas", "[payload] unknown key 'mas'"),
    ("[payloads]\nmass = 2\n", "payloads", "unknown section [payloads]"),
    ("gravty = [0, 0, -9.81]\n", "gravty", "unknown key 'gravty'"),
    ("gravity = [0, 0]\n", "gravity", "gravity = [0, 0]: must be a list of 3 finite numbers"),
    ("gravity = [0, 0, nan]\n", "gravity", "gravity = [0, 0, nan]: must be a list of 3"),
    ('gravity = "down"\n', "gravity", 'gravity = "down": must be a list of 3'),
    ('outputs = ["T1", "T3"]\n', "outputs", "outputs = [\"T1\", \"T3\"]: unknown 'T3'"),
    ("outputs = []\n", "outputs", "outputs = []: must be a non-empty list"),
    ('outputs = ["T1", "T1"]\n', "outputs", "names a value twice"),
    ('methods = ["newton"]\n', "methods", "methods = [\"newton\"]: unknown 'newton'"),
    ('[subsystems]\nleg_model = "stick"\n', "subsystems.leg_model",
     '[subsystems] leg_model = "stick": must be one of full, thin-rod, massless'),
    ('[subsystems]\nplatform = "yes"\n', "subsystems.platform",
     '[subsystems] platform = "yes": must be true or false'),
    ("[subsystems]\nplatform = false\narm = false\n", "subsystems.arm",
     "nothing is left to simulate"),
    ("[subsystems]\ndeck_pose = [0, 0, 0.5, 0, 0, 0]\n", "subsystems.deck_pose",
     "applies to platform = false"),
    ("[subsystems]\narm = false\n[payload]\nmass = 2\n", "payload.mass",
     "payload.mass: 2 kg: the payload hangs from the arm tip, but the robot has no arm"),
    ('outputs = ["Fl1"]\n[subsystems]\nplatform = false\n', "outputs",
     "Fl1 do not exist with [subsystems] platform = false"),
    ('outputs = ["T2"]\n[subsystems]\narm = false\n', "outputs",
     "T2 do not exist with [subsystems] arm = false"),
    ('methods = ["kane", "rnea"]\n[subsystems]\nleg_model = "thin-rod"\n',
     "subsystems.leg_model", "an approximation offered by method kane only"),
    ('[subsystems]\nplatform = false\nleg_model = "massless"\n', "subsystems.leg_model",
     "platform = false (no legs)"),
    ("[robot]\nplatfrom_mass = 3\n", "platfrom_mass",
     "[robot] unknown robot parameter 'platfrom_mass'; did you mean platform_mass"),
    ("[robot]\nplatform_mass = -3\n", "platform.mass", "platform.mass: -3 kg is negative"),
    ('[robot]\nplatform_mass = "heavy"\n', "platform.mass",
     "[robot] robot parameter platform_mass (platform.mass)='heavy' is not a number"),
    ("[robot]\npayload_mass = 3\n[payload]\nmass = 2\n", "payload.mass",
     "[payload] mass = 2 contradicts [robot] payload.mass = 3: give it once"),
    ("[robot]\nwith_arm = 0.5\n", "arm.enabled", "=0.5 must be true or false (1 or 0)"),
    ("[robot]\nwith_arm = 1\n[subsystems]\narm = false\n", "arm.enabled",
     "[subsystems] arm = false contradicts [robot] arm.enabled = true"),
    ('[robot]\ndescription = "nowhere.toml"\n', "robot.description", "no such file"),
    ("robot = 3\n", "robot", "robot = 3: must be a table [robot]"),
    ('[trajectory]\nsource = "nope.csv"\n', "trajectory.source", "no such file"),
    ("[trajectory]\nduration = -2\n", "trajectory.duration",
     "[trajectory] duration = -2: must be > 0 s"),
    ("[trajectory]\nfd_order = 4\n", "trajectory.fd_order", "applies to a CSV trajectory"),
    ("[trajectory]\nrat = 4\n", "trajectory.rat", "[trajectory] unknown key 'rat'"),
]


@pytest.mark.parametrize("text, key, match", BAD, ids=[b[1] + ":" + b[2][:20] for b in BAD])
def test_bad_scene_names_file_and_key(tmp_path, text, key, match):
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(SceneError, match=re.escape(f"{path}: ")) as info:
        scenes.load_scene(path)
    assert match in str(info.value)
    assert info.value.name == key and info.value.path == str(path)
    assert isinstance(info.value, oc.InputError) and "\n" not in str(info.value)


@pytest.mark.parametrize("build, key, match", [
    (lambda: scenes.Scene(payload=scenes.Payload(mass=-1.0)), "payload.mass",
     "payload.mass: -1 kg is negative"),
    (lambda: scenes.Scene(payload=scenes.Payload(1.0, inertia=(1.0, 1.0, 3.0, 0.0, 0.0, 0.0))),
     "payload.inertia", "triangle inequality"),
    (lambda: scenes.Scene(platform=False, outputs=("Fl1",)), "outputs",
     "scene 'default': outputs = [\"Fl1\"]: Fl1 do not exist"),
    (lambda: scenes.Scene(methods=("newton",)), "methods", "must be names out of"),
    (lambda: scenes.Scene(robot={"with_arm": 1}, arm=False), "arm.enabled",
     "arm.enabled = false contradicts robot arm.enabled = true"),
    (lambda: scenes.with_overrides(scenes.Scene(), "the CLI", leg_model="thin-rod",
                                   methods=("rnea",)),
     "subsystems.leg_model", "the CLI: [subsystems] leg_model = \"thin-rod\""),
])
def test_scenes_built_in_python_are_checked(build, key, match):
    with pytest.raises(SceneError, match=re.escape(match)) as info:
        build()
    assert info.value.name == key


def test_csv_trajectory_scene(tmp_path):
    from offshore_crane.motion import trajectories

    t = np.arange(0.0, 2.0, 0.01)
    trajectories.write_csv(tmp_path / "motion.csv", t, trajectories.table1(t)[0])
    path = tmp_path / "s.toml"
    path.write_text('[trajectory]\nsource = "motion.csv"\nfd_order = 6\n'
                    "[subsystems]\nplatform = false\n", encoding="utf-8")
    scene = scenes.load_scene(path)                       # relative to the scene's folder
    assert scene.trajectory == str(tmp_path / "motion.csv") and scene.fd_order == 6
    done = scenes.run(scene)
    assert len(done.trajectory) == 200 and done.result.outputs == tuple(ARM)
    bad = tmp_path / "b.toml"
    bad.write_text('[trajectory]\nsource = "motion.csv"\nrate = 50\n', encoding="utf-8")
    with pytest.raises(SceneError, match="rate = 50: applies to table1 only"):
        scenes.load_scene(bad)


def test_unreadable_scene_files(tmp_path):
    with pytest.raises(SceneError, match=re.escape(f"{tmp_path / 'none.toml'}: cannot read")):
        scenes.load_scene(tmp_path / "none.toml")
    broken = tmp_path / "broken.toml"
    broken.write_text("[payload\nmass = 1\n", encoding="utf-8")
    with pytest.raises(SceneError, match=re.escape(f"{broken}: not valid TOML")):
        scenes.load_scene(broken)


# --------------------------------------------------------------------------- command line
@pytest.mark.parametrize("extra, text, match", [
    ([], "[payload]\nmass = -1\n", "payload.mass: -1 kg is negative"),
    ([], "[payload\n", "not valid TOML"),
    (["--outputs", "Fl1"], "[subsystems]\nplatform = false\n",
     "with the command-line options: outputs = [\"Fl1\"]: Fl1 do not exist"),
    (["--leg-model", "thin-rod"], 'methods = ["kane", "rnea"]\n',
     "leg_model = \"thin-rod\": an approximation offered by method kane only"),
    (["--outputs", "T1,X9"], "", "--outputs: unknown 'X9'"),
])
def test_cli_scene_errors_are_one_line_exit_2(tmp_path, capsys, extra, text, match):
    path = tmp_path / "s.toml"
    path.write_text(text, encoding="utf-8")
    out = tmp_path / "never.csv"
    assert main(["id", "--scene", str(path), "--out", str(out)] + extra) == 2
    err = capsys.readouterr().err
    assert err.startswith("offshore-crane: error: ") and match in err
    assert err.count("\n") == 1 and not out.exists()


def test_cli_missing_scene_file(tmp_path, capsys):
    assert main(["id", "--scene", str(tmp_path / "no.toml")]) == 2
    assert "no.toml: cannot read the scene file" in capsys.readouterr().err


def test_cli_flags_override_the_scene(capsys):
    path = str(SCENES / "full_crane.toml")                # methods kane + rnea, all outputs
    assert main(["id", "--scene", path, "--method", "kane", "--leg-model", "thin-rod",
                 "--outputs", "T1,Fl2", "--duration", "1", "--rate", "50",
                 "--set", "platform_mass=50", "--gravity", "0", "0", "-9.0"]) == 0
    out = capsys.readouterr().out
    assert "51 samples" in out and "Kane vs RNEA" not in out
    assert "APPROXIMATE: thin-rod legs" in out
    assert "\nT1 " in out and "\nFl2 " in out and "\nFl1 " not in out
    robot = oc.load_robot(platform_mass=50)
    from offshore_crane.motion import trajectories

    t = trajectories.time_grid(1.0, 50.0)
    X = solve(robot, *trajectories.table1(t), gravity=(0, 0, -9.0),
              leg_model="thin-rod").X
    assert f"{np.abs(X[:, 4]).max():.4f}" in out          # Fl2 peak of that very run


def test_no_shipped_scene_has_a_lightly_damped_mode():
    """Every shipped scene with a hanging load damps each of its cable's modes
    (``offshore_crane.dynamics.cable.modes``: the sway pendulums and, on an elastic
    cable, the axial mode) by at least 1 % of critical, at the description's cable length
    and at every length of its winch's hoist column (measured: sway 1.5 % on 1.2 m to
    4.3 % on 0.6 m, 2.0 % on 1 m; axial 1.1 % on 0.6 m to 1.6 % on 1.2 m)."""
    from offshore_crane.dynamics import cable

    root = Path(__file__).resolve().parents[2] / "scenes"
    seen = 0
    for path in sorted(root.glob("*.toml")):
        scene = scenes.load_scene(path)
        robot = scenes.load_robot(scene)
        if robot.hybrid.cable is None:
            continue
        seen += 1
        ea = scene.cable.get("ea")
        damping = scene.cable.get("damping", 0.0) if ea is not None else 0.0
        lengths = {robot.hybrid.cable_length}
        if scene.cable.get("winch"):
            lengths |= {row[4] for row in scene.operation}
        for length in lengths:
            for mode in cable.modes(robot, ea=ea, damping=damping, length=length,
                                    gravity=scene.gravity):
                assert mode.zeta >= 0.01, (path.name, length, mode)
    assert seen >= 5
