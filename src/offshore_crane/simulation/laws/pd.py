"""PD on the actuator coordinates ``s`` (arm joints q7..q9 and the six leg lengths, in the
order of X), with or without gravity compensation:

- ``"pd-gravity"``: ``X = ID_model(q, 0, 0) + Kp (s_ref − s) + Kd (ṡ_ref − ṡ)`` (with a
  load: the model's static forces at the measured sway, or with the measured pull);
- ``"pd"``: ``X = Kp (s_ref − s) + Kd (ṡ_ref − ṡ)``.

Gains per actuator: ``kp`` [N·m/rad, N/m], ``kd`` [N·m·s/rad, N·s/m]."""

from __future__ import annotations

import numpy as np

from offshore_crane.simulation.templates import IQ, IQD, coords, gravity
from offshore_crane.simulation.laws import codes
from offshore_crane.simulation.laws._registry import Law, no_state, register


def command(L, P, i, t, y, n_p, qr, qdr, qddr, X):
    """X of the law at ``y`` (``L``: kp, kd, with gravity (bool), scratch s, ṡ, s_ref,
    ṡ_ref, X_g (9,) each)."""
    kp, kd, grav, s, sd, sr, sdr, Xg = L[0], L[1], L[2], L[3], L[4], L[5], L[6], L[7]
    coords(P, y[IQ:IQ + 9], y[IQD:IQD + 9], s, sd)
    coords(P, qr, qdr, sr, sdr)
    if grav:
        gravity(P, i, y, Xg)
    else:
        for j in range(9):
            Xg[j] = 0.0
    for j in range(9):
        X[j] = Xg[j] + (kp[j] * (sr[j] - s[j]) + kd[j] * (sdr[j] - sd[j]))



@register
class PDGravity(Law):
    name = "pd-gravity"
    code = codes.PD_GRAVITY
    gravity = True

    def params(self) -> tuple:
        return (self.kp, self.kd, self.gravity, *(np.zeros(9) for _ in range(5)))

    def templates(self) -> dict:
        return {"command": command, "law_rate": no_state}


@register
class PD(PDGravity):
    name = "pd"
    code = codes.PD
    gravity = False
