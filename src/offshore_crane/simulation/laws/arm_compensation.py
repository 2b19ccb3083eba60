"""Arm motion compensation on line: computed torque whose arm reference is solved at
every evaluation from the *measured* platform, so that the crane tip stays over its aim
while the platform reproduces the ship (docs/simulation.md, "Motion compensation on
line"; the reference computed beforehand is :mod:`offshore_crane.simulation.compensation`).

The aim is where the tip would be on a still ship: the platform at home, the arm at the
reference's pose (the crane operation), its horizontal position ``a(t)`` with its rate
and acceleration formed once on the stage grid; with a moving target
(``Controller(target=deck)``, ``deck(t) -> (x, v, a)`` each ``(n, 3)``, ship-to-ship
transfer) it moves with the deck. At each evaluation, from the measured platform
``q1..q6, q̇1..q̇6`` (the sensors' delay and noise are the measurement's) and the
reference's slider ``q9``:

- the arm's three joints put the tip's horizontal position at ``a``, as near the
  operation's pose ``q_op`` as they can: the offline solver's Newton step
  ``q ← q_op + J⁺ (e − J (q_op − q))`` (``J`` the 2 × 3 horizontal Jacobian of q7..q9,
  ``J⁺ = Jᵀ (J Jᵀ)⁻¹``, ``e`` the tip's miss) from the last solution, to 1e-12 m;
- their rates make the tip's horizontal velocity ``ȧ``: the operation's rates plus the
  least change, ``q̇ = q̇_op + J⁺ (ȧ − v_op)`` (``v_op`` the tip's velocity with the arm at
  the operation's rates);
- their accelerations make its horizontal acceleration ``ä`` with the platform at the
  reference's acceleration: ``q̈ = q̈_op + J⁺ (ä − a_op)``.

The horizontal rows are exact; along the redundant direction the rates are the
operation's (the redundancy's drift, ``ṅ · (q − q_op)`` with ``n`` the null direction, is
left out: it moves the joints, not the tip, to first order). The arm then tracks this
reference by computed torque. With an exact model and no delay the tip stays on the aim
to the tracking error's order. Unlike the offline solver, joint limits are not clipped
(the plant's workspace check stops a run that leaves them); where Newton does not
converge in :data:`ITERATIONS` (the aim out of the arm's reach) the reference keeps the
last iterate, and the tip's departure shows in the record.
"""

from __future__ import annotations

import numpy as np

from offshore_crane.simulation.templates import IQ, IQD, arm_tip, ct_command
from offshore_crane.simulation.laws import computed_torque
from offshore_crane.simulation.laws._registry import no_state, register
from offshore_crane.simulation.laws.computed_torque import ComputedTorque

#: Newton's tolerance on the tip's horizontal position [m] and its iteration cap (from
#: the last solution, one control period earlier, two iterations reach it).
TOLERANCE, ITERATIONS = 1e-12, 30


def columns(L, P, qt, J):
    """``J`` (2, 3): the tip's horizontal velocity per unit rate of q7, q8, q9 at ``qt``."""
    unit, zero, out = L[10], L[11], L[7]
    for c in range(3):
        unit[6 + c] = 1.0
        arm_tip(P, qt, unit, zero, out)
        unit[6 + c] = 0.0
        J[0, c] = out[3]
        J[1, c] = out[4]


def lift(J, r0, r1, x):
    """``x += Jᵀ (J Jᵀ)⁻¹ (r0, r1)``: the least change of the arm's joints that moves
    the tip by ``(r0, r1)`` to first order (the 2 × 2 inverse written out)."""
    a = J[0, 0] * J[0, 0] + J[0, 1] * J[0, 1] + J[0, 2] * J[0, 2]
    b = J[0, 0] * J[1, 0] + J[0, 1] * J[1, 1] + J[0, 2] * J[1, 2]
    c = J[1, 0] * J[1, 0] + J[1, 1] * J[1, 1] + J[1, 2] * J[1, 2]
    det = a * c - b * b
    w0, w1 = (c * r0 - b * r1) / det, (a * r1 - b * r0) / det
    for k in range(3):
        x[6 + k] += J[0, k] * w0 + J[1, k] * w1


def aim_arm(L, P, i, y, rq, rqd, rqdd):
    """The arm's reference q7..q9 with their rates and accelerations written into ``rq``,
    ``rqd``, ``rqdd`` (which hold the operation's on entry) at stage point ``i`` from the
    measured platform in ``y``."""
    aim, qt, qdt, qddt, out, J, last = L[3], L[4], L[5], L[6], L[7], L[8], L[9]
    zero, tol, iterations = L[11], L[15][0], int(L[15][1])
    for j in range(6):
        qt[j] = y[IQ + j]
        qdt[j] = y[IQD + j]
        qddt[j] = rqdd[j]
    for k in range(3):
        qt[6 + k] = last[k]
    for _ in range(iterations):
        arm_tip(P, qt, zero, zero, out)
        e0, e1 = aim[i, 0] - out[0], aim[i, 1] - out[1]
        if abs(e0) <= tol and abs(e1) <= tol:
            break
        columns(L, P, qt, J)
        # the step of the offline solver: q_op + J⁺ (e − J (q_op − q))
        d0, d1 = e0, e1
        for k in range(3):
            d = rq[6 + k] - qt[6 + k]
            d0 -= J[0, k] * d
            d1 -= J[1, k] * d
            qt[6 + k] = rq[6 + k]
        lift(J, d0, d1, qt)
        if not (np.isfinite(qt[6]) and np.isfinite(qt[7]) and np.isfinite(qt[8])):
            break
    columns(L, P, qt, J)
    for k in range(3):                  # the operation's rates, then the least change
        qdt[6 + k] = rqd[6 + k]
    arm_tip(P, qt, qdt, zero, out)
    lift(J, aim[i, 2] - out[3], aim[i, 3] - out[4], qdt)
    for k in range(3):
        qddt[6 + k] = rqdd[6 + k]
    arm_tip(P, qt, qdt, qddt, out)
    lift(J, aim[i, 4] - out[6], aim[i, 5] - out[7], qddt)
    for k in range(3):
        last[k] = qt[6 + k]
        rq[6 + k] = qt[6 + k]
        rqd[6 + k] = qdt[6 + k]
        rqdd[6 + k] = qddt[6 + k]


def command(L, P, i, t, y, n_p, qr, qdr, qddr, X):
    """Computed torque on the reference with the arm solved on line (``L``: kp, kd,
    scratch (9,), the aim (n_stages, 6), work arrays, the last solution, three (9,)
    copies of the reference, Newton's tolerance and iteration cap)."""
    rq, rqd, rqdd = L[12], L[13], L[14]
    for j in range(9):
        rq[j] = qr[j]
        rqd[j] = qdr[j]
        rqdd[j] = qddr[j]
    aim_arm(L, P, i, y, rq, rqd, rqdd)
    ct_command(L, P, i, t, y, n_p, rq, rqd, rqdd, X)


@register
class ArmCompensation(ComputedTorque):
    name = "arm-compensation"
    reference_once = True
    code = None
    plants = ("hanging", "elastic")
    refusal = ("it holds a hanging payload's aim against the platform's motion: give the "
               "payload a cable (payload.cable_length > 0)")

    def __init__(self, controller, plant):
        from offshore_crane.simulation.compensation import check_compensable

        super().__init__(controller, plant)
        check_compensable(plant.model)

    def start(self, q0, qd0):
        """The arm where the law puts it at ``t0`` (the offline solver on the platform's
        start; its rates the operation's plus the least change that gives the tip the
        aim's velocity): the run starts on the aim, without a transient."""
        from offshore_crane.dynamics import backends
        from offshore_crane.dynamics.constants import cable_arrays
        from offshore_crane.dynamics.cable.tip import tip_positions
        from offshore_crane.robot.kinematics.workspace import limits_of
        from offshore_crane.simulation.compensation import solve_arm

        model, aim = self.plant.model, self._aim()
        q = np.array(q0, dtype=float)
        limits = limits_of(model.hybrid).arm[:3]
        q[6:9] = solve_arm(model, q[None], q[None, 6:9], aim[:1, :2], limits)[0][0, 6:9]
        cols = backends.NUMPY.tip_jacobian(cable_arrays(model).kane, q[:, None])[1]
        J = np.array([[float(np.asarray(c[r]).reshape(-1)[0]) for c in cols]
                      for r in range(2)])
        qd = np.array(qd0, dtype=float)
        v = tip_positions(model, q[None], qd[None])[1][0]
        qd[6:9] += J.T @ np.linalg.solve(J @ J.T, aim[0, 2:4] - v[:2])
        return q, qd

    def _aim(self) -> np.ndarray:
        """``(n_stages, 6)``: the aim's horizontal position, velocity and acceleration at
        every stage time [m, m/s, m/s²] (the still-ship tip, moved with the target),
        formed once."""
        if getattr(self, "_aim_grid", None) is not None:
            return self._aim_grid
        if self.grid is None:
            raise RuntimeError("the arm compensation's aim needs the run's stage grid "
                               "(offshore_crane.simulation.runs.prepare sets it)")
        from offshore_crane.simulation.compensation import still_tip

        tt, qr, qdr, qddr = self.grid
        p, v, a = still_tip(self.plant.model, qr, qdr, qddr)
        deck = self.controller.target
        if deck is not None:
            from offshore_crane.validation import as_samples

            x, xd, xdd = (as_samples("target", w, width=3)[0] for w in deck(tt))
            if not len(x) == len(xd) == len(xdd) == len(tt):
                from offshore_crane.errors import InputError

                raise InputError(f"target(t) must give (x, v, a) of {len(tt)} rows each "
                                 "for t (n,), the deck's displacement [m, m/s, m/s²]",
                                 name="target")
            p, v, a = p + x, v + xd, a + xdd
        self._aim_grid = np.ascontiguousarray(np.column_stack([p[:, :2], v[:, :2],
                                                               a[:, :2]]))
        #: ``(n_stages, 3)``: the aim's height, its rate and acceleration [m, m/s, m/s²].
        self.vertical = np.ascontiguousarray(np.column_stack([p[:, 2], v[:, 2], a[:, 2]]))
        return self._aim_grid

    def params(self) -> tuple:
        aim = self._aim()
        qr = self.grid[1]
        return (self.kp, self.kd, np.zeros(9), aim, np.zeros(9), np.zeros(9), np.zeros(9),
                np.zeros(9), np.zeros((2, 3)), np.array(qr[0, 6:9], dtype=float),
                np.zeros(9), np.zeros(9), np.zeros(9), np.zeros(9), np.zeros(9),
                np.array([TOLERANCE, ITERATIONS], dtype=float))

    def templates(self) -> dict:
        return {"command": command, "law_rate": no_state, "aim_arm": aim_arm,
                "columns": columns, "lift": lift, "ct_command": computed_torque.command}
