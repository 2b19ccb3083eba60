"""Excitation trajectories: finite Fourier series in the nine coordinates (Swevers et al.,
"Optimal robot excitation and identification", IEEE Trans. Robotics and Automation
13(5), 1997), periodic, with analytic rates and accelerations, scaled into the robot's
workspace.

``q_j(t) = c_j + Σ_h [a_jh / (h ω) sin(h ω t) − b_jh / (h ω) cos(h ω t)]``, ``ω = 2π / T``;
``q̇_j = Σ_h [a_jh cos(h ω t) + b_jh sin(h ω t)]``, ``q̈_j = Σ_h h ω [−a_jh sin + b_jh cos]``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


#: Scale factors tried (halving) before an excitation is refused.
MAX_HALVINGS = 30


@dataclass(frozen=True)
class Fourier:
    """A finite Fourier series motion (see the module docstring).

    Attributes:
        centre: ``(9,)`` c [m, rad]. a, b: ``(9, H)`` [m/s, rad/s]. period: T [s].
    """

    centre: np.ndarray
    a: np.ndarray
    b: np.ndarray
    period: float

    def __call__(self, t):
        """``(q, q̇, q̈)`` ``(n, 9)`` at times ``t (n,)`` [s]."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        w = 2.0 * math.pi / self.period
        h = np.arange(1, self.a.shape[1] + 1)
        arg = np.outer(t, h * w)                                   # (n, H)
        s, c = np.sin(arg), np.cos(arg)
        q = self.centre + (s @ (self.a / (h * w)).T) - (c @ (self.b / (h * w)).T)
        qd = c @ self.a.T + s @ self.b.T
        qdd = (-s * (h * w)) @ self.a.T + (c * (h * w)) @ self.b.T
        return q, qd, qdd


def fourier_excitation(robot, duration: float, rate: float = 100.0, harmonics: int = 5,
                       period: float | None = None, seed: int = 0, speed: float = 0.5):
    """A random Fourier excitation inside the workspace, as a
    :class:`~offshore_crane.motion.trajectories.Trajectory` with an analytic source.

    Coefficients are uniform in ±``speed`` [m/s, rad/s] per harmonic (the translations'
    at a tenth), centred on the home pose with the arm at zero, then halved together until
    every sample of the record passes the workspace checks.

    Args:
        duration: [s]; rate: samples [Hz]; harmonics: H; period: T [s] (default: the
            duration); seed: of the coefficients.

    Raises:
        InputError: no scale fits the workspace (after :data:`MAX_HALVINGS` halvings).
    """
    from offshore_crane.errors import InputError, WorkspaceError
    from offshore_crane.motion.trajectories import Trajectory, time_grid
    from offshore_crane.robot.kinematics import check_workspace

    t = time_grid(duration, rate)
    rng = np.random.default_rng(seed)
    weight = np.array([0.1, 0.1, 0.1, 1, 1, 1, 1, 1, 0.1])[:, None]
    a = rng.uniform(-speed, speed, (9, harmonics)) * weight
    b = rng.uniform(-speed, speed, (9, harmonics)) * weight
    centre = robot.home_pose().copy()
    T = float(duration if period is None else period)
    for _ in range(MAX_HALVINGS):
        f = Fourier(centre, a, b, T)
        q = f(t)[0]
        try:
            check_workspace(robot, q, t)
        except WorkspaceError:
            a, b = a / 2.0, b / 2.0
            continue
        return Trajectory(f"Fourier excitation (seed {seed}, {harmonics} harmonics)", t,
                          *f(t), source=f)
    raise InputError(f"fourier_excitation: no scale of the seed-{seed} coefficients stays "
                     "in the workspace: lower speed", name="speed")
