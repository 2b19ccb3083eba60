"""Bad-input family of issue 37: laws by name, sensors and actuators. A law name that does
not exist (with "did you mean"), a law a plant cannot run, a sensor delay that is not a
whole number of integration steps, a negative noise, a lag time constant of 0. Gathered
by ``test_bad_inputs._families``.
"""

from __future__ import annotations

from pathlib import Path

import offshore_crane as oc
from offshore_crane import scenes
from offshore_crane.motion import trajectories
from test_bad_inputs import Case, _SCENES, _bytes


def _crane(tmp: Path, control: str = "", extra: str = "") -> Path:
    """controlled_crane.toml with its [control] lines ``control`` added and ``extra``
    sections appended."""
    text = (_SCENES / "controlled_crane.toml").read_text()
    text = text.replace("[control]\n", "[control]\n" + control, 1) + "\n" + extra
    return _bytes(tmp, "crane.toml", text.encode())


def _run(path: Path):
    sc = scenes.load_scene(path)
    robot = scenes.load_robot(sc)
    return oc.simulate(robot, 0.01, trajectories.table1, controller=scenes.controller(
        sc, robot), **scenes.instruments(sc))


CASES = [
    Case("law-misspelt", "[control] law = \"pd-gravty\" (no such law)", oc.SceneError,
         r"unknown control law 'pd-gravty'; did you mean 'pd-gravity'\?",
         lib=lambda tmp: scenes.load_scene(_bytes(tmp, "c.toml", (
             _SCENES / "controlled_crane.toml").read_text().replace(
             'law = "computed-torque"', 'law = "pd-gravty"').encode())),
         cli=lambda tmp: ["simulate", "--scene", str(_SCENES / "controlled_crane.toml"),
                          "--controller", "pd-gravty", "--duration", "0.01"]),
    Case("law-plant-cannot-run", "anti-sway on the rigid robot (its payload is welded)",
         oc.InputError, r"payload is welded",
         lib=lambda tmp: oc.simulate(oc.load_robot(), 0.01, trajectories.table1,
                                     controller=oc.Controller(anti_sway=0.2)),
         cli=lambda tmp: ["simulate", "--scene", str(_SCENES / "controlled_crane.toml"),
                          "--anti-sway", "0.2", "--duration", "0.01"]),
    Case("sensor-delay-not-whole-steps", "[sensors] delay = 0.0025 s at a step of 1 ms",
         oc.InputError, r"sensor delay = 0\.0025 s is not a multiple of the integration "
         r"step 0\.001 s",
         lib=lambda tmp: _run(_crane(tmp, extra="[sensors]\ndelay = 0.0025\n")),
         cli=lambda tmp: ["simulate", "--scene", str(_crane(
             tmp, extra="[sensors]\ndelay = 0.0025\n")), "--duration", "0.01"]),
    Case("sensor-noise-negative", "[sensors] noise_q = -1e-4", oc.SceneError,
         r"\[sensors\] noise_q = -0\.0001: must be ≥ 0 m, rad",
         lib=lambda tmp: scenes.load_scene(_crane(tmp, extra="[sensors]\nnoise_q = -1e-4\n")),
         cli=lambda tmp: ["simulate", "--scene", str(_crane(
             tmp, extra="[sensors]\nnoise_q = -1e-4\n")), "--duration", "0.01"]),
    Case("actuator-lag-zero", "[actuators] lag = 0 s", oc.SceneError,
         r"\[actuators\] lag\[0\] = 0\.0 s: must be finite and > 0",
         lib=lambda tmp: scenes.load_scene(_crane(tmp, extra="[actuators]\nlag = 0.0\n")),
         cli=lambda tmp: ["simulate", "--scene", str(_crane(
             tmp, extra="[actuators]\nlag = 0.0\n")), "--duration", "0.01"]),
]
