"""Kinematics checked independently: loop closure in Pinocchio, finite differences.

Two implementations meet here: the formulas of the Kane kernels
(:func:`offshore_crane.robot.kinematics.legs`) and the RNEA reference's loop closure
(:mod:`offshore_crane.reference.rnea`, Newton on each leg's chain); Pinocchio's own
forward kinematics checks the reference, finite differences check the formulas.
"""

import pytest

import numpy as np

import offshore_crane as oc
import pinocchio as pin

from offshore_crane.errors import InputError
from offshore_crane.conventions import LEG_JOINTS
from offshore_crane.robot.kinematics import legs as leg_kinematics
from offshore_crane.reference.rnea import tree_states
from problems import random_states


def _leg_columns(model, names):
    return [model.idx_vs[model.getJointId(n)] for n in names]


def test_loops_close_in_pinocchio(robot):
    """Tree states of the RNEA reference put leg{i}_tip on platform_anchor{i}: position,
    velocity and classical acceleration (Pinocchio's own forward kinematics)."""
    q, qd, qdd = random_states(robot, 60, seed=5)
    qt, vt, at = tree_states(robot, q, qd, qdd)
    model = robot.pinocchio_model
    data = model.createData()
    tips = [model.getFrameId(f"leg{i}_tip") for i in range(1, 7)]
    anchors = [model.getFrameId(f"platform_anchor{i}") for i in range(1, 7)]
    frame = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    worst = np.zeros(3)
    for k in range(len(q)):
        pin.forwardKinematics(model, data, qt[k], vt[k], at[k])
        pin.updateFramePlacements(model, data)
        for ft, fa in zip(tips, anchors):
            dp = data.oMf[ft].translation - data.oMf[fa].translation
            dv = (pin.getFrameVelocity(model, data, ft, frame).linear
                  - pin.getFrameVelocity(model, data, fa, frame).linear)
            da = (pin.getFrameClassicalAcceleration(model, data, ft, frame).linear
                  - pin.getFrameClassicalAcceleration(model, data, fa, frame).linear)
            worst = np.maximum(worst, [np.abs(dp).max(), np.abs(dv).max(), np.abs(da).max()])
    # positions ~0.5 m, speeds ~1 m/s, accelerations ~10 m/s²: round-off is < 1e-13
    assert worst[0] < 1e-13 and worst[1] < 1e-12 and worst[2] < 1e-11, worst


def test_leg_rates_are_derivatives(robot):
    """Central differences of l(t) and θ(t) along a smooth path reproduce l̇, l̈, θ̇, θ̈."""
    from offshore_crane.motion.trajectories import table1

    h = 1e-4
    t = np.linspace(0.0, 30.0, 61)
    states = [table1(t + s * h) for s in (-1, 0, 1)]
    legs = [leg_kinematics(robot, *st) for st in states]
    lm, l0, lp = legs
    d1 = (lp.length - lm.length) / (2 * h)
    d2 = (lp.length - 2 * l0.length + lm.length) / h**2
    th1 = (lp.theta - lm.theta) / (2 * h)
    th2 = (lp.theta - 2 * l0.theta + lm.theta) / h**2
    # truncation O(h²)·|x'''| ~ 1e-9; round-off of the 2nd difference ε·l/h² ~ 1e-8
    assert np.abs(d1 - l0.rate).max() < 1e-8
    assert np.abs(th1 - l0.theta_d).max() < 1e-8
    assert np.abs(d2 - l0.accel).max() < 1e-6
    assert np.abs(th2 - l0.theta_dd).max() < 1e-6
    # angular velocity of the leg from the rotation matrices: skew(ω) = Ṙ Rᵀ
    Rdot = (lp.R - lm.R) / (2 * h)
    W = Rdot @ np.swapaxes(l0.R, -1, -2)
    omega_fd = np.stack([W[..., 2, 1], W[..., 0, 2], W[..., 1, 0]], axis=-1)
    assert np.abs(omega_fd - l0.omega).max() < 1e-8


def test_partial_velocities_by_finite_differences(robot):
    """v_S,r = ∂S/∂q_r and the leg Jacobian J = ∂l/∂q (u_r = q̇_r, paper Eq. 19)."""
    q, _, _ = random_states(robot, 5, seed=9)
    z = np.zeros_like(q)
    base = leg_kinematics(robot, q, z, z)
    h = 1e-6
    for r in range(6):
        dq = np.zeros(9)
        dq[r] = h
        lp = leg_kinematics(robot, q + dq, z, z)
        lm = leg_kinematics(robot, q - dq, z, z)
        # central difference error O(h²) plus round-off ε/h ~ 1e-10
        assert np.abs((lp.p_S - lm.p_S) / (2 * h) - base.V_S[:, :, r]).max() < 1e-8
        assert np.abs((lp.length - lm.length) / (2 * h) - base.J[:, :, r]).max() < 1e-8


def test_formulas_agree_with_the_reference_closure(robot):
    """The Kane formulas' closed-form legs (U-joint spin, derived accelerations) against
    the reference's Newton closure on the URDF's chains: angles, length, rates and
    accelerations of every leg joint (values ~1, round-off of both ~1e-15)."""
    q, qd, qdd = random_states(robot, 200, seed=6)
    qt, vt, at = tree_states(robot, q, qd, qdd)
    legs = leg_kinematics(robot, q, qd, qdd)
    model = robot.pinocchio_model
    cols = np.array([_leg_columns(model, names) for names in LEG_JOINTS])     # (6, 3)
    for tree, ours in ((qt, np.concatenate([legs.theta, legs.length[..., None]], -1)),
                       (vt, np.concatenate([legs.theta_d, legs.rate[..., None]], -1)),
                       (at, np.concatenate([legs.theta_dd, legs.accel[..., None]], -1))):
        assert np.abs(tree[:, cols] - ours).max() < 1e-12


# --------------------------------------------------------------------------- workspace
@pytest.mark.parametrize("ujoint_limit", [None, 0.35])
def test_check_workspace_equals_the_solvers_limits(ujoint_limit):
    """The kinematic workspace check raises exactly what inverse dynamics with
    ``limits=True`` raises (same message, joint, sample and value) or passes when it
    passes, on seeded random poses around home: arm joints pinned or free, every limit
    category met (a narrowed U-joint limit makes the U-joint category appear)."""
    from offshore_crane.dynamics import solve
    from offshore_crane.errors import WorkspaceError
    from offshore_crane.robot.kinematics import check_workspace

    robot = oc.load_robot(overrides=None if ujoint_limit is None else
                          {"legs.ujoint.limit": ujoint_limit})
    rng = np.random.default_rng(61)
    home = robot.home_pose()
    spread = np.array([0.3, 0.3, 0.4, 0.6, 0.6, 0.6, 2.0, 2.0, 0.2])
    seen = set()

    def outcome(f):
        try:
            f()
        except WorkspaceError as exc:
            return str(exc), exc.joint, exc.index, exc.value
        return None

    for trial in range(600):
        q = home + rng.normal(size=(12, 9)) * spread * rng.uniform(0.0, 1.5)
        if trial % 2:
            q[:, 6:] = 0.0                        # let the legs' categories show
        t = 0.01 * np.arange(12)
        ours = outcome(lambda: check_workspace(robot, q, t))
        numpy_, numba_ = (outcome(lambda: solve(robot, q, 0 * q, 0 * q, t=t, limits=True,
                                                 checks=False, backend=b))
                          for b in ("numpy", "numba"))
        assert ours == numpy_, trial              # the same formulas run by NumPy: identical
        # compiled: the same verdict; the value to round-off (Numba's atan2/sqrt differ by
        # an ulp or two from NumPy's: 1e-12 relative is a thousand times that)
        assert (ours is None) == (numba_ is None), trial
        if ours is not None:
            assert ours[1:3] == numba_[1:3], trial
            np.testing.assert_allclose(ours[3], numba_[3], rtol=1e-12)
        if ours is not None:
            seen.add("height" if "below its U-joint" in ours[0] else "arm"
                     if ours[1].startswith("arm") else ours[1].split("_")[1].rstrip("0123456789"))
    assert seen == ({"height", "slide", "arm", "u"} if ujoint_limit else
                    {"height", "slide", "arm"})


def test_check_workspace_in_threads_names_the_first_violation():
    """Threads share the check's blocks of CHECK_BLOCK samples (thread k every k-th
    block): the same error as one thread, naming the earliest violation even when it lies
    in another thread's share than a later one (blocks 1 and 2 here), and the same pass."""
    from offshore_crane.errors import WorkspaceError
    from offshore_crane.robot.kinematics import CHECK_BLOCK, check_workspace

    robot = oc.load_robot()
    q = np.tile(robot.home_pose(), (5 * CHECK_BLOCK, 1))
    t = 0.01 * np.arange(len(q))
    for n in (1, 2, 3):
        check_workspace(robot, q, t, threads=n)            # home everywhere: passes
    bad = q.copy()
    bad[2 * CHECK_BLOCK + 3, 2] = 5.0                     # legs far too long (block 2)
    bad[CHECK_BLOCK + 5, 2] = 5.0                         # the first one (block 1)
    errors = []
    for n in (1, 2, 3):
        with pytest.raises(WorkspaceError, match=f"sample {CHECK_BLOCK + 5}") as info:
            check_workspace(robot, bad, t, threads=n)
        errors.append((str(info.value), info.value.joint, info.value.index))
    assert errors[1:] == errors[:1] * 2
    with pytest.raises(InputError, match="threads must be a positive integer, got 0"):
        check_workspace(robot, q, t, threads=0)


def test_a_watch_fed_while_the_motion_is_computed_gives_the_same_verdict():
    """A :class:`WorkspaceWatch` fed with the first blocks of a motion as they are filled
    (rows past ``ready`` hold NaN: not read), then given to :func:`check_workspace`: the
    same error as the whole check, whether the first violation lies in a block fed
    before (block 1) or in the rest, and the same pass; a watch that took more samples
    than the motion checked holds is not used."""
    from offshore_crane.errors import WorkspaceError
    from offshore_crane.robot.kinematics import CHECK_BLOCK, WorkspaceWatch, check_workspace

    robot = oc.load_robot()
    n = 3 * CHECK_BLOCK + 17
    q = np.tile(robot.home_pose(), (n, 1))
    t = 0.01 * np.arange(n)

    def watched(motion, ready):
        watch, filling = WorkspaceWatch(robot), np.full_like(motion, np.nan)
        for k in [*range(0, ready, 1000), ready]:   # the record as a loop fills it
            filling[:k] = motion[:k]
            watch.feed(filling, k)
        filling[:] = motion
        assert watch.done == (ready // CHECK_BLOCK) * CHECK_BLOCK
        return watch

    check_workspace(robot, q, t, watch=watched(q, n - 1))
    for row in (CHECK_BLOCK + 5, 3 * CHECK_BLOCK + 2):
        bad = q.copy()
        bad[row, 2] = 5.0                                  # legs far too long
        with pytest.raises(WorkspaceError) as whole:
            check_workspace(robot, bad, t)
        with pytest.raises(WorkspaceError, match=f"sample {row}") as fed:
            check_workspace(robot, bad, t, watch=watched(bad, n - 1))
        assert (str(fed.value), fed.value.index) == (str(whole.value), whole.value.index)
    long_watch = watched(q, n - 1)
    bad = q[:CHECK_BLOCK + 10].copy()
    bad[3, 2] = 5.0                                        # not seen by the fed watch
    with pytest.raises(WorkspaceError, match="sample 3"):
        check_workspace(robot, bad, t[:len(bad)], watch=long_watch)
