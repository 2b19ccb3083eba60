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

from offshore_crane.simulation.laws._registry import register
from offshore_crane.simulation.laws.computed_torque import ComputedTorque

#: Centring frequency of the reference shift, as a fraction of ω0 = √(g/L).
CENTRING = 0.1


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

    def shift_acceleration(self, y, z):
        """δ̈ ``(2,)`` [m/s²] of the reference shift (zeros with ζ = 0)."""
        if not self.k:
            return np.zeros(2)
        pay = self.plant.model_payload(y)
        return self.k * pay[:2] - self.wc * self.wc * z[0:2] - 2.0 * self.wc * z[2:4]

    def command(self, i, t, y, z, ref):
        dd = self.shift_acceleration(y, z)
        qref, qdref, qddref = ref[0].copy(), ref[1].copy(), ref[2].copy()
        qref[:2] += z[0:2]
        qdref[:2] += z[2:4]
        qddref[:2] += dd
        return super().command(i, t, y, z, (qref, qdref, qddref))

    def state_rate(self, i, t, y, z, ref, X_cmd, X):
        return np.concatenate([z[2:4], self.shift_acceleration(y, z)])
