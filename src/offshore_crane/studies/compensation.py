"""Uncompensated, arm-only and arm-plus-winch lifts side by side: what motion
compensation buys, and what it demands of the actuators (``offshore-crane compensate``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np



@dataclass
class CompensationRun:
    """One mode's lift (:func:`compare_compensation`).

    Attributes:
        mode: ``"none"``, ``"arm"`` or ``"arm+winch"``.
        residual: ``(N, 3)`` the payload's position minus the still-ship payload's
            (hanging straight below the still-ship tip, moved with the target deck when
            one is tracked), base frame [m].
        rms, peak: ``(3,)`` RMS and largest |residual| per axis x, y, z [m].
        sway_max_deg: Largest angle of the cable from the tip's vertical [deg]: the
            envelope's ``sway_max`` (the figure ``size`` and a sweep's row report).
        lift: :class:`~offshore_crane.dynamics.cable.LiftMetrics`.
        worst: ``(utilisation, actuator, capacity)`` of the robot's actuators, the
            worst over the run (the envelope's: 1 = 100 %).
        winch: ``{pull, speed, acceleration, power: utilisation}`` (NaN without a winch).
        held: ``{joint: (samples, first time [s])}`` where the arm met its limits.
        result: The run's :class:`CableResult` or :class:`ElasticResult`.
        run: The :class:`~offshore_crane.studies.sweep.CaseRun` it comes from (its
            envelope, motion and record).
    """

    mode: str
    residual: np.ndarray
    rms: np.ndarray
    peak: np.ndarray
    sway_max_deg: float
    lift: object
    worst: tuple
    winch: dict
    held: dict
    result: object
    run: object = None


def compare_compensation(scene, robot=None, modes=("none", "arm", "arm+winch"),
                         delay: float | None = None, **options) -> list[CompensationRun]:
    """The scene's lift under each compensation mode: the scene with ``[control]
    compensation`` set to the mode (and ``delay``) run as ``size`` and a sweep run it
    (:func:`offshore_crane.studies.sweep.record`): the same record, the same start, the
    same envelope, so the mode the scene names reports here what ``size`` reports.

    Args:
        scene: A sea scene with the arm and a payload on a cable; its robot's
            ``actuators.winch`` capacities judge the winch.
        robot: Its robot (default: the scene's).
        modes: Out of :data:`offshore_crane.simulation.compensation.MODES`.
        delay: The measurement's delay [s] the compensation acts on (default: the
            scene's ``[control] delay``, else 0).
        **options: ``limits``, ``thresholds`` of :func:`~offshore_crane.studies.sweep.
            record`.

    Raises:
        The errors of :func:`~offshore_crane.studies.sweep.record` and of
        :func:`~offshore_crane.simulation.compensation.compensated_motion`.
    """
    from dataclasses import replace

    from offshore_crane import progress, scenes
    from offshore_crane.dynamics.cable import lift_metrics
    from offshore_crane.dynamics.cable.tip import payload_positions
    from offshore_crane.simulation.compensation import check_compensable
    from offshore_crane.studies.sweep.cases import record

    _check_comparable(scene)
    robot = robot or scenes.load_robot(scene)
    check_compensable(robot)
    control = dict(scene.control)
    if delay is not None:
        control["delay"] = float(delay)
    runs = []
    with progress.bar(len(modes), "mode", "compensate") as shown:
        for mode in modes:
            with progress.suspended():          # the bar counts the modes
                run = record(replace(scene, control={**control, "compensation": mode}),
                             robot, **options)
            res, comp = run.result.cable, run.compensation
            residual = payload_positions(robot, res) - comp.aim
            lift = lift_metrics(res, scene.gravity)
            env = run.envelope
            runs.append(CompensationRun(
                mode, residual, np.sqrt((residual ** 2).mean(axis=0)),
                np.abs(residual).max(axis=0), float(np.degrees(env.sway_max)), lift,
                env.worst(), lift.winch_utilisation(robot.winch), comp.held, res, run))
            shown.update()
    return runs


def _check_comparable(scene) -> None:
    """A scene whose lift the modes can share: the compensation drives the arm and the
    winch itself, and a ``[lift]`` event is not compensated.

    Raises:
        SceneError: a hoist column (``[cable] winch``) or a ``[lift]``.
    """
    from offshore_crane.errors import SceneError

    if scene.cable.get("winch"):
        raise SceneError(f"{scene.where()}: compensate drives the winch itself, so the "
                         "hoist column ([cable] winch) would be ignored: drop it",
                         path=scene.path, name="cable.winch")
    if scene.lift:
        raise SceneError(f"{scene.where()}: compensate does not model a [lift] event's "
                         "deck: drop [lift], or use offshore-crane id for the lift",
                         path=scene.path, name="lift")


def format_comparison(runs: list[CompensationRun]) -> str:
    """The comparison as a table: residual motion per axis, sway, tension ratios, the
    worst actuator and the winch against their capacities, the limits met."""
    head = (f"{'mode':<10} {'RMS x, y, z [mm]':>22} {'max x, y, z [mm]':>22} "
            f"{'sway':>7} {'T/mg':>11} {'worst actuator':>22} {'winch':>8}")
    lines = [head]
    base = runs[0].rms
    for r in runs:
        u, name, cap = r.worst
        winch = max((v for v in r.winch.values() if v == v), default=float("nan"))
        lines.append(
            f"{r.mode:<10} {', '.join(f'{1e3 * x:6.2f}' for x in r.rms):>22} "
            f"{', '.join(f'{1e3 * x:6.2f}' for x in r.peak):>22} {r.sway_max_deg:6.2f}° "
            f"{r.lift.ratio_min:5.2f}..{r.lift.ratio_max:4.2f} "
            f"{(f'{100 * u:5.1f} % {name} {cap}' if u == u else '—'):>22} "
            f"{(f'{100 * winch:6.1f} %' if winch == winch else '—'):>8}")
    for r in runs[1:]:
        gain = base / np.maximum(r.rms, 1e-300)
        lines.append(f"{r.mode}: RMS reduced {gain[0]:.3g} × (x), {gain[1]:.3g} × (y), "
                     f"{gain[2]:.3g} × (z) against none"
                     + ("; limits met: " + ", ".join(f"{j} held at its limit for {n} "
                                                      f"samples from t = {t0:.2f} s"
                                                      for j, (n, t0) in r.held.items())
                        if r.held else "; no joint limit met"))
    return "\n".join(lines)
