"""Tests of offshore_crane.serial: Kane inverse dynamics of serial robots read from URDFs.

The reference is Pinocchio's RNEA on the same URDF (independent code: spatial algebra,
recursive Newton-Euler). Both are exact algorithms evaluated in float64, so they agree to
rounding, ~1e-15 relative; the issue's acceptance bound is 1e-9 · max(1, max |τ|).
"""

from __future__ import annotations

import argparse
import importlib.metadata
import math
import tomllib
import zlib
from pathlib import Path

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane import serial
from offshore_crane.errors import InputError, ModelError
from offshore_crane.spatial import attitude_matrix, rpy_matrix

import pinocchio as pin
from offshore_crane.serial import reference
from offshore_crane.cli import serial_id as cli

ROBOTS_DIR = Path(importlib.metadata.distribution("example-robot-data").locate_file(
    "cmeel.prefix/share/example-robot-data/robots"))

# Acceptance bound of the issue: max |τ_kane − τ_rnea| ≤ 1e-9 · max(1, max |τ|).
RELATIVE = 1e-9
N_STATES = 200

#: (id, URDF under example-robot-data/robots, tip or None): the list the benchmark times
#: too, with why each robot is in it (tests/data/serial_robots.toml).
ROBOTS = [(r["id"], r["urdf"], r.get("tip")) for r in tomllib.loads(
    (Path(__file__).resolve().parents[1] / "data" / "serial_robots.toml").read_text())["robot"]]

# A chain with every joint kind: revolute, prismatic on a skew axis, continuous on a skew
# axis hanging from a welded link, joint origins and inertial frames with rpy, full
# inertia tensors, a massless welded tool frame.
MIXED = """<?xml version="1.0"?>
<robot name="mixed">
  <link name="base">
    <inertial><origin xyz="0.1 0 0.05"/><mass value="5"/>
      <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="l1"/>
    <origin xyz="0.05 -0.02 0.3" rpy="0.1 -0.2 0.3"/><axis xyz="0 0 1"/>
    <limit lower="-2.5" upper="2.5" effort="10" velocity="1"/>
  </joint>
  <link name="l1">
    <inertial><origin xyz="0.02 0.1 0.15" rpy="0.4 0.1 -0.3"/><mass value="2.5"/>
      <inertia ixx="0.05" iyy="0.04" izz="0.03" ixy="0.002" ixz="-0.001" iyz="0.003"/>
    </inertial>
  </link>
  <joint name="j2" type="prismatic">
    <parent link="l1"/><child link="l2"/>
    <origin xyz="0 0.1 0.4" rpy="-0.5 0.2 0.1"/><axis xyz="0.3 -0.5 0.8"/>
    <limit lower="-0.3" upper="0.5" effort="10" velocity="1"/>
  </joint>
  <link name="l2">
    <inertial><origin xyz="-0.03 0.02 0.1" rpy="0 0.3 0.2"/><mass value="1.5"/>
      <inertia ixx="0.02" iyy="0.03" izz="0.015" ixy="-0.001" ixz="0.0005" iyz="0.001"/>
    </inertial>
  </link>
  <joint name="l2_weld" type="fixed">
    <parent link="l2"/><child link="l2b"/><origin xyz="0.1 0 0.2" rpy="0.2 0.3 -0.4"/>
  </joint>
  <link name="l2b">
    <inertial><origin xyz="0.01 -0.02 0.05" rpy="0.1 0 0"/><mass value="0.8"/>
      <inertia ixx="0.004" iyy="0.005" izz="0.006" ixy="0.0002" ixz="0" iyz="-0.0003"/>
    </inertial>
  </link>
  <joint name="j3" type="continuous">
    <parent link="l2b"/><child link="l3"/>
    <origin xyz="0 0.05 0.1" rpy="0.3 0 0.5"/><axis xyz="1 1 0"/>
  </joint>
  <link name="l3">
    <inertial><origin xyz="0.05 0.05 0.2" rpy="-0.2 0.1 0.3"/><mass value="1.2"/>
      <inertia ixx="0.01" iyy="0.012" izz="0.008" ixy="0.001" ixz="0.0004" iyz="0"/>
    </inertial>
  </link>
  <joint name="j4" type="revolute">
    <parent link="l3"/><child link="l4"/>
    <origin xyz="0.02 0 0.3" rpy="0 -0.4 0"/><axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
  </joint>
  <link name="l4">
    <inertial><origin xyz="0 0.01 0.08" rpy="0.5 0.5 0"/><mass value="0.6"/>
      <inertia ixx="0.002" iyy="0.003" izz="0.0015" ixy="0" ixz="0.0001" iyz="0"/>
    </inertial>
  </link>
  <joint name="tool_weld" type="fixed">
    <parent link="l4"/><child link="tool"/><origin xyz="0.1 0.05 0.2" rpy="0.3 0.2 0.1"/>
  </joint>
  <link name="tool"/>
</robot>
"""

_BRANCH = """  <joint name="j_side" type="revolute">
    <parent link="l1"/><child link="side"/><origin xyz="0.2 0 0"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <link name="side">
    <inertial><mass value="0.7"/>
      <inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
</robot>
"""

_FLOATING_BRANCH = """  <joint name="j_free" type="floating">
    <parent link="l2"/><child link="loose"/><origin xyz="0 0.3 0" rpy="0.2 0 0"/>
  </joint>
  <link name="loose">
    <inertial><origin xyz="0.05 0 0"/><mass value="0.9"/>
      <inertia ixx="0.002" iyy="0.001" izz="0.003" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
</robot>
"""


def _with_type(joint: str, new_type: str) -> str:
    text = MIXED.replace(f'name="{joint}" type="{_type_of(joint)}"',
                         f'name="{joint}" type="{new_type}"')
    assert text != MIXED
    return text


def _type_of(joint: str) -> str:
    return {"j1": "revolute", "j2": "prismatic", "j3": "continuous", "j4": "revolute"}[joint]


def _relative_error(tau, ref) -> float:
    return float(np.abs(tau - ref).max() / max(1.0, np.abs(ref).max()))


def _check_against_rnea(source, chain, n=N_STATES, seed=0, gravity=serial.GRAVITY):
    model = reference.pinocchio_model(source, chain)
    q, qd, qdd = serial.random_states(chain, n, seed=seed)
    tau = serial.inverse_dynamics(chain, q, qd, qdd, gravity=gravity)
    ref = reference.rnea(model, q, qd, qdd, gravity=gravity)
    assert tau.shape == ref.shape == (n, chain.n)
    return _relative_error(tau, ref), ref


# --------------------------------------------------------------------------- robots

@pytest.mark.parametrize("name, rel, tip", ROBOTS, ids=[r[0] for r in ROBOTS])
def test_example_robots_match_pinocchio_rnea(name, rel, tip):
    path = ROBOTS_DIR / rel
    chain = serial.load_chain(path, tip=tip)
    err, ref = _check_against_rnea(path, chain, seed=zlib.crc32(name.encode()))
    assert err <= RELATIVE, f"{name}: relative error {err:.2e}"
    assert np.abs(ref).max() > 0.1  # the states load the robot (not a trivial pass)


@pytest.mark.parametrize("name, rel, tip", [r for r in ROBOTS if r[2] is None],
                         ids=[r[0] for r in ROBOTS if r[2] is None])
def test_joint_order_is_pinocchios(name, rel, tip):
    path = ROBOTS_DIR / rel
    chain = serial.load_chain(path)
    model = pin.buildModelFromUrdf(str(path))
    assert chain.joint_names == tuple(model.names)[1:]


def test_panda_tip_locks_fingers_and_keeps_their_mass():
    path = ROBOTS_DIR / "panda_description/urdf/panda.urdf"
    chain = serial.load_chain(path, tip="panda_hand")
    assert chain.joint_names == tuple(f"panda_joint{i}" for i in range(1, 8))
    assert chain.locked == ("panda_finger_joint1", "panda_finger_joint2")
    assert chain.tip == "panda_hand"
    full = pin.buildModelFromUrdf(str(path))
    moving = sum(inertia.mass for inertia in list(full.inertias)[1:])  # [0]: universe
    # The fingers are welded into the last body, not dropped. 1e-12 kg: a sum of a dozen
    # masses of order 1 kg in a different order.
    assert chain.mass.sum() == pytest.approx(moving, abs=1e-12)
    assert "panda_leftfinger" in chain.frames and chain.frames["panda_leftfinger"][0] == 6


# --------------------------------------------------------------------------- mixed joints

def test_mixed_chain_structure():
    chain = serial.load_chain(MIXED)
    assert chain.joint_names == ("j1", "j2", "j3", "j4")
    assert chain.prismatic.tolist() == [False, True, False, False]
    np.testing.assert_allclose(np.linalg.norm(chain.axis, axis=1), 1.0, rtol=0, atol=1e-15)
    assert chain.lower[2] == -np.inf and chain.upper[2] == np.inf  # continuous
    assert chain.mass.tolist() == pytest.approx([2.5, 1.5 + 0.8, 1.2, 0.6], abs=1e-15)
    assert chain.frames["tool"][0] == 3 and chain.frames["l2b"][0] == 1


@pytest.mark.parametrize("gravity", [serial.GRAVITY, (1.5, -2.0, -8.0)])
def test_mixed_chain_matches_rnea_from_text_and_file(tmp_path, gravity):
    path = tmp_path / "mixed.urdf"
    path.write_text(MIXED)
    for source in (MIXED, path, str(path)):
        chain = serial.load_chain(source)
        err, _ = _check_against_rnea(source, chain, gravity=gravity)
        assert err <= RELATIVE


def test_prismatic_joint_force_is_covered():
    """The prismatic joint's force is a real, varying force that RNEA reproduces."""
    chain = serial.load_chain(MIXED)
    model = reference.pinocchio_model(MIXED, chain)
    q, qd, qdd = serial.random_states(chain, N_STATES, seed=5)
    tau = serial.inverse_dynamics(chain, q, qd, qdd)
    ref = reference.rnea(model, q, qd, qdd)
    assert np.ptp(ref[:, 1]) > 1.0  # [N]: not a constant
    assert np.abs(tau[:, 1] - ref[:, 1]).max() <= RELATIVE * np.abs(ref[:, 1]).max()


def test_continuous_joint_is_periodic():
    chain = serial.load_chain(MIXED)
    q, qd, qdd = serial.random_states(chain, 20, seed=2)
    shifted = q.copy()
    shifted[:, 2] += 2 * math.pi
    a = serial.inverse_dynamics(chain, q, qd, qdd)
    b = serial.inverse_dynamics(chain, shifted, qd, qdd)
    # sin/cos of angles differing by 2π agree to ~1e-15; scaled by torques of order 10.
    np.testing.assert_allclose(a, b, rtol=0, atol=1e-12)


def test_tip_in_mid_chain_locks_the_rest():
    chain = serial.load_chain(MIXED, tip="l2b")
    assert chain.joint_names == ("j1", "j2")
    assert chain.locked == ("j3", "j4")
    err, _ = _check_against_rnea(MIXED, chain)
    assert err <= RELATIVE


def test_tip_cuts_branches_including_a_floating_one():
    text = MIXED.replace("</robot>\n", _BRANCH.replace("</robot>\n", "") + _FLOATING_BRANCH)
    chain = serial.load_chain(text, tip="tool")
    assert chain.joint_names == ("j1", "j2", "j3", "j4")
    assert set(chain.locked) == {"j_side", "j_free"}
    err, _ = _check_against_rnea(text, chain)
    assert err <= RELATIVE


# --------------------------------------------------------------------------- batching

@pytest.mark.parametrize("source, tip", [(MIXED, None),
                                         (ROBOTS_DIR / ROBOTS[0][1], None)])
def test_batch_equals_per_sample_loop(source, tip):
    chain = serial.load_chain(source, tip=tip)
    q, qd, qdd = serial.random_states(chain, 50, seed=11)
    wrench = (np.random.default_rng(1).normal(size=(50, 3)),
              np.random.default_rng(2).normal(size=(50, 3)))
    batch = serial.inverse_dynamics(chain, q, qd, qdd, wrench=wrench)
    loop = np.array([serial.inverse_dynamics(chain, q[i], qd[i], qdd[i],
                                             wrench=(wrench[0][i], wrench[1][i]))
                     for i in range(50)])
    assert loop.shape == batch.shape == (50, chain.n)
    assert serial.inverse_dynamics(chain, q[0], qd[0], qdd[0]).shape == (chain.n,)
    # Same operations in the same order except BLAS kernels chosen by array size: the
    # results agree to rounding (a few ulps of |τ| ~ 10-100).
    np.testing.assert_allclose(batch, loop, rtol=0, atol=1e-12 * max(1, np.abs(loop).max()))


# --------------------------------------------------------------------------- wrench

def _wrench_reference(source, chain, frame, q, qd, qdd, F, M):
    """τ_rnea − Jᵀ [F; M] with the frame's LOCAL_WORLD_ALIGNED Jacobian."""
    model = reference.pinocchio_model(source, chain)
    J = reference.frame_jacobians(model, q, frame)
    return (reference.rnea(model, q, qd, qdd)
            - np.einsum("nkr,nk->nr", J, np.hstack([F, M])))


@pytest.mark.parametrize("source, tip, frame", [
    (MIXED, None, "tool"),
    (MIXED, None, "l3"),
    (ROBOTS_DIR / "panda_description/urdf/panda.urdf", "panda_hand", None),
    (ROBOTS_DIR / "ur_description/urdf/ur5_robot.urdf", None, "tool0"),
])
def test_external_wrench_matches_jacobian_transpose(source, tip, frame):
    chain = serial.load_chain(source, tip=tip)
    q, qd, qdd = serial.random_states(chain, N_STATES, seed=8)
    rng = np.random.default_rng(9)
    F, M = rng.uniform(-50, 50, (N_STATES, 3)), rng.uniform(-10, 10, (N_STATES, 3))
    tau = serial.inverse_dynamics(chain, q, qd, qdd, wrench=(F, M), frame=frame)
    ref = _wrench_reference(source, chain, frame or chain.tip, q, qd, qdd, F, M)
    assert _relative_error(tau, ref) <= RELATIVE
    # The wrench changes the answer (a wrong frame or sign would be caught).
    assert np.abs(tau - serial.inverse_dynamics(chain, q, qd, qdd)).max() > 1.0


def test_wrench_default_frame_is_last_body_and_base_frame_takes_nothing():
    chain = serial.load_chain(MIXED)
    q, qd, qdd = serial.random_states(chain, 10, seed=3)
    w = ((1.0, 2.0, 3.0), (0.1, -0.2, 0.3))
    np.testing.assert_array_equal(serial.inverse_dynamics(chain, q, qd, qdd, wrench=w),
                                  serial.inverse_dynamics(chain, q, qd, qdd, wrench=w,
                                                          frame="l4"))
    np.testing.assert_array_equal(serial.inverse_dynamics(chain, q, qd, qdd, wrench=w,
                                                          frame="base"),
                                  serial.inverse_dynamics(chain, q, qd, qdd))


# --------------------------------------------------------------------------- base pose

def test_base_pose_equals_gravity_and_wrench_in_base_axes():
    chain = serial.load_chain(MIXED)
    q, qd, qdd = serial.random_states(chain, 30, seed=6)
    R = rpy_matrix(np.array([0.4, -0.7, 1.1]))
    g = np.array([0.0, 0.0, -9.81])
    F, M = np.array([3.0, -1.0, 2.0]), np.array([0.5, 0.2, -0.4])
    moved = serial.inverse_dynamics(chain, q, qd, qdd, gravity=g, wrench=(F, M),
                                    base_pose=(R, (5.0, -3.0, 2.0)))
    local = serial.inverse_dynamics(chain, q, qd, qdd, gravity=R.T @ g,
                                    wrench=(R.T @ F, R.T @ M))
    # Same physics in two frames: differences are rounding of rotated vectors.
    np.testing.assert_allclose(moved, local, rtol=0, atol=1e-12 * np.abs(local).max())


def test_hybrid_arm_on_a_still_platform_matches_the_hybrid_model():
    robot = oc.load_robot()
    q0 = np.array([0.03, 0.0176, 0.535, 0.342, 0.333, 0.3215])  # table1 at t = 0
    for source in (robot.urdf, robot.urdf_path):
        if source is None:
            continue
        chain = serial.load_chain(source, base="platform")
        assert chain.joint_names == ("arm_joint1", "arm_joint2", "arm_slide")
        assert chain.prismatic.tolist() == [False, False, True]
        qa, qda, qdda = serial.random_states(chain, N_STATES, seed=12)
        zeros = np.zeros((N_STATES, 6))
        q = np.hstack([np.tile(q0, (N_STATES, 1)), qa])
        qd, qdd = np.hstack([zeros, qda]), np.hstack([zeros, qdda])
        tau = serial.inverse_dynamics(chain, qa, qda, qdda,
                                      base_pose=(attitude_matrix(*q0[3:6]), q0[:3]))
        for method in ("kane", "rnea"):
            X = oc.inverse_dynamics(robot, q, qd, qdd, method=method)
            assert _relative_error(tau, X[:, :3]) <= RELATIVE, method


# --------------------------------------------------------------------------- errors

def test_branching_without_tip_names_the_joints():
    with pytest.raises(ModelError, match="branches.*'panda_finger_joint1', "
                                         "'panda_finger_joint2'"):
        serial.load_chain(ROBOTS_DIR / "panda_description/urdf/panda.urdf")
    text = MIXED.replace("</robot>\n", _BRANCH)
    with pytest.raises(ModelError, match="branches below link 'l1'.*'j2', 'j_side'") as exc:
        serial.load_chain(text)
    assert exc.value.element == "j_side"


@pytest.mark.parametrize("joint, kind", [("j1", "floating"), ("j3", "floating"),
                                         ("j2", "planar")])
def test_floating_and_planar_joints_are_refused(joint, kind):
    with pytest.raises(ModelError, match=f"joint '{joint}' is {kind}") as exc:
        serial.load_chain(_with_type(joint, kind))
    assert exc.value.element == joint


def test_mimic_joint_is_refused():
    text = MIXED.replace('<axis xyz="0 1 0"/>', '<axis xyz="0 1 0"/><mimic joint="j1"/>')
    with pytest.raises(ModelError, match="joint 'j4' mimics 'j1'") as exc:
        serial.load_chain(text)
    assert exc.value.element == "j4"
    # Cut above it with a tip, the mimic joint is locked instead.
    assert serial.load_chain(text, tip="l3").locked == ("j4",)


@pytest.mark.parametrize("kwargs, match", [
    ({"tip": "gripper_tip"}, "no link or frame 'gripper_tip'"),
    ({"tip": "base", "base": "l2"}, "tip 'base' is not below the base link 'l2'"),
    ({"base": "nowhere"}, "no link 'nowhere'"),
    ({"tip": "base"}, "no movable joint between 'base' and the tip 'base'"),
    ({"base": "l4"}, "no movable joint below 'l4'"),
])
def test_bad_tip_or_base(kwargs, match):
    with pytest.raises(ModelError, match=match):
        serial.load_chain(MIXED, **kwargs)


def test_bad_files_and_inputs(tmp_path):
    with pytest.raises(InputError, match="cannot read the URDF file"):
        serial.load_chain(tmp_path / "missing.urdf")
    with pytest.raises(ModelError, match="not well-formed"):
        serial.load_chain("<robot><link></robot>")
    chain = serial.load_chain(MIXED)
    q, qd, qdd = serial.random_states(chain, 3)
    with pytest.raises(InputError, match=r"q has shape \(3, 3\)"):
        serial.inverse_dynamics(chain, q[:, :3], qd, qdd)
    bad = qd.copy()
    bad[1, 2] = np.nan
    with pytest.raises(InputError, match=r"qd\[1, 2\] is nan"):
        serial.inverse_dynamics(chain, q, bad, qdd)
    with pytest.raises(InputError, match="sample counts differ"):
        serial.inverse_dynamics(chain, q, qd, qdd[:2])
    with pytest.raises(InputError, match="not a rotation"):
        serial.inverse_dynamics(chain, q, qd, qdd, base_pose=(2 * np.eye(3), np.zeros(3)))
    with pytest.raises(InputError, match="wrench force has shape"):
        serial.inverse_dynamics(chain, q, qd, qdd, wrench=(np.zeros(2), np.zeros(3)))
    with pytest.raises(ModelError, match="wrench frame 'hand' is not a link of the chain"):
        serial.inverse_dynamics(chain, q, qd, qdd, wrench=(np.zeros(3), np.zeros(3)),
                                frame="hand")
    with pytest.raises(InputError, match="at least 1"):
        serial.random_states(chain, 0)


def test_random_states_respect_limits():
    chain = serial.load_chain(MIXED)
    q, qd, qdd = serial.random_states(chain, 500, seed=1)
    assert np.all(q[:, [0, 1, 3]] >= chain.lower[[0, 1, 3]])
    assert np.all(q[:, [0, 1, 3]] <= chain.upper[[0, 1, 3]])
    assert np.all(np.abs(q[:, 2]) <= math.pi)  # continuous: ±π
    assert np.all(np.abs(qd) <= 2) and np.all(np.abs(qdd) <= 2)
    again = serial.random_states(chain, 500, seed=1)
    assert all(np.array_equal(a, b) for a, b in zip((q, qd, qdd), again))


# --------------------------------------------------------------------------- CLI

def _cli(argv) -> int:
    parser = argparse.ArgumentParser()
    cli.add_parser(parser.add_subparsers(dest="command"))
    return cli.run(parser.parse_args(argv))


def test_cli_prints_torques_and_checks(capsys):
    path = str(ROBOTS_DIR / "panda_description/urdf/panda.urdf")
    assert _cli(["serial-id", path, "--tip", "panda_hand", "--random", "3", "--seed", "7",
                 "--check"]) == 0
    out = capsys.readouterr().out
    assert "panda_joint7 [N·m]" in out and "locked at 0: panda_finger_joint1" in out
    assert len([line for line in out.splitlines() if line.strip().startswith(("0", "1", "2"))
                ]) >= 3
    assert "OK" in out and "check against Pinocchio RNEA" in out


def test_cli_prismatic_units_and_failed_check(tmp_path, capsys, monkeypatch):
    path = tmp_path / "mixed.urdf"
    path.write_text(MIXED)
    assert _cli(["serial-id", str(path)]) == 0
    assert "j2 [N]" in capsys.readouterr().out
    real = reference.rnea
    monkeypatch.setattr(reference, "rnea", lambda *a, **k: real(*a, **k) + 1e-6)
    assert _cli(["serial-id", str(path), "--check"]) == 1
    assert "FAILED" in capsys.readouterr().out


def test_cli_errors():
    with pytest.raises(InputError, match="--random must be at least 1"):
        _cli(["serial-id", "x.urdf", "--random", "0"])
    with pytest.raises(ModelError, match="branches"):
        _cli(["serial-id", str(ROBOTS_DIR / "panda_description/urdf/panda.urdf")])


def test_main_entry_point(capsys):
    from offshore_crane.__main__ import main

    path = str(ROBOTS_DIR / "ur_description/urdf/ur5_robot.urdf")
    assert main(["serial-id", path, "--random", "2", "--check"]) == 0
    assert main(["serial-id", path, "--tip", "nope"]) == 2
    assert "no link or frame 'nope'" in capsys.readouterr().err


# --------------------------------------------------------------------------- backends

@pytest.mark.parametrize("source, tip", [(ROBOTS_DIR / r[1], r[2]) for r in ROBOTS]
                         + [(MIXED, None)], ids=[r[0] for r in ROBOTS] + ["mixed"])
def test_the_compiled_loop_equals_the_vectorised_formulas(source, tip):
    """backend="numba" (the arm recursion's text compiled, one loop over samples) against
    backend="numpy" (the same text vectorised), with a per-sample base attitude and an
    external wrench: equal to 1e-13 of max(1, |τ|) (measured: bit for bit on every robot
    here, the same operations in the same order); one sample alone equals its row of the
    batch."""
    chain = serial.load_chain(source, tip=tip)
    N = 64
    q, qd, qdd = serial.random_states(chain, N, seed=12)
    rng = np.random.default_rng(13)
    R = np.array([rpy_matrix(a) for a in rng.uniform(-1.0, 1.0, (N, 3))])
    F, M = rng.uniform(-20, 20, (N, 3)), rng.uniform(-5, 5, (N, 3))
    kw = dict(gravity=(0.3, -0.2, -9.8), wrench=(F, M), base_pose=(R, np.zeros(3)))
    fast = serial.inverse_dynamics(chain, q, qd, qdd, backend="numba", **kw)
    slow = serial.inverse_dynamics(chain, q, qd, qdd, backend="numpy", **kw)
    assert _relative_error(fast, slow) <= 1e-13
    one = serial.inverse_dynamics(chain, q[5], qd[5], qdd[5], backend="numba",
                                  gravity=kw["gravity"], wrench=(F[5], M[5]),
                                  base_pose=(R[5], np.zeros(3)))
    np.testing.assert_array_equal(one, fast[5])


def test_one_sample_takes_the_short_way_with_the_same_result():
    """One plain sample (no wrench, no base pose) goes straight to the compiled sample:
    equal bit for bit to its row of a NumPy batch, for (n,) and (1, n) inputs; a NaN
    falls back to the general path, which names it."""
    chain = serial.load_chain(ROBOTS_DIR / "panda_description/urdf/panda.urdf",
                              tip="panda_hand")
    q, qd, qdd = serial.random_states(chain, 8, seed=21)
    batch = serial.inverse_dynamics(chain, q, qd, qdd, gravity=(0.1, 0.0, -9.7),
                                    backend="numpy")
    for k in range(8):
        one = serial.inverse_dynamics(chain, q[k], qd[k], qdd[k], gravity=(0.1, 0.0, -9.7))
        row = serial.inverse_dynamics(chain, q[k:k + 1], qd[k:k + 1], qdd[k:k + 1],
                                      gravity=(0.1, 0.0, -9.7))
        assert one.shape == (chain.n,) and row.shape == (1, chain.n)
        np.testing.assert_array_equal(one, batch[k])
        np.testing.assert_array_equal(row[0], batch[k])
    bad = q[0].copy()
    bad[3] = np.nan
    with pytest.raises(InputError, match="q"):
        serial.inverse_dynamics(chain, bad, qd[0], qdd[0])


def test_an_unknown_backend_is_refused():
    chain = serial.load_chain(MIXED)
    q, qd, qdd = serial.random_states(chain, 2)
    for a, b, c in ((q, qd, qdd), (q[0], qd[0], qdd[0])):
        with pytest.raises(InputError, match="unknown backend 'fortran'"):
            serial.inverse_dynamics(chain, a, b, c, backend="fortran")
