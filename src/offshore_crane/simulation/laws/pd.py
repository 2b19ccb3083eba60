"""PD on the actuator coordinates ``s`` (arm joints q7..q9 and the six leg lengths, in the
order of X), with or without gravity compensation:

- ``"pd-gravity"``: ``X = ID_model(q, 0, 0) + Kp (s_ref − s) + Kd (ṡ_ref − ṡ)`` (with a
  load: the model's static forces at the measured sway, or with the measured pull);
- ``"pd"``: ``X = Kp (s_ref − s) + Kd (ṡ_ref − ṡ)``.

Gains per actuator: ``kp`` [N·m/rad, N/m], ``kd`` [N·m·s/rad, N·s/m]."""

from __future__ import annotations

from offshore_crane.simulation.laws import codes
from offshore_crane.simulation.laws._registry import Law, register


@register
class PDGravity(Law):
    name = "pd-gravity"
    code = codes.PD_GRAVITY
    gravity = True

    def errors(self, y, ref):
        """``(s_ref − s, ṡ_ref − ṡ)`` ``(9,)`` each [m, rad, /s]."""
        p = self.plant
        s, sd = p.actuator_coordinates(p.q(y), p.qd(y))
        sr, sdr = p.actuator_coordinates(ref[0], ref[1])
        return sr - s, sdr - sd

    def command(self, i, t, y, z, ref):
        e, ed = self.errors(y, ref)
        X = self.plant.gravity(i, y) if self.gravity else 0.0 * e
        return X + (self.kp * e + self.kd * ed)


@register
class PD(PDGravity):
    name = "pd"
    code = codes.PD
    gravity = False
