"""The robot with its payload on an elastic cable and a winch (docs/cable.md, "Forward
simulation of the real lift"): ``y = (q, p, q̇, v)`` (24,), the payload a point mass at
``p`` (base frame) with three free coordinates; with a commanded winch (a reflected mass
``m_w`` > 0) ``y = (q, p, q̇, v, L, L̇)`` (26,) and the winch's line pull ``Fw`` the 10th
actuator force: ``m_w L̈ = T − Fw`` (the tension pays the line out, the pull hauls it in).

- the cable's tension ``T = EA s / L + c ṡ`` while taut and pulling, else 0 (the formulas
  of :func:`offshore_crane.dynamics.sway.cable_tension`, ``L(t)`` the winch's length);
- the payload: ``m p̈ = m g − T ρ̂ + F_s + F_d`` (``ρ`` from the tip to the payload; the
  sway damping ``F_s`` while the cable pulls and the air's drag ``F_d``, as the elastic
  cable's inverse dynamics, :mod:`offshore_crane.dynamics.cable.elastic`);
- the robot: its equations of motion with the cable's pull ``P = T ρ̂ − F_s`` on it at the
  payload's place, written as actuator forces: ``a = FD(q, q̇, X − ΔX(P))``, with ``ΔX(P)``
  the forces the pull alone asks of the actuators (the Kane pass with the pull,
  :func:`offshore_crane.dynamics.cable.forces.kane_forces`, at zero acceleration less the
  same without pull: exact, the pull enters the equations linearly).

The law's side measures the pull at the tip (a load cell): computed torque is the Kane
pass with that pull at the commanded accelerations. Its stops: a non-finite state, the
workspace. Checked against the elastic cable's inverse dynamics of the simulated motion
(``tests/simulation/test_elastic_simulation.py``)."""

from __future__ import annotations

import math

import numpy as np

from offshore_crane.simulation.plants._base import Plant
from offshore_crane.stops import StopCause


class ElasticPlant(Plant):
    name = "elastic"
    size = 24
    Q = slice(0, 9)
    QD = slice(12, 21)
    POWER_FROM_RECORD = True
    RECORDED = {"payload": 3, "payload_velocity": 3, "tension": 0, "length": 0, "energy": 0,
                "length_rate": 0}
    KERNELS = "offshore_crane.simulation.plants._elastic_kernels"

    def __init__(self, robot, model, gravity, *, ea, damping, lengths, winch_mass=0.0,
                 winch_gains=(0.0, 0.0)):
        """``lengths`` ``(n_stages, 3)``: the winch's L [m], L̇, L̈ at every stage time
        (with a commanded winch, the profile its drive follows). ``winch_mass``: the
        winch's reflected mass [kg] (0: its length is the profile's); ``winch_gains``:
        its drive's ``(kp [1/s²], kd [1/s])`` (the kernels' ``winch``)."""
        from offshore_crane.dynamics import backends
        from offshore_crane.dynamics.cable.grid import cable_robot
        from offshore_crane.dynamics.constants import cable_arrays

        robot = cable_robot(robot)
        super().__init__(robot, robot, gravity)
        self.empty = robot.without_hanging_payload()
        self.m = float(robot.hybrid.cable.mass[-1])
        self.ea, self.damping, self.Lg = float(ea), float(damping), lengths
        self.winch_mass, self.winch_gains = float(winch_mass), tuple(winch_gains)
        self.commanded = self.winch_mass > 0.0
        #: The state's entries and the actuator forces (the winch's state and pull).
        self.size, self.nx = (26, 10) if self.commanded else (24, 9)
        #: The cable's shortest axial period ``2π √(m L_min / EA)`` [s].
        self.axial_period = 2.0 * math.pi * math.sqrt(self.m * float(lengths[:, 0].min())
                                                      / self.ea)
        self._B, self._one = backends.NUMPY, backends.PYTHON
        self._C = cable_arrays(robot).kane
        self._c1, self._c2 = (float(c) for c in robot.hybrid.sway_damping)
        self._drag = float(robot.hybrid.drag)
        self._memo = (None, None, None)

    def _pulled(self, q, qd, qdd, pull, at):
        """X of the robot moving at qdd with ``pull`` [N] on it at ``at`` [m] from the
        tip (the Kane pass)."""
        from offshore_crane.dynamics.cable.forces import kane_forces
        from offshore_crane.robot.kinematics.workspace import Thresholds

        return kane_forces(self.robot, np.zeros(1), q[None], qd[None], qdd[None],
                           np.zeros((1, 6)), self.g, False, False, Thresholds(),
                           P=pull[None], at=at[None])[0][0]

    def kernels(self):
        """The compiled kernels: with a commanded winch, their variant compiled with it
        (:mod:`._elastic_kernels`)."""
        module = super().kernels()
        return module._commanded() if self.commanded else module

    @property
    def variant(self) -> str:
        return "commanded winch" if self.commanded else ""

    def length(self, i, y) -> tuple[float, float]:
        """``(L [m], L̇ [m/s])`` at stage point i: the commanded winch's state, else the
        profile's."""
        if self.commanded:
            return float(y[24]), float(y[25])
        return float(self.Lg[i, 0]), float(self.Lg[i, 1])

    def cable(self, i, y):
        """``(pull on the robot (3,), where it acts (ρ, 3,), tension, the cable's, the
        damping's and the air's force on the payload (3,))`` at stage point i, state y
        (the last one kept: the law and the plant read the same stage)."""
        key = y.tobytes()
        if self._memo[0] == i and self._memo[1] == key:
            return self._memo[2]
        from offshore_crane.dynamics.cable.elastic import drag_forces
        from offshore_crane.dynamics.cable.tip import tip_positions

        pt, vt = (x[0] for x in tip_positions(self.robot, y[None, :9], y[None, 12:21]))
        rho, rhod = y[9:12] - pt, y[21:24] - vt
        L, Ld = (np.array([x]) for x in self.length(i, y))
        with np.errstate(divide="ignore", invalid="ignore"):
            T, s, _ = self._B.cable_tension(tuple(rho[:, None]), tuple(rhod[:, None]),
                                            L, Ld, self.ea, self.damping)
        T = float(T[0]) if (s[0] > 0 and T[0] > 0) else 0.0
        pull = T * rho / np.linalg.norm(rho)
        if T > 0.0 and self._c1 + self._c2 > 0.0:     # the sway damping, carried by the cable
            Rt, w = self._one.tip_motion(self._C, y[:9].tolist(), y[12:21].tolist(),
                                         [0.0] * 9)[:2]
            pull = pull - np.array(self._one.sway_damping_force(
                Rt, w, tuple(rho.tolist()), tuple(rhod.tolist()), self._c1, self._c2),
                dtype=float)
        out = pull, rho, T, drag_forces(y[None, 21:24], self._drag)[0] - pull
        self._memo = (i, key, out)
        return out

    def channels(self, i, y):
        """The payload, the tension, the length and the load cell (the compiled
        kernel's measure)."""
        from offshore_crane.dynamics.cable import elastic_plant as ep

        P, cell = self.params(), np.zeros(ep.CELL)
        L, Ld = self.length(i, y)
        T = ep.measure(P[0], P[1], P[2], P[6], L, Ld, np.ascontiguousarray(y, dtype=float),
                       cell, np.zeros(ep.WORK))
        return {"payload": y[9:12].copy(), "payload_velocity": y[21:24].copy(),
                "tension": T, "length": L, "length_rate": Ld, "pull": cell[0:3].copy(),
                "pull_at": cell[3:6].copy()}

    def observed_names(self) -> tuple[str, ...]:
        return ("tension_N",) + (() if self.commanded else ("L_m",))

    def observe(self, i, y, X, out):
        """The cable's tension [N] at the measured state (the load cell's measure:
        :meth:`channels`' ``tension``) and, when the winch follows a profile, its length
        there [m] (a commanded winch's is in the state)."""
        from offshore_crane.dynamics.cable import elastic_plant as ep

        P = self.params()
        L, Ld = self.length(i, y)
        if getattr(self, "_measured", None) is None:     # the load cell's scratch, once
            self._measured = (np.zeros(ep.CELL), np.zeros(ep.WORK))
        out[0] = ep.measure(P[0], P[1], P[2], P[6], L, Ld,
                            np.ascontiguousarray(y, dtype=float), *self._measured)
        if not self.commanded:
            out[1] = L

    def derivative(self, i, y, X):
        """``(ẏ (24,) or (26,), aux)`` from the vectorised public pieces (the Kane pass
        with the pull, forward dynamics, the tip's kinematics in NumPy): the reference the compiled
        kernels (:mod:`offshore_crane.dynamics.cable.elastic_plant`) are tested against
        (``tests/dynamics/test_elastic_plant.py``); the driver runs the kernels."""
        from offshore_crane.dynamics.forward import forward_dynamics

        pull, at, T, force = self.cable(i, y)
        rest = np.zeros(9)
        shift = (self._pulled(y[:9], y[12:21], rest, pull, at)
                 - self._pulled(y[:9], y[12:21], rest, 0 * pull, at))
        a = forward_dynamics(self.empty, y[:9], y[12:21], X[:9] - shift, self.g)
        a_p = self.g + force / self.m
        L, Ld = self.length(i, y)
        winch = [Ld, (T - X[9]) / self.winch_mass] if self.commanded else []
        return np.concatenate([y[12:21], y[21:24], a, a_p, winch]), {
            "ok": True, "tension": T, "length": L}

    def own_names(self) -> tuple[str, ...]:
        winch = ("L_m", "Ld_m_s") if self.commanded else ()
        return (*(f"payload_{a}_m" for a in "xyz"), *(f"payload_v{a}_m_s" for a in "xyz"),
                *winch)

    def finish(self, res, rec, limits, follow=None):
        from offshore_crane.simulation.record import Follower, workspace_stop

        n = len(res)
        res.tension, res.energy = rec["tension"][:n], rec["energy"][:n]
        res.info.update(payload=rec["payload"][:n], payload_velocity=rec[
            "payload_velocity"][:n], length=rec["length"][:n],
            length_rate=rec["length_rate"][:n])
        if self.commanded:       # the winch's pull apart: X stays the robot's 9 forces
            res.info.update(winch_force=res.X[:, 9].copy(),
                            winch_force_cmd=res.X_cmd[:, 9].copy(),
                            winch_saturated=res.saturated[:, 9].copy(),
                            winch_power=-res.X[:, 9] * res.info["length_rate"])
            res.X, res.X_cmd = res.X[:, :9].copy(), res.X_cmd[:, :9].copy()
            res.saturated = res.saturated[:, :9].copy()
        follow = follow or Follower(self.robot, False, True)
        res.power = follow.power(res.q, res.qd, res.X)
        found = workspace_stop(self.robot, res, limits, follow.workspace)
        return None if found is None else (found[0], StopCause.WORKSPACE, found[1])
