"""Pictures: the renderer, GIF / MP4 animations, the still, the run CSV reader and the
command line's bad inputs (offshore_crane.outputs.visual, offshore-crane animate / show)."""

import subprocess
from pathlib import Path
import sys

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.__main__ import main
from offshore_crane.outputs.visual import animate as an
from offshore_crane.outputs.visual import motion as mo
from offshore_crane.outputs.visual import colours, poses, render

from PIL import Image as PIL

SCENES = Path(__file__).resolve().parents[2] / "scenes"

#: The URDF's arm colour (material "orange", rgba 0.95 0.50 0.10) after flat shading
#: (intensity 0.45..1): red well above green well above blue.
def orange_pixels(a: np.ndarray) -> int:
    r, g, b = (a[..., k].astype(int) for k in range(3))
    return int(((r > 100) & (r > g + 40) & (g > b + 20)).sum())


def pose(robot, q7=0.0, q8=0.0):
    return np.array([0.0, 0.0, robot.home_height, 0.0, 0.0, 0.0, q7, q8, 0.0])


def test_frames_non_empty_and_differ_between_poses(robot):
    q = np.array([pose(robot), pose(robot, 1.5, -1.0)])
    P = poses.link_poses(robot, q)
    r = render.Renderer(robot, P, 320, 240)
    a, b = (np.asarray(r.frame(k)) for k in range(2))
    assert a.shape == (240, 320, 3)
    background = np.asarray(r._background)
    assert (np.abs(a.astype(int) - background).sum(axis=2) > 30).mean() > 0.1  # robot drawn
    assert orange_pixels(a) > 200 and orange_pixels(b) > 200                   # the arm
    assert (np.abs(a.astype(int) - b).sum(axis=2) > 30).sum() > 500            # it moved


def test_projection_is_a_pinhole(robot):
    """The target lands at the picture's centre; a point one metre to the camera's right
    at the target's depth lands focal pixels to the right (tan-based focal length)."""
    P = poses.link_poses(robot, pose(robot))
    r = render.Renderer(robot, P, 400, 300, render.Camera(azimuth=10, elevation=30, fov=40))
    (xy, z) = r.project(np.array([r.target, r.target + r.R_cam[0]]))
    d = np.linalg.norm(r.eye - r.target)
    focal = 150.0 / np.tan(np.radians(20.0))
    assert np.allclose(xy[0], [200, 150], atol=1e-9) and np.isclose(z[0], d)
    assert np.allclose(xy[1], [200 + focal / d, 150], atol=1e-9)


def test_gif_has_the_requested_frames(robot, tmp_path):
    out = tmp_path / "a.gif"
    traj = oc.motion.trajectories.load("table1", duration=2.0, rate=50.0)
    done = an.animate(robot, mo.from_trajectory(traj), str(out), fps=10, duration=1.5,
                      width=160, height=120)
    im = PIL.open(out)
    assert done.frames == 16 and im.n_frames == 16                # t = 0, 0.1, ..., 1.5 s
    assert im.info["duration"] == 100 and im.size == (160, 120)
    im.seek(0)
    first = np.asarray(im.convert("RGB")).copy()
    im.seek(15)
    assert np.abs(first.astype(int) - np.asarray(im.convert("RGB"))).sum() > 0


def test_speed_and_frame_times():
    m = mo.Motion("x", np.linspace(0.0, 10.0, 11), np.zeros((11, 9)))
    assert np.allclose(mo.frame_times(m, 2.0, speed=4.0), [0, 2, 4, 6, 8, 10])
    assert len(mo.frame_times(m, 30.0)) == 301
    with pytest.raises(oc.InputError, match=r"--fps 0 must be a finite number > 0"):
        mo.frame_times(m, 0)
    with pytest.raises(oc.InputError, match=r"--speed -1 must be a finite number > 0"):
        mo.frame_times(m, 10, speed=-1)
    with pytest.raises(oc.InputError, match=r"--duration 11 s is longer than the motion"):
        mo.frame_times(m, 10, duration=11.0)


def test_mp4_frames(robot, tmp_path):
    import imageio_ffmpeg as iio
    out = tmp_path / "a.mp4"
    traj = oc.motion.trajectories.load("table1", duration=2.0, rate=50.0)
    done = an.animate(robot, mo.from_trajectory(traj), out, fps=20, duration=1.0,
                      width=160, height=120, color_by="force")
    assert done.frames == 21
    assert iio.count_frames_and_secs(str(out))[0] == 21
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.mp4"]   # no temporary left


def test_legs_coloured_by_force(robot):
    """Push (> 0) red, pull blue: the colour map against hand-picked values."""
    assert np.allclose(colours.diverging(np.array([-1.0, 0.0, 1.0])),
                       [[0.1, 0.3, 0.9], [0.85, 0.85, 0.85], [0.9, 0.15, 0.1]])
    X = np.zeros((2, 9))
    X[:, 3:] = [[100, -50, 0, 0, 0, 0], [-200, 0, 0, 0, 0, 0]]
    v, scale = mo.leg_values(robot, X, "force")
    assert scale == 200 and v[0, 0] == 0.5 and v[1, 0] == -1.0
    caps = robot.capacities
    u, top = mo.leg_values(robot, X, "utilisation")
    assert np.isclose(u[0, 0], 100 / caps.push_max[3]) and np.isclose(u[0, 1],
                                                                        50 / caps.pull_max[4])
    bare = oc.Robot(robot.urdf)                     # no description: no capacities
    with pytest.raises(oc.InputError, match="--color-by utilisation needs the legs' "
                       "capacities"):
        mo.leg_values(bare, X, "utilisation")


def test_still_and_cli_show(robot, tmp_path, capsys):
    out = tmp_path / "pose.png"
    assert main(["show", "--pose", f"0,0,{robot.home_height},0.05,0,0.1,0.6,-0.8,0.05",
                 "--size", "400x300", "--out", str(out)]) == 0
    a = np.asarray(PIL.open(out).convert("RGB"))
    assert a.shape == (300, 400, 3) and orange_pixels(a) > 300
    assert main(["show", "--pose", "1,2,3", "--out", str(tmp_path / "b.png")]) == 2
    assert "--pose 1,2,3: give 9 finite comma-separated numbers" in capsys.readouterr().err


def simulate_csv(tmp_path):
    csv = tmp_path / "sim.csv"
    assert main(["simulate", "--trajectory", "table1", "--duration", "0.5", "--rate", "50",
                 "--out", str(csv)]) == 0
    return csv


def test_from_simulate_csv_uses_its_forces(robot, tmp_path):
    csv = simulate_csv(tmp_path)
    m = mo.read_run(csv)
    assert m.q.shape == (26, 9) and m.X.shape == (26, 9) and m.sway is None
    text = csv.read_text().splitlines()
    assert np.allclose(m.X[3], [float(x) for x in text[4].split(",")[19:28]])
    out = tmp_path / "sim.gif"
    assert main(["animate", "--from", str(csv), "--fps", "20", "--color-by", "force",
                 "--size", "160x120", "--out", str(out)]) == 0
    assert PIL.open(out).n_frames == 11


def test_run_csv_errors(tmp_path):
    ids = tmp_path / "id.csv"
    assert main(["id", "--duration", "0.1", "--out", str(ids)]) == 0
    with pytest.raises(oc.TrajectoryError, match="holds actuator forces only"):
        mo.read_run(ids)
    bad = tmp_path / "bad.csv"
    bad.write_text("t_s,q1,q2,q3,q4,q5,q6,q7,q8,q9,wind\n" + "0,0,0,0.5,0,0,0,0,0,0,1\n" * 2)
    with pytest.raises(oc.TrajectoryError, match="unknown column\\(s\\) 'wind'"):
        mo.read_run(bad)
    bad.write_text("t_s,q1,q2,q3,q4,q5,q6,q7,q8,q9\n0,0,0,0.5,0,0,0,0,0,0\n"
                   "0.1,0,0,nan,0,0,0,0,0,0\n")
    with pytest.raises(oc.TrajectoryError, match="data row 2, column q3_m: 'nan' is not finite"):
        mo.read_run(bad)


@pytest.mark.parametrize("argv, match", [
    (["--trajectory", "table1", "--out", "{tmp}/a.avi"], "the file type '.avi' is not one "
     "of .gif, .mp4"),
    (["--trajectory", "table1", "--fps", "0", "--out", "{tmp}/a.gif"],
     "--fps 0 must be a finite number > 0"),
    (["--trajectory", "table1", "--fps", "-5", "--out", "{tmp}/a.gif"],
     "--fps -5 must be a finite number > 0"),
    (["--trajectory", "table1", "--speed", "0", "--out", "{tmp}/a.mp4"],
     "--speed 0 must be a finite number > 0"),
    (["--trajectory", "table1", "--camera", "1,2,3,4", "--out", "{tmp}/a.gif"],
     "--camera 1,2,3,4: give AZIMUTH,ELEVATION"),
    (["--trajectory", "table1", "--camera", "0,95", "--out", "{tmp}/a.gif"],
     "camera elevation 95 deg must lie in"),
    (["--trajectory", "table1", "--size", "641x481", "--out", "{tmp}/a.mp4"],
     "an MP4 needs an even width and height"),
    (["--trajectory", "table1", "--from", "x.csv", "--out", "{tmp}/a.gif"],
     "--from and --trajectory both give the motion"),
    (["--trajectory", "table1", "--set", "payload.mass=2", "--set",
      "payload.cable_length=0.5", "--gravity", "0", "0", "9.81", "--out", "{tmp}/a.gif"],
     "the cable goes slack at sample 0"),
])
def test_cli_bad_input_one_line_exit_2(argv, match, tmp_path, capsys):
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    assert main(["animate", *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("offshore-crane: error: ") and match in err, err
    assert err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []                        # nothing left behind


def test_library_rejects_unknown_suffix(robot):
    with pytest.raises(oc.InputError, match=r"unknown animation type '.avi'"):
        an.output_format("run.avi")


def test_missing_extra_gives_install_hint(robot, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "imageio_ffmpeg", None)     # import fails
    traj = oc.motion.trajectories.load("table1", duration=1.0, rate=20.0)
    with pytest.raises(oc.BackendMissingError, match=r"pip install offshore-crane\[animate\]"):
        an.animate(robot, mo.from_trajectory(traj), tmp_path / "a.mp4", fps=5,
                   width=64, height=48)
    assert list(tmp_path.iterdir()) == []


def test_nothing_heavy_at_import_and_for_a_gif(tmp_path):
    """``import offshore_crane`` and a GIF import neither viser, imageio, MuJoCo,
    matplotlib nor Pinocchio."""
    out = tmp_path / "a.gif"
    code = ("import sys; import offshore_crane; "
            "heavy = ('viser', 'imageio', 'imageio_ffmpeg', 'mujoco', 'PIL', 'matplotlib', "
            "'pinocchio', 'selenium'); "
            "bad = [m for m in heavy if m in sys.modules]; assert not bad, bad; "
            "from offshore_crane.__main__ import main; "
            f"assert main(['animate', '--duration', '0.5', '--fps', '4', '--size', '64x48', "
            f"'--out', {str(out)!r}]) == 0; "
            "bad = [m for m in heavy[:4] + heavy[5:] if m in sys.modules]; assert not bad, bad")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr


def test_the_hanging_load_swings_in_the_pictures(tmp_path):
    """A payload on a cable is drawn where the swing puts it: the frames of a run with
    an initial sway differ from those of the same run hanging still."""
    from offshore_crane.dynamics import cable
    from offshore_crane.outputs.visual import motion as mo
    from offshore_crane.outputs.visual.animate import frames
    from offshore_crane.motion.trajectories import table1, time_grid

    robot = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 0.5})
    t = time_grid(1.0, 50.0)
    still = mo.Motion("still", t, *table1(t), source=table1)
    a = mo.hanging_load(robot, still, oc.GRAVITY)
    b = mo.hanging_load(robot, still, oc.GRAVITY, {"initial": (0.4, 0.0)})
    ref = cable.inverse_dynamics(robot, *table1(t), reference=table1, initial=(0.4, 0.0), t=t)
    np.testing.assert_array_equal(b.sway, ref.sway)
    times = t[-1:]
    imgs = [next(iter(frames(robot, mo.at(m, times), width=160, height=120)[1]))
            for m in (a, b)]
    assert (np.asarray(imgs[0]) != np.asarray(imgs[1])).any()


def _lab(rgb) -> np.ndarray:
    """sRGB 0..255 ``(..., 3)`` to CIE L*a*b* (D65), for colour distances."""
    c = np.asarray(rgb, dtype=float) / 255.0
    c = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    M = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722],
                  [0.0193, 0.1192, 0.9505]])
    xyz = c @ M.T / np.array([0.95047, 1.0, 1.08883])
    f = np.where(xyz > (6 / 29) ** 3, np.cbrt(xyz), xyz / (3 * (6 / 29) ** 2) + 4 / 29)
    return np.stack([116 * f[..., 1] - 16, 500 * (f[..., 0] - f[..., 1]),
                     200 * (f[..., 1] - f[..., 2])], axis=-1)


def test_a_force_gif_shows_the_scales_ends_in_every_frame(tmp_path):
    """The README's headline picture, short: one palette for every frame, and in every
    frame the colour bar's pull end (blue) and push end (red) within ΔE (CIE76) ≤ 10 of
    their definitions (colours.diverging(∓1)); a pushing leg's red hue is kept. Each frame
    once had its own 64-colour palette, where pull came out grey or near-black."""
    out = tmp_path / "run.gif"
    assert main(["animate", "--scene", str(SCENES / "sea_state_crane.toml"),
                 "--color-by", "force", "--duration", "3", "--out", str(out)]) == 0
    blue, red = colours.diverging(np.array([-1.0, 1.0])) * 255.0
    gif = PIL.open(out)
    assert gif.n_frames == 31                             # 10 fps, the GIF default
    W, w = 640, 120
    x0, y0 = W - w - 14, 22                               # the legend's bar (animate._legend)
    palettes = set()
    for k in range(gif.n_frames):
        gif.seek(k)
        palettes.add(bytes(gif.getpalette() or b""))
        frame = np.asarray(gif.convert("RGB"), dtype=float)
        left = frame[y0 + 3:y0 + 8, x0 + 1:x0 + 3].reshape(-1, 3)
        right = frame[y0 + 3:y0 + 8, x0 + w - 3:x0 + w - 1].reshape(-1, 3)
        assert np.linalg.norm(_lab(left) - _lab(blue), axis=1).max() <= 10.0, k
        assert np.linalg.norm(_lab(right) - _lab(red), axis=1).max() <= 10.0, k
    assert len(palettes - {b""}) == 1          # the global palette; no frame has its own


def test_the_gif_palette_holds_the_scale_and_the_bodies(robot):
    """gif_palette: every step of the colour scale and every body colour at full shade is
    in the palette exactly; 256 entries at most."""
    traj = oc.motion.trajectories.load("table1", duration=1.0, rate=50.0)
    motion = mo.forces(robot, mo.from_trajectory(traj), oc.conventions.GRAVITY, "full")
    times = np.linspace(0.0, 1.0, 5)
    r, picture, _ = an.painter(robot, mo.at(motion, times), width=160, height=120,
                               color_by="force")
    palette = np.array(an.gif_palette(r, picture, len(times), "force").getpalette()[:768]
                       ).reshape(-1, 3)
    have = {tuple(c) for c in palette.tolist()}
    ramp = colours.diverging(np.linspace(-1.0, 1.0, an.GIF_SCALE_STEPS)) * 255.0
    assert {tuple(c) for c in np.clip(ramp, 0, 255).astype(np.uint8).tolist()} <= have
    bodies = np.unique(np.round(r.geo.rgb, 6), axis=0)
    full = np.clip(bodies * (render.AMBIENT + render.DIFFUSE) * 255, 0, 255).astype(np.uint8)
    assert {tuple(c) for c in full.tolist()} <= have
    assert len(palette) == 256


def test_the_floor_is_drawn_under_the_base_unless_seen_from_below(robot):
    """The lab's floor (with its grid) is painted into the static background: from the
    default camera it changes a good part of the plain gradient; from a camera below the
    floor it is not drawn (it would hide the robot)."""
    m = mo.from_trajectory(oc.motion.trajectories.load("table1", duration=1.0, rate=10.0))
    P = poses.link_poses(robot, mo.at(m, np.array([0.0])).q)

    def floor_share(camera):
        r = render.Renderer(robot, P, 160, 120, camera)
        plain = np.asarray(r._gradient(160, 120), dtype=int)
        painted = np.asarray(r._background, dtype=int)
        return float((np.abs(painted - plain).sum(axis=2) > 0).mean()), r

    share, r = floor_share(render.Camera())
    assert share > 0.05 and r.eye[2] > 0                 # the floor seen from above
    share, r = floor_share(render.Camera(elevation=-70.0))
    assert r.eye[2] < 0 and share == 0.0                 # from below: not drawn


def test_the_still_water_line_is_drawn_at_the_scenes_model_scale_level(robot, tmp_path):
    """A sea scene's still water line: ``point[2] / scale`` below the home height (the
    home pose stands for the vessel's ``point``, given from the RAO table's reference point
    in the calm waterplane); drawn in WATER_RGB into the background, absent without a sea.
    """
    scene = oc.scenes.load_scene(SCENES / "sea_state_crane.toml")
    assert oc.scenes.still_water_level(scene, robot) == robot.home_height
    raised = oc.scenes.with_overrides(scene, "test", sea={**scene.sea, "point": [0, 0, 4.0]})
    assert oc.scenes.still_water_level(raised, robot) == pytest.approx(
        robot.home_height - 4.0 / 20.0, abs=1e-15)
    assert oc.scenes.still_water_level(oc.scenes.load_scene(SCENES / "full_crane.toml"),
                                       robot) is None
    m = mo.from_trajectory(oc.motion.trajectories.load("table1", duration=1.0, rate=10.0))
    P = poses.link_poses(robot, mo.at(m, np.array([0.0])).q)

    def water_pixels(water):
        a = np.asarray(render.Renderer(robot, P, 320, 240, water=water)._background, int)
        return int((np.abs(a - np.array(render.WATER_RGB)).sum(axis=2) < 30).sum())

    assert water_pixels(None) == 0
    assert water_pixels(robot.home_height) > 300          # four sides of a square, 2 px


# --------------------------------------------------------------------------- a varying cable
def test_a_load_given_by_position_is_drawn_where_the_sway_puts_it():
    """poses.link_poses(load=...): the cable joints take the load's direction (the sway
    convention inverted) and the payload sits at the tip plus the load: on a rigid swing
    (offshore_crane.dynamics.cable's run along Table 1) the same poses as from its sway
    angles, to 1e-12 m, and a load 20 % farther puts the payload 20 % farther."""
    from offshore_crane.dynamics import cable
    from offshore_crane.dynamics.cable.tip import payload_positions, tip_positions
    from offshore_crane.motion.trajectories import table1, time_grid

    robot = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 0.5})
    t = time_grid(3.0, 50.0)
    res = cable.inverse_dynamics(robot, *table1(t), reference=table1, initial=(0.4, -0.3),
                                 t=t)
    load = payload_positions(robot, res) - tip_positions(robot, res.q)[0]
    by_sway = poses.link_poses(robot, res.q, res.sway)
    by_load = poses.link_poses(robot, res.q, load=load)
    assert np.abs(by_sway.p - by_load.p).max() <= 1e-12
    longer = poses.link_poses(robot, res.q, load=1.2 * load)
    tip, pay = longer.index("arm_tip"), longer.index("payload")
    reach = np.linalg.norm(longer.p[:, pay] - longer.p[:, tip], axis=1)
    assert np.abs(reach - 0.6).max() <= 1e-12


def test_a_slack_cable_is_dashed_and_the_lifts_deck_drawn(tmp_path, capsys):
    """animate --scene of a lift (scenes/deck_lift.toml): the varying cable is drawn as
    a line from the tip to the payload (the URDF's fixed-length rod hidden), dashed while
    slack — fewer cable pixels than the same frame drawn taut — and the deck as a plate
    under the load; --from a run's CSV with such a scene is refused in one line."""
    from offshore_crane import scenes
    from offshore_crane.outputs.visual.animate import painter

    scene = scenes.load_scene(SCENES / "deck_lift.toml")
    robot = scenes.load_robot(scene)
    run = scenes.run_swing(scene, robot, scenes.load_trajectory(scene, robot), "kane")
    motion = mo.varying_cable(robot, run.cable, "lift", None, scenes.lift_deck(scene))
    k = int(np.argmax(motion.slack))                   # resting: the cable slack
    shown = mo.at(motion, motion.t[[k, k]])
    taut = mo.at(motion, motion.t[[k, k]])
    taut = type(taut)(**{**taut.__dict__, "slack": np.array([False, False])})

    def dark(m) -> int:
        a = np.asarray(painter(robot, m, width=320, height=240)[1](0)).astype(int)
        return int((a.max(axis=-1) < 60).sum())

    def plate(m) -> int:
        a = np.asarray(painter(robot, m, width=320, height=240)[1](0)).astype(int)
        return int((np.abs(a - np.array(render.DECK_RGB)).max(axis=-1) <= 3).sum())
    assert dark(shown) < dark(taut)
    assert plate(shown) > 100
    out = tmp_path / "lift.gif"
    assert main(["animate", "--scene", str(SCENES / "deck_lift.toml"), "--out", str(out),
                 "--duration", "1"]) == 0
    assert PIL.open(out).n_frames == 11
    capsys.readouterr()
    run_csv = tmp_path / "run.csv"
    run_csv.write_text("t_s,q1_m\n0,0\n")
    assert main(["animate", "--scene", str(SCENES / "deck_lift.toml"), "--from",
                 str(run_csv), "--out", str(tmp_path / "x.gif")]) == 2
    err = capsys.readouterr().err
    assert "--from reads a rigid cable's run only" in err
    assert len(err.strip().splitlines()) == 1


def test_the_ship_to_ship_target_is_drawn_where_the_load_should_be(tmp_path):
    """animate --scene scenes/ship_to_ship.toml: the plate is the compensation's moving
    aim (the load's place above the second deck) and is drawn."""
    from dataclasses import replace

    from offshore_crane import scenes
    from offshore_crane.cli.animate import load_motion
    from offshore_crane.outputs.visual.animate import painter
    from offshore_crane.simulation.compensation import compensated_motion

    path = SCENES / "ship_to_ship.toml"
    scene = scenes.load_scene(path)
    args = type("Args", (), {"run_csv": None})()
    robot, motion = load_motion(args, scene)
    traj = scenes.load_trajectory(scene, robot)
    comp = compensated_motion(robot, traj, "arm+winch", 0.02, scenes.target_deck(scene),
                              scene.gravity)
    assert np.array_equal(motion.deck, comp.aim)
    shown = mo.at(motion, motion.t[:1])
    a = np.asarray(painter(robot, shown, width=320, height=240)[1](0)).astype(int)
    assert (np.abs(a - np.array(render.DECK_RGB)).max(axis=-1) <= 3).sum() > 50
    bare = replace(shown, deck=None)
    b = np.asarray(painter(robot, bare, width=320, height=240)[1](0)).astype(int)
    assert (np.abs(b - np.array(render.DECK_RGB)).max(axis=-1) <= 3).sum() == 0
