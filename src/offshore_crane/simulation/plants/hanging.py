"""The robot with its payload hanging on a rigid cable (docs/cable.md): 11 coordinates,
q1..q9 and the sway angles φ1, φ2, and their rates, ``y = (q, φ, q̇, φ̇)`` (22,). The
accelerations solve ``M a + h = [A X; −c φ̇] + Jᵀ f`` (M, h from the explicit Kane pass on
the arm chain continued by the sway joints and the payload,
:func:`offshore_crane.dynamics.cable.kernels.accelerations`; ``Jᵀ f`` the payload's air
drag). Its stops: a non-finite or runaway state, a singular mass matrix (the attitude
singularity, cos φ2 = 0), a slack cable, the workspace. Checked against the pendulum's own
equations on the tip's motion (the hanging load's inverse dynamics) and by its energy
(``tests/simulation/test_cable_simulation.py``)."""

from __future__ import annotations

import numpy as np

from offshore_crane.simulation.plants._base import Plant
from offshore_crane.stops import StopCause


class HangingPlant(Plant):
    name = "hanging"
    size = 22
    Q = slice(0, 9)
    QD = slice(11, 20)
    POWER_FROM_RECORD = True
    RECORDED = {"sway": 2, "sway_rate": 2, "sway_acc": 2, "energy": 0, "tension": 0}
    KERNELS = "offshore_crane.simulation.plants._hanging_kernels"

    def __init__(self, robot, model, gravity, hoist=None, tt=None):
        """``hoist``: a winch, ``hoist(t (n,)) -> (L, L̇, L̈)`` [m, m/s, m/s²]
        (:func:`~offshore_crane.dynamics.cable.hoist_profile`), read at the stage times
        ``tt``; None: the cable's fixed length."""
        from offshore_crane.dynamics.cable import cable_robot, hoist_grid
        from offshore_crane.dynamics.constants import cable_arrays
        from offshore_crane.dynamics.runtime import compiled_kernels

        robot = cable_robot(robot)
        model = cable_robot(model) if model is not robot else robot
        super().__init__(robot, model, gravity)
        compiled_kernels()
        self.plant_arrays, self.model_arrays = cable_arrays(robot), cable_arrays(model)
        self.damp_p, self.damp_c = robot.hybrid.sway_damping, model.hybrid.sway_damping
        self.drag_p, self.drag_c = float(robot.hybrid.drag), float(model.hybrid.drag)
        self.hoist = hoist
        #: ``(n_stages, 3)`` the winch's L [m], L̇ [m/s], L̈ [m/s²] at every stage time,
        #: or ``(1, 3)``: the fixed length (the model's: a winch sets both).
        self.lengths = (np.array([[model.hybrid.cable_length, 0.0, 0.0]]) if hoist is None
                        else hoist_grid(hoist, np.asarray(tt, dtype=float)))

    def channels(self, i, y):
        Lh = self.lengths[i if len(self.lengths) > 1 else 0]
        return {"sway": y[9:11].copy(), "sway_rate": y[20:22].copy(),
                "length": float(Lh[0]), "length_rate": float(Lh[1])}

    def pendulum_frequency(self) -> float:
        """ω0 = √(|g| / L) [rad/s] of the model's pendulum (at the winch's starting
        length)."""
        return float(np.sqrt(np.linalg.norm(self.g) / self.lengths[0, 0]))

    def words(self, cause, res):
        return ("the mass matrix became singular (the attitude coordinates at q5 = ±π/2, "
                "or the sway at cos φ2 = 0)")

    def own_names(self) -> tuple[str, ...]:
        return ("phi1_rad", "phi2_rad", "phid1_rad_s", "phid2_rad_s")

    def observed_names(self) -> tuple[str, ...]:
        return (*(f"payload_{a}_m" for a in "xyz"), "tension_N", "L_m")

    def observe(self, i, y, X, out):
        """At the measured q, φ and their rates: the payload's position [m] in the base
        frame (the tip's, ``arm_tip``, and the payload's from it, ``payload``, on the
        compiled kernels); the cable's tension [N] under the forces ``X`` acting (a
        rigid cable's tension is the pendulum's pull at the accelerations they give:
        the plant's ``rhs``, then the record's own formulas, :func:`cable_tension`);
        the cable's length [m] (a winch's profile there, else the fixed length)."""
        K, P = self.kernels(), self.params()
        y = np.ascontiguousarray(y, dtype=float)
        if getattr(self, "_observed", None) is None:      # the kernels' outputs, once
            self._observed = (np.empty(6), np.empty(9), np.empty(22), np.zeros(9),
                              np.zeros(2))
        pay, tip, dy, zero, aux = self._observed
        K.payload(P, i, y, pay)
        K.arm_tip(P, y[:9], y[11:20], zero, tip)
        out[:3] = tip[:3] + pay[3:6]
        K.rhs(P, i, y, np.ascontiguousarray(X, dtype=float), dy, aux)
        hoisted = len(self.lengths) > 1
        kane = np.nan if hoisted else K.tension(P[0], P[1], P[2], P[5], y, dy, P[18])
        rows = (y[None, :9], y[None, 11:20], dy[None, 11:20], y[None, 9:11],
                y[None, 20:22], dy[None, 20:22])
        out[3] = cable_tension(self.robot, *rows, self.lengths[i][None] if hoisted else
                               None, self.g, np.array([kane]))[0]
        out[4] = self.lengths[i if hoisted else 0, 0]

    def finish(self, res, rec, limits, follow=None):
        n = len(res)
        res.sway, res.sway_rate = rec["sway"][:n], rec["sway_rate"][:n]
        res.energy = rec["energy"][:n]
        L = None
        if self.hoist is not None:
            from offshore_crane.dynamics.cable import hoist_grid

            L = hoist_grid(self.hoist, res.t)
            res.info["length"] = L[:, 0]
        return finish(self.robot, res, rec["sway_acc"][:n], self.g, limits, L,
                      rec["tension"][:n], follow)


def finish(robot, res, sway_acc, g, limits, L, tension, follow=None):
    """The hanging plant's record completed (:func:`_finish`) and its first slack-cable
    sample or workspace violation ``(sample, StopCause, words)``, or None (``follow``:
    the driver's :class:`~offshore_crane.simulation.record.Follower`, or None)."""
    from offshore_crane.simulation.record import Follower, finite_rows

    follow = follow or Follower(robot, False, True)
    _finish(robot, res, sway_acc, g, L, tension, follow)
    return _slack_or_workspace(robot, res.truncated(finite_rows(res)), limits,
                               follow.workspace)


def _finish(robot, res, sway_acc, g, L, tension, follow) -> None:
    """The tension and the actuators' power filled in from the recorded samples: on a
    cable of a fixed length the ``tension`` the loop recorded (the Kane pass at each
    sample, :func:`~offshore_crane.simulation.plants._hanging_kernels` ``keep``) and the
    drag's share along the cable; with a winch's ``L`` ``(n, 3)`` [m, m/s, m/s²], the
    hoisted pendulum's pull on NumPy arrays."""
    n = len(res)
    if n == 0:
        return
    res.tension = cable_tension(robot, res.q, res.qd, res.qdd, res.sway, res.sway_rate,
                                sway_acc[:n], L, g, tension)
    res.power = follow.power(res.q, res.qd, res.X)


def cable_tension(robot, q, qd, qdd, sway, sway_rate, sway_acc, L, g, kane) -> np.ndarray:
    """``(n,)`` the rigid cable's tension [N] at ``n`` states ``q, q̇, q̈`` ``(n, 9)``,
    ``φ, φ̇, φ̈`` ``(n, 2)``: with a winch's ``L`` ``(n, 3)`` [m, m/s, m/s²] the hoisted
    pendulum's pull on NumPy arrays; on a cable of a fixed length (``L`` None) the
    Kane pass's ``kane`` ``(n,)`` (the force its store carries across the sway joints:
    the compiled kernels' ``tension``) and the drag's share along the cable."""
    from offshore_crane.dynamics.constants import cable_arrays

    if L is not None:
        from offshore_crane.dynamics.cable.forces import hoisted_pull

        Y = np.hstack([sway, sway_rate, sway_acc])
        return hoisted_pull(robot, cable_arrays(robot).kane, q, qd, qdd, Y, L, g)[2][:, 3]
    T = np.array(kane, dtype=float)
    if robot.hybrid.drag > 0.0:             # the pull along the cable takes the drag too
        from offshore_crane.dynamics.cable.forces import hanging_drag

        f, _, _, _, e = hanging_drag(robot, cable_arrays(robot).kane, q, qd, qdd,
                                     np.hstack([sway, sway_rate]), None)
        T += np.einsum("ij,ij->i", f, e)
    return T


def _slack_or_workspace(robot, res, limits, watch=None):
    """``(sample, StopCause, words)`` of the first slack-cable sample or workspace
    violation, or None."""
    from offshore_crane.simulation.record import workspace_stop

    slack = ~(res.tension > 0.0)
    first = None
    if slack.any():
        k = int(np.argmax(slack))
        first = (k, StopCause.SLACK, f"the cable went slack (tension {res.tension[k]:.4g} "
                 "N: a cable cannot push, the pendulum model no longer holds)")
    outside = workspace_stop(robot, res, limits, watch)
    if outside is not None and (first is None or outside[0] < first[0]):
        first = (outside[0], StopCause.WORKSPACE, outside[1])
    return first
