"""The simulation runs whose results are kept bit for bit across the simulation core's
unification (issue 37): every plant (rigid robot, rigid hanging load, elastic cable with a
winch) under every law and option that runs today, on short records.

``python tests/simulation/golden_cases.py OUT.npz`` writes them (done once, from main
025ad9a, before the core moved: ``tests/data/golden_sim_025ad9a.npz``);
``test_golden_simulation.py`` runs the same calls and compares.
"""

from __future__ import annotations

import sys

import numpy as np

import offshore_crane as oc
from offshore_crane.motion.trajectories import table1

#: Arrays kept of every run (those present), every 7th sample.
FIELDS = ("t", "q", "qd", "qdd", "q_ref", "X_cmd", "X", "saturated", "energy", "power",
          "sway", "sway_rate", "tension")
EVERY = 7


def _hold(q_hold):
    def reference(t):
        n = len(np.atleast_1d(t))
        return np.tile(q_hold, (n, 1)), np.zeros((n, 9)), np.zeros((n, 9))
    return reference


def _python_ct(robot):
    """Computed torque written in Python (the Python path of today's simulate)."""
    kp, kd = np.full(9, 400.0), np.full(9, 40.0)

    def law(t, q, qd, qr, qdr, qddr):
        cmd = qddr + kd * (qdr - qd) + kp * (qr - q)
        return oc.inverse_dynamics(robot, q[None], qd[None], cmd[None])[0]
    return law


def _kept(call, *args, **kwargs):
    """The run's result, or what a stopped run kept (its message in ``info["stopped"]``)."""
    from offshore_crane.errors import SimulationError

    try:
        return call(*args, **kwargs)
    except SimulationError as exc:
        exc.result.info = dict(exc.result.info, stopped=str(exc))
        return exc.result


def runs() -> dict:
    """``{case: SimulationResult}``."""
    from offshore_crane.dynamics import cable
    from offshore_crane.simulation.elastic import simulate_elastic

    C = oc.Controller
    robot = oc.load_robot()
    heavy = oc.load_robot(overrides={"payload.mass": 6.0})
    out = {
        "rigid_ct": _kept(oc.simulate, robot, 1.0, table1),
        "rigid_ct_rate_noise_model": _kept(oc.simulate, 
            robot, 1.0, table1, controller=C(rate=250.0, noise_q=1e-5, noise_qd=1e-4,
                                              seed=3, model=heavy)),
        "rigid_ct_out_rate": _kept(oc.simulate, robot, 0.5, table1, rate=200.0,
                                         q0=table1(np.zeros(1))[0][0] + 1e-3),
        "rigid_pd_gravity": _kept(oc.simulate, robot, 0.5, table1, controller=C(law="pd-gravity")),
        "rigid_pd_rate_stops": _kept(oc.simulate, robot, 0.5, table1,
                                      controller=C(law="pd", rate=100.0)),
        "rigid_none": _kept(oc.simulate, robot, 0.3, _hold(robot.home_pose()),
                                  controller=C(law="none"), limits=False),
        "rigid_saturated": _kept(oc.simulate, robot, 0.5, table1, controller=C(
            upper=[5.0, 5.0, 50.0] + [300.0] * 6, lower=[-5.0, -5.0, -50.0] + [-300.0] * 6)),
        "rigid_dop853": _kept(oc.simulate, robot, 0.2, table1, integrator="dop853", rate=100.0),
        "rigid_python": _kept(oc.simulate, robot, 0.3, table1, controller=_python_ct(robot)),
    }
    crane = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 0.5,
                                     "payload.sway_damping": 0.05, "payload.drag_area": 0.3})
    home = _hold(crane.home_pose())
    out |= {
        "swing_ct": _kept(oc.simulate, crane, 1.0, table1, initial=(0.1, -0.05)),
        "swing_anti_sway": _kept(oc.simulate, crane, 1.0, home, controller=C(anti_sway=0.3),
                                       initial=(0.05, 0.02), initial_rate=(0.0, 0.1)),
        "swing_rate_model": _kept(oc.simulate, crane, 0.5, table1,
                                        controller=C(rate=200.0, model=oc.load_robot(
                                            overrides={"payload.mass": 2.2,
                                                       "payload.cable_length": 0.5})),
                                        rate=500.0),
        "swing_none": _kept(oc.simulate, crane, 0.3, home, controller=C(law="none"),
                                  initial=(0.2, 0.0), limits=False),
    }
    flown = oc.load_robot(overrides={"payload.mass": 2.0, "payload.cable_length": 1.0,
                                     "payload.sway_damping": 0.2 * 2.0 * np.sqrt(9.81),
                                     "payload.drag_area": 0.5})
    hoist = cable.hoist_profile([(0.1, 1.0), (0.4, 0.8)])
    out |= {
        "elastic_ct_hoist": _kept(simulate_elastic, flown, 0.5, table1, ea=2e4, damping=3.0,
                                             hoist=hoist, step=1e-3),
        "elastic_ct_rate": _kept(simulate_elastic, flown, 0.3, table1, controller=C(rate=200.0), ea=2e4,
                                            step=5e-4, rate=1000.0,
                                            initial=(0.05, 0.0, -1.0)),
        "elastic_none": _kept(simulate_elastic, flown, 0.2, home, controller=C(law="none"), ea=5e3,
                                         limits=False),
    }
    return out


def arrays(results: dict) -> dict:
    """The arrays kept: ``{"case/field": array}`` (and the elastic payload, length)."""
    out = {}
    for case, res in results.items():
        for f in FIELDS:
            a = getattr(res, f)
            if a is not None:
                out[f"{case}/{f}"] = np.asarray(a)[::EVERY]
        if "stopped" in res.info:
            out[f"{case}/stopped"] = np.array(res.info["stopped"])
        for key in ("payload", "payload_velocity", "length"):
            if key in res.info:
                out[f"{case}/{key}"] = np.asarray(res.info[key])[::EVERY]
    return out


if __name__ == "__main__":
    np.savez_compressed(sys.argv[1], **arrays(runs()))
