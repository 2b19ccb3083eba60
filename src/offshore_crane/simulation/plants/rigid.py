"""The rigid robot: the 9 coordinates q1..q9 and their rates, ``y = (q, q̇)`` (18,);
``M q̈ + h = A X`` (:func:`offshore_crane.dynamics.forward.forward_dynamics`, its
one-sample path). Its stops: a non-finite state, the workspace. Checked against
Pinocchio's constraint dynamics (``tests/simulation/test_simulate.py``) and by its
work–energy balance."""

from __future__ import annotations

import numpy as np

from offshore_crane.simulation.plants._base import Plant
from offshore_crane.stops import StopCause


class RigidPlant(Plant):
    name = "rigid"
    size = 18
    KERNELS = "offshore_crane.simulation.plants._rigid_kernels"

    def __init__(self, robot, model, gravity):
        from offshore_crane.dynamics.constants import robot_arrays

        super().__init__(robot, model, gravity)
        self._model = robot_arrays(model).kane
        self._gt = tuple(float(x) for x in gravity)
        na = self._model.n_arm
        self._w = (np.zeros(9), np.empty((6, 6)), np.zeros((9, 9)),
                   np.empty((max(na, 1), 27)), np.empty((9, 3)), np.empty((9, 3)),
                   np.empty((9, 3)), np.zeros((7, 6)), np.empty((1, 3)), np.empty((6, 6)),
                   np.empty(6), np.empty(6), np.empty((6, 13)), np.zeros(9), np.empty(9),
                   np.empty(9), np.empty(9), np.empty(9), np.empty(9))

    def derivative(self, i, y, X):
        from offshore_crane.dynamics.forward import forward_dynamics

        from offshore_crane.errors import SingularConfigurationError, WorkspaceError

        q, qd = y[:9].copy(), y[9:].copy()
        try:
            try:
                qdd = forward_dynamics(self.robot, q, qd, X, gravity=self.g)
            except WorkspaceError:       # a stage outside: the record's check stops it
                qdd = forward_dynamics(self.robot, q, qd, X, gravity=self.g, limits=False,
                                       checks=False)
        except SingularConfigurationError:
            return np.concatenate([qd, np.full(9, np.nan)]), {"ok": False}
        return np.concatenate([qd, qdd]), {"ok": True}

    def finish(self, res, rec, limits):
        from offshore_crane.simulation.record import actuator_power, workspace_stop

        res.power = actuator_power(self.robot, res.q, res.qd, res.X)
        found = workspace_stop(self.robot, res, limits)
        return None if found is None else (found[0], StopCause.WORKSPACE, found[1])

    def _law(self, code, q, qd, qdd):
        """The compiled loop's law ``code`` with zero gains at reference ``(q, q̇, q̈)``:
        exactly its inverse dynamics at ``q̈`` (or its gravity compensation)."""
        from offshore_crane.simulation import rk4

        X, zero = np.empty(9), np.zeros(9)
        rk4.law(self._model, self._gt, code, zero, zero, np.ascontiguousarray(q),
                np.ascontiguousarray(qd), np.ascontiguousarray(q), np.ascontiguousarray(qd),
                np.ascontiguousarray(qdd), X, self._w)
        return X

    def inverse(self, i, y, qdd):
        from offshore_crane.simulation.laws import codes

        return self._law(codes.COMPUTED_TORQUE, y[:9], y[9:], qdd)

    def gravity(self, i, y):
        from offshore_crane.simulation.laws import codes

        return self._law(codes.PD_GRAVITY, y[:9], np.zeros(9), np.zeros(9))
