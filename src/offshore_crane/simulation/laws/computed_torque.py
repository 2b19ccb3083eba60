"""Computed torque: ``X = ID_model(q, q̇, q̈_ref + Kd (q̇_ref − q̇) + Kp (q_ref − q))`` at
the measured state, with the controller's own model of the plant (with a hanging load the
model's inverse dynamics reads the sway; on an elastic cable the pull measured at the
tip). With an exact model the tracking error obeys ``ë + Kd ė + Kp e = 0`` in each
coordinate. Gains per coordinate q1..q9: ``kp`` [1/s²], ``kd`` [1/s]."""

from __future__ import annotations

import numpy as np

from offshore_crane.simulation.templates import IQ, IQD, inverse
from offshore_crane.simulation.laws import codes
from offshore_crane.simulation.laws._registry import Law, no_state, register


def command(L, P, i, t, y, n_p, qr, qdr, qddr, X):
    """X of the law at ``y`` (``L``: kp, kd, a scratch (9,))."""
    kp, kd, cmd = L[0], L[1], L[2]
    for j in range(9):
        cmd[j] = qddr[j] + kd[j] * (qdr[j] - y[IQD + j]) + kp[j] * (qr[j] - y[IQ + j])
    inverse(P, i, y, cmd, X)



@register
class ComputedTorque(Law):
    name = "computed-torque"
    code = codes.COMPUTED_TORQUE
    ct_gains = True

    def params(self) -> tuple:
        return (self.kp, self.kd, np.zeros(9))

    def templates(self) -> dict:
        return {"command": command, "law_rate": no_state}
