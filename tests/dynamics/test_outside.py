"""The compiled workspace check of a few samples (:mod:`offshore_crane.dynamics.outside`)
against :func:`~offshore_crane.robot.kinematics.check_workspace`, sample by sample: the
same verdict on poses that leave the workspace every way it can be left."""

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.errors import WorkspaceError
from offshore_crane.robot.kinematics import check_workspace, leg_positions
from offshore_crane.robot.kinematics import workspace as ws


@pytest.fixture(scope="module")
def robot():
    return oc.load_robot()


def _poses(robot, n: int, seed: int) -> np.ndarray:
    """``2 n`` seeded poses: ``n`` with the platform at home and the arm over 1.5 × its
    joints' ranges, ``n`` with the arm at home and the platform moved by up to ±1.2 of
    the legs' anchor radius sideways, from below the base to past the legs' stroke in
    height, tilted by up to ±0.6 rad: every way out of the workspace, and poses inside."""
    rng = np.random.default_rng(seed)
    home = robot.home_pose()
    radius = float(np.linalg.norm(robot.hybrid.p_base_P[:, :2], axis=1).mean())
    stroke = ws.limits_of(robot.hybrid).stroke
    lim = ws.limits_of(robot.hybrid).arm
    arm = np.repeat(home[None, :], n, axis=0)
    mid, span = 0.5 * (lim[:, 1] + lim[:, 0]), lim[:, 1] - lim[:, 0]
    arm[:, 6:6 + len(lim)] = mid + rng.uniform(-0.75, 0.75, (n, len(lim))) * span
    plat = np.repeat(home[None, :], n, axis=0)
    plat[:, :2] = rng.uniform(-1.2, 1.2, (n, 2)) * radius
    plat[:, 2] = rng.uniform(-0.2, 1.2, n) * stroke[:, 1].max()
    plat[:, 3:6] = rng.uniform(-0.6, 0.6, (n, 3))
    return np.concatenate([arm, plat])


def test_the_compiled_check_gives_check_workspaces_verdict_sample_by_sample(robot):
    from offshore_crane.dynamics import outside

    q = _poses(robot, 400, seed=31)
    g = outside.geometry(robot)
    numpy_out = np.empty(len(q), dtype=bool)
    for k in range(len(q)):
        try:
            check_workspace(robot, q[k:k + 1])
            numpy_out[k] = False
        except WorkspaceError:
            numpy_out[k] = True
    compiled_out = np.array([outside.first_outside(q, k, k + 1, *g) == k
                             for k in range(len(q))])
    np.testing.assert_array_equal(compiled_out, numpy_out)
    # each way out alone, the other limits opened to ±inf (on these poses a way out
    # seldom comes alone): the compiled test against NumPy's on the same positions
    lim = ws.limits_of(robot.hybrid)
    length, height, theta = leg_positions(robot, q)
    arm = q[:, 6:6 + lim.arm.shape[0]]
    ways = {"arm": ((arm < lim.arm[:, 0]) | (arm > lim.arm[:, 1])).any(axis=1),
            "below": (height <= 0.0).any(axis=1),
            "stroke": ((length < lim.stroke[:, 0]) | (length > lim.stroke[:, 1])).any(axis=1),
            "ujoint": ((theta < lim.ujoint[..., 0]) | (theta > lim.ujoint[..., 1]))
            .any(axis=(1, 2))}
    pS, pP, RU = g[:3]
    for way, expected in ways.items():
        assert 10 <= expected.sum() < len(q) - 10, (way, int(expected.sum()))
        opened = [np.where(np.arange(2) == 0, -np.inf, np.inf) * np.ones_like(x)
                  for x in g[3:]]
        keep = {"arm": 0, "stroke": 1, "ujoint": 2}.get(way)
        if keep is not None:
            opened[keep] = g[3 + keep]
        got = [outside.first_outside(q, k, k + 1, pS, pP, RU, *opened) == k
               for k in range(len(q))]
        # (a sphere centre below its U-joint has no limit to open: it stays a way out)
        np.testing.assert_array_equal(got, expected | ways["below"], err_msg=way)
    # over a range: the first sample out, or -1
    first = int(np.flatnonzero(numpy_out)[0])
    assert outside.first_outside(q, 0, len(q), *g) == first
    inside = np.flatnonzero(~numpy_out)
    assert outside.first_outside(q[inside], 0, len(inside), *g) == -1
