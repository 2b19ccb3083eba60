"""Bad-input family of issue 36: runs that could not be stopped, and physical bounds.

An elastic cable stiffer than any rope for its payload, or whose axial period the
samples' step rule cannot resolve (the steps vanished: a run that ignored SIGTERM for
minutes); a measurement delay shorter than any measurement chain's or longer than a
sixth of the sea's peak period; a lift-off whose deck lies below the hanging load, a
set-down whose load starts below the deck (a traceback); a compensation target out of
reach (it said "lengthen the cable"); ``compensate`` on a scene with a hoist column or a
``[lift]`` (ignored, exit 0). Instances of their own, not the issue's. Gathered by
``test_bad_inputs._families``.
"""

from __future__ import annotations

from pathlib import Path

import offshore_crane as oc
from offshore_crane import scenes
from offshore_crane.motion import trajectories
from test_bad_inputs import Case, _SCENES, _bytes

#: A 2 kg payload on a 1 m cable: EA <= m g / STRAIN_MIN = 1.962e8 N (g = 9.81 m/s²).
_STIFF = 'name = "s"\n[payload]\nmass = 2.0\ncable_length = 1.0\n[cable]\nea = {ea}\n' \
         '[trajectory]\nsource = "table1"\nduration = 0.2\nrate = {rate}\n'


def _stiff(tmp: Path, ea: str, rate: str = "100.0") -> Path:
    return _bytes(tmp, "stiff.toml", _STIFF.format(ea=ea, rate=rate).encode())


def _scene(tmp: Path, name: str, *edits) -> Path:
    """The shipped scene ``name`` with ``(old, new)`` text replacements."""
    text = (_SCENES / name).read_text()
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new)
    return _bytes(tmp, name, text.encode())


def _elastic(ea: float, rate: float, **options):
    """The lab robot with 2 kg on 0.5 m, Table 1 for 0.5 s at ``rate`` on an elastic cable."""
    robot = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 0.5})
    t = trajectories.time_grid(0.5, rate)
    q, qd, qdd = trajectories.table1(t)
    return oc.dynamics.cable.elastic_inverse_dynamics(robot, q, qd, qdd, t=t, ea=ea,
                                                      **options)


#: deck_lift.toml without its winch (a [lift] that compensate could otherwise run).
_NO_WINCH = (("winch = true", "winch = false"),
             ("waypoints = [[0, 0.6, -0.8, 0.0, 1.02], [2, 0.6, -0.8, 0.0, 1.02], "
              "[5, 0.6, -0.8, 0.0, 0.6],\n             [20, 0.6, -0.8, 0.0, 0.6]]",
              "waypoints = [[0, 0.6, -0.8, 0.0]]"))

CASES = [
    Case("elastic-ea-beyond-any-rope", "[cable] ea = 7e9 N for a 2 kg payload (static "
         "strain 2.8e-9: the steps vanished, the run ignored SIGTERM)", oc.SceneError,
         r"\[cable\] ea = 7e\+09 N: stiffer than any rope for a 2 kg payload .*give ea <= "
         r"1\.962e\+08 N",
         lib=lambda tmp: scenes.load_scene(_stiff(tmp, "7e9")),
         cli=lambda tmp: ["id", "--scene", str(_stiff(tmp, "7e9"))]),
    Case("elastic-ea-axial-period-under-the-step-rule", "[cable] ea = 5e7 N sampled at 4 Hz:"
         " an axial period 1/400 of the sample interval", oc.SceneError,
         r"\[cable\] ea = 5e\+07 N: axial period 0\.00126 s .* under 1/20 of the sample "
         r"interval 0\.25 s",
         lib=lambda tmp: scenes.load_scene(_stiff(tmp, "5e7", "4.0")),
         cli=lambda tmp: ["id", "--scene", str(_stiff(tmp, "5e7", "4.0"))]),
    Case("elastic-ea-library-step-rule", "elastic_inverse_dynamics with EA 3e6 N at 5 Hz",
         oc.InputError, r"cable ea = 3e\+06 N: axial period .* give ea <= .* or sample "
         "faster", lib=lambda tmp: _elastic(3e6, 5.0)),
    Case("elastic-substeps-beyond-the-bound", "elastic_inverse_dynamics(substeps=4096)",
         oc.InputError, r"substeps = 4096 must be an integer >= 1 and <= 1000",
         lib=lambda tmp: _elastic(1e4, 100.0, substeps=4096)),
    Case("compensate-delay-beyond-a-sixth-of-tp", "compensate --delay 2.5 s on Tp 8 s at "
         "1:20 (1.79 s model scale)", oc.InputError,
         r"--delay = 2\.5 s: over a sixth of the sea's peak period 1\.789 s .* give <= "
         r"0\.2981 s",
         cli=lambda tmp: ["compensate", "--scene", str(_SCENES / "compensated_lift.toml"),
                          "--delay", "2.5", "--record", "scene"]),
    Case("compensate-delay-below-any-chain", "compensate --delay 4e-13 s", oc.InputError,
         r"--delay = 4e-13 s: shorter than any measurement chain's",
         cli=lambda tmp: ["compensate", "--scene", str(_SCENES / "ship_to_ship.toml"),
                          "--delay", "4e-13", "--record", "scene"]),
    Case("control-delay-beyond-a-sixth-of-tp", "[control] delay = 0.75 s on the shipped "
         "ship-to-ship scene", oc.SceneError, r"\[control\] delay = 0\.75 s: over a sixth",
         lib=lambda tmp: scenes.load_scene(_scene(tmp, "ship_to_ship.toml", (
             "delay = 0.02 ", "delay = 0.75 ")))),
    Case("lift-off-deck-below-the-load", "[lift] deck_height = -0.45 m, 0.29 m below where "
         "the load hangs (the cable started stretched, the load flung)", oc.SceneError,
         r"\[lift\] lift-off: the deck at .* m is 0\.\d+ m below where the load hangs .* "
         "raise deck_height above",
         cli=lambda tmp: ["id", "--scene", str(_scene(tmp, "deck_lift.toml", (
             "deck_height = -0.12 ", "deck_height = -0.45 ")))]),
    Case("set-down-load-below-the-deck", "[lift] event = \"set-down\" with the deck 0.25 m "
         "above the hanging load (an argmax of an empty sequence)", oc.SceneError,
         r"\[lift\] set-down: the load starts 0\.\d+ m below the deck .* lower deck_height",
         cli=lambda tmp: ["id", "--scene", str(_scene(tmp, "deck_lift.toml", (
             'event = "lift-off"', 'event = "set-down"'), (
             "deck_height = -0.12 ", "deck_height = 0.09 ")))]),
    Case("compensation-target-out-of-reach", "[control] target 1500 m forward on the "
         "second vessel in Hs 8 m, 30° seas: it pitches above the crane tip (it said "
         "\"cable length -9.6 m: lengthen the cable\")", oc.InputError,
         r"compensation: the target \(\[control\] target\) is out of reach, .* m above the "
         r"crane tip at t = .* s: pick a point that heaves less",
         cli=lambda tmp: ["id", "--scene", str(_scene(
             tmp, "ship_to_ship.toml", ("point = [10.0, 0.0, 2.0]", "point = [1500.0, 0.0, 2.0]"),
             ("duration = 60.0 ", "duration = 10.0 "), ("heading = 90.0 ", "heading = 30.0 "),
             ("hs = 2.5 ", "hs = 8.0 ")))]),
    Case("compensate-with-a-hoist-column", "compensate on the winch lift (its hoist column "
         "was ignored, exit 0)", oc.SceneError,
         r"compensate drives the winch itself, so the hoist column \(\[cable\] winch\) "
         "would be ignored",
         cli=lambda tmp: ["compensate", "--scene", str(_SCENES / "winch_lift.toml"),
                          "--record", "scene"]),
    Case("compensate-with-a-lift", "compensate on a lift-off scene without winch (its "
         "[lift] was ignored, exit 0)", oc.SceneError,
         r"compensate does not model a \[lift\] event's deck",
         cli=lambda tmp: ["compensate", "--scene", str(_scene(tmp, "deck_lift.toml",
                                                              *_NO_WINCH))]),
]
