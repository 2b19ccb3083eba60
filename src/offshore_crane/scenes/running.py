"""Running a scene: inverse dynamics by each method asked for (the swing with a hanging load)
and their comparison.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from offshore_crane.conventions import ACTUATORS
from offshore_crane.scenes.assembly import load_robot, load_trajectory
from offshore_crane.scenes.scene import Scene, hoist_waypoints


@dataclass
class SceneRun:
    """A scene's results.

    Attributes:
        scene: The scene.
        robot: Its robot.
        trajectory: The trajectory as solved (deck pose applied).
        results: ``{method: Result}`` in the order of ``scene.methods``.
        seconds: ``{method: run time [s]}``: the method's own computation, its kernels
            already loaded or compiled.
        prepare: ``{method: seconds [s]}`` spent before, loading (or, the first time,
            compiling) the method's kernels on the first two samples.
        compiled: Kernels compiled (not found in the cache) while preparing.
    """

    scene: Scene
    robot: object
    trajectory: object
    results: dict
    seconds: dict
    prepare: dict = field(default_factory=dict)
    compiled: int = 0

    @property
    def result(self):
        """The first method's :class:`~offshore_crane.dynamics.Result`."""
        return next(iter(self.results.values()))


def solve_scene(scene: Scene, robot, traj, method: str, leg_model: str, **options):
    from offshore_crane.dynamics import solve

    if robot.hybrid.cable is not None:
        return run_swing(scene, robot, traj, method, **options)
    return solve(robot, traj.q, traj.qd, traj.qdd, method=method, gravity=scene.gravity,
                 leg_model=leg_model, outputs=scene.wanted(), t=traj.t, **options)


#: The hanging load's path for each scene method: Kane's, or the Pinocchio reference.
CABLE_METHODS = {"kane": "kane", "rnea": "pinocchio"}


@dataclass
class SwingPlan:
    """What a hanging-load scene runs (:func:`swing_plan`).

    Attributes:
        trajectory: The robot's motion as it runs: the scene's record, or the arm's (and
            the winch's) commands under ``[control] compensation``.
        options: The cable's keyword arguments (``[cable]`` options, the winch's
            ``hoist`` profile, the compensation's starting state).
        compensation: The :class:`~offshore_crane.simulation.compensation.Compensated`
            motion (its aim, tip and held joints) when the scene names a compensation
            mode (``"none"`` included), else None.
    """

    trajectory: object
    options: dict
    compensation: object = None


def swing_plan(scene: Scene, robot, traj) -> SwingPlan:
    """The motion and cable options a scene with a payload on a cable runs: its
    ``[control] compensation`` applied to the record (any mode the scene names, ``"none"``
    included, starts the payload as :func:`~offshore_crane.simulation.compensation.
    still_start` says unless ``[cable] initial`` is given), and the winch's hoist
    column.

    Raises:
        SceneError: a winch whose capacities the description does not give; the errors
            of :func:`_compensated`.
    """
    from offshore_crane.dynamics.cable import hoist_profile
    from offshore_crane.errors import SceneError

    options = {k: v for k, v in scene.cable.items() if k not in ("ea", "damping", "winch")}
    comp = None
    if "compensation" in scene.control:
        traj, options, comp = _compensated(scene, robot, traj, options)
    waypoints = hoist_waypoints(scene)
    if waypoints is not None:
        if not robot.winch.given():
            raise SceneError(f"{scene.where()}: [cable] winch = true, but the robot "
                             "description gives no winch capacities: set actuators.winch."
                             "pull_max, speed_max, acceleration_max, power_max ([actuators."
                             "winch] in the scene)", path=scene.path, name="cable.winch")
        options["hoist"] = hoist_profile(waypoints)
    return SwingPlan(traj, options, comp)


def run_swing(scene: Scene, robot, traj, method: str, limits: bool = True, checks: bool = True,
              thresholds=None, threads: int = 1, plan: SwingPlan | None = None, **ignored):
    """A scene with a payload on a cable: :func:`offshore_crane.dynamics.cable.swing` (the
    ``[cable]`` options; ``threads`` split the rigid cable's Kane pass, ``backend`` does
    not apply), with a winch when
    ``[cable] winch = true`` (the hoist column of ``[operation]``), or on an elastic cable
    when ``[cable] ea`` is given (:func:`~offshore_crane.dynamics.cable.elastic_inverse_dynamics`,
    Kane's path only), as a :class:`~offshore_crane.dynamics.Result` holding the
    :class:`CableResult` or :class:`ElasticResult` (whose ``t, q, qd, qdd`` are the
    motion that ran: the compensated one under a compensation). ``plan``: the scene's
    :func:`swing_plan` when the caller has it.

    Raises:
        SceneError: a winch whose capacities the description does not give; an elastic
            cable asked of the Pinocchio reference.
    """
    from offshore_crane.dynamics.cable import elastic_inverse_dynamics, swing
    from offshore_crane.dynamics import Result
    from offshore_crane.errors import SceneError
    from offshore_crane.robot.kinematics.workspace import Thresholds

    plan = plan or swing_plan(scene, robot, traj)
    traj, options = plan.trajectory, dict(plan.options)
    checked = dict(gravity=scene.gravity, limits=limits, checks=checks,
                   thresholds=thresholds or Thresholds())
    if scene.lift:
        return _lift_event(scene, robot, traj, method, options.get("hoist"), checked)
    if "ea" in scene.cable:
        if method != "kane":
            raise SceneError(f"{scene.where()}: the elastic cable ([cable] ea) has Kane's "
                             f"path only: use methods = [\"kane\"], not {method!r}",
                             path=scene.path, name="methods")
        keys = ("substeps", "hoist") + (("initial", "initial_velocity")
                                        if "initial_velocity" in options else ())
        elastic = {k: v for k, v in options.items() if k in keys}
        res = elastic_inverse_dynamics(
            robot, traj.q, traj.qd, traj.qdd, t=traj.t,
            reference=traj.reference if traj.source is not None else None,
            ea=scene.cable["ea"], damping=scene.cable.get("damping", 0.0), **elastic,
            **checked)
        return Result(X=res.X, method=method, leg_model="full", outputs=scene.wanted(),
                      condition=np.full(len(res.t), np.nan), gimbal=None, attitude=None,
                      backend="numba", cable=res)
    res = swing(robot, traj, method=CABLE_METHODS[method], **checked, **options,
                threads=threads)
    return Result(X=res.X, method=method, leg_model="full", outputs=scene.wanted(),
                  condition=res.condition, gimbal=None, attitude=None,
                  backend="numba" if method == "kane" else "pinocchio", cable=res)


def cable_simulation(scene: Scene, robot, traj) -> tuple:
    """What ``simulate`` runs for a scene whose cable's length varies (a winch, a
    compensation): the reference (the compensated arm's commands under ``[control]
    compensation``) and the keyword arguments of the simulation — the cable (on an
    elastic one, ``[cable] ea``, :func:`offshore_crane.simulation.elastic.simulate_elastic`;
    else the rigid cable's :func:`offshore_crane.simulation.swing.simulate_swing`), the
    winch's profile (the hoist column, or the compensation's), the payload's start (the
    compensation's still start; the scene's ``[cable] initial`` and ``initial_rate`` on a
    rigid cable). Returns ``(reference trajectory, options)``.

    Raises:
        SceneError: a ``[lift]`` (the deck's contact is not simulated).
    """
    from offshore_crane.dynamics.cable import hoist_profile
    from offshore_crane.errors import SceneError

    where = scene.where()
    if scene.lift:
        raise SceneError(f"{where}: [lift]: simulate does not model the deck's contact; "
                         "use offshore-crane id for the lift-off or set-down",
                         path=scene.path, name="lift")
    elastic = "ea" in scene.cable
    options = ({"ea": scene.cable["ea"], "damping": scene.cable.get("damping", 0.0)}
               if elastic else {k: v for k, v in scene.cable.items()
                                if k in ("initial", "initial_rate")})
    waypoints = hoist_waypoints(scene)
    if waypoints is not None:
        options["hoist"] = hoist_profile(waypoints)
    if scene.compensation != "none":
        traj, extra, _ = _compensated(scene, robot, traj, options)
        options.update(extra)
    return traj, options


def plant_options(scene: Scene, robot, traj) -> tuple:
    """What a scene's simulation gives its plant (``simulate --scene`` and
    :func:`~offshore_crane.scenes.stepping.stepper` alike): ``(reference
    trajectory, elastic, swing)``. On an elastic cable whose length varies, ``elastic``
    holds :func:`~offshore_crane.simulation.elastic.simulate_elastic`'s keyword
    arguments (:func:`cable_simulation`) and ``swing`` is empty; else ``elastic`` is None
    and ``swing`` the rigid cable's (its sway's start, a winch's profile; empty without
    a cable). The reference is the compensated arm's commands under ``[control]
    compensation``.

    Raises:
        SceneError: as :func:`cable_simulation`.
    """
    varying = None
    if scene.varying_cable:             # a winch, a compensation: the cable's length varies
        traj, varying = cable_simulation(scene, robot, traj)
        if "ea" in varying:
            return traj, varying, {}
    if robot.hybrid.cable is None:
        return traj, None, {}
    return traj, None, (varying if varying is not None else
                        {k: v for k, v in scene.cable.items()
                         if k in ("initial", "initial_rate")})


def _lift_event(scene: Scene, robot, traj, method: str, hoist, checked: dict):
    """A ``[lift]`` scene: the load lifted off the deck (resting on it, then flying:
    :func:`offshore_crane.dynamics.cable.lift_off`) or lowered onto it (flying, then
    resting where it landed: :func:`~offshore_crane.dynamics.cable.set_down`), on the
    elastic cable; the :class:`~offshore_crane.dynamics.Result` holds the record and its event."""
    from dataclasses import replace as swap

    from offshore_crane.dynamics import Result
    from offshore_crane.dynamics.cable import lift_off, set_down
    from offshore_crane.errors import InputError, SceneError
    from offshore_crane.scenes.assembly import lift_deck

    if method != "kane":
        raise SceneError(f"{scene.where()}: [lift] runs on the elastic cable, Kane's path "
                         f"only: use methods = [\"kane\"], not {method!r}", path=scene.path,
                         name="methods")
    deck = lift_deck(scene)
    cable = dict(ea=scene.cable["ea"], damping=scene.cable.get("damping", 0.0), hoist=hoist,
                 gravity=checked["gravity"], substeps=scene.cable.get("substeps"))
    checks = {k: checked[k] for k in ("limits", "checks", "thresholds")}
    try:
        if scene.lift["event"] == "lift-off":
            event = lift_off(robot, traj, deck, **cable, **checks)
            res = swap(event.result, event=event)
        else:
            res = set_down(robot, traj, deck, **cable, **checks)[2]
    except InputError as exc:                   # the deck's height: the scene's key
        if exc.name != "deck":
            raise
        raise SceneError(f"{scene.where()}: [lift] {exc}", path=scene.path,
                         name="lift.deck_height") from None
    return Result(X=res.X, method=method, leg_model="full", outputs=scene.wanted(),
                  condition=np.full(len(res.t), np.nan), gimbal=None, attitude=None,
                  backend="numba", cable=res)


def _compensated(scene: Scene, robot, traj, options: dict):
    """The scene's ``[control] compensation`` applied to its sea record: the arm's (and
    the winch's) commands (:func:`offshore_crane.simulation.compensation.compensated_motion`)
    towards the still-ship point or the ``[control] target`` deck, on the platform's
    motion measured ``[control] delay`` late (:func:`load_trajectory`
    starts the record once the first measurement has arrived), the payload starting still
    unless ``[cable] initial`` says otherwise. Returns ``(trajectory, cable options,
    Compensated)``.

    Raises:
        SceneError: compensation with the winch's hoist column (the winch is the
            compensation's), or without a sea.
    """
    from offshore_crane.errors import SceneError
    from offshore_crane.simulation.compensation import compensated_motion, still_start

    where = scene.where()
    if scene.trajectory != "sea":
        raise SceneError(f"{where}: [control] compensation cancels the platform's motion: "
                         "it needs [trajectory] source = \"sea\"", path=scene.path,
                         name="control.compensation")
    if scene.cable.get("winch"):
        raise SceneError(f"{where}: [control] compensation drives the winch itself: drop "
                         "[cable] winch and the hoist column", path=scene.path,
                         name="control.compensation")
    delay = float(scene.control.get("delay", 0.0))     # load_trajectory starts it late
    from offshore_crane.scenes.assembly import target_deck

    comp = compensated_motion(robot, traj, scene.compensation, delay, target_deck(scene),
                              scene.gravity)
    options = dict(options)
    if comp.hoist is not None:
        options["hoist"] = comp.hoist_function()
    if "initial" not in options:
        options.update(still_start(robot, comp, scene.gravity, scene.cable.get("ea")))
    return comp.trajectory, options, comp


def run(scene: Scene, robot=None, trajectory=None, **options) -> SceneRun:
    """Solve the scene with each of its methods.

    Args:
        scene: The scene.
        robot: Its robot (default :func:`load_robot`).
        trajectory: Its trajectory (default :func:`load_trajectory`).
        **options: ``limits``, ``checks``, ``thresholds`` of
            :func:`offshore_crane.dynamics.solve`.

    Raises:
        The errors of :func:`offshore_crane.dynamics.solve` and of the loaders.
    """
    from offshore_crane import kernel_cache

    robot = robot or load_robot(scene)
    traj = trajectory or load_trajectory(scene, robot)
    results, seconds, prepare = {}, {}, {}
    compiled = kernel_cache.COMPILED[0]
    for m in scene.methods:
        t0 = time.perf_counter()
        _prepare(scene, robot, traj, m, **options)
        prepare[m] = time.perf_counter() - t0
        t0 = time.perf_counter()
        results[m] = solve_scene(scene, robot, traj, m, scene.leg_model, **options)
        seconds[m] = time.perf_counter() - t0
    return SceneRun(scene, robot, traj, results, seconds, prepare,
                    kernel_cache.COMPILED[0] - compiled)


def _prepare(scene: Scene, robot, traj, method: str, **options) -> None:
    """Run ``method`` on the trajectory's first samples, so that its kernels are loaded
    (or compiled) before its run is timed: :data:`~offshore_crane.conventions.LANES` of
    them when the run has as many (the fused Kane pass then runs on blocks of samples),
    else two. Its result is dropped, and so is an error: the run itself meets it and
    reports it."""
    from offshore_crane.conventions import LANES
    from offshore_crane.errors import OffshoreCraneError

    if len(traj.t) <= 2:
        return
    n = LANES if len(traj.t) >= LANES else 2
    head = replace(traj, t=traj.t[:n], q=traj.q[:n], qd=traj.qd[:n], qdd=traj.qdd[:n])
    try:
        solve_scene(scene, robot, head, method, scene.leg_model, **options)
    except OffshoreCraneError:
        pass


def compare_methods(run_: SceneRun) -> list[tuple[str, float, float, int, int]]:
    """Each method after the first against the first, over the wanted actuators.

    Returns:
        ``[(method, max |ΔX|, max |X_first|, relative, sample, column of X), ...]``.
    """
    cols = [k for k, n in enumerate(ACTUATORS) if n in run_.result.outputs]
    ref = run_.result.X[:, cols]
    scale = np.abs(ref).max()
    out = []
    for m, res in list(run_.results.items())[1:]:
        diff = np.abs(res.X[:, cols] - ref)
        i, j = np.unravel_index(np.argmax(diff), diff.shape)
        rel = diff.max() / scale if scale > 0 else diff.max()
        out.append((m, float(diff.max()), float(scale), float(rel), int(i), cols[j]))
    return out
