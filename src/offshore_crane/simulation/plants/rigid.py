"""The rigid robot: the 9 coordinates q1..q9 and their rates, ``y = (q, q̇)`` (18,);
``M q̈ + h = A X`` (the equations of motion of
:mod:`offshore_crane.simulation.rigid_equations`, in its compiled kernels
:mod:`._rigid_kernels`). Its stops: a singular mass matrix, a
non-finite state, the workspace. Checked against
Pinocchio's constraint dynamics (``tests/simulation/test_simulate.py``) and by its
work–energy balance (its energy recorded at every output sample)."""

from __future__ import annotations

from offshore_crane.simulation.plants._base import Plant
from offshore_crane.stops import StopCause


class RigidPlant(Plant):
    name = "rigid"
    size = 18
    RECORDED = {"energy": 0, "power": 0}
    KERNELS = "offshore_crane.simulation.plants._rigid_kernels"

    def finish(self, res, rec, limits, follow=None):
        from offshore_crane.simulation.record import workspace_stop

        res.energy = rec["energy"][:len(res)]
        res.power = rec["power"][:len(res)]
        found = workspace_stop(self.robot, res, limits,
                               None if follow is None else follow.workspace)
        return None if found is None else (found[0], StopCause.WORKSPACE, found[1])
