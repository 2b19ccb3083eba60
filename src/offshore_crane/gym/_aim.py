"""Where a lift's payload is and where its reference puts it (:class:`Aim`), the two
positions the default reward compares (:class:`~offshore_crane.gym.LiftReward`)."""

from __future__ import annotations

import numpy as np


class Aim:
    """The payload's position now and its aim at every control instant of a stepper's run
    (:class:`~offshore_crane.simulation.stepper.Stepper`), base frame [m].

    The tip is the ``arm_tip`` frame's origin by the cable's formulas (a rigid robot's
    through the same description with a cable hung at the tip, which moves nothing of the
    arm's kinematics): the aim's at every instant at once on NumPy arrays
    (:func:`~offshore_crane.dynamics.cable.tip.tip_positions`), the payload's now by the
    hanging plant's compiled kernels (``arm_tip``). The payload: an elastic cable's is in
    the state, a hanging load's is formed from q and the sway (the hanging plant's
    ``payload`` kernel, as its observation), a welded one is the tip.
    """

    def __init__(self, sim):
        from offshore_crane.dynamics.cable.tip import tip_positions
        from offshore_crane.simulation.plants.hanging import HangingPlant

        plant = sim.plant
        self.kind = plant.name
        robot = plant.robot if plant.name != "rigid" else _with_cable(plant.robot)
        tipped = plant if plant.name == "hanging" else HangingPlant(robot, robot, plant.g)
        self._K, self._P = tipped.kernels(), tipped.params()
        self._out, self._zero = np.empty(9), np.zeros(9)
        self._pay = np.empty(6)
        self._plant = plant
        t, qr, _ = sim.plan()
        tip = tip_positions(robot, qr)[0]
        down = plant.g / np.linalg.norm(plant.g)
        self.positions = tip + np.outer(self._hanging(plant, sim, len(t)), down)

    def tip(self, q: np.ndarray) -> np.ndarray:
        """The tip's position (3,) [m] at ``q`` (9,)."""
        self._K.arm_tip(self._P, np.ascontiguousarray(q, dtype=float), self._zero,
                        self._zero, self._out)
        return self._out[:3].copy()

    def payload(self, i: int, y: np.ndarray) -> np.ndarray:
        """The payload's position (3,) [m] in the plant's state ``y`` at stage point
        ``i``."""
        if self.kind == "elastic":
            return y[9:12].copy()
        if self.kind == "hanging":                  # from the tip, on the model
            self._K.payload(self._P, i, np.ascontiguousarray(y, dtype=float), self._pay)
            return self.tip(y[:9]) + self._pay[3:6]
        return self.tip(y[:9])

    @staticmethod
    def _hanging(plant, sim, n: int) -> np.ndarray:
        """``(n,)`` [m] how far below the tip the load hangs at rest at each control
        instant: 0 welded; the cable's length (a winch's profile there), stretched by
        ``m|g| L / EA`` on an elastic cable."""
        if plant.name == "rigid":
            return np.zeros(n)
        hold = sim.control_steps
        if plant.name == "hanging":
            L = plant.lengths[:, 0]
            return np.full(n, L[0]) if len(L) == 1 else L[::2 * hold][:n]
        L = plant.Lg[::2 * hold, 0][:n]
        return L * (1.0 + plant.m * float(np.linalg.norm(plant.g)) / plant.ea)


def _with_cable(robot):
    """``robot``'s description with a point mass hung at the tip on a cable: the same
    arm, whose ``arm_tip`` the cable's kernels reach (the payload's mass, centre and
    inertia, which move nothing of the arm's kinematics, set as a hanging one needs)."""
    from offshore_crane.robot import load_robot

    over = {"payload.cable_length": 1.0, "payload.mass": 1.0, "payload.com": [0.0] * 3,
            **{f"payload.inertia.{k}": 0.0 for k in ("ixx", "iyy", "izz", "ixy", "ixz",
                                                     "iyz")}}
    return load_robot(robot.description_path, {**robot.overrides, **over})
