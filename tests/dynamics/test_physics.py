"""Hand checks and conservation laws, computed without our solver's kinematics
(tree states from the RNEA reference's own loop closure, energies from Pinocchio)."""

import numpy as np
import pinocchio as pin
import pytest

import offshore_crane as oc
from offshore_crane.conventions import LEG_JOINTS
from offshore_crane.robot.kinematics import legs as leg_kinematics
from offshore_crane.robot.kinematics import formulas
from offshore_crane.reference.rnea import tree_states
from offshore_crane.spatial import attitude_matrix
from offshore_crane.motion.trajectories import table1

G = 9.81


def test_static_massless_legs_support_the_weight():
    """With massless legs each leg is a two-force member: at rest, the leg forces along
    u_i balance the weight of platform + arm (forces and moments about O2)."""
    robot = oc.load_robot(leg_lower_mass=0.0, leg_upper_mass=0.0)
    h = robot.hybrid
    q = np.array([0.01, -0.02, 0.52, 0.1, -0.15, 0.2, 0.7, -0.4, 0.05])
    z = np.zeros(9)
    X = oc.inverse_dynamics(robot, q, z, z)
    legs = leg_kinematics(robot, q)
    u, S = legs.u[0], legs.p_S[0]
    support = (X[3:, None] * u).sum(axis=0)
    weight = (h.platform_mass + h.arm.mass.sum()) * G
    assert support == pytest.approx([0.0, 0.0, weight], abs=1e-9 * weight)
    # moments about O2: legs' forces vs weights of platform and arm bodies (from Pinocchio)
    model = robot.pinocchio_model
    data = model.createData()
    qt, _, _ = tree_states(robot, q, z, z)
    pin.forwardKinematics(model, data, qt[0])
    weight_moment = np.zeros(3)
    for name in ("platform_roll", "arm_joint1", "arm_joint2", "arm_slide"):
        jid = model.getJointId(name)
        c = data.oMi[jid].act(model.inertias[jid].lever)
        weight_moment += np.cross(c - q[:3], [0, 0, -model.inertias[jid].mass * G])
    leg_moment = np.cross(S - q[:3], X[3:, None] * u).sum(axis=0)
    assert leg_moment + weight_moment == pytest.approx(np.zeros(3), abs=1e-9 * weight)


def test_static_arm_hand_values(robot):
    """Level platform: gravity is along the joint axes, so T1 = T2 = Fs = 0. Pitched by
    q5 with the arm along x: Fs = −m_slider·g·sin(q5), and T1 = T2 = 0 (the weights'
    moments, x4 × g ∥ y, are orthogonal to the tilted joint axes z3 = z4 in the x–z plane)."""
    z = np.zeros(9)
    q = np.array([0, 0, 0.5, 0, 0, 0, 0.3, -0.8, 0.1])
    X = oc.inverse_dynamics(robot, q, z, z)
    assert np.abs(X[:3]).max() < 1e-12
    pitch = 0.2
    q = np.array([0, 0, 0.5, 0, pitch, 0, 0, 0, 0.1])
    X = oc.inverse_dynamics(robot, q, z, z)
    m_s = robot.hybrid.arm.mass[2]
    # x4 = (cos q5, 0, −sin q5): gravity pulls the slider along +x4 by m g sin q5
    assert X[2] == pytest.approx(-m_s * G * np.sin(pitch), rel=1e-12)
    assert np.abs(X[:2]).max() < 1e-12


def test_energy_balance_table1(robot):
    """Σ X_k · (rate of joint k) = d(T + V)/dt for all 17 bodies, T and V from Pinocchio
    on the tree (central difference, h = 1e-4 s: truncation ~h²·|E'''| ≈ 1e-8 W)."""
    t = np.linspace(0.0, 10 * np.pi, 400)
    h = 1e-4
    q, qd, qdd = table1(t)
    X = oc.inverse_dynamics(robot, q, qd, qdd)
    _, vt, _ = tree_states(robot, q, qd, qdd)
    model = robot.pinocchio_model
    slides = [model.idx_vs[model.getJointId(names[2])] for names in LEG_JOINTS]
    power = (X[:, :3] * qd[:, 6:9]).sum(axis=1) + (X[:, 3:] * vt[:, slides]).sum(axis=1)

    data = model.createData()

    def energy(tt):
        qt, vt_, _ = tree_states(robot, *table1(tt))
        return np.array([pin.computeKineticEnergy(model, data, qt[k], vt_[k])
                         + pin.computePotentialEnergy(model, data, qt[k])
                         for k in range(len(tt))])

    dEdt = (energy(t + h) - energy(t - h)) / (2 * h)
    assert np.abs(power - dEdt).max() <= 1e-6 * np.abs(power).max()


def test_rotating_frame_partials_match_attitude():
    """w4, w5, w6 (docs/conventions.md) give skew(Ω) = Ṙ Rᵀ for R = Rz(q6)Ry(q5)Rx(q4)."""
    rng = np.random.default_rng(1)
    q = rng.uniform(-1, 1, (20, 9))
    qd = rng.uniform(-1, 1, (20, 9))
    h = 1e-6
    Rp = attitude_matrix(*(q + h * qd)[:, 3:6].T)
    Rm = attitude_matrix(*(q - h * qd)[:, 3:6].T)
    R = attitude_matrix(*q[:, 3:6].T)
    W = (Rp - Rm) / (2 * h) @ np.swapaxes(R, -1, -2)
    omega = np.stack([W[:, 2, 1], W[:, 0, 2], W[:, 1, 0]], axis=-1)
    _, w4, w5, _ = formulas.attitude(q.T)
    ours = np.array(formulas.platform_rates(w4, w5, qd.T, np.zeros_like(q).T)[0]).T
    assert np.abs(ours - omega).max() < 1e-9
