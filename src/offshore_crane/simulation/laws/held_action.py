"""The actions of a controller outside the simulation: the forces a stepper was given
(:class:`~offshore_crane.simulation.stepper.Stepper`), applied at each control instant
and held over the period like any sampled law's (the sensors, rate limit, lag and
capacities between them as for every law). Not selectable by name: a stepper binds it."""

from __future__ import annotations

import numpy as np

from offshore_crane.simulation.laws._registry import Law, no_state, register


def command(L, P, i, t, y, n_p, qr, qdr, qddr, X):
    """X of the law: the action ``L[0]`` (as many forces as the plant takes)."""
    a = L[0]
    for j in range(a.shape[0]):
        X[j] = a[j]


@register
class HeldAction(Law):
    name = "held-action"
    selectable = False

    def __init__(self, controller, plant):
        super().__init__(controller, plant)
        #: The action the next control instant applies ``(plant.nx,)`` [N·m, N].
        self.action = np.zeros(plant.nx)

    def params(self) -> tuple:
        return (self.action,)

    def templates(self) -> dict:
        return {"command": command, "law_rate": no_state}
