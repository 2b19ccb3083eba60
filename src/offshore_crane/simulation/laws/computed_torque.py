"""Computed torque: ``X = ID_model(q, q̇, q̈_ref + Kd (q̇_ref − q̇) + Kp (q_ref − q))`` at
the measured state, with the controller's own model of the plant (with a hanging load the
model's inverse dynamics reads the sway; on an elastic cable the pull measured at the
tip). With an exact model the tracking error obeys ``ë + Kd ė + Kp e = 0`` in each
coordinate. Gains per coordinate q1..q9: ``kp`` [1/s²], ``kd`` [1/s]."""

from __future__ import annotations

from offshore_crane.simulation.laws import codes
from offshore_crane.simulation.laws._registry import Law, register


@register
class ComputedTorque(Law):
    name = "computed-torque"
    code = codes.COMPUTED_TORQUE

    def commanded(self, y, ref):
        """``q̈_ref + Kd (q̇_ref − q̇) + Kp (q_ref − q)`` ``(9,)``."""
        p = self.plant
        return ref[2] + self.kd * (ref[1] - p.qd(y)) + self.kp * (ref[0] - p.q(y))

    def command(self, i, t, y, z, ref):
        return self.plant.inverse(i, y, self.commanded(y, ref))
