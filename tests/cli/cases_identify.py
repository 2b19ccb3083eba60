"""The identification family of the bad-input catalogue (issue 36): ``identify`` on logs
it cannot explain (a hanging or elastic load, a winch, another robot, positions outside
the workspace), inputs that are no file, cut-offs it cannot realise, ``excite`` on
excitations too short to determine the base parameters, a robot on a cable, and ``--set``
on fields that per-leg tables shadow (the identified description has them). Each: one
line, exit 2, nothing written, the inputs unchanged (tests/cli/test_bad_inputs.py).

The logs are small (1 s at 200 Hz of a Fourier excitation of the lab robot, its rates
and Kane's forces: the columns of ``simulate --out`` with the rates, so that no filter
needs a longer log), with what each case changes.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import offshore_crane as oc
from offshore_crane.conventions import Q_COLUMNS
from test_bad_inputs import Case, _bytes

_ROOT = Path(__file__).resolve().parents[2]
_HS = _ROOT / "models" / "descriptions" / "harib_srinivasan_2003.toml"
_CACHE: dict = {}


def _motion():
    """``(t, q, qd, qdd, X)`` of the small log (computed once)."""
    if "motion" not in _CACHE:
        from offshore_crane.studies import identification as ident

        robot = oc.load_robot()
        ex = ident.fourier_excitation(robot, 1.0, 200.0, harmonics=3, seed=3)
        _CACHE["motion"] = (ex.t, ex.q, ex.qd, ex.qdd,
                            oc.inverse_dynamics(robot, ex.q, ex.qd, ex.qdd))
    return _CACHE["motion"]


def _log(name: str, extra: dict | None = None, edit=None):
    """A case builder writing the small log as ``name`` (``extra``: ``{column: value
    on every row}`` appended; ``edit(columns)`` changes the ``{column: (N,) values}``)."""
    from offshore_crane.conventions import QD_COLUMNS, QDD_COLUMNS
    from offshore_crane.outputs.visual.motion import FORCE_COLUMNS

    def write(tmp: Path) -> Path:
        t, q, qd, qdd, X = _motion()
        cols = {"t_s": t}
        for names, values in ((Q_COLUMNS, q), (QD_COLUMNS, qd), (QDD_COLUMNS, qdd),
                              (FORCE_COLUMNS, X)):
            cols.update(zip(names, values.T.copy()))
        cols.update({k: np.full(len(t), v) for k, v in (extra or {}).items()})
        if edit is not None:
            edit(cols)
        rows = [",".join(cols)] + [",".join(repr(float(c[k])) for c in cols.values())
                                   for k in range(len(t))]
        return _bytes(tmp, name, ("\n".join(rows) + "\n").encode())
    return write


def _identify(write, *extra):
    """``identify --log LOG ... --out tmp/out/id.toml``."""
    return lambda tmp: ["identify", "--log", str(write(tmp)), *extra,
                        "--out", str(tmp / "out" / "id.toml")]


def _set_column(names, value):
    def edit(cols):
        for n in names:
            cols[n] = np.full(len(cols["t_s"]), value)
    return edit


def _shift(name, by):
    def edit(cols):
        cols[name] = cols[name] + by
    return edit


def _identified(tmp: Path) -> Path:
    """A description as identify writes it (per-leg tables), of the nominal values."""
    from offshore_crane.studies import identification as ident

    robot = oc.load_robot()
    q, qd, qdd = ident.random_states(robot, 1, seed=0)
    R = ident.regressor(robot, q, qd, qdd)
    return _bytes(tmp, "identified.toml", ident.identified_description(robot, R, R.pi,
                                                                      "test").encode())


def _general(tmp: Path) -> Path:
    """tests/description_cases.py's general description (per-leg lower mass and com,
    per-leg upper inertia)."""
    import description_cases as dc

    return dc.write(tmp, dc.general())


CASES = [
    # ---- logs of a run identify cannot model: their columns say so
    Case("identify-elastic-log", "identify on an elastic cable's log (simulate's columns)",
         oc.InputError, r"--log .*elastic\.csv: columns payload_x_m, payload_y_m, "
         r"payload_z_m and 2 more record a payload on an elastic cable: identify models the "
         r"payload welded",
         cli=_identify(_log("elastic.csv", {"payload_x_m": 0.0, "payload_y_m": 0.0,
                                            "payload_z_m": -1.0, "tension_N": 20.0,
                                            "L_m": 1.0}))),
    Case("identify-winch-log", "identify on a log with a winch's columns",
         oc.InputError, r"columns L_m, Ld_m_s, Fw_N record a winch hoisting the payload",
         cli=_identify(_log("winch.csv", {"L_m": 1.0, "Ld_m_s": 0.0, "Fw_N": 19.6}))),
    Case("identify-tension-alone", "identify on a log with a cable's tension column",
         oc.InputError, r"columns tension_N record a payload swinging on a cable: .*log a "
         r"run with payload\.cable_length = 0",
         cli=_identify(_log("tension.csv", {"tension_N": 19.6}))),
    Case("identify-validate-sway", "--validate on a hanging load's log (sway columns)",
         oc.InputError, r"--validate .*sway\.csv: columns phi1_rad, phi2_rad record a "
         r"payload swinging on a cable",
         cli=lambda tmp: _identify(_log("good.csv"), "--validate", str(_log(
             "sway.csv", {"phi1_rad": 0.01, "phi2_rad": 0.0})(tmp)))(tmp)),
    Case("identify-forces-only", "identify on forces without positions (id --out)",
         oc.InputError, r"forces without positions \(what offshore-crane id writes\)",
         cli=_identify(_log("forces.csv", edit=lambda c: [c.pop(n) for n in Q_COLUMNS]))),
    # ---- another robot
    Case("identify-armless-log", "the lab robot on a log whose arm forces are nan (a "
         "platform without the arm, as id writes it)", oc.InputError,
         r"columns T1_Nm, T2_Nm, Fs_N are nan on every row: a run of a platform without the "
         r"crane arm; give that robot's description with --robot",
         cli=_identify(_log("armless.csv", edit=_set_column(("T1_Nm", "T2_Nm", "Fs_N"),
                                                            np.nan)))),
    Case("identify-arm-log-platform-robot", "the H&S platform (no arm) on a log whose "
         "arm moves", oc.InputError, r"q7\.\.q9 move, but the robot \(.*harib_srinivasan_"
         r"2003\.toml\) has no crane arm: a run of another robot",
         cli=_identify(_log("arm.csv"), "--robot", str(_HS))),
    Case("identify-arm-forces-platform-robot", "the H&S platform on a log whose arm stands "
         "still but carries forces", oc.InputError, r"columns T1_Nm, T2_Nm, Fs_N hold "
         r"forces, but the robot .* has no crane arm",
         cli=_identify(_log("still.csv", edit=_set_column(("q7_rad", "q8_rad", "q9_m"), 0.0)),
                       "--robot", str(_HS))),
    Case("identify-leg-force-missing", "a log whose Fl4 column is nan on every row",
         oc.InputError, r"column\(s\) Fl4_N are nan on every row: identify needs every "
         r"actuator's force", cli=_identify(_log("fl4.csv", edit=_set_column(("Fl4_N",),
                                                                              np.nan)))),
    Case("identify-arm-force-missing", "a log of the lab robot whose T2 column alone is "
         "nan on every row", oc.InputError, r"column\(s\) T2_Nm are nan on every row: "
         r"identify needs every actuator's force",
         cli=_identify(_log("t2.csv", edit=_set_column(("T2_Nm",), np.nan)))),
    Case("identify-outside-workspace", "a log whose platform runs 0.3 m higher (a bigger "
         "robot's)", oc.InputError, r"the positions leave the robot's workspace: leg\d "
         r"length = .* is outside .*: a run of another robot\? give its description with "
         r"--robot", cli=_identify(_log("high.csv", edit=_shift("q3_m", 0.3)))),
    Case("identify-cable-robot", "identify a robot whose payload hangs on a cable",
         oc.InputError, r"the robot's payload hangs on a 0\.7 m cable: identify models it "
         r"welded \(--set payload\.cable_length=0\)",
         cli=_identify(_log("good.csv"), "--set", "payload.mass=1", "--set",
                       "payload.cable_length=0.7")),
    # ---- inputs that are no file, and a missing one
    Case("identify-log-directory", "--log names a directory", oc.TrajectoryError,
         r"--log .*logs: is a directory, not a run's CSV",
         cli=lambda tmp: ["identify", "--log", str(_mkdir(tmp / "logs"))]),
    Case("identify-validate-device", "--validate names a character device",
         oc.TrajectoryError, r"--validate /dev/null: is a character device, not a run's CSV",
         cli=lambda tmp: _identify(_log("good.csv"), "--validate", "/dev/null")(tmp)),
    Case("identify-validate-missing", "--validate names no file (said before any fit)",
         oc.TrajectoryError, r"--validate .*nope\.csv: no such file",
         cli=lambda tmp: _identify(_log("good.csv"), "--validate", str(tmp / "nope.csv"))(tmp)),
    # ---- cut-offs the filter cannot realise
    Case("identify-cutoff-nyquist", "--cutoff at the log's Nyquist frequency (200 Hz log)",
         oc.InputError, r"cutoff = 100\.0 Hz: give a frequency in \(0, 100\) Hz",
         cli=_identify(_log("good.csv"), "--cutoff", "100")),
    Case("identify-cutoff-nan", "--cutoff nan", oc.InputError,
         r"--cutoff nan: give a frequency > 0", cli=_identify(_log("good.csv"), "--cutoff",
                                                               "nan")),
    # ---- excite: too short to determine the base parameters
    Case("excite-too-few-equations", "excite 0.05 s at 100 Hz: 6 samples, 54 equations",
         oc.InputError, r"--duration 0\.05 at 100 Hz: 6 samples, 54 equations for the 100 "
         r"base parameters: give --duration ≥ 0\.11 s",
         cli=lambda tmp: ["excite", "--duration", "0.05", "--out",
                          str(tmp / "out" / "e.csv")]),
    Case("excite-rank-deficient", "excite 0.3 s: enough equations, too little motion",
         oc.InputError, r"--duration 0\.3: the excitation's base regressor is rank-deficient "
         r"\(it excites \d+ of the 100 base parameters\)",
         cli=lambda tmp: ["excite", "--duration", "0.3", "--seeds", "1", "--iterations", "2",
                          "--out", str(tmp / "out" / "e.csv")]),
    # ---- --set on a field per-leg tables shadow (the identified description has them)
    Case("set-shadowed-identified", "--set legs.upper.mass on an identified description",
         oc.DescriptionError, r"identified\.toml with legs\.upper\.mass = 1\.5: legs 1-6 have "
         r"their own legs\.N\.upper\.mass \(per-leg tables\)",
         cli=lambda tmp: ["id", "--robot", str(_identified(tmp)), "--set",
                          "legs.upper.mass=1.5", "--duration", "0.1"]),
    Case("set-shadowed-inertia", "an override of legs.upper.inertia where each leg has its "
         "own", oc.DescriptionError, r"legs 1-6 have their own legs\.N\.upper\.inertia",
         lib=lambda tmp: oc.load_robot(_general(tmp), {"legs.upper.inertia": {
             "ixx": 0.01, "iyy": 0.01, "izz": 0.001}})),
]


def _mkdir(path: Path) -> Path:
    path.mkdir(exist_ok=True)
    return path
