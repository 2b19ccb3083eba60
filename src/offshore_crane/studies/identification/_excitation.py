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

from offshore_crane.dynamics.runtime import one_blas_thread

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
    if not robot.hybrid.has_arm:
        weight[6:] = 0.0                                   # no arm: q7..q9 stay 0
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


#: Samples of an excitation the optimiser evaluates its condition number on (evenly
#: spread: the regressor costs a Pinocchio call a sample).
OPTIMISE_SAMPLES = 300


@one_blas_thread()
def excitation_condition(robot, traj, base, samples: int = OPTIMISE_SAMPLES) -> float:
    """The condition number of the base regressor (columns scaled to unit norm) on
    ``samples`` evenly spread samples of ``traj``; ``inf`` when it is rank-deficient
    (:func:`excited` below ``base.rank``: some base parameter not excited at all)."""
    s = _singular_values(robot, traj, base, samples)
    if len(s) < base.rank or not s[-1] > _rank_tolerance() * s[0]:
        return math.inf
    return float(s[0] / s[-1])


@one_blas_thread()
def excited(robot, traj, base, samples: int = OPTIMISE_SAMPLES) -> int:
    """How many independent combinations of the base parameters ``traj`` excites (the
    base regressor's numerical rank on ``samples`` of its samples, at
    :data:`~._base.RANK_TOLERANCE`): ``base.rank`` when it excites them all."""
    s = _singular_values(robot, traj, base, samples)
    return int(np.sum(s > _rank_tolerance() * s[0])) if len(s) and s[0] > 0 else 0


def _rank_tolerance() -> float:
    from offshore_crane.studies.identification._base import RANK_TOLERANCE

    return RANK_TOLERANCE


def _singular_values(robot, traj, base, samples: int) -> np.ndarray:
    """The base regressor's singular values (columns scaled to unit norm) on ``samples``
    evenly spread samples of ``traj``, on the actuators the robot has."""
    from offshore_crane.studies.identification._regressor import actuator_rows, regressor

    k = np.unique(np.linspace(0, len(traj.t) - 1, min(samples, len(traj.t))).astype(int))
    W = base.base_regressor(regressor(robot, traj.q[k], traj.qd[k], traj.qdd[k]).Y)
    W = W[:, actuator_rows(robot)].reshape(-1, W.shape[-1])
    norms = np.linalg.norm(W, axis=0)
    return np.linalg.svd(W / np.where(norms > 0, norms, 1.0), compute_uv=False)


def within_limits(robot, traj, gravity) -> bool:
    """Every sample inside the workspace (strokes, U-joints, sphere heights, arm limits)
    and every actuator's push, pull and speed within the description's capacities (the
    sizing envelope's utilisations of the nominal robot's inverse dynamics, ≤ 1)."""
    from offshore_crane.dynamics import inverse_dynamics
    from offshore_crane.errors import OffshoreCraneError
    from offshore_crane.robot.kinematics import check_workspace
    from offshore_crane.studies.sizing import CAPACITIES, envelope

    try:
        check_workspace(robot, traj.q, traj.t)
        X = inverse_dynamics(robot, traj.q, traj.qd, traj.qdd, gravity=gravity)
    except OffshoreCraneError:
        return False
    util = envelope(robot, traj.t, traj.q, traj.qd, X).utilisation
    cols = [CAPACITIES.index(c) for c in ("push", "pull", "speed")]
    return bool(np.nan_to_num(util[:, cols], nan=0.0).max() <= 1.0)


@one_blas_thread()
def optimise_excitation(robot, base, duration: float, rate: float = 100.0,
                        harmonics: int = 10, period: float = 10.0, seeds=range(4),
                        iterations: int = 60, gravity=None):
    """An excitation whose base regressor is well conditioned, inside every limit
    (:func:`within_limits`): the best of :func:`fourier_excitation`'s seeds, then its nine
    coordinates' amplitudes scaled by factors ``exp(s_j)`` optimised with SciPy's
    Nelder–Mead on ``log cond`` (an excitation out of limits scores inf).

    Returns:
        ``(trajectory, condition)``.

    Raises:
        InputError: no seed gives an excitation inside the limits.
    """
    from offshore_crane import progress
    from offshore_crane.conventions import GRAVITY

    g = GRAVITY if gravity is None else gravity
    seeds = list(seeds)
    with progress.bar(len(seeds) + iterations, "evaluation", "excite") as shown:
        return _optimise(robot, base, duration, rate, harmonics, period, seeds, iterations,
                         g, shown)


def _optimise(robot, base, duration, rate, harmonics, period, seeds, iterations, g, shown):
    """:func:`optimise_excitation`'s work, each evaluation counted on ``shown``."""
    from scipy.optimize import minimize

    from offshore_crane.errors import InputError
    from offshore_crane.motion.trajectories import Trajectory

    best = None
    for seed in seeds:
        traj = fourier_excitation(robot, duration, rate, harmonics, period, seed, speed=1.0)
        shown.update()
        if not within_limits(robot, traj, g):
            continue
        c = excitation_condition(robot, traj, base)
        if best is None or c < best[1]:
            best = (traj, c)
    if best is None:
        raise InputError("optimise_excitation: no seed's excitation stays within the "
                         "robot's limits and capacities: lower the harmonics or lengthen "
                         "the period", name="seeds")
    f0 = best[0].source

    def scaled(s):
        f = Fourier(f0.centre, f0.a * np.exp(s)[:, None], f0.b * np.exp(s)[:, None],
                    f0.period)
        return Trajectory(best[0].name + ", optimised", best[0].t, *f(best[0].t), source=f)

    def cost(s):
        shown.update()
        traj = scaled(s)
        if not within_limits(robot, traj, g):
            return math.inf
        return math.log(excitation_condition(robot, traj, base))

    out = minimize(cost, np.zeros(9), method="Nelder-Mead",
                   options={"maxfev": iterations})
    s = out.x if math.isfinite(out.fun) and out.fun < math.log(best[1]) else np.zeros(9)
    traj = scaled(s)
    return traj, excitation_condition(robot, traj, base)
