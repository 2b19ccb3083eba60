"""Anti-sway: computed torque tracking a reference whose platform position is shifted to
damp the hanging load's swing (docs/cable.md, "Simulation and anti-sway").

Suspension-point velocity feedback, the classic law that damps a pendulum by moving its
pivot along the load's relative velocity (Abdel-Rahman, Nayfeh & Masoud, "Dynamics and
control of cranes: a review", Journal of Vibration and Control 9(7), 2003). For a
pendulum of length L on a pivot accelerated by ``a``, the load's horizontal offset d obeys
``d̈ + ω0² d = −a`` (small sway, ω0 = √(g/L)); with ``a = k ḋ`` it becomes
``d̈ + k ḋ + ω0² d = 0``, a damping ratio ``ζ = k / (2 ω0)``. The law shifts the platform's
horizontal reference by δ (x, y), ``δ̈ = 2 ζ ω0 ḋ − ω_c² δ − 2 ω_c δ̇``, which the
computed-torque loop tracks (its bandwidth, 20 rad/s by default, is well above ω0); the
centring term (ω_c = :data:`CENTRING` ω0, critically damped) brings the platform back to
its reference once the swing has died out. The shift (δ, δ̇) is the law's state (4).
``Controller(anti_sway=ζ)`` selects it.
"""

from __future__ import annotations

import numpy as np

from offshore_crane.simulation.templates import ct_command, payload
from offshore_crane.simulation.laws import computed_torque
from offshore_crane.simulation.laws._registry import register
from offshore_crane.simulation.laws.computed_torque import ComputedTorque

#: Centring frequency of the reference shift, as a fraction of ω0 = √(g/L).
CENTRING = 0.1


def shift(L, P, i, y, n_p, dd):
    """δ̈ ``(2,)`` [m/s²] of the reference shift into ``dd`` at stage point ``i`` (zeros
    with ζ = 0)."""
    k, wc, pay = L[3], L[4], L[5]
    if k == 0.0:
        dd[0] = 0.0
        dd[1] = 0.0
        return
    payload(P, i, y, pay)
    for j in range(2):
        dd[j] = k * pay[j] - wc * wc * y[n_p + j] - 2.0 * wc * y[n_p + 2 + j]


def command(L, P, i, t, y, n_p, qr, qdr, qddr, X):
    """Computed torque on the shifted reference (``L``: kp, kd, scratch (9,), k, ω_c,
    scratch (6,), (2,), (9,) × 3)."""
    dd, rq, rqd, rqdd = L[6], L[7], L[8], L[9]
    shift(L, P, i, y, n_p, dd)
    for j in range(9):
        rq[j] = qr[j]
        rqd[j] = qdr[j]
        rqdd[j] = qddr[j]
    for j in range(2):
        rq[j] += y[n_p + j]
        rqd[j] += y[n_p + 2 + j]
        rqdd[j] += dd[j]
    ct_command(L, P, i, t, y, n_p, rq, rqd, rqdd, X)


def law_rate(L, P, i, t, y, n_p, qr, qdr, qddr, Xc, X, dy):
    """``(δ̇, δ̈)`` into ``dy[n_p:n_p + 4]``."""
    dd = L[6]
    shift(L, P, i, y, n_p, dd)
    dy[n_p] = y[n_p + 2]
    dy[n_p + 1] = y[n_p + 3]
    dy[n_p + 2] = dd[0]
    dy[n_p + 3] = dd[1]


@register
class AntiSway(ComputedTorque):
    name = "anti-sway"
    code = None
    plants = ("hanging",)
    refusal = ("it damps the swing of a payload on a rigid cable (payload.cable_length > 0, "
               "no [cable] ea)")
    state_size = 4

    def __init__(self, controller, plant):
        super().__init__(controller, plant)
        zeta = controller.anti_sway or 0.0
        w0 = plant.pendulum_frequency()
        self.k = 2.0 * zeta * w0 if zeta else 0.0
        self.wc = CENTRING * w0

    def params(self) -> tuple:
        return (self.kp, self.kd, np.zeros(9), float(self.k), float(self.wc), np.zeros(6),
                np.zeros(2), np.zeros(9), np.zeros(9), np.zeros(9))

    def templates(self) -> dict:
        return {"command": command, "law_rate": law_rate, "shift": shift,
                "ct_command": computed_torque.command}
