"""No control: ``X = 0`` (a free, unactuated motion; for energy checks)."""

from __future__ import annotations

from offshore_crane.simulation.laws import codes
from offshore_crane.simulation.laws._registry import Law, no_state, register


def command(L, P, i, t, y, n_p, qr, qdr, qddr, X):
    for j in range(9):
        X[j] = 0.0



@register
class NoControl(Law):
    name = "none"
    code = codes.NONE

    def params(self) -> tuple:
        return (0.0,)

    def templates(self) -> dict:
        return {"command": command, "law_rate": no_state}
