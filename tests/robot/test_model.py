"""The robot description: names of docs/conventions.md, loading in Pinocchio and yourdfpy,
xacro overrides and the expansion cache."""

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.robot import xacro_arguments
from offshore_crane.robot.urdf import parse_urdf

BODIES = (["platform"] + [f"leg{i}_{s}" for i in range(1, 7) for s in ("lower", "upper")]
          + ["arm_column", "arm_link1", "arm_link2", "arm_slider"])


def test_contract_names_and_17_bodies(robot):
    urdf = parse_urdf(robot.urdf)
    assert urdf.root == "base"
    massive = {name for name, i in urdf.inertials.items() if i is not None and i.mass > 0}
    assert massive == set(BODIES) and len(BODIES) == 17  # the paper's 17 moving bodies
    for i in range(1, 7):
        for j in ("u1", "u2", "slide"):
            assert f"leg{i}_{j}" in urdf.joints
        assert f"leg{i}_tip" in urdf.inertials and f"platform_anchor{i}" in urdf.inertials
    for name in ("arm_joint1", "arm_joint2", "arm_slide"):
        assert name in urdf.joints


def test_masses_match_pinocchio(robot):
    model = robot.pinocchio_model
    data = model.createData()
    import pinocchio as pin

    pin.computeTotalMass(model, data)
    assert data.mass[0] == pytest.approx(robot.hybrid.total_mass, rel=1e-14)
    assert robot.hybrid.total_mass == pytest.approx(45 + 6 * 2.8 + 4 + 3 + 1, rel=1e-14)


def test_loads_in_yourdfpy(robot, tmp_path):
    import yourdfpy

    path = tmp_path / "robot.urdf"
    path.write_text(robot.urdf)
    model = yourdfpy.URDF.load(str(path), load_meshes=False, build_scene_graph=True)
    assert set(BODIES) <= set(model.link_map)
    assert model.validate()
    cfg = {name: 0.0 for name in model.actuated_joint_names}
    cfg.update({f"leg{i}_slide": 0.6 for i in range(1, 7)}, platform_z=0.5)
    model.update_cfg(cfg)
    T = model.get_transform("arm_column", "base")
    assert T[2, 3] == pytest.approx(0.5 + 0.02)  # on the plate's upper face


def test_override_changes_model():
    heavy = oc.load_robot(platform_mass=55)
    assert heavy.hybrid.platform_mass == pytest.approx(55 + 5)
    assert heavy.overrides == {"platform.mass": 55.0}      # the alias's dotted name
    assert oc.load_robot(platform_mass="55.0") is heavy  # memoised on normalised values
    assert oc.load_robot(overrides={"platform.mass": 55.0}) is heavy


@pytest.mark.parametrize("kwargs, match", [
    ({"platfrom_mass": 1}, "unknown robot parameter 'platfrom_mass'; did you mean "
                           "platform_mass"),
    ({"platform_mass": "heavy"}, r"platform_mass \(platform.mass\)='heavy' is not a number"),
    ({"platform_mass": float("nan")}, "is not finite"),
])
def test_bad_overrides(kwargs, match):
    with pytest.raises(oc.ModelError, match=match):
        oc.load_robot(**kwargs)


def test_every_number_is_an_argument():
    args = xacro_arguments()
    assert len(args) >= 30
    assert all(float(v) == float(v) for v in args.values())


def test_cache_is_reused(tmp_path, monkeypatch):
    """A cache hit returns the stored URDF; an edited entry is rebuilt with a warning
    (tests/test_model_loading.py covers the cache in detail)."""
    from offshore_crane.robot.description import resolve
    from offshore_crane.robot.xacro_cache import CacheWarning, expand

    monkeypatch.setenv("OFFSHORE_CRANE_CACHE", str(tmp_path))
    data = resolve(overrides={"arm.column.mass": 6.0}).xacro_data()
    text, path = expand(data)
    assert path.parent == tmp_path and path.read_text().startswith(text)
    assert expand(data) == (text, path)
    path.write_text(path.read_text().replace('name="offshore_crane"', 'name="edited"'))
    with pytest.warns(CacheWarning, match="does not match its checksum"):
        assert expand(data)[0] == text
    assert expand(resolve(overrides={"arm.column.mass": 7.0}).xacro_data())[1] != path


def test_table1_within_strokes_and_far_from_singularities(robot, table1):
    from offshore_crane.robot.kinematics import legs as leg_kinematics

    _, q, qd, qdd = table1
    legs = leg_kinematics(robot, q, qd, qdd)
    lo, hi = robot.hybrid.stroke.T
    assert np.all(legs.length > lo + 0.01) and np.all(legs.length < hi - 0.01)
    assert np.abs(legs.cos_theta2).min() > 0.9       # U-joints ≥ 64° from gimbal lock
    assert np.linalg.cond(legs.J).max() < 20         # Stewart Jacobian well conditioned
