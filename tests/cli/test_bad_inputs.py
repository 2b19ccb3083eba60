"""Catalogue of bad inputs (issues 6 and 10): each gives one clear error, never a silent
result.

Every case runs through the library (``pytest.raises(<OffshoreCraneError subclass>,
match=...)``) and/or the command line (``main(argv)``: exit status 2, stderr exactly one
line ``offshore-crane: error: ...``, no traceback, no file left where ``--out`` and
``--plot`` pointed, and every input — the case's files and the shipped scenes — unchanged
by checksum). :data:`CASES` is a plain list so that
``scripts/bad_input_catalogue.py`` can print every case with the message it produces.
Cases marked ``gap`` document a known shortcoming (strict xfail: the test turns red when
it is fixed, so the marker is removed with the fix).
"""

from __future__ import annotations

import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane import scenes
from offshore_crane.conventions import LEGACY_COLUMNS
from offshore_crane.motion import trajectories
from offshore_crane.__main__ import main
from offshore_crane.robot.kinematics.workspace import Thresholds
from offshore_crane.dynamics import solve

PREFIX = "offshore-crane: error: "
#: The longest message a case may print (issue 22: the rest goes to --help and the docs).
MESSAGE_MAX = 200


@dataclass(frozen=True)
class Case:
    """One bad input.

    Attributes:
        id: Short name (pytest id).
        description: What is wrong, for the catalogue.
        error: The library exception class expected.
        match: Regex searched in the library's message (and the CLI's, by default).
        lib: ``lib(tmp_dir)`` performs the library call, or None.
        cli: ``cli(tmp_dir)`` returns the ``offshore-crane`` argv, or None.
        gap: Why this case does not yet behave (strict xfail), or "".
        cli_match: Regex for the CLI's line when it words the error differently (the
            CLI checks its options through the scene layer), or None.
    """

    id: str
    description: str
    error: type
    match: str
    lib: Callable[[Path], object] | None = None
    cli: Callable[[Path], list] | None = None
    gap: str = ""
    cli_match: str | None = None


_SCENES = Path(__file__).resolve().parents[2] / "scenes"
_LAB = Path(__file__).resolve().parents[2] / "models" / "descriptions" / "lab.toml"


# --------------------------------------------------------------------------- helpers
def _robot():
    return oc.load_robot()


def _states(n=5):
    return [x.copy() for x in trajectories.table1(np.linspace(0.0, 1.0, n))]


def _with(index, value, which=0, n=5):
    """Table 1 states with ``states[which][index] = value``."""
    s = _states(n)
    s[which][index] = value
    return s


def _id(*states, **kw):
    return oc.inverse_dynamics(_robot(), *states, **kw)


def _rows(n=20, edit=None):
    """Text rows of a valid trajectory CSV (Table 1 at 100 Hz), optionally edited."""
    t = np.arange(n) / 100.0
    q = trajectories.table1(t)[0]
    if edit is not None:
        edit(q)
    return [",".join(trajectories.CSV_COLUMNS)] + [
        ",".join(repr(float(x)) for x in (ti, *qi)) for ti, qi in zip(t, q)]


def _csv(name, rows=None, text=None):
    """A case builder writing ``name`` in the scratch directory and returning its path."""
    def write(tmp: Path) -> Path:
        path = tmp / name
        path.write_text(text if text is not None else "\n".join(rows) + "\n")
        return path
    return write


def _cell(rows, line, column, value):
    """``rows`` with data line ``line`` (1-based after the header), ``column`` replaced."""
    rows = list(rows)
    cells = rows[line].split(",")
    cells[trajectories.CSV_COLUMNS.index(LEGACY_COLUMNS.get(column, column))] = value
    rows[line] = ",".join(cells)
    return rows


def _pose(**set_q):
    """Rows of a static trajectory at Table 1's t = 0 pose with some q_j replaced."""
    def edit(q):
        for name, value in set_q.items():
            q[:, int(name[1:]) - 1] = value
    return _rows(edit=edit)


def _yaw_sweep(q):
    q[:, :] = 0.0
    q[:, 2] = 0.5
    q[:, 5] = np.radians(np.linspace(80.0, 100.0, len(q)))   # through 90° (sample 10)


def _load(write, **kw):
    return lambda tmp: trajectories.load(write(tmp), **kw)


def _solve_csv(write, **kw):
    def run(tmp):
        traj = trajectories.load(write(tmp))
        return solve(_robot(), traj.q, traj.qd, traj.qdd, t=traj.t, **kw)
    return run


def _argv(write, *extra):
    return lambda tmp: ["id", "--trajectory", str(write(tmp)), *extra]


def _bytes(tmp: Path, name: str, data: bytes) -> Path:
    path = tmp / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)
    return path


#: A one-joint serial robot (edited by the serial-id cases).
SERIAL = (b'<robot name="r"><link name="a"/><link name="b"><inertial><mass value="1"/>'
          b'<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>'
          b'<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
          b'<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
          b'</robot>')


def _set(*items):
    return lambda tmp: ["id", "--duration", "1", *[a for i in items for a in ("--set", i)]]


def _urdf_with(link, **attrs):
    """The default URDF with ``link``'s inertia attributes replaced (hand-edited URDF)."""
    text = _robot().urdf
    start = text.index(f'<link name="{link}">')
    end = text.index("</inertial>", start)
    block = text[start:end]
    for key, value in attrs.items():
        block = re.sub(rf'{key}="[^"]*"', f'{key}="{value}"', block)
    return text[:start] + block + text[end:]


def _validate(link, **attrs):
    def run(tmp):
        from offshore_crane.robot.urdf import parse_urdf
        from offshore_crane.robot.validate import validate

        validate(parse_urdf(_urdf_with(link, **attrs)))
    return run


GOOD = _rows()
BAD_VALUE = r"is (nan|inf|-inf) \(sample \d+, column \d\); every value must be finite"
# An exact U-joint gimbal pose (leg 1 along its first U-joint axis: cos θ2 = 0 exactly).
EXACT_GIMBAL = [0.5353804327714754, -0.6782249000139075, 0.07484517189224046,
                0.2503646726300526, -0.21959124201396008, -0.014809025568364942, 0.0, 0.0,
                0.0]

CASES = [
    # ---- NaN / inf
    Case("nan-q", "NaN in q", oc.InputError, r"q\[3, 4\] is nan \(sample 3, column 5\)",
         lib=lambda tmp: _id(*_with((3, 4), np.nan))),
    Case("inf-qd", "inf in qd", oc.InputError, r"qd\[1, 0\] is inf \(sample 1, column 1\)",
         lib=lambda tmp: _id(*_with((1, 0), np.inf, which=1))),
    Case("ninf-qdd", "-inf in qdd", oc.InputError, r"qdd\[4, 8\] is -inf \(sample 4, column 9\)",
         lib=lambda tmp: _id(*_with((4, 8), -np.inf, which=2))),
    Case("nan-csv", "NaN in a CSV cell", oc.TrajectoryError,
         r"line 4, column q5_rad: 'nan' is not finite",
         lib=_load(_csv("nan.csv", _cell(GOOD, 3, "q5", "nan"))),
         cli=_argv(_csv("nan.csv", _cell(GOOD, 3, "q5", "nan")))),
    Case("inf-csv", "inf in a CSV cell", oc.TrajectoryError,
         r"line 6, column q1_m: '-inf' is not finite",
         lib=_load(_csv("inf.csv", _cell(GOOD, 5, "q1", "-inf"))),
         cli=_argv(_csv("inf.csv", _cell(GOOD, 5, "q1", "-inf")))),
    Case("nan-time-csv", "NaN time in a CSV", oc.TrajectoryError,
         r"line 3, column t_s: 'nan' is not finite",
         cli=_argv(_csv("nant.csv", _cell(GOOD, 2, "t_s", "nan")))),
    Case("nan-gravity", "NaN gravity", oc.InputError, r"gravity must be 3 finite numbers",
         lib=lambda tmp: _id(*_states(), gravity=(0, 0, np.nan)),
         cli=lambda tmp: ["id", "--duration", "1", "--gravity", "0", "0", "nan"],
         cli_match=r"gravity.*must be 3 finite numbers"),
    # ---- shapes and lengths
    Case("q-8-columns", "q with 8 columns", oc.InputError,
         r"q has shape \(5, 8\); expected \(9,\) or \(N, 9\)",
         lib=lambda tmp: _id(_states()[0][:, :8], *_states()[1:])),
    Case("qd-3d", "qd with three axes", oc.InputError,
         r"qd has shape \(1, 5, 9\); expected \(9,\) or \(N, 9\)",
         lib=lambda tmp: _id(_states()[0], _states()[1][None], _states()[2])),
    Case("q-empty", "q with no samples", oc.InputError, r"q has no samples",
         lib=lambda tmp: _id(*(x[:0] for x in _states()))),
    Case("lengths-differ", "q, qd, qdd of different lengths", oc.InputError,
         r"sample counts differ: q has 5, qd has 4, qdd has 5",
         lib=lambda tmp: _id(_states()[0], _states()[1][:4], _states()[2])),
    Case("q-text", "q not numeric", oc.InputError, r"q must be an array of numbers",
         lib=lambda tmp: _id(np.full((5, 9), "x"), *_states()[1:])),
    Case("t-length", "t of the wrong length", oc.InputError,
         r"t has shape \(4,\); expected \(5,\)",
         lib=lambda tmp: solve(_robot(), *_states(), t=np.arange(4.0))),
    Case("gravity-shape", "gravity with 2 components", oc.InputError,
         r"gravity must be 3 finite numbers",
         lib=lambda tmp: _id(*_states(), gravity=(0, -9.81))),
    Case("outputs-unknown", "unknown actuator name in outputs", oc.InputError,
         r"unknown outputs \['Fl7'\]",
         lib=lambda tmp: _id(*_states(), outputs=["Fl7"]),
         cli=lambda tmp: ["id", "--duration", "1", "--outputs", "T1,Fl7"],
         cli_match=r"unknown.*'?Fl7'?.*choose among T1, T2, Fs, Fl1"),
    Case("method-unknown", "unknown method", oc.InputError, r"unknown method 'newton'",
         lib=lambda tmp: _id(*_states(), method="newton")),
    Case("leg-model-rnea", "approximate leg model with the RNEA method", oc.InputError,
         r"leg model 'thin-rod' is an approximation offered by method 'kane' only",
         lib=lambda tmp: _id(*_states(), method="rnea", leg_model="thin-rod"),
         cli=lambda tmp: ["id", "--duration", "1", "--method", "rnea", "--leg-model",
                          "thin-rod"],
         cli_match=r"thin-rod.*approximation offered by method '?kane'? only"),
    # ---- CSV files
    Case("csv-missing-column", "CSV without column q9", oc.TrajectoryError,
         r"line 1: missing column\(s\) q9",
         lib=_load(_csv("miss.csv", [r.rsplit(",", 1)[0] for r in GOOD])),
         cli=_argv(_csv("miss.csv", [r.rsplit(",", 1)[0] for r in GOOD]))),
    Case("csv-extra-column", "CSV with an extra column q10", oc.TrajectoryError,
         r"line 1: unknown column\(s\) 'q10'",
         lib=_load(_csv("extra.csv", [GOOD[0] + ",q10"] + [r + ",0" for r in GOOD[1:]])),
         cli=_argv(_csv("extra.csv", [GOOD[0] + ",q10"] + [r + ",0" for r in GOOD[1:]]))),
    Case("csv-column-order", "CSV with q1 and q2 swapped in the header", oc.TrajectoryError,
         r"columns are in the order t_s,q2_m,q1_m,",
         cli=_argv(_csv("order.csv", [GOOD[0].replace("q1_m,q2_m", "q2_m,q1_m")] + GOOD[1:]))),
    Case("csv-short-row", "CSV row with a missing cell", oc.TrajectoryError,
         r"line 5: 9 cells, expected 10",
         lib=_load(_csv("short.csv", GOOD[:4] + [GOOD[4].rsplit(",", 1)[0]] + GOOD[5:])),
         cli=_argv(_csv("short.csv", GOOD[:4] + [GOOD[4].rsplit(",", 1)[0]] + GOOD[5:]))),
    Case("csv-non-numeric", "CSV with a non-numeric cell", oc.TrajectoryError,
         r"line 3, column q3_m: 'abc' is not a number",
         lib=_load(_csv("text.csv", _cell(GOOD, 2, "q3", "abc"))),
         cli=_argv(_csv("text.csv", _cell(GOOD, 2, "q3", "abc")))),
    Case("csv-time-decreasing", "CSV whose time goes backwards", oc.TrajectoryError,
         r"line 8: time t_s = 0\.04 s does not increase after 0\.05 s on line 7",
         lib=_load(_csv("back.csv", _cell(GOOD, 7, "t_s", "0.04"))),
         cli=_argv(_csv("back.csv", _cell(GOOD, 7, "t_s", "0.04")))),
    Case("csv-time-repeated", "CSV with a repeated time", oc.TrajectoryError,
         r"line 9: time t_s = 0\.06 s does not increase after 0\.06 s on line 8",
         cli=_argv(_csv("dup.csv", _cell(GOOD, 8, "t_s", "0.06")))),
    Case("csv-time-uneven", "CSV with non-uniform time steps", oc.TrajectoryError,
         r"the time axis is not uniform: step 8 \(t\[9\] - t\[8\] = 0\.013 s\)",
         lib=_load(_csv("uneven.csv", _cell(GOOD, 10, "t_s", "0.093"))),
         cli=_argv(_csv("uneven.csv", _cell(GOOD, 10, "t_s", "0.093")))),
    Case("csv-too-short", "CSV too short for the finite differences", oc.TrajectoryError,
         r"finite differences of order 4 need at least 6 samples, got 4",
         lib=_load(_csv("four.csv", GOOD[:5])), cli=_argv(_csv("four.csv", GOOD[:5]))),
    Case("csv-one-row", "CSV with one data row", oc.TrajectoryError,
         r"1 data row\(s\), at least 2 are needed",
         cli=_argv(_csv("one.csv", GOOD[:2]))),
    Case("csv-empty", "empty CSV file", oc.TrajectoryError, r"empty.csv' is empty",
         lib=_load(_csv("empty.csv", text="")), cli=_argv(_csv("empty.csv", text=""))),
    Case("csv-with-duration", "--duration given with a CSV trajectory", oc.TrajectoryError,
         r"duration and rate \(--duration, --rate\) apply to table1 only",
         lib=_load(_csv("ok.csv", GOOD), duration=5.0),
         cli=_argv(_csv("ok.csv", GOOD), "--duration", "5")),
    # ---- trajectory names and table1 options
    Case("trajectory-unknown", "unknown trajectory name", oc.TrajectoryError,
         r"unknown trajectory 'table2': use 'table1' or the path of a CSV file",
         lib=lambda tmp: trajectories.load("table2"),
         cli=lambda tmp: ["id", "--trajectory", "table2"]),
    Case("trajectory-missing-file", "CSV path that does not exist", oc.TrajectoryError,
         r"unknown trajectory '.*nope\.csv'",
         cli=lambda tmp: ["id", "--trajectory", str(tmp / "nope.csv")]),
    Case("rate-negative", "negative sampling rate", oc.TrajectoryError,
         r"rate must be positive and finite \[Hz\], got -5\.0",
         lib=lambda tmp: trajectories.load("table1", rate=-5),
         cli=lambda tmp: ["id", "--rate", "-5"]),
    Case("duration-inf", "infinite duration", oc.TrajectoryError,
         r"duration must be positive and finite \[s\], got inf",
         cli=lambda tmp: ["id", "--duration", "inf"]),
    Case("too-many-samples", "more samples than the limit", oc.TrajectoryError,
         r"gives about 1e\+11 samples, more than the limit 100000000",
         cli=lambda tmp: ["id", "--duration", "1e9"]),
    Case("thresholds-order", "warning threshold above the error threshold", oc.InputError,
         r"condition-number thresholds need 1 <= warn <= error, got warn=1e\+09, error=1e\+08",
         lib=lambda tmp: solve(_robot(), *_states(), thresholds=Thresholds(1e9)),
         cli=lambda tmp: ["id", "--duration", "1", "--warn-cond", "1e9"]),
    Case("thresholds-nan", "NaN threshold", oc.InputError,
         r"condition-number thresholds need 1 <= warn <= error",
         cli=lambda tmp: ["id", "--duration", "1", "--error-cond", "nan"]),
    Case("out-dir-missing", "--out in a directory that does not exist", oc.InputError,
         r"cannot write .*x\.csv: directory .*missing does not exist",
         cli=lambda tmp: ["id", "--duration", "1", "--out", str(tmp / "missing" / "x.csv")]),
    # ---- unreachable poses
    Case("below-base", "platform below the base", oc.WorkspaceError,
         r"sphere centre S1 is 0\.\d+ m below its U-joint at sample 0 \(t = 0 s\) "
         r"\(platform below the base\)",
         lib=_solve_csv(_csv("below.csv", _pose(q3=-0.3))),
         cli=_argv(_csv("below.csv", _pose(q3=-0.3)))),
    Case("leg-too-long", "legs that cannot reach (platform too high)", oc.WorkspaceError,
         r"leg\d length = 0\.9\d+ m at sample 0 \(t = 0 s\) is outside \[0\.4, 0\.82\] m",
         lib=_solve_csv(_csv("high.csv", _pose(q3=0.9))),
         cli=_argv(_csv("high.csv", _pose(q3=0.9)))),
    Case("leg-too-short", "legs shorter than their stroke (platform too low)",
         oc.WorkspaceError,
         r"leg\d length = 0\.[0-3]\d+ m at sample 0 .* outside \[0\.4, 0\.82\] m",
         cli=_argv(_csv("low.csv", _pose(q3=0.3)))),
    Case("stroke-on-table1", "Table 1 beyond a shortened stroke", oc.WorkspaceError,
         r"leg\d length = 0\.7\d+ m at sample \d+ \(t = [\d.]+ s\) is outside \[0\.4, 0\.7\] m",
         cli=lambda tmp: ["id", "--set", "leg_max_length=0.7"]),
    Case("arm-joint-limit", "arm joint beyond its limit", oc.WorkspaceError,
         r"arm_joint2 = 2\.5 rad at sample 0 \(t = 0 s\) is outside \[-2, 2\] rad",
         lib=_solve_csv(_csv("arm.csv", _pose(q8=2.5))),
         cli=_argv(_csv("arm.csv", _pose(q8=2.5)))),
    Case("ujoint-limit", "U-joint beyond its limit (platform far sideways)", oc.WorkspaceError,
         r"leg\d_u\d = -?1\.\d+ rad at sample 0 .* outside \[-1\.2, 1\.2\] rad",
         cli=_argv(_csv("side.csv", _pose(q1=0.9, q3=0.5)), "--set", "leg_max_length=2")),
    Case("stewart-singular", "trajectory through a Stewart singularity (--no-limits)",
         oc.SingularConfigurationError,
         r"leg-Jacobian singularity: condition number [\d.]+e\+\d+ at sample 10 "
         r"\(t = 0\.1 s\) exceeds 1e\+08",
         lib=_solve_csv(_csv("sing.csv", _rows(21, _yaw_sweep)), limits=False),
         cli=_argv(_csv("sing.csv", _rows(21, _yaw_sweep)), "--no-limits")),
    # ---- robot parameters (--set / load_robot overrides)
    Case("set-unknown", "unknown --set name", oc.ModelError,
         r"unknown robot parameter 'platfrom_mass'; did you mean platform_mass",
         lib=lambda tmp: oc.load_robot(platfrom_mass=3), cli=_set("platfrom_mass=3")),
    Case("set-no-value", "--set without '='", oc.InputError,
         r"--set expects name=value, got 'platform_mass'",
         cli=lambda tmp: ["id", "--set", "platform_mass"]),
    Case("set-text", "non-numeric parameter", oc.ModelError,
         r"robot parameter platform_mass \(platform\.mass\)='heavy' is not a number",
         lib=lambda tmp: oc.load_robot(platform_mass="heavy"), cli=_set("platform_mass=heavy")),
    Case("set-nan", "NaN parameter", oc.ModelError,
         r"robot parameter link1_mass \(arm\.link1\.mass\)=nan is not finite",
         cli=_set("link1_mass=nan")),
    Case("mass-negative", "negative mass", oc.ModelError,
         r"lab\.toml \(default\) with platform\.mass = -5: "
         r"platform\.mass: -5 kg is negative; give a mass >= 0",
         lib=lambda tmp: oc.load_robot(platform_mass=-5), cli=_set("platform_mass=-5")),
    Case("leg-mass-negative", "negative leg mass", oc.ModelError,
         r"with legs\.upper\.mass = -0\.8: legs\.upper\.mass: -0\.8 kg is negative",
         cli=_set("leg_upper_mass=-0.8")),
    Case("inertia-not-pd", "inertia with a negative principal moment (URDF)", oc.ModelError,
         r"link 'platform': inertia is not positive definite, principal moments "
         r"\(-1, 1\.60533, 3\.2\) kg·m² include a negative one",
         lib=_validate("platform", ixx="-1")),
    Case("inertia-triangle", "inertia violating the triangle inequality (URDF)",
         oc.ModelError, r"link 'arm_link1': principal moments of inertia \(0\.001, 0\.001, 1\) "
         r"kg·m² violate the triangle inequality \(1 > 0\.001 \+ 0\.001\)",
         lib=_validate("arm_link1", ixx="0.001", iyy="0.001", izz="1")),
    Case("payload-inertia-not-pd", "payload inertia with a negative moment", oc.ModelError,
         r"with payload\.mass = 10, payload\.inertia\.ixx = -1: payload\.inertia: "
         r"not positive definite: principal moments \(-1, 0, 0\) kg·m² include a negative "
         r"one",
         lib=lambda tmp: oc.load_robot(payload_mass=10, payload_ixx=-1),
         cli=_set("payload_mass=10", "payload_ixx=-1")),
    Case("payload-inertia-triangle", "payload inertia violating the triangle inequality",
         oc.ModelError, r"payload\.inertia: principal moments \(0\.1, 0\.1, 1\) kg·m² break the "
         r"triangle inequality",
         cli=_set("payload_mass=10", "payload_ixx=0.1", "payload_iyy=0.1", "payload_izz=1")),
    Case("payload-mass-negative", "negative payload mass (which the xacro would drop)",
         oc.ModelError, r"with payload\.mass = -3: payload\.mass: -3 kg is negative",
         cli=_set("payload_mass=-3")),
    Case("inertia-nan", "NaN in an inertia (URDF)", oc.ModelError,
         r"link 'arm_slider': inertia is not finite", lib=_validate("arm_slider", iyy="nan")),
    Case("link-zero-length", "zero-length arm link", oc.ModelError,
         r"with arm\.link1\.shape\.size\.x = 0: arm\.link2\.origin: arm_joint2 lies on "
         r"arm_joint1's axis: link 'arm_link1' would have zero length",
         lib=lambda tmp: oc.load_robot(link1_length=0),
         cli=_set("link1_length=0")),
    Case("leg-link-zero-length", "zero-length leg link", oc.ModelError,
         r"legs\.upper\.length: 0 m must be positive: links 'leg\{i\}_upper' would have "
         r"zero length", cli=_set("leg_upper_length=0")),
    Case("radius-negative", "negative radius", oc.ModelError,
         r"arm\.column\.shape\.radius: -0\.05 m must not be negative",
         cli=_set("column_radius=-0.05")),
    Case("stroke-empty", "leg stroke with lower >= upper", oc.ModelError,
         r"with legs\.stroke\.min = 0\.9: legs\.stroke: the stroke \[0\.9, 0\.82\] m "
         r"of leg 1 is empty \(need min < max\)",
         lib=lambda tmp: oc.load_robot(leg_min_length=0.9), cli=_set("leg_min_length=0.9")),
    Case("ujoint-limit-zero", "U-joint range of zero width", oc.ModelError,
         r"legs\.ujoint\.limit: 0 rad: need 0 < limit <= pi/2",
         cli=_set("ujoint_limit=0")),
    Case("home-unreachable", "legs that cannot reach the home pose", oc.ModelError,
         r"legs\.stroke: leg 1 cannot reach the home pose: \|P1S1\| = 0\.551062 m is outside "
         r"the stroke \[0\.4, 0\.45\] m",
         lib=lambda tmp: oc.load_robot(leg_max_length=0.45), cli=_set("leg_max_length=0.45")),
    Case("home-below-base", "home pose with the platform below the U-joints", oc.ModelError,
         r"with home\.height = 0\.03: home\.height: at the home pose sphere centre S1 "
         r"is 0\.04 m below its U-joint \(platform below the base\)",
         cli=_set("home_height=0.03")),
    Case("anchors-coincide", "base anchors on a circle of radius zero", oc.ModelError,
         r"with base\.joints\.radius = 0: base\.joints: P1 and P2 coincide",
         cli=_set("base_radius=0")),
    Case("design-singular", "anchors making every leg vertical (singular design)",
         oc.ModelError, r"with base\.joints\.radius = 0\.35, "
         r"base\.joints\.half_angle_deg = 45: platform\.joints: singular legs at the home "
         r"pose \(Stewart matrix condition inf\): move the anchors",
         lib=lambda tmp: oc.load_robot(base_radius=0.35, base_half_angle_deg=45),
         cli=_set("base_radius=0.35", "base_half_angle_deg=45")),
    # ---- one override path (issue 10, family 7): scene fields and --set
    Case("set-contradicts-scene", "--set with_arm=1 on a scene without arm", oc.SceneError,
         r"--set arm\.enabled = true contradicts the scene's \[subsystems\] arm = false",
         lib=lambda tmp: scenes.with_robot_overrides(
             scenes.load_scene(_SCENES / "platform_only.toml"), {"arm.enabled": True}),
         cli=lambda tmp: ["id", "--scene", str(_SCENES / "platform_only.toml"), "--set",
                          "with_arm=1"]),
    Case("set-payload-no-arm", "--set payload_mass on a scene without arm", oc.SceneError,
         r"payload\.mass: 100 kg: the payload hangs from the arm tip, but the robot has no "
         r"arm", cli=lambda tmp: ["id", "--scene", str(_SCENES / "platform_only.toml"),
                                  "--set", "payload_mass=100"]),
    Case("with-arm-number", "with_arm given a number other than 0/1", oc.ModelError,
         r"with_arm \(arm\.enabled\)=0\.5 must be true or false \(1 or 0\)",
         lib=lambda tmp: oc.load_robot(with_arm=0.5), cli=_set("with_arm=0.5")),
    Case("mass-huge", "a mass beyond what float64 carries through the dynamics",
         oc.ModelError, r"platform_mass \(platform\.mass\)=1e\+308 exceeds the magnitude "
         r"limit 1e\+100", lib=lambda tmp: oc.load_robot(platform_mass=1e308),
         cli=_set("platform_mass=1e308")),
    # ---- former gaps (fixed: argparse errors, early output checks, exact singularity)
    Case("argparse-choice", "unknown --method (argparse)", oc.InputError,
         r"argument --method: invalid choice: 'foo'",
         cli=lambda tmp: ["id", "--method", "foo"]),
    Case("argparse-float", "non-numeric --rate (argparse)", oc.InputError,
         r"argument --rate: invalid float value: 'abc'",
         cli=lambda tmp: ["id", "--rate", "abc"]),
    Case("plot-format", "--plot with an unsupported file type", oc.InputError,
         r"xyz", cli=lambda tmp: ["id", "--duration", "1", "--plot", str(tmp / "out" / "x.xyz")]),
    Case("exact-gimbal", "pose exactly at a U-joint gimbal lock", oc.SingularConfigurationError,
         r"U-joint gimbal singularity|leg-Jacobian singularity",
         lib=lambda tmp: solve(_robot(), EXACT_GIMBAL, np.eye(9)[0] * 0.1, np.zeros(9),
                               limits=False)),
    # ---- issue 10: numbers beyond float64's reach give an error, never NaN/inf
    Case("gravity-huge", "a gravity of 1e308 m/s²", oc.InputError,
         r"gravity .* exceeds 1e\+06 m/s² in size",
         lib=lambda tmp: _id(*_states(), gravity=(0.0, 0.0, -1e308)),
         cli=lambda tmp: ["id", "--duration", "1", "--gravity", "0", "0", "-1e308"]),
    Case("rates-overflow", "rates of 1e160 (the forces overflow)", oc.NumericalError,
         r"T1 is not finite at sample 0: the dynamics overflowed",
         lib=lambda tmp: _id(*_with((slice(None), slice(None)), 1e160, which=1),
                             limits=False, checks=False)),
    # ---- issue 10: foreign exceptions from odd library arguments
    Case("gravity-text", "gravity given as a string", oc.InputError,
         r"gravity must be 3 real numbers", lib=lambda tmp: _id(*_states(), gravity="down")),
    Case("thresholds-number", "thresholds given as a number", oc.InputError,
         r"thresholds must be a Thresholds", lib=lambda tmp: _id(*_states(), thresholds=5)),
    Case("outputs-number", "outputs given as a number", oc.InputError,
         r"outputs must be a list of actuator names", lib=lambda tmp: _id(*_states(), outputs=3)),
    Case("complex-q", "complex coordinates", oc.InputError, r"q has complex values",
         lib=lambda tmp: _id(_states()[0] + 0j, *_states()[1:])),
    Case("masked-q", "a masked array", oc.InputError, r"q is a masked array",
         lib=lambda tmp: _id(np.ma.masked_less(_states()[0], 0.0), *_states()[1:])),
    Case("read-csv-none", "read_csv(None)", oc.TrajectoryError,
         r"the trajectory file must be a path, got None",
         lib=lambda tmp: trajectories.read_csv(None)),
    Case("write-csv-directory", "write_csv to a directory", oc.OffshoreCraneError,
         r"cannot write .*: is a directory",
         lib=lambda tmp: trajectories.write_csv(tmp, [0.0, 1.0], np.zeros((2, 9)))),
    # ---- issue 10: text that is not UTF-8
    Case("scene-key-quoted-and-dotted", "one robot field given as a quoted key and as "
         "dotted keys in one scene table (the last silently won)", oc.SceneError,
         r"\[robot\] legs\.lower\.mass is given twice, as \"legs\.lower\.mass\" \(a quoted "
         r"key\) and as legs\.lower\.mass \(dotted keys\): give it once",
         lib=lambda tmp: oc.scenes.load_scene(_bytes(tmp, "twice.toml", b'[robot]\n'
                                                     b'"legs.lower.mass" = 3.1\n'
                                                     b'legs.lower.mass = 3.2\n')),
         cli=lambda tmp: ["id", "--scene", str(_bytes(tmp, "twice.toml", b'[robot]\n'
                                                      b'legs.lower.mass = 3.2\n'
                                                      b'"legs.lower.mass" = 3.1\n'))]),
    Case("scene-not-utf8", "a scene file with a non-UTF-8 byte", oc.SceneError,
         r"x\.toml, line 1, column 9: byte 0xff is not UTF-8",
         lib=lambda tmp: oc.scenes.load_scene(_bytes(tmp, "x.toml", b'name = "\xff"\n')),
         cli=lambda tmp: ["id", "--scene", str(_bytes(tmp, "x.toml", b'name = "\xff"\n'))]),
    Case("csv-not-utf8", "a trajectory CSV with a non-UTF-8 byte", oc.TrajectoryError,
         r"x\.csv, line 2, column 3: byte 0xff is not UTF-8",
         lib=lambda tmp: trajectories.load(_bytes(tmp, "x.csv", b"t_s\n0,\xff\n")),
         cli=lambda tmp: ["id", "--trajectory", str(_bytes(tmp, "x.csv", b"t_s\n0,\xff\n"))]),
    Case("fd-order-table1", "--fd-order with table1", oc.InputError,
         r"--fd-order applies to a CSV trajectory only", cli=lambda tmp: ["id", "--fd-order", "2"]),
    # ---- issue 10: serial-id validates its URDF
    Case("serial-duplicate-link", "serial-id: a link defined twice", oc.ModelError,
         r"defines link 'b' twice",
         lib=lambda tmp: oc.serial.load_chain(_bytes(tmp, "r.urdf", SERIAL.replace(
             b'<link name="b">', b'<link name="b"/><link name="b">'))),
         cli=lambda tmp: ["serial-id", str(_bytes(tmp, "r.urdf", SERIAL.replace(
             b'<link name="b">', b'<link name="b"/><link name="b">')))]),
    Case("serial-no-limits", "serial-id: a revolute joint without <limit>", oc.ModelError,
         r"joint 'j' is revolute but has no <limit>",
         lib=lambda tmp: oc.serial.load_chain(_bytes(tmp, "r.urdf", SERIAL.replace(
             b'<limit lower="-1" upper="1" effort="1" velocity="1"/>', b""))),
         cli=lambda tmp: ["serial-id", str(_bytes(tmp, "r.urdf", SERIAL.replace(
             b'<limit lower="-1" upper="1" effort="1" velocity="1"/>', b"")))]),
    Case("serial-nan-mass", "serial-id: a NaN mass", oc.ModelError,
         r"link 'b': mass nan kg is not finite",
         lib=lambda tmp: oc.serial.load_chain(_bytes(tmp, "r.urdf", SERIAL.replace(
             b'mass value="1"', b'mass value="nan"'))),
         cli=lambda tmp: ["serial-id", str(_bytes(tmp, "r.urdf", SERIAL.replace(
             b'mass value="1"', b'mass value="nan"')))]),
    Case("serial-negative-mass", "serial-id: a negative mass", oc.ModelError,
         r"link 'b': mass -1 kg is negative",
         lib=lambda tmp: oc.serial.load_chain(_bytes(tmp, "r.urdf", SERIAL.replace(
             b'mass value="1"', b'mass value="-1"')))),
    Case("serial-inverted-limits", "serial-id: lower > upper", oc.ModelError,
         r"joint 'j': limits \[1, -1\] rad is empty",
         lib=lambda tmp: oc.serial.load_chain(_bytes(tmp, "r.urdf", SERIAL.replace(
             b'lower="-1" upper="1"', b'lower="1" upper="-1"')))),
    Case("serial-not-utf8", "serial-id: a URDF with a non-UTF-8 byte", oc.InputError,
         r"r\.urdf: byte .* is not UTF-8",
         cli=lambda tmp: ["serial-id", str(_bytes(tmp, "r.urdf", SERIAL.replace(
             b'name="r"', b'name="\xff"')))]),
    Case("serial-negative-seed", "serial-id --seed -1", oc.InputError,
         r"the seed must be an integer ≥ 0, got -1",
         cli=lambda tmp: ["serial-id", str(_bytes(tmp, "r.urdf", SERIAL)), "--seed", "-1"]),
    Case("serial-too-many", "serial-id --random 1e11", oc.InputError,
         r"random states must be at least 1 and at most 10,000,000",
         cli=lambda tmp: ["serial-id", str(_bytes(tmp, "r.urdf", SERIAL)),
                          "--random", "100000000000"]),
    # ---- the hanging load (issue 14)
    Case("cable-negative-length", "a negative cable length", oc.DescriptionError,
         r"payload\.cable_length: -1 m must not be negative",
         lib=lambda tmp: oc.load_robot(overrides={"payload.mass": 2.0,
                                                  "payload.cable_length": -1.0}),
         cli=lambda tmp: ["id", "--duration", "1", "--set", "payload.mass=2", "--set",
                          "payload.cable_length=-1"]),
    Case("cable-without-mass", "a cable with no payload mass", oc.DescriptionError,
         r"a cable needs a payload to hang from it",
         lib=lambda tmp: oc.load_robot(overrides={"payload.cable_length": 0.5}),
         cli=lambda tmp: ["id", "--duration", "1", "--set", "payload.cable_length=0.5"]),
    Case("cable-rigid-payload", "a cable with a payload offset", oc.DescriptionError,
         r"the payload is a point mass at the cable's end",
         lib=lambda tmp: oc.load_robot(overrides={"payload.mass": 2.0, "payload.com": [0, 0,
                                                  -0.1], "payload.cable_length": 0.5})),
    Case("cable-zero-length-argument", "cable.inverse_dynamics(length=0, mass=2)",
         oc.InputError, r"length = 0\.0 m: the cable needs a finite length > 0",
         lib=lambda tmp: oc.dynamics.cable.inverse_dynamics(
             oc.load_robot(), **_cable_states(), length=0.0, mass=2.0)),
    Case("cable-nan-sway", "a NaN initial sway", oc.InputError,
         r"initial must be two finite numbers",
         lib=lambda tmp: oc.dynamics.cable.inverse_dynamics(_crane(), **_cable_states(),
                                                   initial=(np.nan, 0.0)),
         cli=lambda tmp: ["id", "--duration", "1", "--set", "payload.mass=2", "--set",
                          "payload.cable_length=0.5", "--initial-sway", "nan", "0"]),
    Case("cable-singular-sway", "an initial sway on the singular set cos(phi2) = 0",
         oc.InputError, r"lies on the singular set cos\(phi2\) = 0",
         lib=lambda tmp: oc.dynamics.cable.inverse_dynamics(_crane(), **_cable_states(),
                                                   initial=(0.0, np.pi / 2)),
         cli=lambda tmp: ["id", "--duration", "1", "--set", "payload.mass=2", "--set",
                          "payload.cable_length=0.5", "--initial-sway", "0",
                          "1.5707963267948966"]),
    Case("cable-slack", "gravity pointing up: the cable would have to push",
         oc.SlackCableError, r"the cable goes slack at sample 0",
         lib=lambda tmp: oc.dynamics.cable.inverse_dynamics(_crane(), **_cable_states(),
                                                   gravity=(0, 0, 9.81)),
         cli=lambda tmp: ["id", "--duration", "1", "--set", "payload.mass=2", "--set",
                          "payload.cable_length=0.5", "--gravity", "0", "0", "9.81"]),
    Case("cable-simulation-stops-at-start", "a hanging-load simulation that stops at its "
         "first sample (once an IndexError in the CLI)", oc.SimulationError,
         r"stopped at t = 0 s: the cable went slack .*; no sample was computed before it",
         cli=lambda tmp: ["simulate", "--scene", str(_SCENES / "hanging_load.toml"),
                          "--duration", "0.05", "--gravity", "0", "0", "9.81",
                          "--out", str(tmp / "run.csv")]),
    Case("set-nested-too-deeply", "an expression of 1000 minus signs (once a "
         "RecursionError)", oc.ModelError,
         r"payload\.mass\)?: '-{57}\.\.\.' \(1001 characters\) is nested too deeply to "
         r"evaluate: simplify it",
         lib=lambda tmp: oc.load_robot(overrides={"payload.mass": "-" * 1000 + "1"}),
         cli=lambda tmp: ["id", "--duration", "0.1", "--set",
                          "payload_mass=" + "-" * 1000 + "1"]),
    Case("simulate-rate-zero", "simulate --rate 0 (once a ZeroDivisionError)", oc.InputError,
         r"rate = 0(\.0)? Hz: must be positive and finite",
         lib=lambda tmp: oc.simulate(_robot(), 0.01, trajectories.table1, rate=0.0),
         cli=lambda tmp: ["simulate", "--duration", "0.01", "--rate", "0"]),
    Case("rao-header-only", "an RAO file with its header and no rows (once an IndexError)",
         oc.SeaStateError, r"rao\.csv, line 1: the header has no data rows under it",
         lib=lambda tmp: oc.motion.sea.load_raos(_bytes(
             tmp, "rao.csv", b"omega_rad_s,heading_deg,dof,amplitude,phase_rad\n")),
         cli=lambda tmp: ["motion", "--duration", "1", "--hs", "2", "--tp", "8", "--heading",
                          "90", "--scale", "20", "--vessel", str(_bytes(
                              tmp, "rao.csv",
                              b"omega_rad_s,heading_deg,dof,amplitude,phase_rad\n"))]),
    Case("gif-fps-too-low", "animate --fps 0.001 to a GIF (once an OverflowError: a GIF "
         "frame lasts at most 655.35 s)", oc.InputError,
         r"--fps 0\.001: a GIF frame lasts at most 655\.35 s .* needs --fps >= 0\.001526",
         cli=lambda tmp: ["animate", "--fps", "0.001", "--out", str(tmp / "out" / "a.gif")]),
    Case("animate-speed-memory", "animate --speed 1e-9 (once 6.9 TiB allocated before the "
         "pixel guard)", oc.InputError,
         r"314100000001 frames of 31\.4\d* s at --fps 10 .* of memory, over the limit .*raise --speed",
         cli=lambda tmp: ["animate", "--speed", "1e-9", "--out", str(tmp / "out" / "a.gif")]),
    Case("animate-out-no-type", "animate --out a (was worded 'the file type '.'')",
         oc.InputError, r"--out: cannot write .*/a: the name has no file type: end it in "
         r"\.gif, \.mp4",
         cli=lambda tmp: ["animate", "--out", str(tmp / "out" / "a")]),
    Case("export-dangling-link", "export to a symbolic link whose target's directory does "
         "not exist (was 'directory . does not exist')", oc.InputError,
         r"dangling\.xml: is a symbolic link to /nonexistent-\w+/x\.xml, whose directory "
         r"/nonexistent-\w+ does not exist: create it or remove the link",
         cli=lambda tmp: ["export", "--mjcf", str(_link(tmp / "dangling.xml",
                                                         "/nonexistent-dir/x.xml"))]),
    Case("grid-boolean", "a boolean grid value (was worded 'must be a finite number')",
         oc.GridError, r"grid\.toml: hs\[0\] = true: is a boolean, not a number",
         lib=lambda tmp: oc.studies.sweep.check_grid(
             scenes.load_scene(_SCENES / "sweep_crane.toml"),
             oc.studies.sweep.load_grid(_bytes(tmp, "grid.toml", b"hs = [true, 2.0]\n")),
             "grid.toml"),
         cli=lambda tmp: ["sweep", "--scene", str(_SCENES / "sweep_crane.toml"), "--grid",
                          str(_bytes(tmp, "grid.toml", b"hs = [true, 2.0]\n")), "--out",
                          str(tmp / "out" / "results")]),
    # ---- a sweep's outputs inside its own results directory (issue 21, item 1)
    Case("sweep-csv-in-new-results", "sweep --csv inside the --out directory it creates",
         oc.OutputError, r"--csv: cannot write .*/out/res/rows\.csv: is inside --out "
         r".*/out/res, whose files are the run's alone",
         cli=lambda tmp: ["sweep", "--scene", str(_SCENES / "sweep_crane.toml"), "--grid",
                          str(_bytes(tmp, "grid.toml", b"hs = [1.0]\n")), "--out",
                          str(tmp / "out" / "res"), "--csv",
                          str(tmp / "out" / "res" / "rows.csv")]),
    Case("sweep-csv-over-manifest", "sweep --csv onto an existing results directory's "
         "manifest (once turned into CSV: the directory then refused as damaged)",
         oc.OutputError, r"--csv: cannot write .*/old/_manifest\.json: is inside --out",
         cli=lambda tmp: ["sweep", "--scene", str(_SCENES / "sweep_crane.toml"), "--grid",
                          str(_bytes(tmp, "grid.toml", b"hs = [1.0]\n")), "--out",
                          str(_bytes(tmp, "old/_manifest.json", b"{}").parent), "--csv",
                          str(tmp / "old" / "_manifest.json")]),
    Case("sweep-plot-is-results", "sweep --plot into the results directory (once a PNG in "
         "the Parquet dataset: read_results failed)", oc.OutputError,
         r"--plot: cannot write .*/out/res/\.\./res: is inside --out",
         cli=lambda tmp: ["sweep", "--scene", str(_SCENES / "sweep_crane.toml"), "--grid",
                          str(_bytes(tmp, "grid.toml", b"hs = [1.0]\n")), "--out",
                          str(tmp / "out" / "res"), "--plot",
                          str(tmp / "out" / "res" / ".." / "res")]),
    # ---- an output that is an input read through another (issue 21, item 1)
    Case("export-over-its-description", "export --mjcf onto the --robot description it "
         "reads (named .xml)", oc.OutputError,
         r"--mjcf: cannot write .*desc\.xml: is also an input",
         cli=lambda tmp: ["export", "--robot", str(_bytes(tmp, "desc.xml", _LAB.read_bytes())),
                          "--mjcf", str(tmp / "desc.xml")]),
    Case("scene-description-as-output", "id --out onto the description the scene names",
         oc.OutputError, r"--out: cannot write .*robot\.toml: is also an input",
         cli=lambda tmp: ["id", "--scene", str(_scene_with_description(tmp)), "--out",
                          str(tmp / "robot.toml")]),
    # ---- sizes and addresses checked by our code first (issue 21, items 4 and 5)
    Case("cable-substeps-memory", "--substeps 1e8 on a hanging load (once 298 GiB "
         "allocated)", oc.InputError,
         r"substeps\) needs .* of memory, over the limit .*lower substeps "
         r"\(--substeps\)",
         cli=lambda tmp: ["id", "--duration", "10", "--set", "payload.mass=2", "--set",
                          "payload.cable_length=0.5", "--substeps", "100000000"]),
    Case("scheduler-negative-port", "sweep --scheduler with a negative port (once a "
         "ValueError from distributed)", oc.SchedulerError,
         r"--scheduler tcp://127\.0\.0\.1:-5: the port must be 1\.\.65535",
         cli=lambda tmp: ["sweep", "--scene", str(_SCENES / "sweep_crane.toml"), "--grid",
                          str(_bytes(tmp, "grid.toml", b"hs = [1.0]\n")), "--scheduler",
                          "tcp://127.0.0.1:-5", "--out", str(tmp / "out" / "res")]),
    # ---- the hanging load's limits (issue 22, item 4)
    Case("load-limit-sway-over-90", "a sway limit beyond the horizontal", oc.ModelError,
         r"payload\.limits\.sway_max_deg: 100° must be in \(0, 90\]",
         lib=lambda tmp: oc.load_robot(overrides={"payload.limits.sway_max_deg": 100.0}),
         cli=lambda tmp: ["size", "--set", "payload.limits.sway_max_deg=100"]),
    Case("load-limit-ratio-one", "a slack criterion of the whole static tension",
         oc.ModelError, r"payload\.limits\.tension_ratio_min: 1 must be in \[0, 1\)",
         lib=lambda tmp: oc.load_robot(overrides={"payload.limits.tension_ratio_min": 1.0})),
    Case("load-limits-not-a-table", "[payload] limits = 3 in a scene", oc.SceneError,
         r"\[payload\] limits.*must be a table of sway_max_deg, tension_ratio_min, "
         r"tension_max",
         lib=lambda tmp: scenes.load_scene(_bytes(tmp, "s.toml", b'name = "s"\n[payload]\n'
                                                 b"mass = 2.0\nlimits = 3\n"))),
    # ---- the consistency pass (issue 22, item 5)
    Case("show-pose-outside-workspace", "show --pose with the legs detached (once drawn, "
         "exit 0, where export refused it)", oc.WorkspaceError,
         r"--pose: leg1 length = 2\.45\d* m is outside \[0\.4, 0\.82\] m; give a pose "
         r"inside the workspace",
         cli=lambda tmp: ["show", "--pose", "0,0,2.5,0,0,0,0,0,0", "--out",
                          str(tmp / "out" / "p.png")]),
    Case("show-arm-outside-limits", "show --pose with q8 beyond its limit", oc.WorkspaceError,
         r"--pose: arm_joint2 = 3 rad is outside \[-2, 2\] rad",
         cli=lambda tmp: ["show", "--pose", "0,0,0.6,0,0,0,0,3,0", "--out",
                          str(tmp / "out" / "p.png")]),
    Case("motion-without-a-sea", "motion with no arguments (once answered in scene-file "
         "words: '[trajectory] source = \"sea\" needs [sea] hs')", oc.InputError,
         r"a sea state needs --hs --tp --heading --scale .*e\.g\. motion --hs 2\.5",
         cli=lambda tmp: ["motion"]),
    Case("set-misspelt-suggests-once", "a misspelt --set name (once 'did you mean' twice)",
         oc.ModelError, r"payload has no 'mas'; did you mean 'payload\.mass'\? \(all "
         r"names: docs/robot-description\.md\)",
         lib=lambda tmp: oc.load_robot(overrides={"payload.mas": 2.0}),
         cli=lambda tmp: ["id", "--duration", "0.1", "--set", "payload.mas=2"]),
    # ---- values a cast would silently change (issue 21, item 6)
    Case("complex-sea-times", "complex times for a ship's motion", oc.SeaStateError,
         r"t has complex values: give real numbers \[s\]",
         lib=lambda tmp: oc.motion.sea.ship_motion(np.array([0.0, 1j]), 2.0, 8.0, 30.0)),
    Case("complex-table1-times", "complex times for Table 1", oc.TrajectoryError,
         r"t has complex values: give real numbers \[s\]",
         lib=lambda tmp: trajectories.table1(np.array([0.0, 0.5 + 1e-3j]))),
    Case("complex-spectrum-frequency", "complex frequencies for a wave spectrum",
         oc.SeaStateError, r"omega has complex values",
         lib=lambda tmp: oc.motion.sea.spectrum(np.array([0.5 + 0.1j]), 2.0, 8.0)),
    Case("complex-initial-state", "a complex initial state for a simulation", oc.InputError,
         r"q0 has complex values",
         lib=lambda tmp: oc.simulate(oc.load_robot(), 0.01, trajectories.table1,
                                     q0=trajectories.table1(0.0)[0] + 1e-3j)),
    Case("initial-state-shape", "an initial state of 8 numbers", oc.InputError,
         r"q0 has shape \(8,\); expected \(9,\)",
         lib=lambda tmp: oc.simulate(oc.load_robot(), 0.01, trajectories.table1,
                                     q0=np.zeros(8))),
    Case("simulate-step-zero", "simulate --step 0 (once silently the default step)",
         oc.InputError, r"step = 0(\.0)? s: must be positive and finite",
         lib=lambda tmp: oc.simulate(oc.load_robot(), 0.1, trajectories.table1, step=0.0),
         cli=lambda tmp: ["simulate", "--duration", "0.1", "--step", "0"]),
    Case("sea-spectrum-below-band", "a peak period of 1e300 s: every wave below the RAO "
         "band (once an all-zero record, exit 0)", oc.SeaStateError,
         r"tp = 1e\+300 s .* 0 % of its energy in the vessel's RAO band "
         r"0\.1047\.\.3\.142 rad/s: give tp between 2 and 60 s",
         lib=lambda tmp: oc.motion.sea.sea_state(2.0, 1e300, 30.0, 10.0, 10.0),
         cli=lambda tmp: ["motion", "--hs", "2", "--tp", "1e300", "--heading", "30",
                          "--scale", "20", "--duration", "10"]),
    Case("sea-spectrum-above-band", "a peak period of 1.2 s (1.5 s at 1:20): under 1 % of "
         "the sea inside the supply vessel's band", oc.SeaStateError,
         r"tp = 1\.2 s \(peak 5\.236 rad/s\) has 0\.\d+ % of its energy",
         lib=lambda tmp: oc.motion.sea.sea_state(2.0, 1.2, 30.0, 200.0, 10.0),
         cli=lambda tmp: ["motion", "--hs", "2", "--tp", "1.5", "--heading", "30",
                          "--scale", "20", "--duration", "10"],
         cli_match=r"tp = 1\.5 s \(peak 4\.189 rad/s\) has 0\.76 % of its energy"),
    Case("cable-rigid-solver", "the rigid inverse dynamics of a robot with a cable",
         oc.ModelError, r"this robot's payload hangs on a cable",
         lib=lambda tmp: oc.inverse_dynamics(_crane(), *_states())),
    Case("cable-flags-without-cable", "--initial-sway on a welded payload", oc.InputError,
         r"--initial-sway: applies to a payload on a cable",
         cli=lambda tmp: ["id", "--duration", "1", "--initial-sway", "0.1", "0"]),
    # ---- the real lift (issue 23): the winch and the elastic cable
    Case("cable-negative-ea", "an elastic cable of negative axial stiffness", oc.SceneError,
         r"\[cable\] ea = -5: must be > 0 N",
         lib=lambda tmp: scenes.load_scene(_lift(tmp, ea="-5.0")),
         cli=lambda tmp: ["id", "--scene", str(_lift(tmp, ea="-5.0")), "--out",
                          str(tmp / "out" / "x.csv")]),
    Case("cable-ea-library", "elastic_inverse_dynamics(ea=-1)", oc.InputError,
         r"cable ea = -1\.0 N: give a finite number > 0",
         lib=lambda tmp: oc.dynamics.cable.elastic_inverse_dynamics(
             _crane(), *_states(), t=np.arange(5) * 0.01, ea=-1.0)),
    Case("winch-without-capacities", "[cable] winch = true on a description without "
         "actuators.winch", oc.SceneError,
         r"winch = true, but the robot description gives no winch capacities",
         lib=lambda tmp: scenes.run(scenes.load_scene(_lift(tmp, capacities=False))),
         cli=lambda tmp: ["id", "--scene", str(_lift(tmp, capacities=False)), "--out",
                          str(tmp / "out" / "x.csv")]),
    Case("winch-without-hoist-column", "[cable] winch = true with 4-column waypoints",
         oc.SceneError, r"winch = true needs the hoist column in \[operation\]",
         lib=lambda tmp: scenes.load_scene(_lift(tmp, hoist=False))),
    Case("hoist-column-without-winch", "a fifth waypoint column without [cable] winch",
         oc.SceneError, r"have a fifth column .*set \[cable\] winch = true",
         lib=lambda tmp: scenes.load_scene(_lift(tmp, winch="false"))),
    Case("compensation-with-winch-column", "[control] compensation with the winch's hoist "
         "column (both would drive the winch)", oc.SceneError,
         r"compensation drives the winch itself: drop \[cable\] winch",
         lib=lambda tmp: scenes.run(scenes.load_scene(_bytes(
             tmp, "c.toml", (_SCENES / "winch_lift.toml").read_bytes()
             + b'\n[control]\ncompensation = "arm"\n'))),
         cli=lambda tmp: ["id", "--scene", str(_bytes(
             tmp, "c.toml", (_SCENES / "winch_lift.toml").read_bytes()
             + b'\n[control]\ncompensation = "arm"\n'))]),
    Case("compensation-unknown-mode", "[control] compensation = \"full\"", oc.SceneError,
         r"\[control\] compensation.*must be one of none, arm, arm\+winch",
         lib=lambda tmp: scenes.load_scene(_bytes(
             tmp, "c.toml", (_SCENES / "compensated_lift.toml").read_bytes().replace(
                 b'compensation = "arm+winch"', b'compensation = "full"')))),
    Case("compensate-without-a-cable", "compensate on a scene whose payload is welded",
         oc.InputError, "compensation needs the crane arm and a payload on a cable",
         cli=lambda tmp: ["compensate", "--scene", str(_SCENES / "sea_state_crane.toml")]),
    Case("compensate-without-a-sea", "compensate on a scene whose platform no sea moves",
         oc.InputError, r"compensate cancels the ship's motion: .* has no sea",
         cli=lambda tmp: ["compensate", "--scene", str(_bytes(
             tmp, "c.toml", b'name = "c"\n[payload]\nmass = 2.0\ncable_length = 1.0\n'))]),
    Case("hoist-profile-bad-length", "a hoist of length 0 m in a library profile",
         oc.InputError, "hoist waypoints need increasing times and lengths > 0 m",
         lib=lambda tmp: oc.dynamics.cable.hoist_profile([(0.0, 1.0), (2.0, 0.0)])),
]


def _lift(tmp: Path, ea: str = "1.25e4", winch: str = "true", hoist: bool = True,
          capacities: bool = True) -> Path:
    """scenes/winch_lift.toml with one thing changed."""
    text = (_SCENES / "winch_lift.toml").read_text()
    text = text.replace("ea = 1.25e4", f"ea = {ea}").replace("winch = true",
                                                               f"winch = {winch}")
    if not capacities:
        head, rest = text.split("[actuators.winch]")
        text = head + rest[rest.index("[cable]"):]
    if not hoist:
        text = text[:text.index("\n[operation]") + 1] + (
            "[operation]\nwaypoints = [[0, 0.0, 0.0, 0.0], [5, 0.5, 0.0, 0.0]]\n")
    return _bytes(tmp, "lift.toml", text.encode())


def _scene_with_description(tmp: Path) -> Path:
    """A Table 1 scene whose ``[robot] description`` is a copy of lab.toml beside it."""
    _bytes(tmp, "robot.toml", _LAB.read_bytes())
    return _bytes(tmp, "s.toml", b'name = "s"\n[robot]\ndescription = "robot.toml"\n'
                  b'[trajectory]\nsource = "table1"\nduration = 0.1\n')


def _link(path: Path, target: str) -> Path:
    """``path`` made a symbolic link to ``target`` (which need not exist)."""
    path.symlink_to(target)
    return path


def _crane():
    """The lab robot with 2 kg on a 0.5 m cable."""
    return oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 0.5})


def _cable_states():
    """``{q, qd, qdd, t}``: 0.1 s of Table 1 at 100 Hz, as keywords."""
    t = trajectories.time_grid(0.1, 100.0)
    return dict(zip(("q", "qd", "qdd"), trajectories.table1(t)), t=t)


def _families() -> list:
    """The families kept in modules of their own (``tests/cli/cases_*.py``, each a
    ``CASES`` list of :class:`Case` that may use this module's helpers), in file order:
    a family grows in its own file."""
    import importlib

    here = str(Path(__file__).resolve().parent)
    if here not in sys.path:
        sys.path.insert(0, here)
    out = []
    for path in sorted(Path(here).glob("cases_*.py")):
        out += importlib.import_module(path.stem).CASES
    return out


CASES += _families()


def _params(kind):
    out = []
    for case in CASES:
        if getattr(case, kind) is None:
            continue
        marks = [pytest.mark.xfail(strict=True, reason=case.gap)] if case.gap else []
        out.append(pytest.param(case, id=case.id, marks=marks))
    return out


def test_catalogue_ids_are_unique():
    assert len({c.id for c in CASES}) == len(CASES)


@pytest.mark.parametrize("case", _params("lib"))
def test_library(case, tmp_path):
    with pytest.raises(case.error, match=case.match) as info:
        case.lib(tmp_path)
    assert isinstance(info.value, oc.OffshoreCraneError)
    assert "\n" not in str(info.value)


def run_cli(case, tmp: Path):
    """Run ``case`` through ``main`` with --out and --plot in ``tmp/out``.

    Returns ``(status, stderr lines, files left in tmp/out)``; a SystemExit (argparse)
    counts as its code, any other exception propagates.
    """
    import contextlib
    import io

    out = tmp / "out"
    out.mkdir(exist_ok=True)
    argv = case.cli(tmp)
    if argv[0] == "id" and "--out" not in argv:
        argv += ["--out", str(out / "x.csv")]
    if argv[0] == "id" and "--plot" not in argv:
        argv += ["--plot", str(out / "x.png")]
    err, stdout = io.StringIO(), io.StringIO()
    before = _checksums(tmp, out)
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(stdout):
        try:
            status = main(argv)
        except SystemExit as exc:
            status = exc.code
    assert _checksums(tmp, out) == before, "an input file was changed"
    return status, err.getvalue().splitlines(), sorted(p.name for p in out.iterdir())


def _checksums(tmp: Path, out: Path) -> dict:
    """SHA-256 of every file a case may read: its scratch files (``out`` aside) and the
    shipped scenes."""
    import hashlib

    files = [p for p in tmp.rglob("*") if out not in p.parents and p.is_file()]
    files += [p for p in _SCENES.rglob("*") if p.is_file()]
    return {str(p): hashlib.sha256(p.read_bytes()).hexdigest() for p in files}


@pytest.mark.parametrize("case", _params("cli"))
def test_cli(case, tmp_path):
    status, lines, left = run_cli(case, tmp_path)
    assert status == 2
    assert len(lines) == 1 and lines[0].startswith(PREFIX), lines
    assert re.search(case.cli_match or case.match, lines[0]), lines[0]
    assert left == [], f"files left behind: {left}"
    # at most 200 characters of message (the rest belongs in --help and the docs); a path
    # counts by its file name: the user's own path is as long as it is
    shown = re.sub(r"/[^\s:,']*/", "", lines[0][len(PREFIX):])
    assert len(shown) <= MESSAGE_MAX, f"{len(shown)} characters: {shown}"


def test_cli_process_has_no_traceback(tmp_path):
    """One case as a real process: exit status 2, one line, no traceback."""
    path = _csv("nan.csv", _cell(GOOD, 3, "q5", "nan"))(tmp_path)
    proc = subprocess.run([sys.executable, "-m", "offshore_crane", "id", "--trajectory",
                           str(path), "--out", str(tmp_path / "x.csv")],
                          capture_output=True, text=True)
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.count("\n") == 1 and proc.stderr.startswith(PREFIX)
    assert "Traceback" not in proc.stderr and not (tmp_path / "x.csv").exists()


def test_errors_carry_their_data(tmp_path):
    """Beyond the message: the exception attributes a caller can act on."""
    with pytest.raises(oc.InputError) as info:
        _id(*_with((3, 4), np.nan))
    assert (info.value.name, info.value.index) == ("q", 3)
    with pytest.raises(oc.WorkspaceError) as info:
        _solve_csv(_csv("arm.csv", _pose(q8=2.5)))(tmp_path)
    assert (info.value.joint, info.value.index, info.value.value) == ("arm_joint2", 0, 2.5)
    with pytest.raises(oc.errors.DescriptionError) as info:
        oc.load_robot(platform_mass=-5)
    assert info.value.field == info.value.element == "platform.mass"
    assert info.value.path.endswith("lab.toml")
    with pytest.raises(oc.TrajectoryError) as info:
        trajectories.load(_csv("text.csv", _cell(GOOD, 2, "q3", "abc"))(tmp_path))
    assert (info.value.name, info.value.index) == ("q3_m", 1)


def test_no_limits_allows_study_outside_limits(tmp_path):
    """--no-limits: the same out-of-stroke trajectory runs (and says where it is)."""
    path = _csv("high.csv", _pose(q3=0.9))(tmp_path)
    assert main(["id", "--trajectory", str(path), "--no-limits"]) == 0
