"""Link poses from q (offshore_crane.outputs.visual.poses): closed loops, Pinocchio's forward
kinematics on the equivalent tree as the independent reference, batch = per sample,
the cable convention, errors."""


import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.outputs.visual import poses

#: Tolerances. Loop closure: the leg angles come from atan2 of the same vectors that the
#: tree composes back, so the cut frames meet to a few ulps of the ~0.5 m lever arms
#: (2e-16 measured); 1e-12 m leaves 4 decades. Against Pinocchio: two products of ~10
#: rotations in different orders, same bound.
CLOSURE_TOL = 1e-12
PIN_TOL = 1e-12


def random_poses(robot, n, seed):
    """``(n, 9)`` poses around home inside the workspace (checked by the kinematics)."""
    rng = np.random.default_rng(seed)
    h = robot.home_height
    q = np.zeros((n, 9))
    q[:, 0:2] = rng.uniform(-0.04, 0.04, (n, 2))
    q[:, 2] = h + rng.uniform(-0.03, 0.03, n)
    q[:, 3:6] = rng.uniform(-0.12, 0.12, (n, 3))
    q[:, 6:8] = rng.uniform(-3.0, 3.0, (n, 2))
    lo, hi = robot.description.joint("arm_slide").lower, robot.description.joint("arm_slide").upper
    q[:, 8] = rng.uniform(lo, hi, n)
    return q


def test_leg_tips_meet_platform_anchors(robot):
    q = random_poses(robot, 200, seed=1)
    P = poses.link_poses(robot, q)
    for i in range(1, 7):
        tip, anchor = P.of(f"leg{i}_tip")[0], P.of(f"platform_anchor{i}")[0]
        assert np.abs(tip - anchor).max() <= CLOSURE_TOL


def test_platform_pose_is_q(robot):
    q = random_poses(robot, 50, seed=2)
    p, R = poses.link_poses(robot, q).of("platform")
    from offshore_crane.spatial import attitude_matrix

    assert np.array_equal(p, q[:, :3]) or np.abs(p - q[:, :3]).max() < 1e-15
    assert np.abs(R - attitude_matrix(q[:, 3], q[:, 4], q[:, 5])).max() < 1e-15


def test_equals_pinocchio_forward_kinematics(robot):
    """Every link frame against pinocchio.forwardKinematics on robot.pinocchio_model,
    given the tree joint values."""
    import pinocchio as pin
    model = robot.pinocchio_model
    data = model.createData()
    q = random_poses(robot, 20, seed=3)
    values = poses.joint_values(robot, q)
    P = poses.link_poses(robot, q)
    frames = {link: model.getFrameId(link, pin.FrameType.BODY) for link in P.links}
    worst = 0.0
    for n in range(len(q)):
        qp = pin.neutral(model)
        for name, v in values.items():
            jid = model.getJointId(name)
            qp[model.joints[jid].idx_q] = v[n]
        pin.forwardKinematics(model, data, qp)
        pin.updateFramePlacements(model, data)
        for k, link in enumerate(P.links):
            M = data.oMf[frames[link]]
            worst = max(worst, np.abs(M.translation - P.p[n, k]).max(),
                        np.abs(M.rotation - P.R[n, k]).max())
    assert worst <= PIN_TOL


def test_batch_equals_per_sample(robot):
    q = random_poses(robot, 7, seed=4)
    P = poses.link_poses(robot, q)
    for n in range(len(q)):
        one = poses.link_poses(robot, q[n])
        assert len(one) == 1
        np.testing.assert_array_equal(one.p[0], P.p[n])
        np.testing.assert_array_equal(one.R[0], P.R[n])


def test_cable_direction_follows_the_sway_convention(robot):
    """e = R_base_tip Rx(phi1) Ry(phi2) (0, 0, -1), payload at arm_tip + L e."""
    from offshore_crane.spatial import rot_x, rot_y

    L = 0.7
    hung = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": L})
    q = random_poses(hung.without_hanging_payload(), 30, seed=5)
    sway = np.random.default_rng(6).uniform(-0.6, 0.6, (30, 2))
    P = poses.link_poses(hung, q, sway)
    p_tip, R_tip = P.of("arm_tip")
    e = np.einsum("nij,nj->ni", R_tip @ rot_x(sway[:, 0]) @ rot_y(sway[:, 1]),
                  np.broadcast_to([0.0, 0.0, -1.0], (30, 3)))
    assert np.abs(P.of("payload")[0] - (p_tip + L * e)).max() < 1e-14
    with pytest.raises(oc.InputError, match=r"give the sway angles sway \(N, 2\)"):
        poses.link_poses(hung, q)
    with pytest.raises(oc.InputError, match="sway has 3 samples and q 30"):
        poses.link_poses(hung, q, sway[:3])


def test_errors(robot):
    q = random_poses(robot, 3, seed=7)
    with pytest.raises(oc.InputError, match="sway given, but the robot has no cable"):
        poses.link_poses(robot, q, np.zeros((3, 2)))
    with pytest.raises(oc.InputError, match=r"q has shape \(3, 8\)"):
        poses.link_poses(robot, q[:, :8])
    bad = q.copy()
    bad[1, 4] = np.nan
    with pytest.raises(oc.InputError, match=r"q\[1, 4\] is nan \(sample 1"):
        poses.link_poses(robot, bad)
    hanging = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 0.5})
    with pytest.raises(oc.InputError, match=r"give the sway angles sway \(N, 2\)"):
        poses.link_poses(hanging, q)


def test_urdf_visuals_parsed_with_material_colours():
    from offshore_crane.robot.urdf import parse_urdf

    text = """<robot name="r"><material name="red"><color rgba="1 0 0 1"/></material>
      <link name="a"><visual><origin xyz="0 0 0.5" rpy="0 0 1.5707963267948966"/>
        <geometry><cylinder radius="0.1" length="1"/></geometry><material name="red"/></visual>
        <visual><geometry><box size="1 2 3"/></geometry>
          <material name="own"><color rgba="0 0 1 0.5"/></material></visual>
        <visual><geometry><mesh filename="x.stl"/></geometry></visual></link></robot>"""
    (cyl, box) = parse_urdf(text).visuals["a"]
    assert cyl.shape == "cylinder" and cyl.size.tolist() == [0.1, 0.1, 1.0]
    assert cyl.rgba.tolist() == [1, 0, 0, 1] and cyl.xyz.tolist() == [0, 0, 0.5]
    assert np.allclose(cyl.R, [[0, -1, 0], [1, 0, 0], [0, 0, 1]], atol=1e-15)
    assert box.size.tolist() == [1, 2, 3] and box.rgba.tolist() == [0, 0, 1, 0.5]
    with pytest.raises(oc.ModelError, match=r"material 'red': rgba '2 0 0 1' has values "
                       "outside 0..1"):
        parse_urdf(text.replace('rgba="1 0 0 1"', 'rgba="2 0 0 1"'))
    with pytest.raises(oc.ModelError, match=r"link 'a' visual 2: rgba '0 0 1 -1' has values"):
        parse_urdf(text.replace('rgba="0 0 1 0.5"', 'rgba="0 0 1 -1"'))
    with pytest.raises(oc.ModelError, match="link 'a' visual 1: missing attribute 'radius'"):
        parse_urdf(text.replace('radius="0.1" ', ''))
