"""The robot as MJCF at a pose: our state as MuJoCo joint values, the static forces that hold
the pose, and :func:`export`.
"""

from __future__ import annotations

import numpy as np

from offshore_crane.conventions import (ACTUATED_JOINTS, ACTUATORS, ARM_JOINTS, GRAVITY, N_LEGS,
                                        PLATFORM_ANCHORS, PLATFORM_JOINTS, LEG_TIPS)
from offshore_crane.errors import InputError, ModelError
from offshore_crane.outputs.export.mjcf.settings import CABLE_JOINTS, MJCF, TIMESTEP
from offshore_crane.outputs.export.mjcf.tree import mjcf_from_urdf


# --------------------------------------------------------------------------- our state
def _has_cable(robot) -> bool:
    """True when the robot's URDF hangs the payload on a cable; checks that a description
    asking for a cable (``payload.cable_length`` > 0) has one."""
    joints = robot.description.joints
    if all(name in joints for name in CABLE_JOINTS):
        return True
    values = getattr(robot.spec, "values", None) or {}
    length = values.get("payload.cable_length", 0.0)
    if length:
        raise ModelError(f"the description sets payload.cable_length = {length:g} m but its "
                         f"URDF has no joints {', '.join(CABLE_JOINTS)}: update the xacro "
                         "(docs/cable.md) before exporting the hanging load", element="payload")
    return False


def joint_values(robot, q, qd=None, sway=None, sway_rate=None) -> dict:
    """The URDF's joint positions and rates that close the loops at ``q``.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q: ``(N, 9)`` or ``(9,)`` coordinates [m, rad] (``docs/conventions.md``).
        qd: Same shape, rates [m/s, rad/s] (zero if omitted).
        sway: ``(N, 2)`` or ``(2,)`` cable angles (phi1, phi2) [rad] for a robot with a
            hanging load (zero if omitted); refused without one.
        sway_rate: Same shape, [rad/s].

    Returns:
        ``{joint name: (position (N,), rate (N,))}`` for every movable joint of the URDF:
        the platform's six virtual joints and the arm's (from q), the U-joint angles
        θ1, θ2 [rad] and the leg lengths [m] (:func:`offshore_crane.robot.kinematics.legs`), the
        cable joints (from ``sway``).

    Raises:
        InputError: bad shapes or non-finite values; ``sway`` for a robot without cable.
        ModelError: a movable URDF joint this function does not know.
    """
    from offshore_crane.robot.kinematics import legs
    from offshore_crane.validation import as_samples

    q = as_samples("q", q)[0]
    N = len(q)
    qd = np.zeros_like(q) if qd is None else as_samples("qd", qd)[0]
    if len(qd) != N:
        raise InputError(f"qd has {len(qd)} samples, q has {N}: give one rate per sample",
                         name="qd")
    out = {}
    for k, name in enumerate(PLATFORM_JOINTS):
        out[name] = (q[:, k], qd[:, k])
    if robot.hybrid.has_arm:
        for k, name in enumerate(ARM_JOINTS):
            out[name] = (q[:, 6 + k], qd[:, 6 + k])
    L = legs(robot, q, qd)
    for i in range(N_LEGS):
        out[f"leg{i + 1}_u1"] = (L.theta[:, i, 0], L.theta_d[:, i, 0])
        out[f"leg{i + 1}_u2"] = (L.theta[:, i, 1], L.theta_d[:, i, 1])
        out[f"leg{i + 1}_slide"] = (L.length[:, i], L.rate[:, i])
    if _has_cable(robot):
        s = np.zeros((N, 2)) if sway is None else as_samples("sway", sway, width=2)[0]
        sd = np.zeros((N, 2)) if sway_rate is None else as_samples("sway_rate", sway_rate,
                                                                    width=2)[0]
        for name, a in (("sway", s), ("sway_rate", sd)):
            if len(a) != N:
                raise InputError(f"{name} has {len(a)} samples, q has {N}", name=name)
        for k, name in enumerate(CABLE_JOINTS):
            out[name] = (s[:, k], sd[:, k])
    elif sway is not None or sway_rate is not None:
        raise InputError("sway given, but the robot has no hanging load (joints "
                         f"{', '.join(CABLE_JOINTS)}): leave it out", name="sway")
    movable = [j.name for j in robot.description.joints.values() if j.type != "fixed"]
    unknown = [name for name in movable if name not in out]
    if unknown:
        raise ModelError(f"the URDF has movable joints {unknown} that the MJCF export does "
                         "not know how to place: it knows the platform's, the legs', the "
                         "arm's and the cable's", element=unknown[0])
    return out


def _static_forces(robot, q: np.ndarray, gravity, sway=None) -> np.ndarray:
    """Actuator forces X ``(9,)`` [N·m, N] that hold ``q`` at rest.

    With a hanging load they come from ``offshore_crane.dynamics.cable.inverse_dynamics`` at the
    robot's rest, the payload at ``sway`` (default hanging straight down the tip frame's
    z) with no sway rate: the forces of that instant (an equilibrium when the cable is
    vertical).
    """
    if _has_cable(robot):
        from offshore_crane.dynamics import cable

        rest = np.repeat(q[None], 2, axis=0)
        res = cable.inverse_dynamics(robot, rest, 0 * rest, 0 * rest, t=np.array([0.0, 1e-3]),
                                     gravity=gravity, initial=(0.0, 0.0) if sway is None
                                     else np.reshape(sway, 2), limits=False)
        return np.asarray(res.X)[0]
    from offshore_crane.dynamics import inverse_dynamics

    zeros = np.zeros(9)
    return inverse_dynamics(robot, q, zeros, zeros, gravity=gravity)


# --------------------------------------------------------------------------- export
def export(robot, q=None, *, sway=None, gravity=GRAVITY, limits: bool = False,
           hold: bool = True, timestep: float = TIMESTEP) -> MJCF:
    """The robot as a MuJoCo model, written at ``q`` with the loops closed.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q: ``(9,)`` the configuration to write [m, rad]; default the home pose
            ``(0, 0, home_height, 0, 0, 0, 0, 0, 0)``. It must lie in the workspace.
        sway: ``(2,)`` cable angles (phi1, phi2) [rad] for a robot with a hanging load.
        gravity: ``(3,)`` [m/s²] in the base frame (``<option gravity>``).
        limits: False (the comparison model): no joint ranges, no force limits. True:
            the URDF's joint ranges on the legs' and arm's joints (never on the
            platform's virtual joints) and the motors' ``ctrlrange`` from
            ``robot.capacities`` (``[-pull_max, push_max]`` where finite).
        hold: Compute the static actuator forces at ``q`` for the keyframe ``hold``.
        timestep: ``<option timestep>`` [s]; the loops' time constant is two steps.

    Returns:
        :class:`MJCF`. The sway joints carry the URDF's damping
        (``payload.sway_damping``); the payload's air drag (``payload.drag_area``) is not
        written: MuJoCo's fluid models act on every body (docs/mjcf.md).

    Raises:
        InputError: a bad ``q``, ``sway``, ``gravity`` or ``timestep``.
        WorkspaceError: ``q`` outside the workspace (leg stroke, joint limits).
        ModelError: a URDF the exporter cannot map (unknown movable joints, a moving
            body without mass), or a hanging load without its dynamics module.
    """
    from offshore_crane.validation import as_gravity, as_samples

    g = as_gravity(gravity)
    if q is None:
        q = robot.home_pose()
    q = as_samples("q", q)[0]
    if len(q) != 1:
        raise InputError(f"q must be one configuration (9,), got {len(q)} samples",
                         name="q")
    q = q[0]
    if not (isinstance(timestep, (int, float)) and np.isfinite(timestep) and timestep > 0):
        raise InputError(f"timestep {timestep:g} s must be a finite number > 0",
                         name="timestep")
    values = joint_values(robot, q, sway=None if sway is None else np.reshape(sway, (1, -1)))
    positions = {name: float(v[0][0]) for name, v in values.items()}
    _check_limits(robot.description, positions, PLATFORM_JOINTS)
    X = _static_forces(robot, q, g, sway) if hold else None
    names = robot.hybrid.actuators
    joints = [ACTUATED_JOINTS[ACTUATORS.index(a)] for a in names]
    ranges = None
    if limits:
        caps = robot.capacities
        ranges = {a: (-caps.pull_max[ACTUATORS.index(a)], caps.push_max[ACTUATORS.index(a)])
                  for a in names}
    ctrl = None if X is None else np.array([X[ACTUATORS.index(a)] for a in names])
    model_name = robot.spec.name if robot.spec is not None else robot.description.name
    return mjcf_from_urdf(robot.urdf, positions, name=model_name, gravity=g,
                          actuators=list(zip(names, joints)), ctrlrange=ranges,
                          loops=list(zip(LEG_TIPS, PLATFORM_ANCHORS)), hold=ctrl,
                          joint_limits=limits, virtual=PLATFORM_JOINTS, timestep=timestep,
                          description=robot.description)


def _check_limits(urdf, positions: dict, virtual) -> None:
    """Every joint of the written configuration inside its URDF range (leg strokes,
    U-joint and arm limits; the platform's virtual joints have none).

    Raises:
        WorkspaceError: naming the joint, its value and its range.
    """
    from offshore_crane.errors import WorkspaceError

    for name, value in positions.items():
        j = urdf.joints[name]
        if name in virtual or j.type == "continuous":
            continue
        if not j.lower <= value <= j.upper:
            unit = "m" if j.type == "prismatic" else "rad"
            raise WorkspaceError(f"the pose puts joint '{name}' at {value:.6g} {unit}, outside its "
                                 f"range [{j.lower:g}, {j.upper:g}] {unit}: give a pose "
                                 "inside the workspace", joint=name, value=value)
