"""The small design problem of the design tests (tests/studies/test_design.py,
tests/cli/test_design_cli.py): the crane slewing in Hs 2.5 m beam seas at 1:20 on its own
4 s record at 25 Hz (each case a few ms), judged over 2 seeds; two link lengths, the
reach (an expression of description fields) against the first arm motor's push
utilisation (a verdict column)."""

from __future__ import annotations

from pathlib import Path

SCENE = """
name = "design test"
payload = { mass = 2.0, offset = [0.0, 0.0, -0.05] }
trajectory = { source = "sea", duration = 4.0, rate = 25.0 }
sea = { hs = 2.5, tp = 8.0, heading = 90.0, scale = 20.0, seed = 1, highpass = 0.2 }
# each case the scene's own short record; a candidate's cases: seeds 1 and 2 (as size
# runs them)
extremes = { record = "scene", seeds = 2 }
operation = { waypoints = [[0, 0.0, 0.0, 0.0], [2, 1.2, -0.6, 0.0], [3.5, 0.0, 0.0, 0.0],
                           [4, 0.0, 0.0, 0.0]] }
"""

L1, L2 = "arm.link1.shape.size.x", "arm.link2.shape.size.x"
REACH = f"{L1} + {L2} + arm.slider.max"
#: The two-variable problem: bounds as the lab design's links give or take 0.2 m.
SPACE = f"""
[variables]
"{L1}" = [0.3, 0.7]
"{L2}" = [0.2, 0.6]
[objectives]
maximise = ["{REACH}"]
minimise = ["T1_util_push"]
"""


def write(folder: Path, scene: str = SCENE, space: str = SPACE) -> tuple[Path, Path]:
    """The scene and space files in ``folder``."""
    (folder / "scene.toml").write_text(scene)
    (folder / "space.toml").write_text(space)
    return folder / "scene.toml", folder / "space.toml"
