"""No control: ``X = 0`` (a free, unactuated motion; for energy checks)."""

from __future__ import annotations

import numpy as np

from offshore_crane.simulation.laws import codes
from offshore_crane.simulation.laws._registry import Law, register


@register
class NoControl(Law):
    name = "none"
    code = codes.NONE

    def command(self, i, t, y, z, ref):
        return np.zeros(9)
