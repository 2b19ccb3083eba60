"""The Gymnasium environment of a scene's crane (:class:`CraneLift`), on the simulation
you step (:class:`~offshore_crane.simulation.stepper.Stepper`)."""

from __future__ import annotations

import gymnasium
import numpy as np

from offshore_crane.errors import InputError


class CraneLift(gymnasium.Env):
    """A scene's crane under an agent's control: one :meth:`step` a control period, the
    action held over it.

    Args:
        scene: A scene file's path or a :class:`~offshore_crane.scenes.Scene`: its robot,
            sea and reference, cable and winch, sensors and actuators, capacities
            (``[control] saturation``), as ``offshore-crane simulate --scene`` runs it
            (:func:`offshore_crane.scenes.stepper`).
        control_period: [s] a whole number of the scene's integration steps.
        duration: [s] an episode (default: the scene's, in whole periods): then
            ``truncated``.
        action: ``"forces"``: the actuators' forces (``T1`` ... ``Fl6``, ``Fw`` with a
            commanded winch) [N·m, N], bounded by their capacities; ``"reference"``:
            ``q_ref``, ``q̇_ref`` for the scene's built-in law (an outer loop).
        reward: ``reward(env, observation, action) -> float``; default
            :class:`~offshore_crane.gym.LiftReward` ``()``.
        limits: Terminate on leaving the workspace (``simulate``'s ``limits``).
        render_mode: None only (pictures of a run: ``offshore-crane animate``, the
            record's plots).

    Attributes:
        observation_names, action_names: The channels, in order: the CSV's names with
            their units (:class:`~offshore_crane.simulation.stepper.Stepper`).
        sim: The :class:`~offshore_crane.simulation.stepper.Stepper` (its ``record()``
            is the episode's run, as ``simulate`` returns it).

    ``terminated``: the workspace left, a singular or diverged state, the cable's tension
    below the description's slack criterion; ``truncated``: the duration reached.
    ``info``: ``time`` [s]. A force beyond its capacity is clipped when the scene asks
    for saturation, else refused (:class:`~offshore_crane.errors.InputError`), as are
    actions of the wrong shape, NaN or inf and a step after the episode ended.
    """

    metadata = {"render_modes": []}

    def __init__(self, scene, control_period: float = 0.01, duration: float | None = None,
                 action: str = "forces", reward=None, limits: bool = True,
                 render_mode: str | None = None):
        from offshore_crane.gym._aim import Aim
        from offshore_crane.gym._reward import LiftReward
        from offshore_crane.scenes.stepping import stepper

        if render_mode is not None:
            raise InputError(f"render_mode = {render_mode!r}: the environment draws "
                             "nothing; give None (offshore-crane animate draws a run)",
                             name="render_mode")
        if reward is not None and not callable(reward):
            raise InputError(f"reward = {reward!r}: give a callable reward(env, "
                             "observation, action) -> float", name="reward")
        self.render_mode = None
        self.sim = stepper(scene, control_period=control_period, duration=duration,
                           limits=limits, action=action)
        self.control_period = float(control_period)
        self.observation_names = self.sim.observation_names
        self.action_names = self.sim.action_names
        #: ``(lower, upper)`` ``(nx,)`` the actuators' capacities [N·m, N].
        self.capacities = self.sim.capacities
        lo, hi = self.sim.action_bounds
        self.action_space = gymnasium.spaces.Box(lo, hi, dtype=np.float64)
        n = len(self.observation_names)
        self.observation_space = gymnasium.spaces.Box(-np.inf, np.inf, (n,),
                                                      dtype=np.float64)
        self.reward = reward if reward is not None else LiftReward()
        self._aim = Aim(self.sim)
        self._started = False

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        """The episode from the scene's initial state; ``seed`` seeds the sensors' noise
        (None: the next of the environment's generator, seeded by the last seed given).
        Returns ``(observation, info)``."""
        super().reset(seed=seed)
        noise = int(self.np_random.integers(2 ** 31 - 1))
        observation = self.sim.reset(seed=noise)
        self._started = True
        return observation, {"time": self.sim.time}

    def step(self, action):
        """One control period under ``action`` (held). Returns ``(observation, reward,
        terminated, truncated, info)``."""
        if not self._started:
            raise InputError("step() before reset(): call reset() first", name="reset")
        observation = self.sim.step(action)
        reward = float(self.reward(self, observation, action))
        return (observation, reward, self.sim.terminated, self.sim.truncated,
                {"time": self.sim.time})

    # ------------------------------------------------------------- for a reward
    def payload(self) -> np.ndarray:
        """The payload's position (3,) [m] now, base frame, as simulated (the tip's
        for a welded payload)."""
        return self._aim.payload(2 * self.sim.periods_done * self.sim.control_steps,
                                 self.sim.state)

    def aim(self) -> np.ndarray:
        """Where the scene's reference puts the payload now (3,) [m]
        (:class:`~offshore_crane.gym.LiftReward`)."""
        return self._aim.positions[self.sim.periods_done]

    def applied(self) -> np.ndarray:
        """The forces the actuators applied over the last period, their mean over its
        recorded samples ``(nx,)`` [N·m, N] (zero before a step)."""
        return self.sim.applied()
