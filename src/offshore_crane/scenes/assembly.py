"""From a scene to the pipeline's inputs: the robot, the motion (trajectory, sea state), the
deck pose and the controller; scenes changed by command-line options.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from offshore_crane.errors import SceneError
from offshore_crane.io import toml_value
from offshore_crane.scenes.keys import (CONTROLLER_KEYS, SCENE_FIELDS, SEA_DURATION, SEA_RATE,
                                        scene_field)
from offshore_crane.scenes.scene import Scene, sea_arguments


def controller(scene: Scene, robot=None):
    """The :class:`~offshore_crane.simulation.control.Controller` of the scene's ``[control]``
    section (its ``model`` table overrides the scene's robot for the controller; under
    ``law = "arm-compensation"`` its ``target`` is the law's moving aim)."""
    from offshore_crane.simulation.control import Controller

    c = scene.control
    model = None
    if "model" in c:
        model = load_robot(scene, c["model"])
    on_line = c.get("law") in ("arm-compensation", "arm-winch-compensation")
    target = target_deck(scene) if on_line else None
    return Controller(**{k: v for k, v in c.items() if k in CONTROLLER_KEYS}, model=model,
                      target=target)


def instruments(scene: Scene) -> dict:
    """``{"sensors": Sensors | None, "actuators": Actuators | None}`` of the scene's
    ``[sensors]`` and ``[actuators] rate_limit, lag`` (None where the scene has none):
    :func:`offshore_crane.simulation.rigid.simulate`'s keyword arguments."""
    from offshore_crane.simulation.instruments import Actuators, Sensors

    return {"sensors": Sensors(**scene.sensors) if scene.sensors else None,
            "actuators": Actuators(**scene.actuator_models) if scene.actuator_models
            else None}


# --------------------------------------------------------------------------- running
def deck_pose(scene: Scene, robot) -> np.ndarray:
    """q1..q6 ``(6,)`` of the fixed deck [m, rad]: ``scene.deck_pose`` or home."""
    if scene.deck_pose is not None:
        return np.array(scene.deck_pose)
    return robot.home_pose()[:6]


def still_water_level(scene: Scene, robot) -> float | None:
    """Height of the calm sea surface in the base frame at model scale [m], or None for
    a scene without a sea.

    The platform's home pose stands for the vessel's ``[sea] point``, given relative to
    the RAO table's reference point in the calm waterplane: the water is
    ``point[2] / scale`` below the home height (``point`` defaults to the reference
    point itself, so the water is then at the home height).
    """
    if scene.trajectory != "sea" or not scene.sea:
        return None
    args = sea_arguments(scene)
    point = args.get("point") or (0.0, 0.0, 0.0)
    return float(robot.home_pose()[2] - float(point[2]) / float(args["scale"]))


def sea_trajectory(scene: Scene, robot, check: bool = True, threads: int = 1):
    """The model-scale record of a ``source = "sea"`` scene
    (:func:`offshore_crane.motion.sea.platform_trajectory`, analytic rates and accelerations;
    its ``source`` evaluates the same motion at any times); ``threads`` share its FFT and
    workspace check.

    Raises:
        SceneError: a bad ``[sea]`` value. SeaWorkspaceError: the record leaves the
            workspace (with the smallest scale that fits).
    """
    from offshore_crane.errors import SeaStateError
    from offshore_crane.motion.sea import platform_trajectory

    args = sea_arguments(scene)
    name = (f"sea Hs {args['hs']:g} m Tp {args['tp']:g} s heading {args['heading_deg']:g}° "
            f"at scale {args['scale']:g}")
    try:
        return platform_trajectory(
            SEA_DURATION if scene.duration is None else scene.duration,
            SEA_RATE if scene.rate is None else scene.rate, robot=robot, check=check,
            name=name, threads=threads, **args)
    except SeaStateError as exc:
        section = "operation" if exc.name == "waypoints" else "sea"
        raise SceneError(f"{scene.where()}: [{section}] {exc}", path=scene.path,
                         name=f"{section}.{exc.name}") from None


def target_deck(scene: Scene):
    """The ``[control] target`` of a scene: the point on a second vessel's deck
    (:func:`offshore_crane.motion.sea.deck_motion`: the scene's sea state with the
    target's seed, point and vessel, on the record's frequency grid), or None."""
    target = scene.control.get("target")
    return None if target is None else _second_vessel(scene, target, "[control] target")


def _second_vessel(scene: Scene, point: dict, what: str):
    """:func:`offshore_crane.motion.sea.deck_motion` of ``point`` (``{point, seed,
    vessel}``) in the scene's sea, its errors named as ``what``'s."""
    from offshore_crane.errors import SeaStateError
    from offshore_crane.motion.sea import deck_motion

    args = {k: v for k, v in sea_arguments(scene).items() if k != "operation"}
    args.update(point)
    try:
        return deck_motion(SEA_DURATION if scene.duration is None else scene.duration,
                           SEA_RATE if scene.rate is None else scene.rate, **args)
    except SeaStateError as exc:
        raise SceneError(f"{scene.where()}: {what}: {exc}", path=scene.path,
                         name=what.replace("[", "").replace("] ", ".")) from None


def lift_deck(scene: Scene):
    """The ``[lift]`` deck under the load: ``deck(t) -> (z, ż, z̈)`` [m, m/s, m/s²], base
    frame — ``deck_height`` plus the heave of ``[lift] deck`` (a point on a second vessel
    in the scene's sea), or still at ``deck_height``."""
    height = float(scene.lift["deck_height"])
    point = scene.lift.get("deck")
    if point is None:
        return lambda t: (np.full(len(t), height), np.zeros(len(t)), np.zeros(len(t)))
    heave = _second_vessel(scene, point, "[lift] deck")

    def deck(t):
        x, v, a = heave(t)
        return height + x[:, 2], v[:, 2], a[:, 2]
    return deck


def load_robot(scene: Scene, overrides: dict | None = None):
    """The scene's robot; ``overrides`` (dotted names or aliases) are applied on top, for
    a model that differs from the scene's on purpose (a controller's model). Command-line
    ``--set`` goes through :func:`with_robot_overrides` instead, which refuses
    contradictions."""
    from offshore_crane.robot import load_robot as _load
    from offshore_crane.robot.overrides import normalise

    return _load(scene.robot_description,
                 {**scene.robot_overrides(), **normalise(overrides, "robot overrides")})


def _field_owner(scene: Scene, name: str) -> str:
    """The scene's section that sets ``name`` (for messages)."""
    if name in SCENE_FIELDS or name.startswith("actuators."):
        return scene_field(name)
    return f"[robot] {name}"


def with_robot_overrides(scene: Scene, overrides: dict, source: str = "--set") -> Scene:
    """``scene`` with robot overrides (e.g. ``--set``) added, re-checked.

    Args:
        overrides: Checked overrides (:func:`offshore_crane.robot.overrides.parse_set`).

    Raises:
        SceneError: an override contradicts a field the scene sets (its ``[robot]``,
            ``[payload]`` or ``[subsystems] arm``), or the result does not fit together
            (a payload without arm, ...).
    """
    from offshore_crane.robot.overrides import conflicts

    if not overrides:
        return scene
    where = scene.where()
    clash = conflicts(scene.robot, overrides)
    if clash:
        c = clash[0]
        raise SceneError(f"{where}: {source} {c.field} = {toml_value(c.cli)} contradicts the "
                         f"scene's {_field_owner(scene, c.field)} = "
                         f"{toml_value(c.scene)}: change the scene or drop the {source}",
                         path=scene.path, name=c.field)
    robot = {**scene.robot, **overrides}
    return replace(scene, robot=robot, arm=None, payload=None,
                   origin=f"{where} with {source}")


def load_trajectory(scene: Scene, robot, threads: int = 1, check: bool = True):
    """The scene's trajectory; with ``platform = false``, q1..q6 held at the deck pose;
    with ``[control] compensation`` (any mode, so that every mode runs on the same
    samples) and ``delay``, from the time the first measurement has arrived. ``threads`` share a sea record's FFT and workspace check (the same
    record in any count). ``check=False`` leaves a sea record's workspace check to the
    caller, whose dynamics check the same limits anyway (``limits=True``): on their
    :class:`~offshore_crane.errors.WorkspaceError` it calls :func:`sea_workspace_error`
    for the error that names the smallest scale that fits (a compensated record is
    checked here all the same: its source is not the sea's).

    Returns:
        :class:`offshore_crane.motion.trajectories.Trajectory` (``(N, 9)`` arrays).
    """
    from offshore_crane.motion import trajectories

    if scene.trajectory == "sea":
        named = "compensation" in scene.control           # any mode, "none" included
        traj = sea_trajectory(scene, robot, check or named, threads)
        if not named:
            return traj
        from offshore_crane.simulation.compensation import measured_from

        return measured_from(traj, float(scene.control.get("delay", 0.0)))
    traj = trajectories.load(scene.trajectory, duration=scene.duration, rate=scene.rate,
                             fd_order=scene.fd_order)
    if scene.platform:
        return traj
    q, qd, qdd = traj.q.copy(), traj.qd.copy(), traj.qdd.copy()
    q[:, :6] = deck_pose(scene, robot)
    qd[:, :6] = 0.0
    qdd[:, :6] = 0.0
    return trajectories.Trajectory(f"{traj.name} on a fixed deck", traj.t, q, qd, qdd)


def sea_workspace_error(robot, traj, threads: int = 1) -> None:
    """Raise the :class:`~offshore_crane.errors.SeaWorkspaceError` of a sea record loaded
    with ``check=False`` (:func:`load_trajectory`) that the dynamics found outside the
    workspace: the record's own check, which names the smallest scale that fits; nothing
    for another trajectory (its caller re-raises the dynamics' error)."""
    check = getattr(traj.source, "check", None)
    if check is not None:
        check(robot, traj, threads)


def with_trajectory(scene: Scene, where: str, source: str | None) -> Scene:
    """``scene`` driven by another trajectory source (``--trajectory``): its ``[sea]``,
    ``[operation]``, ``[extremes]``, span and finite-difference order belong to its own
    source and are dropped; the same source (or None) leaves the scene as it is."""
    if source is None or source == scene.trajectory:
        return scene
    return replace(scene, origin=where, trajectory=source, sea={}, operation=None,
                   duration=None, rate=None, fd_order=4, extremes={})


def with_overrides(scene: Scene, where: str, **changes) -> Scene:
    """``scene`` with some fields replaced (e.g. by command-line flags), re-checked.

    Raises:
        SceneError: the result does not fit together (:func:`check_scene`).
    """
    changes = {k: v for k, v in changes.items() if v is not None}
    if not changes:
        return scene
    return replace(scene, origin=where, **changes)


def with_values(scene: Scene, values: dict, origin: str | None = None) -> Scene:
    """``scene`` with ``[sea]`` keys (``hs``, ``tp``, ``heading``, ``seed``, ...: the
    scene file's, full scale) and robot fields (dotted names, ``payload.mass``) replaced
    by ``values``, re-checked (a sweep's case, an FMU's parameters).

    Raises:
        SceneError: the result does not fit together (:func:`check_scene`).
    """
    from offshore_crane.scenes.keys import SEA_KEYS

    sea = {k: v for k, v in values.items() if k in SEA_KEYS}
    robot = {k: v for k, v in values.items() if k not in SEA_KEYS}
    changes = {}
    if sea:
        changes["sea"] = {**scene.sea, **sea}
    if robot:
        changes.update(robot={**scene.robot, **robot}, arm=None, payload=None)
    if not changes:
        return scene
    return replace(scene, origin=origin or f"{scene.where()} with {values}", **changes)
