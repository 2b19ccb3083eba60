"""PID with gravity compensation on the actuator coordinates ``s`` (arm joints and leg
lengths, in the order of X), with anti-windup by back-calculation:

``X = ID_model(q, 0, 0) + Kp e + Kd ė + Ki z``, ``e = s_ref − s``,
``ż = e + (X_applied − X) / (Ki T_t)``,

the integral ``z`` [m·s, rad·s] the law's state (9). While an actuator saturates, the
back-calculation term drives its integral so that the command returns to the limit with
the time constant ``T_t`` (Åström & Hägglund, *Advanced PID Control*, ISA 2006, Sec.
3.5: ``T_t = √(T_i T_d)``, ``T_i = Kp / Ki``, ``T_d = Kd / Kp``, the rule used when
``windup`` is not given). Gains per actuator: ``kp``, ``kd`` as PD; ``ki`` [N·m/(rad·s),
N/(m·s)], by default ``Kp / T_i`` with Ziegler–Nichols' ratio ``T_i = 4 T_d``.

The integral removes the steady error that a model error leaves to PD with gravity
compensation (a payload heavier than the model's: ``docs/simulation.md``).
"""

from __future__ import annotations

import numpy as np

from offshore_crane.simulation.templates import IQ, IQD, coords, pd_command
from offshore_crane.simulation.laws import pd
from offshore_crane.simulation.laws._registry import register
from offshore_crane.simulation.laws.pd import PDGravity

#: Ziegler–Nichols' ratio of the integral to the derivative time, ``T_i = 4 T_d``.
TI_OVER_TD = 4.0


def default_ki(kp: np.ndarray, kd: np.ndarray) -> np.ndarray:
    """``Ki = Kp / T_i`` with ``T_i = 4 T_d = 4 Kd / Kp`` (0 where Kd = 0)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ki = kp * kp / (TI_OVER_TD * kd)
    return np.where(kd > 0.0, ki, 0.0)


def command(L, P, i, t, y, n_p, qr, qdr, qddr, X):
    """PD with gravity compensation plus ``Ki z`` (``L``: PD's, then ki, the
    back-calculation gain 1/(Ki T_t))."""
    pd_command(L, P, i, t, y, n_p, qr, qdr, qddr, X)
    ki = L[8]
    for j in range(9):
        X[j] = X[j] + ki[j] * y[n_p + j]


def law_rate(L, P, i, t, y, n_p, qr, qdr, qddr, Xc, X, dy):
    """``ż = e + (X − X_cmd) / (Ki T_t)`` into ``dy[n_p:n_p + 9]``."""
    s, sd, sr, sdr, back = L[3], L[4], L[5], L[6], L[9]
    coords(P, y[IQ:IQ + 9], y[IQD:IQD + 9], s, sd)
    coords(P, qr, qdr, sr, sdr)
    for j in range(9):
        dy[n_p + j] = (sr[j] - s[j]) + back[j] * (X[j] - Xc[j])


@register
class PID(PDGravity):
    name = "pid"
    code = None
    state_size = 9

    def __init__(self, controller, plant):
        super().__init__(controller, plant)
        ki = controller.integral_gains
        self.ki = default_ki(self.kp, self.kd) if ki is None else ki
        with np.errstate(divide="ignore", invalid="ignore"):
            ti = self.kp / self.ki
            td = self.kd / self.kp
            tt = np.sqrt(ti * td) if controller.windup is None else np.full(9,
                                                                            controller.windup)
            self.back = np.where((self.ki > 0.0) & (tt > 0.0), 1.0 / (self.ki * tt), 0.0)

    def params(self) -> tuple:
        return (*super().params(), self.ki, self.back)

    def templates(self) -> dict:
        return {"command": command, "law_rate": law_rate, "pd_command": pd.command}
