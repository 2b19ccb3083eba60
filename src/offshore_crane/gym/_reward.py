"""The lift's default reward: the payload's distance from its aim and the actuators'
effort, each on a scale a user reads in SI units (:class:`LiftReward`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class LiftReward:
    """``r = −T (|p − p_aim|² / position_scale² + effort_weight · mean_j (X_j / C_j)²)``
    over a control period of ``T`` [s] (a cost integrated over the period: an episode's
    return does not change with the control period).

    - ``p`` [m]: the payload in the base frame at the period's end, as simulated (not as
      measured): on a cable, the hanging load; without one, the crane's tip (the
      ``arm_tip`` frame, where a welded payload sits).
    - ``p_aim`` [m]: where the reference puts it: the tip under the scene's reference
      ``q_ref`` (the arm's plan, compensated where the scene compensates), the load
      hanging straight down (along g) by the cable's length there (a winch's profile),
      stretched by its static tension ``m|g| L / EA`` on an elastic cable.
    - ``X_j`` [N·m, N]: the forces the actuators applied over the period (after the
      capacities and the lag; their mean over the period's recorded samples), ``C_j``
      [N·m, N] the capacity on their side (an actuator without one counts no effort).

    Args:
        position_scale: [m] a distance from the aim that costs as much as full effort
            with ``effort_weight = 1``.
        effort_weight: [-] the effort's weight against the position's.

    A reward of one's own is any callable ``reward(env, observation, action) -> float``
    given as ``gymnasium.make(..., reward=...)``; it may read ``env.payload()``,
    ``env.aim()`` and ``env.applied()`` as this one does.
    """

    position_scale: float = 0.05
    effort_weight: float = 0.1

    def __post_init__(self):
        from offshore_crane.errors import InputError

        if not (np.isfinite(self.position_scale) and self.position_scale > 0):
            raise InputError(f"position_scale = {self.position_scale!r} m: give a "
                             "positive distance", name="position_scale")
        if not (np.isfinite(self.effort_weight) and self.effort_weight >= 0):
            raise InputError(f"effort_weight = {self.effort_weight!r}: give a finite "
                             "weight >= 0", name="effort_weight")

    def __call__(self, env, observation, action) -> float:
        d = env.payload() - env.aim()
        X, (lo, hi) = env.applied(), env.capacities
        cap = np.where(X < 0.0, -lo, hi)
        share = np.where(np.isfinite(cap) & (cap > 0.0), X / cap, 0.0)
        cost = (d @ d) / self.position_scale ** 2 + self.effort_weight * float(
            np.mean(share * share))
        return -env.control_period * float(cost)
