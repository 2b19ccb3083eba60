"""Reference problems shared by the tests: seeded random states inside the workspace."""

from __future__ import annotations

import numpy as np

from offshore_crane.robot.kinematics import legs

#: Sampling box of the random states [m, rad]: Table 1's range with margins.
Q_LOW = np.array([-0.06, -0.06, 0.44, -0.45, -0.45, -0.45, -np.pi, -1.9, -0.19])
Q_HIGH = np.array([0.06, 0.06, 0.56, 0.45, 0.45, 0.45, np.pi, 1.9, 0.19])


def random_states(robot, n: int, seed: int, speed: float = 1.0, accel: float = 5.0):
    """``n`` random (q, qd, qdd) ``(n, 9)`` with every leg inside its stroke.

    q is uniform in [Q_LOW, Q_HIGH] (rejection-sampled on the leg strokes), qd uniform in
    ±speed [m/s, rad/s], qdd uniform in ±accel [m/s², rad/s²].
    """
    rng = np.random.default_rng(seed)
    stroke = robot.hybrid.stroke
    kept = []
    while sum(len(k) for k in kept) < n:
        q = rng.uniform(Q_LOW, Q_HIGH, size=(2 * n, 9))
        length = legs(robot, q).length
        ok = np.all((length > stroke[:, 0]) & (length < stroke[:, 1]), axis=1)
        kept.append(q[ok])
    q = np.concatenate(kept)[:n]
    qd = rng.uniform(-speed, speed, size=q.shape)
    qdd = rng.uniform(-accel, accel, size=q.shape)
    return q, qd, qdd


def held_at_home(robot, duration: float, rate: float):
    """The robot held at home for ``duration`` [s] at ``rate`` [Hz] (a frozen crane):
    ``t (N,), q, qd, qdd (N, 9)`` with q3 the home height, everything else zero."""
    from offshore_crane.motion.trajectories import time_grid

    t = time_grid(duration, rate)
    q = np.zeros((len(t), 9))
    q[:, 2] = robot.home_height
    return t, q, np.zeros_like(q), np.zeros_like(q)
