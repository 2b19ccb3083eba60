"""Arm and winch motion compensation on line: the arm held as
:mod:`offshore_crane.simulation.laws.arm_compensation` holds it (the tip over its
still-ship aim, or a moving target), and the commanded winch (the elastic plant with
``actuators.winch.reflected_mass`` > 0) holding the payload's height: its length's
reference is the offline arm + winch compensation's ``L_r = L0 + z_tip − z_aim``
(:mod:`offshore_crane.simulation.compensation`; ``L0`` the model's cable length,
``z_aim`` the aim's height, moved with the target), formed on line from the tip's
height, rate and acceleration with the *measured* platform and the arm on its solved
reference, and its line pull is the winch's drive towards it (the plant's ``winch_to``:
``Fw = T − m_w (L̈_r + kd ė + kp e)`` from the measured tension). The robot's 9 forces are
the arm compensation's computed torque."""

from __future__ import annotations

import numpy as np

from offshore_crane.simulation.templates import arm_command, arm_tip, winch_to
from offshore_crane.simulation.laws import arm_compensation as arm
from offshore_crane.simulation.laws import computed_torque
from offshore_crane.simulation.laws._registry import no_state, register


def command(L, P, i, t, y, n_p, qr, qdr, qddr, X):
    """The arm compensation's command (:func:`~.arm_compensation.command`) and the
    winch's pull towards ``L0 + z_tip − z_aim`` (``L[16]``: the aim's height, rate and
    acceleration at every stage; ``L[17][0]``: ``L0`` [m])."""
    arm_command(L, P, i, t, y, n_p, qr, qdr, qddr, X)
    qt, qdt, qddt, out, rq, rqd, rqdd = L[4], L[5], L[6], L[7], L[12], L[13], L[14]
    for k in range(3):                  # the arm on its solved reference
        qt[6 + k] = rq[6 + k]
        qdt[6 + k] = rqd[6 + k]
        qddt[6 + k] = rqdd[6 + k]
    arm_tip(P, qt, qdt, qddt, out)
    v = L[16]
    winch_to(P, i, y, L[17][0] + out[2] - v[i, 0], out[5] - v[i, 1], out[8] - v[i, 2], X)


@register
class ArmWinchCompensation(arm.ArmCompensation):
    name = "arm-winch-compensation"
    plants = ("elastic",)
    refusal = ("it commands the winch's line pull: give the cable its EA ([cable] ea) "
               "and the winch its reflected mass (actuators.winch.reflected_mass)")

    def __init__(self, controller, plant):
        from offshore_crane.errors import InputError

        super().__init__(controller, plant)
        if plant.nx < 10:
            raise InputError("control law 'arm-winch-compensation' commands the winch's "
                             "line pull: give the winch its reflected mass "
                             "(actuators.winch.reflected_mass > 0)",
                             name="actuators.winch.reflected_mass")

    def winch_start(self, q0, qd0):
        """The winch on its reference at the start, ``L0 + z_tip − z_aim`` and its rate
        (the tip at ``(q0, q̇0)``, which :meth:`start` puts on the aim): no transient."""
        from offshore_crane.dynamics.cable.tip import tip_positions

        self._aim()
        p, v = (x[0] for x in tip_positions(self.plant.model, np.asarray(q0)[None],
                                            np.asarray(qd0)[None]))
        L0 = self.plant.model.hybrid.cable_length
        return L0 + p[2] - self.vertical[0, 0], v[2] - self.vertical[0, 1]

    def params(self) -> tuple:
        base = super().params()
        return (*base, self.vertical,
                np.array([self.plant.model.hybrid.cable_length], dtype=float))

    def templates(self) -> dict:
        return {"command": command, "law_rate": no_state, "arm_command": arm.command,
                "aim_arm": arm.aim_arm, "columns": arm.columns, "lift": arm.lift,
                "ct_command": computed_torque.command}
