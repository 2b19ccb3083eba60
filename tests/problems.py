"""Reference problems shared by the tests: seeded random states inside the workspace, a
robot held at home, and a perturbed "true" robot for identification."""

from __future__ import annotations

import numpy as np

from offshore_crane.robot.kinematics import legs

#: Sampling box of the random states [m, rad]: Table 1's range with margins.
Q_LOW = np.array([-0.06, -0.06, 0.44, -0.45, -0.45, -0.45, -np.pi, -1.9, -0.19])
Q_HIGH = np.array([0.06, 0.06, 0.56, 0.45, 0.45, 0.45, np.pi, 1.9, 0.19])


def random_states(robot, n: int, seed: int, speed: float = 1.0, accel: float = 5.0):
    """``n`` random (q, qd, qdd) ``(n, 9)`` with every leg inside its stroke.

    q is uniform in [Q_LOW, Q_HIGH] (rejection-sampled on the leg strokes), qd uniform in
    ±speed [m/s, rad/s], qdd uniform in ±accel [m/s², rad/s²].
    """
    rng = np.random.default_rng(seed)
    stroke = robot.hybrid.stroke
    kept = []
    while sum(len(k) for k in kept) < n:
        q = rng.uniform(Q_LOW, Q_HIGH, size=(2 * n, 9))
        length = legs(robot, q).length
        ok = np.all((length > stroke[:, 0]) & (length < stroke[:, 1]), axis=1)
        kept.append(q[ok])
    q = np.concatenate(kept)[:n]
    qd = rng.uniform(-speed, speed, size=q.shape)
    qdd = rng.uniform(-accel, accel, size=q.shape)
    return q, qd, qdd


def held_at_home(robot, duration: float, rate: float):
    """The robot held at home for ``duration`` [s] at ``rate`` [Hz] (a frozen crane):
    ``t (N,), q, qd, qdd (N, 9)`` with q3 the home height, everything else zero."""
    from offshore_crane.motion.trajectories import time_grid

    t = time_grid(duration, rate)
    q = np.zeros((len(t), 9))
    q[:, 2] = robot.home_height
    return t, q, np.zeros_like(q), np.zeros_like(q)


def true_robot(nominal, fraction: float = 0.2, seed: int = 0):
    """The lab robot with every body's mass, CoM and principal inertias perturbed by up to
    ``fraction`` (the CoM by that share of its largest coordinate, at least 1 cm), each
    inertia kept physically consistent (the triangle inequalities; redrawn otherwise)."""
    rng = np.random.default_rng(seed)
    s = nominal.spec
    bodies = {"platform": s.platform, "legs.lower": s.lower[0], "legs.upper": s.upper[0]}
    for name in ("column", "link1", "link2", "slider"):
        v = s.arm[name]
        bodies[f"arm.{name}"] = v.body if hasattr(v, "body") else next(
            x for x in v if hasattr(x, "mass"))
    out = {}
    for name, b in bodies.items():
        out[f"{name}.mass"] = b.mass * (1.0 + rng.uniform(-fraction, fraction))
        reach = max(np.abs(b.com).max(), 0.01)
        out[f"{name}.com"] = list(b.com + rng.uniform(-fraction, fraction, 3) * reach)
        while True:
            J = np.diag(b.inertia) * (1.0 + rng.uniform(-fraction, fraction, 3))
            if J[0] + J[1] >= J[2] and J[1] + J[2] >= J[0] and J[0] + J[2] >= J[1]:
                break
        out[f"{name}.inertia"] = dict(ixx=J[0], iyy=J[1], izz=J[2], ixy=0.0, ixz=0.0,
                                      iyz=0.0)
    from offshore_crane import load_robot

    return load_robot(overrides=out)


def assert_cable_paths_agree(kane, pinocchio, sway: float, rel: float) -> None:
    """Kane's and Pinocchio's hanging-load results (``dynamics.cable.inverse_dynamics``)
    agree: the sway angles to ``sway`` [rad]; X, the cable's pull on the tip, and the
    tension (the winch's line pull) to ``rel`` of their largest magnitudes."""
    assert np.abs(kane.sway - pinocchio.sway).max() <= sway
    for name in ("X", "force_tip", "tension"):
        k, p = getattr(kane, name), getattr(pinocchio, name)
        assert np.abs(k - p).max() <= rel * np.abs(p).max(), name


def computed_torque_law(robot):
    """Computed torque written in Python on ``robot``'s model without its hanging load
    (the load's forces are the law's to meet, not the model's), at the default gains:
    ``law(t, q, qd, q_ref, qd_ref, qdd_ref) -> X (9,)`` [N·m, N]."""
    import offshore_crane as oc

    kp, kd = oc.Controller().gains
    model = robot.without_hanging_payload()

    def law(t, q, qd, q_ref, qd_ref, qdd_ref):
        return oc.inverse_dynamics(model, q, qd, qdd_ref + kd * (qd_ref - qd)
                                   + kp * (q_ref - q))
    return law


def simulated_on_scene(path, law, seconds: float, period: float):
    """``simulate``'s run (``simulate_elastic`` on an elastic cable) of the Python
    ``law`` sampled every ``period`` [s] for ``seconds`` on the scene file ``path``'s
    inputs, set up as ``simulate --scene`` sets them (``scenes.plant_options``, the
    instruments, step, gravity and saturation): ``(result, robot)``."""
    import offshore_crane as oc
    from offshore_crane import scenes
    from offshore_crane.simulation.elastic import simulate_elastic

    sc = scenes.load_scene(path)
    robot = scenes.load_robot(sc)
    traj, elastic, swing = scenes.plant_options(sc, robot, scenes.load_trajectory(sc, robot))
    control = oc.Controller(function=law, rate=1 / period,
                            saturation=scenes.controller(sc, robot).saturation)
    run = simulate_elastic if elastic is not None else oc.simulate
    return run(robot, seconds, traj.reference, controller=control, gravity=sc.gravity,
               step=sc.control.get("step", 1e-3), t0=float(traj.t[0]),
               **(elastic or swing), **scenes.instruments(sc)), robot
