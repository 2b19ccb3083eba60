"""Robot description files (issue 11): the default reproduces the former xacro exactly,
general platforms load and Kane agrees with RNEA on them, leg order and reference point
are conventions only, every validation rule has a failing example, the dotted names,
aliases and override path, and the shipped literature platform.

Tolerances (each the round-off of the operations compared):
- default description vs the former xacro: the URDF numbers are compared with ``==``
  (the description evaluates the same float expressions in the same order), so the
  forces are computed from identical numbers and compared with ``==`` too;
- Kane vs RNEA: 1e-9 relative (docs/conventions.md, AGREEMENT: both exact methods);
- permuted legs, moved reference point: 1e-11 relative (the same physics written in
  another order or another frame: round-off of a different summation order and of the
  coordinate transformation, observed ~1e-14).
"""

from __future__ import annotations

import math
import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane import scenes
from offshore_crane.motion import trajectories
from offshore_crane.dynamics import solve
from offshore_crane.errors import DescriptionError
from offshore_crane.robot import Robot
from offshore_crane.robot import description as desc
from offshore_crane.robot.overrides import ALIASES, conflicts, normalise, parse_set

import description_cases as dc

ROOT = Path(__file__).resolve().parents[2]
OLD_XACRO = Path(__file__).resolve().parents[1] / "data" / "offshore_crane_v1.urdf.xacro"
LITERATURE = ROOT / "models" / "descriptions" / "harib_srinivasan_2003.toml"
AGREEMENT = 1e-9
CONVENTION = 1e-11


def relative_error(X, Y) -> float:
    return float(np.abs(X - Y).max() / np.abs(Y).max())


# ------------------------------------------------------------ default == former xacro
def _old_urdf(**args) -> str:
    import xacro
    mappings = {k: repr(float(v)) for k, v in args.items()}
    return xacro.process_file(str(OLD_XACRO), mappings=mappings).toprettyxml(indent="  ")


def _numbers(text: str):
    try:
        return [float(x) for x in text.split()]
    except ValueError:
        return None


#: Elements the xacro has added since the former one, on purpose: a massive payload is
#: drawn (a sphere of its mass in steel, for the animations of issue 16).
ADDED = ("robot/link[payload]/visual[]",)


def _same_urdf(old: str, new: str) -> int:
    """Assert two URDFs have the same elements and attributes, every number equal (==)
    and every other attribute text equal (but for the elements in ``ADDED``, which only
    the new one has); return the count of numbers compared."""
    count = 0
    stack = [(ET.fromstring(old.encode()), ET.fromstring(new.encode()), "robot")]
    while stack:
        a, b, where = stack.pop()
        assert (a.tag, sorted(a.attrib)) == (b.tag, sorted(b.attrib)), where
        for key, text in a.attrib.items():
            x, y = _numbers(text), _numbers(b.attrib[key])
            if x is None or y is None:
                assert text == b.attrib[key], (where, key)
            else:
                assert x == y, (where, key, x, y)
                count += len(x)
        kids = [x for x in b if f"{where}/{x.tag}[{x.get('name', '')}]" not in ADDED]
        assert len(a) == len(kids), where
        stack += [(x, y, f"{where}/{x.tag}[{x.get('name', '')}]") for x, y in zip(a, kids)]
    return count


def test_default_description_gives_the_former_urdf():
    """Whitespace and float formatting aside ("0" vs "0.0"), the URDF is the former
    xacro's: same elements in the same order, and all 972 numbers bit for bit."""
    assert _same_urdf(_old_urdf(), oc.load_robot().urdf) == 972


@pytest.mark.parametrize("alias", [a for a in ALIASES if a != "with_arm"])
def test_each_alias_changes_the_robot_as_its_xacro_argument_did(alias):
    """Each flat name moves every number the former xacro argument moved, exactly."""
    default = float(oc.load_robot().parameters[alias])
    value = default * 1.1 + 0.01           # away from the default, and from zero
    if alias in ("payload_ixy", "payload_ixz", "payload_iyz"):
        value = 0.002                      # a product of inertia the moments allow
    if alias.startswith("payload_"):
        extra = {"payload_mass": 2.0, "payload_ixx": 0.01, "payload_iyy": 0.01,
                 "payload_izz": 0.01}
        extra[alias] = value if alias != "payload_mass" else 3.0
    else:
        extra = {alias: value}
    _same_urdf(_old_urdf(**extra), oc.load_robot(**extra).urdf)


def test_without_arm_as_before():
    _same_urdf(_old_urdf(with_arm=0), oc.load_robot(with_arm=False).urdf)


def test_default_description_gives_the_former_forces(table1):
    """Identical URDF numbers give identical arrays, hence identical forces (==)."""
    old = Robot(_old_urdf())
    new = oc.load_robot()
    _, q, qd, qdd = table1
    for method in ("kane", "rnea"):
        assert np.array_equal(oc.inverse_dynamics(old, q, qd, qdd, method=method),
                              oc.inverse_dynamics(new, q, qd, qdd, method=method))


# ------------------------------------------------------------ general descriptions
@pytest.fixture(scope="module")
def general_path(tmp_path_factory):
    return dc.write(tmp_path_factory.mktemp("general"), dc.general())


@pytest.fixture(scope="module")
def general(general_path):
    return oc.load_robot(general_path)


def _solve(robot, q, qd, qdd, method):
    """Any method on any robot, with the default backend and checks (the random states lie
    inside the workspace)."""
    return solve(robot, q, qd, qdd, method=method).X


def test_general_description_reaches_the_solvers(general):
    """What the file says is what the solvers read (through the URDF), unchanged."""
    data, h = dc.general(), general.hybrid
    np.testing.assert_array_equal(h.p_base_P, data["base"]["joints"]["points"])
    np.testing.assert_array_equal(h.p_platform_S, data["platform"]["joints"]["points"])
    a1 = np.array(data["base"]["ujoint_axes"])
    np.testing.assert_allclose(h.R_base_U[:, :, 1], a1, atol=1e-15)
    np.testing.assert_allclose(h.R_base_U[:, :, 0], data["base"]["ujoint_axes2"], atol=1e-15)
    assert h.lower_mass.tolist() == [2.0 + 0.1 * i for i in range(1, 7)]
    np.testing.assert_array_equal(h.lower_com[2], [0.01, 0.006, 0.14])
    np.testing.assert_array_equal(general.description.inertials["leg1_upper"].com,
                                  [-0.004, 0.007, -0.12])     # the URDF's numbers
    np.testing.assert_allclose(h.upper_com[0], [-0.004, 0.007, -0.12], rtol=1e-15)
    I = dc.tensor((0.0102 + 5e-5 * 4, 0.0102, 0.0004), (1, 4, 0.3), 0.8)
    np.testing.assert_array_equal(h.upper_inertia[3], [[I["ixx"], I["ixy"], I["ixz"]],
                                                       [I["ixy"], I["iyy"], I["iyz"]],
                                                       [I["ixz"], I["iyz"], I["izz"]]])
    assert h.upper_inertia[3][0, 1] != 0.0 and h.lower_com[0][0] != 0.0
    caps = general.capacities
    assert caps.push_max.tolist() == [300.0, math.inf, math.inf, 8000, 8000, 9000, 8000,
                                      8000, 8000]
    assert caps.power_max[0] == 500.0 and caps.pull_max[3] == 6000.0


def test_general_description_kane_explicit_equals_rnea(general):
    q, qd, qdd = dc.random_states(general, 1000, seed=20260111)
    Xk = _solve(general, q, qd, qdd, "kane-explicit")
    Xr = _solve(general, q, qd, qdd, "rnea")
    assert relative_error(Xk, Xr) <= AGREEMENT
    scale = np.abs(Xr).max(axis=1)
    assert np.all(np.abs(Xk - Xr).max(axis=1) <= AGREEMENT * scale)   # per sample too


@pytest.mark.parametrize("leg_model", ["full", "thin-rod"])
def test_general_description_fused_kane_equals_rnea(general, leg_model):
    """The default (fused) Kane kernel on legs with off-axis CoMs and full tensors equals
    RNEA, overall and per sample. The thin-rod approximation has no exact reference on
    such legs: its compiled and vectorised paths (one text) must agree to round-off."""
    q, qd, qdd = dc.random_states(general, 1000, seed=20260111)
    if leg_model == "full":
        Xk = oc.inverse_dynamics(general, q, qd, qdd, method="kane")
        Xr = _solve(general, q, qd, qdd, "rnea")
        assert relative_error(Xk, Xr) <= AGREEMENT
        scale = np.abs(Xr).max(axis=1)
        assert np.all(np.abs(Xk - Xr).max(axis=1) <= AGREEMENT * scale)
    else:
        Xf = solve(general, q, qd, qdd, method="kane", leg_model="thin-rod").X
        Xn = solve(general, q, qd, qdd, method="kane", leg_model="thin-rod",
                   backend="numpy").X
        assert relative_error(Xf, Xn) <= 1e-13   # compiled = vectorised, same text


def test_permuting_the_legs_permutes_the_forces(general, tmp_path):
    order = [3, 0, 5, 1, 4, 2]                     # new leg k is old leg order[k]
    robot = oc.load_robot(dc.write(tmp_path, dc.permuted(dc.general(), order)))
    q, qd, qdd = dc.random_states(general, 200, seed=5)
    X = _solve(general, q, qd, qdd, "kane-explicit")
    Xp = _solve(robot, q, qd, qdd, "kane-explicit")
    assert relative_error(Xp[:, 3:], X[:, 3:][:, order]) <= CONVENTION
    assert relative_error(Xp[:, :3], X[:, :3]) <= CONVENTION
    assert robot.capacities.push_max[3 + order.index(2)] == 9000.0


@pytest.mark.parametrize("method", ["kane-explicit", "rnea"])
def test_another_reference_point_leaves_the_forces_unchanged(general, tmp_path, method):
    """O2 moved by c (platform frame): q1..q3 become O2's new position p + R c, their
    rates p' + ω × Rc and p'' + α × Rc + ω × (ω × Rc); the forces do not change."""
    c = np.array([0.03, -0.05, 0.04])
    robot = oc.load_robot(dc.write(tmp_path, dc.moved_reference(dc.general(), c)))
    assert robot.spec.home_height == pytest.approx(dc.HOME + c[2], abs=1e-15)
    q, qd, qdd = dc.random_states(general, 300, seed=9)
    Rc = np.einsum("nij,j->ni", dc.attitude(q), c)
    w, a = dc.angular(q, qd, qdd)
    q2, qd2, qdd2 = q.copy(), qd.copy(), qdd.copy()
    q2[:, :3] += Rc
    qd2[:, :3] += np.cross(w, Rc)
    qdd2[:, :3] += np.cross(a, Rc) + np.cross(w, np.cross(w, Rc))
    X = _solve(general, q, qd, qdd, method)
    assert relative_error(_solve(robot, q2, qd2, qdd2, method), X) <= CONVENTION


def test_angular_rates_of_the_helper():
    """The test's own ω, α (used above) against finite differences of R(t)."""
    t = np.linspace(0.0, 1.0, 2001)
    q = np.zeros((len(t), 9))
    q[:, 3:6] = np.stack([0.3 * np.sin(2 * t), 0.2 * np.cos(3 * t), 0.5 * t ** 2], -1)
    qd = np.gradient(q, t, axis=0, edge_order=2)
    qdd = np.gradient(qd, t, axis=0, edge_order=2)
    R = dc.attitude(q)
    Rd = np.gradient(R, t, axis=0, edge_order=2)
    W = np.einsum("nij,nkj->nik", Rd, R)           # Ṙ Rᵀ = [ω]×
    w, a = dc.angular(q, qd, qdd)
    k = slice(10, -10)                             # central differences: O(dt²) = 2.5e-7
    np.testing.assert_allclose(np.stack([W[:, 2, 1], W[:, 0, 2], W[:, 1, 0]], -1)[k], w[k],
                               atol=1e-5)
    np.testing.assert_allclose(np.gradient(w, t, axis=0)[k], a[k], atol=1e-4)


# ------------------------------------------------------------ validation rules
def _broken(tmp_path, change, base=None):
    data = base() if base else dc.general()
    change(data)
    return dc.write(tmp_path, data)


def _set(path_keys, value):
    def change(data):
        node = data
        for k in path_keys[:-1]:
            node = node.setdefault(k, {})
        node[path_keys[-1]] = value
    return change


def _drop(path_keys):
    def change(data):
        node = data
        for k in path_keys[:-1]:
            node = node[k]
        del node[path_keys[-1]]
    return change


def _coincident(data):
    pts = data["platform"]["joints"]["points"]
    pts[4] = list(pts[1])


def _collinear(data):
    data["base"]["joints"]["points"] = [[0.1 * k - 0.3, 0.05 * k, 0.05] for k in range(6)]


def _parallel_a1(data):
    P = np.array(data["base"]["joints"]["points"][0])
    S = np.array(data["platform"]["joints"]["points"][0]) + [0, 0, dc.HOME]
    data["base"]["ujoint_axes"][0] = list(S - P)
    del data["base"]["ujoint_axes2"]


def _tilted_a1(data):
    P = np.array(data["base"]["joints"]["points"][2])
    S = np.array(data["platform"]["joints"]["points"][2]) + [0, 0, dc.HOME]
    u = (S - P) / np.linalg.norm(S - P)
    h = np.cross([0, 0, 1.0], u)
    data["base"]["ujoint_axes"][2] = list(h / np.linalg.norm(h) + 3.0 * u)  # 72° from ⟂
    del data["base"]["ujoint_axes2"]


def _a2_not_perpendicular(data):
    data["base"]["ujoint_axes2"][1] = data["base"]["ujoint_axes"][1]


RULES = [
    ("inertia-not-pd", _set(["legs", "lower", "inertia"], {"ixx": -0.01, "iyy": 0.02,
                                                           "izz": 0.02}),
     "legs.lower.inertia", r"legs\.lower\.inertia: not positive definite: principal moments "
     r"\(-0\.01, 0\.02, 0\.02\) kg·m² include a negative one"),
    ("inertia-triangle", _set(["platform", "inertia"], {"ixx": 0.1, "iyy": 0.1, "izz": 1.0}),
     "platform.inertia", r"platform\.inertia: principal moments \(0\.1, 0\.1, 1\) kg·m² break "
     r"the triangle inequality \(1 > 0\.1 \+ 0\.1\)"),
    ("com-outside-part", _set(["legs", "upper", "com"], [0.0, 0.0, 0.05]),
     "legs.upper.com", r"legs\.upper\.com: z = 0\.05 m lies outside the upper part \(-0\.4 to "
     r"0 m along the leg from its joint\)"),
    ("com-outside-part-one-leg", _set(["legs", "4", "lower", "com"], [0.0, 0.0, 0.43]),
     "legs.4.lower.com", r"legs\.4\.lower\.com: z = 0\.43 m lies outside the lower part"),
    ("anchors-coincide", _coincident, "platform.joints",
     r"platform\.joints: S2 and S5 coincide at \(0\.0607769, 0\.344683, -0\.035\) m"),
    ("anchors-collinear", _collinear, "base.joints",
     r"base\.joints: the six P_i lie on one line"),
    ("home-outside-stroke", _set(["legs", "stroke", "max"], 0.5), "legs.stroke",
     r"legs\.stroke: leg 1 cannot reach the home pose: \|P1S1\| = 0\.522235 m is outside "
     r"the stroke \[0\.3, 0\.5\] m"),
    ("home-outside-ujoint-range", _tilted_a1, "legs.ujoint.limit",
     r"legs\.ujoint\.limit: at the home pose the U-joint angle 2 of leg 3 is -1\.249 rad, "
     r"outside ±1\.2 rad"),
    ("ujoint-parallel", _parallel_a1, "base.ujoint_axes.1",
     r"base\.ujoint_axes\.1: a1 of leg 1 is parallel to the leg at the home pose"),
    ("a2-not-perpendicular", _a2_not_perpendicular, "base.ujoint_axes2.2",
     r"base\.ujoint_axes2\.2: a2 is not perpendicular to a1"),
    ("missing-field", _drop(["platform", "mass"]), "platform.mass",
     r"platform\.mass: missing: give the mass of the platform \[kg\]"),
    ("missing-anchors", _drop(["platform", "joints"]), "platform.joints",
     r"platform\.joints: missing: give the six S_i \(platform frame\)"),
    ("unit-string", _set(["platform", "mass"], "40 kg"), "platform.mass",
     r"platform\.mass: '40 kg' is not a number nor an arithmetic expression \(values are SI "
     r"numbers without unit strings\)"),
    ("degrees-for-radians", _set(["legs", "ujoint", "limit"], 60.0), "legs.ujoint.limit",
     r"legs\.ujoint\.limit: 60 rad: need 0 < limit <= pi/2 .*\(degrees given for radians\?\)"),
    ("wrong-shape", _set(["platform", "com"], [0.0, 0.0]), "platform.com",
     r"platform\.com: \[0, 0\] must be a list of 3 numbers \[m\]"),
    ("wrong-type", _set(["legs", "lower", "mass"], [2.0]), "legs.lower.mass",
     r"legs\.lower\.mass: \[2\] must be a number \[kg\] or an expression in quotes"),
    ("not-finite", _set(["platform", "mass"], math.nan), "platform.mass",
     r"platform\.mass: nan is not a finite number"),
    ("too-large", _set(["platform", "mass"], 1e150), "platform.mass",
     r"platform\.mass: 1e\+150 exceeds the magnitude limit 1e\+100"),
    ("unknown-key", _set(["legs", "lower", "mas"], 2.0), "legs.lower.mas",
     r"legs\.lower\.mas: unknown key \(did you mean 'legs\.lower\.mass'\?\)"),
    ("unknown-table", _set(["platfrom"], {"mass": 2.0}), "platfrom",
     r"platfrom: unknown key \(did you mean 'platform'\?\)"),
    ("expression-cycle", lambda d: (d["legs"]["lower"].update(length="legs.upper.length"),
                                    d["legs"]["upper"].update(length="legs.lower.length")),
     "legs.lower.length", r"expressions refer to each other in a cycle: legs\.lower\.length "
     r"-> legs\.upper\.length -> legs\.lower\.length"),
    ("expression-unknown-field", _set(["home", "height"], "base.joints.radius * 2"),
     "home.height", r"home\.height: refers to base\.joints\.radius, which the description "
     r"does not give"),
    ("empty-range", _set(["arm", "link2", "min"], 2.5), "arm.link2.min",
     r"arm\.link2\.min: the range \[2\.5, 2\] is empty"),
    ("payload-without-arm", _set(["arm", "enabled"], False), "payload.mass",
     r"payload\.mass: 2 kg: the payload hangs from the arm tip, but the robot has no arm"),
    ("negative-capacity", _set(["actuators", "Fs", "push_max"], -1.0), "actuators.Fs.push_max",
     r"actuators\.Fs\.push_max: -1 must be >= 0"),
    ("format-version", _set(["format"], 2), "format", r"format: 2 is not a known format"),
]


@pytest.mark.parametrize("case", RULES, ids=[r[0] for r in RULES])
def test_validation_rule(tmp_path, case):
    _, change, field, match = case
    path = _broken(tmp_path, change)
    with pytest.raises(DescriptionError, match=match) as info:
        oc.load_robot(path)
    message = str(info.value)
    assert "\n" not in message and message.startswith(str(path))
    assert info.value.field == field and info.value.path == str(path)


def test_published_inertia_as_transcribed_is_refused(tmp_path):
    """The literature platform's lower leg inertia read as the part's principal moments
    (I_2_x the axial one) breaks the triangle inequality (the file explains the reading
    it holds instead)."""
    text = LITERATURE.read_text().replace(
        "inertia = { ixx = 2.728149289983384e-2, iyy = 2.728149289983384e-2, izz = 1.0e-12 }",
        "inertia = { ixx = 2.7092491e-2, iyy = 2.2567492e-2, izz = 3.2057427e-3 }")
    path = tmp_path / "hs.toml"
    path.write_text(text)
    with pytest.raises(DescriptionError, match=r"legs\.lower\.inertia: principal moments "
                       r"\(0\.00320574, 0\.0225675, 0\.0270925\) kg·m² break the triangle"):
        oc.load_robot(path)


@pytest.mark.parametrize("content, match", [
    (b"mass = \xff\n", r"line 1, column 8: byte 0xff is not UTF-8: save the robot description"),
    (b"[platform\nmass = 1\n", r"not valid TOML"),
])
def test_unreadable_files(tmp_path, content, match):
    path = tmp_path / "bad.toml"
    path.write_bytes(content)
    with pytest.raises(DescriptionError, match=match):
        oc.load_robot(path)
    with pytest.raises(DescriptionError, match="cannot read the robot description"):
        oc.load_robot(tmp_path / "missing.toml")


# ------------------------------------------------------------ names and overrides
def test_every_alias_names_a_field_of_the_default():
    robot = oc.load_robot()
    for alias, name in ALIASES.items():
        assert alias in robot.parameters, alias
        if alias != "with_arm":
            assert float(robot.parameters[alias]) == robot.spec.values[name]


def test_parse_set_reads_toml_values_and_expressions():
    out = parse_set(["legs.lower.mass=3.1", "payload.com=[0, 0, -0.05]", "with_arm=true",
                     "platform_mass=55", "legs.upper.mass = legs.lower.mass / 2",
                     "payload.inertia={ ixx = 1e-3, iyy = 1e-3, izz = 2e-3 }",
                     "payload_mass=2"])
    assert out == {"legs.lower.mass": 3.1, "payload.com": [0, 0, -0.05], "arm.enabled": True,
                   "platform.mass": 55.0, "legs.upper.mass": "legs.lower.mass / 2",
                   "payload.inertia": {"ixx": 1e-3, "iyy": 1e-3, "izz": 2e-3},
                   "payload.mass": 2.0}
    robot = oc.load_robot(overrides=out)
    assert robot.hybrid.upper_mass.tolist() == [3.1 / 2] * 6
    assert robot.spec.payload.inertia[2, 2] == 2e-3 and robot.spec.payload.com[2] == -0.05
    with pytest.raises(oc.InputError, match="--set expects name=value, got 'platform_mass'"):
        parse_set(["platform_mass"])


@pytest.mark.parametrize("overrides, match", [
    ({"with_arm": 2}, r"with_arm \(arm\.enabled\)=2 must be true or false"),
    ({"with_arm": "yes"}, r"must be true or false"),
    ({"platform_mass": 1, "platform.mass": 2}, r"platform_mass and platform\.mass name the "
                                               r"same field"),
    ({"platform.mass": 1e200}, r"exceeds the magnitude limit 1e\+100"),
    ({"legs.lower.mass": "legs.nothing * 2"}, r"names 'legs\.nothing', which is no field"),
    ({"legs.7.lower.mass": 1.0}, r"legs has no '7'"),
    ({"payload.com.w": 1.0}, r"payload\.com has no component 'w'"),
])
def test_bad_overrides(overrides, match):
    with pytest.raises(DescriptionError, match=match):
        normalise(overrides)


def test_override_of_a_field_moves_its_dependants():
    """platform.shape.length places the sphere centres and the column (lab expressions)."""
    robot = oc.load_robot(overrides={"platform.shape.length": 0.06})
    assert np.all(robot.hybrid.p_platform_S[:, 2] == -0.03)
    assert robot.spec.arm["column"][0][2] == 0.03


def test_per_leg_override(tmp_path):
    robot = oc.load_robot(overrides={"legs.3.lower.mass": 2.5, "actuators.Fl5.push_max": 7e3})
    assert robot.hybrid.lower_mass.tolist() == [2.0, 2.0, 2.5, 2.0, 2.0, 2.0]
    assert robot.capacities.push_max.tolist() == [500, 500, 5000, 5000, 5000, 5000, 5000,
                                                  7000, 5000]


def test_scene_tables_and_conflicts(tmp_path):
    data = tomllib.loads("""
        [robot]
        description = "robot.toml"
        legs.upper.mass = 3.0
        "platform.mass" = 50.0
        ujoint_limit = 1.0
        [payload]
        mass = 2.0
        offset = [0.0, 0.0, -0.05]
        [subsystems]
        arm = true
    """)
    dc.write(tmp_path, dc.general())
    scene = scenes.scene_from_dict(data, "s.toml", tmp_path)
    path, over = scene.robot_description, scene.robot
    assert path == str(tmp_path / "robot.toml")
    assert over == {"legs.upper.mass": 3.0, "platform.mass": 50.0, "legs.ujoint.limit": 1.0,
                    "payload.mass": 2.0, "payload.com": [0.0, 0.0, -0.05],
                    "arm.enabled": True}
    cli = parse_set(["payload.com.z=-0.1", "payload_mass=2", "with_arm=0",
                     "legs.lower.length=0.4"])
    found = {c.field: (c.scene, c.cli) for c in conflicts(over, cli)}
    assert found == {"payload.com.z": ([0.0, 0.0, -0.05], -0.1), "arm.enabled": (True, False)}
    assert "the scene sets true, --set gives false" in str(conflicts(over, cli)[-1])
    assert oc.load_robot(path, over).spec.payload.mass == 2.0
    # the description gives every leg its own lower mass: legs.lower.mass would change
    # nothing, and says so (issue 36)
    data["robot"]["legs"]["lower"] = {"mass": 3.0}
    with pytest.raises(oc.SceneError, match=r"legs 1-6 have their own legs\.N\.lower\.mass "
                       r"\(per-leg tables\)"):
        scenes.scene_from_dict(data, "s.toml", tmp_path)
    with pytest.raises(oc.SceneError, match=r'\[robot\] description = "nope\.toml": no such'):
        scenes.scene_from_dict({"robot": {"description": "nope.toml"}}, "s.toml", tmp_path)


def test_capacities_of_the_default():
    caps = oc.load_robot().capacities
    assert caps.names == oc.ACTUATORS
    assert caps.push_max.tolist() == [500, 500] + [5000] * 7
    assert caps.speed_max.tolist() == [3, 3] + [0.5] * 7
    assert np.all(np.isinf(caps.power_max))


# ------------------------------------------------------------ the literature platform
def test_literature_platform_loads_with_its_sources():
    robot = oc.load_robot(LITERATURE)
    spec = robot.spec
    assert "Harib" in spec.source and not spec.has_arm
    assert robot.hybrid.platform_mass == 8.08
    np.testing.assert_allclose(np.degrees(np.arctan2(spec.p_base_P[:, 1], spec.p_base_P[:, 0]))
                               % 360, dc.BASE_DEG, atol=1e-12)
    np.testing.assert_allclose(np.degrees(np.arctan2(spec.p_platform_S[:, 1],
                                                     spec.p_platform_S[:, 0])) % 360,
                               dc.PLATFORM_DEG, atol=1e-12)
    # every number has its origin written: "[impl]" (transcribed) or "ASSUMED", on its
    # line, in the comments right above or below it, or on its table's header
    lines = LITERATURE.read_text().splitlines()
    header = ""
    for i, line in enumerate(lines):
        stripped = line.strip()
        if stripped.startswith("["):
            header = stripped
            continue
        if stripped.startswith(("#", "format")) or "=" not in stripped:
            continue
        value = stripped.split("#")[0].split("=", 1)[1].strip()
        if value.startswith('"') or not any(c.isdigit() for c in value):
            continue                               # text, or no number
        near = [line, header]
        j = i - 1
        while j >= 0 and lines[j].strip().startswith("#"):
            near.append(lines[j])
            j -= 1
        j = i + 1
        while j < len(lines) and lines[j].startswith(" ") and lines[j].strip().startswith("#"):
            near.append(lines[j])
            j += 1
        assert any("[impl]" in x or "ASSUMED" in x for x in near), line


def test_literature_scene_runs(tmp_path):
    scene = ROOT / "scenes" / "harib_srinivasan_2003.toml"
    data = tomllib.loads(scene.read_text())
    robot = scenes.load_robot(scenes.load_scene(scene))
    traj = trajectories.load(str(scene.parent / data["trajectory"]["source"]), fd_order=4)
    Xk = _solve(robot, traj.q, traj.qd, traj.qdd, "kane-explicit")
    Xr = _solve(robot, traj.q, traj.qd, traj.qdd, "rnea")
    assert relative_error(Xk[:, 3:], Xr[:, 3:]) <= AGREEMENT
    assert not robot.hybrid.has_arm
    length = dc.leg_lengths(robot, traj.q)
    assert np.all((length > 0.33) & (length < 0.45))     # inside the assumed stroke
    import importlib.util

    spec = importlib.util.spec_from_file_location("gen", ROOT / "scripts" /
                                                  "make_hs2003_motion.py")
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    assert (scene.parent / data["trajectory"]["source"]).read_text() == gen.text()


# ------------------------------------------------------------ documentation
def test_documentation_lists_every_field_and_alias():
    doc = (ROOT / "docs" / "robot-description.md").read_text()
    for name, _ in desc.field_names():
        if not name.startswith(("actuators.Fl1", "actuators.Fl2", "actuators.Fl3",
                                "actuators.Fl4", "actuators.Fl5", "actuators.Fl6")):
            assert f"`{name}`" in doc, name       # (FlN: "the keys of actuators.Fl")
    for alias, name in ALIASES.items():
        assert f"`{alias}`" in doc and f"`{name}`" in doc, alias


def test_documentation_example_loads(tmp_path):
    doc = (ROOT / "docs" / "robot-description.md").read_text()
    example = doc.split("```toml\n", 1)[1].split("```", 1)[0]
    path = tmp_path / "my_platform.toml"
    path.write_text(example)
    robot = oc.load_robot(path)
    assert robot.spec.name == "my hexapod" and not robot.hybrid.has_arm
    assert robot.capacities.push_max.tolist() == [math.inf] * 3 + [2000.0] * 6
