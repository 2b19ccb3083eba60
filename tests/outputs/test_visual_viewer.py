"""The browser viewer (offshore_crane.outputs.visual.viewer, offshore-crane view).

The browser test drives Debian's Chromium (``/usr/bin/chromium``, ``/usr/bin/chromedriver``,
never a downloaded driver) headless with WebGL on SwiftShader, and asserts on the
screenshot's pixels. Without a browser it skips with the reason, unless
``OFFSHORE_CRANE_BROWSER_TEST=required`` (set by ``.ci/run``), which makes it fail.
"""

import os
import shutil
import re
import socket
import sys
import tempfile
import time

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.__main__ import main
from offshore_crane.outputs.visual import motion as mo

#: A real headless browser: slow (``pytest -m 'not slow'`` leaves it out; CI runs it).
pytestmark = pytest.mark.slow

CHROMIUM, CHROMEDRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"
REQUIRED = os.environ.get("OFFSHORE_CRANE_BROWSER_TEST") == "required"
#: How long the page may take to show the robot [s]: SwiftShader compiles the shaders in
#: software on a shared 2-core machine (3-8 s measured).
PAGE_TIMEOUT = 60.0


def browser_or_skip():
    missing = [p for p in (CHROMIUM, CHROMEDRIVER) if not os.path.exists(p)]
    for module in ("selenium", "viser"):
        try:
            __import__(module)
        except ImportError:
            missing.append(f"Python module {module}")
    if missing:
        reason = (f"browser test needs {', '.join(missing)} (apt-get install chromium "
                  "chromium-driver; pip install 'offshore-crane[test,view]')")
        if REQUIRED:
            pytest.fail(f"OFFSHORE_CRANE_BROWSER_TEST=required: {reason}")
        pytest.skip(reason)


def orange(a: np.ndarray) -> np.ndarray:
    """Pixels of the arm's URDF colour (rgba 0.95 0.50 0.10) under any lighting: red well
    above green well above blue."""
    r, g, b = (a[..., k].astype(int) for k in range(3))
    return (r > 90) & (r > g + 35) & (g > b + 15)


def shown_motion(robot):
    traj = oc.motion.trajectories.load("table1", duration=4.0, rate=50.0)
    m = mo.from_trajectory(traj)
    return mo.at(m, mo.frame_times(m, 10.0))


@pytest.fixture
def viewer(robot):
    from offshore_crane.outputs.visual.viewer import Viewer

    browser_or_skip()
    v = Viewer(robot, shown_motion(robot), port=0, play=False)
    yield v
    v.close()


def screenshot(driver) -> np.ndarray:
    from io import BytesIO

    from PIL import Image

    return np.asarray(Image.open(BytesIO(driver.get_screenshot_as_png())).convert("RGB"))


def test_viewer_page_shows_the_robot_and_moves(viewer):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    profile = tempfile.mkdtemp(prefix="oc-chromium-")
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for arg in ("--headless=new", "--no-sandbox", "--use-angle=swiftshader",
                "--enable-unsafe-swiftshader", "--disable-background-networking",
                "--disable-component-update", "--disable-sync", "--no-first-run",
                "--disable-dev-shm-usage", "--window-size=1000,750",
                f"--user-data-dir={profile}"):
        options.add_argument(arg)
    driver = webdriver.Chrome(service=Service(executable_path=CHROMEDRIVER), options=options)
    try:
        driver.get(viewer.url)
        deadline = time.monotonic() + PAGE_TIMEOUT
        first = None
        while time.monotonic() < deadline:
            canvas = driver.execute_script("return document.querySelector('canvas') !== null")
            if canvas:
                first = screenshot(driver)
                if orange(first).sum() > 300:
                    break
            time.sleep(0.5)
        assert first is not None, "the page never made a canvas"
        assert orange(first).sum() > 300, "the robot's colours never appeared"
        assert len(viewer.frames) > 10
        viewer.slider.value = 2.5                   # the GUI handle, from Python
        assert viewer.index(2.5) == 25
        moved, diff = None, 0
        deadline = time.monotonic() + PAGE_TIMEOUT
        while time.monotonic() < deadline:
            time.sleep(0.5)
            moved = screenshot(driver)
            diff = int((np.abs(moved.astype(int) - first).sum(axis=2) > 40).sum())
            if diff > 300:
                break
        assert diff > 300, f"the picture did not change at another time ({diff} pixels)"
        assert orange(moved).sum() > 300
    finally:
        driver.quit()
        shutil.rmtree(profile, ignore_errors=True)


def test_port_in_use_is_one_line_exit_2(capsys):
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        port = s.getsockname()[1]
        assert main(["view", "--trajectory", "table1", "--port", str(port)]) == 2
    err = capsys.readouterr().err
    assert err == (f"offshore-crane: error: --port {port}: cannot listen on 127.0.0.1:"
                   f"{port} (Address already in use): another program uses it; choose "
                   "another port with --port\n")


def test_port_out_of_range(capsys):
    assert main(["view", "--port", "70000"]) == 2
    assert "--port 70000: give a port number in 0..65535" in capsys.readouterr().err


@pytest.mark.parametrize("host, match", [
    ("999.1.1.1", r"--host 999\.1\.1\.1: not an address \(.*\): give an address of this "
                  r"machine"),                                   # once "choose another port"
    ("192.0.2.1", r"cannot listen on 192\.0\.2\.1:0 \(.*\): 192\.0\.2\.1 is not an address "
                  r"of this machine; give one of its addresses with --host"),   # TEST-NET-1
])
def test_a_bad_host_is_named_not_the_port(capsys, host, match):
    assert main(["view", "--trajectory", "table1", "--host", host, "--port", "0"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and re.search(match, err), err


def test_missing_viser_gives_install_hint(robot, monkeypatch):
    from offshore_crane.outputs.visual.viewer import Viewer

    monkeypatch.setitem(sys.modules, "viser", None)
    with pytest.raises(oc.BackendMissingError, match=r"pip install offshore-crane\[view\]"):
        Viewer(robot, shown_motion(robot), port=0)


def test_quaternions_against_rotation_matrices():
    """Round trip through the standard quaternion-to-matrix formula, including the four
    branches (rotations by ~pi about x, y, z and small ones)."""
    from offshore_crane.spatial import axis_angle_matrix
    from offshore_crane.outputs.visual.viewer import quaternions

    rng = np.random.default_rng(8)
    axes = rng.normal(size=(400, 3))
    axes /= np.linalg.norm(axes, axis=1)[:, None]
    angles = rng.uniform(-np.pi, np.pi, 400)
    angles[:30] = np.pi - 1e-9
    axes[:10], axes[10:20], axes[20:30] = [1, 0, 0], [0, 1, 0], [0, 0, 1]
    R = np.array([axis_angle_matrix(a, t) for a, t in zip(axes, angles)])
    w, x, y, z = quaternions(R).T
    back = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    assert np.abs(np.moveaxis(back, 2, 0) - R).max() < 1e-14


def test_the_viewer_colours_the_legs_as_animate_does(robot):
    """--color-by in the viewer: at each shown frame every leg's meshes take animate's
    colour for that frame (colours.diverging of the leg's force over the run's scale)."""
    from offshore_crane.outputs.visual.colours import diverging
    from offshore_crane.outputs.visual.viewer import Viewer

    traj = oc.motion.trajectories.load("table1", duration=2.0, rate=50.0)
    m = mo.forces(robot, mo.from_trajectory(traj), oc.conventions.GRAVITY, "full")
    shown = mo.at(m, mo.frame_times(m, 10.0))
    v = Viewer(robot, shown, port=0, play=False, color_by="force")
    try:
        assert sorted(v.legs) == list(range(6)) and all(len(x) == 2 for x in v.legs.values())
        values, _ = mo.leg_values(robot, shown.X, "force")
        for k in (0, 7, len(shown.t) - 1):
            assert v.show(float(shown.t[k])) == k
            want = np.clip(np.round(diverging(values[k]) * 255.0), 0, 255).astype(int)
            for leg, meshes in v.legs.items():
                for mesh in meshes:
                    assert tuple(mesh.color) == tuple(want[leg]), (k, leg)
    finally:
        v.close()
    plain = Viewer(robot, shown, port=0, play=False)
    try:
        assert plain.leg_rgb is None
        assert sorted(plain.references) == ["floor"]           # no sea: no water line
    finally:
        plain.close()


def test_the_viewer_draws_the_floor_and_the_still_water_line(robot):
    from dataclasses import replace

    from offshore_crane.outputs.visual.viewer import Viewer

    v = Viewer(robot, replace(shown_motion(robot), water=0.3), port=0, play=False)
    try:
        assert sorted(v.references) == ["floor", "still_water"]
        assert v.references["still_water"].position[2] == pytest.approx(0.3)
        assert v.references["floor"].position[2] < 0.3
    finally:
        v.close()


def test_the_viewer_draws_a_varying_cable_and_the_lifts_deck():
    """A lift (scenes/deck_lift.toml) in the browser viewer: the payload where the lift
    puts it (the tip plus its load, to 1e-12 m), the cable's line paler while slack, the
    deck's plate moved to its height of the frame."""
    from pathlib import Path

    from offshore_crane import scenes
    from offshore_crane.outputs.visual import motion as mo
    from offshore_crane.outputs.visual.viewer import CABLE_RGB, SLACK_RGB, Viewer

    path = Path(__file__).resolve().parents[2] / "scenes" / "deck_lift.toml"
    scene = scenes.load_scene(path)
    robot = scenes.load_robot(scene)
    run = scenes.run_swing(scene, robot, scenes.load_trajectory(scene, robot), "kane")
    motion = mo.varying_cable(robot, run.cable, "lift", None, scenes.lift_deck(scene))
    shown = mo.at(motion, motion.t[::50])
    v = Viewer(robot, shown, port=0, play=False)
    try:
        P = v.poses
        tip, pay = P.index("arm_tip"), P.index("payload")
        assert np.abs(P.p[:, pay] - P.p[:, tip] - shown.load).max() <= 1e-12
        for k in (int(np.argmax(shown.slack)), int(np.argmin(shown.slack))):
            v.show(float(shown.t[k]))
            want = SLACK_RGB if shown.slack[k] else CABLE_RGB
            assert tuple(np.asarray(v.cable[1].colors).reshape(-1, 3)[0]) == want
            assert np.allclose(v.deck[1].position, shown.deck[k])
    finally:
        v.close()


def test_the_cable_line_speaks_each_viser_version():
    """viser 1.0 takes ``line_width``; 1.1 deprecates it for ``thickness`` in screen
    units (a DeprecationWarning in every run otherwise)."""
    from offshore_crane.outputs.visual.viewer import _thin_line

    class Old:
        def add_line_segments(self, name, points, colors, *, line_width=1.0, visible=True):
            pass

    class New:
        def add_line_segments(self, name, points, colors, *, thickness=0.01,
                              thickness_units="world", **_deprecated_kwargs):
            pass

    assert _thin_line(Old()) == {"line_width": 2.0}
    assert _thin_line(New()) == {"thickness": 2.0, "thickness_units": "screen"}
