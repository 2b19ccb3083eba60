"""Uncompensated, arm-only and arm-plus-winch lifts side by side: what motion
compensation buys, and what it demands of the actuators (``offshore-crane compensate``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from offshore_crane.conventions import GRAVITY


@dataclass
class CompensationRun:
    """One mode's lift (:func:`compare_compensation`).

    Attributes:
        mode: ``"none"``, ``"arm"`` or ``"arm+winch"``.
        residual: ``(N, 3)`` the payload's position minus the still-ship payload's
            (hanging straight below the still-ship tip, moved with the target deck when
            one is tracked), base frame [m].
        rms, peak: ``(3,)`` RMS and largest |residual| per axis x, y, z [m].
        sway_max_deg: Largest angle of the cable from the vertical [deg].
        lift: :class:`~offshore_crane.dynamics.cable.LiftMetrics`.
        worst: ``(utilisation, actuator, capacity)`` of the robot's actuators, the
            worst over the run (``size``'s measure: 1 = 100 %).
        winch: ``{pull, speed, acceleration, power: utilisation}`` (NaN without a winch).
        held: ``{joint: (samples, first time [s])}`` where the arm met its limits.
        result: The run's :class:`CableResult` or :class:`ElasticResult`.
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


def compare_compensation(robot, trajectory, cable: dict | None = None, gravity=GRAVITY,
                         modes=("none", "arm", "arm+winch"),
                         delay: float = 0.0, deck=None) -> list[CompensationRun]:
    """The same sea and operation lifted under each compensation mode.

    Args:
        robot: With the arm and a payload on a cable; its ``actuators.winch``
            capacities judge the winch.
        trajectory: The sea record (q1..q6 the ship, q7..q9 the operation); with a
            delay, its source must reach ``delay`` before its first sample
            (:func:`~offshore_crane.simulation.compensation.measured_from`).
        cable: ``[cable]`` options: ``ea``, ``damping`` (an elastic cable), ``initial``,
            ``initial_rate``, ``substeps``, ``slack`` (a rigid one). Without ``initial``
            the payload starts hanging still along g
            (:func:`~offshore_crane.simulation.compensation.still_start`).
        gravity: ``(3,)`` [m/s²].
        modes: Out of :data:`offshore_crane.simulation.compensation.MODES`.
        delay: The measurement's delay [s] the compensation acts on.
        deck: A moving target (:class:`~offshore_crane.motion.sea.DeckMotion`, a point on
            a second vessel's deck), or None: the still-ship point.

    Raises:
        The errors of :func:`~offshore_crane.simulation.compensation.compensated_motion`
        and of the cable's inverse dynamics.
    """
    from offshore_crane.dynamics.cable import (elastic_inverse_dynamics, inverse_dynamics,
                                               lift_metrics)
    from offshore_crane.dynamics.cable.tip import payload_positions
    from offshore_crane.simulation.compensation import compensated_motion, still_start
    from offshore_crane.studies.sizing.envelopes import envelope, worst_utilisation

    cable = dict(cable or {})
    elastic = {k: cable.pop(k) for k in ("ea", "damping") if k in cable}
    cable.pop("winch", None)
    g = np.asarray(gravity, dtype=float)
    down = g / np.linalg.norm(g)
    runs = []
    for mode in modes:
        comp = compensated_motion(robot, trajectory, mode, delay, deck, g)
        tr = comp.trajectory
        args = dict(t=tr.t, gravity=g, hoist=comp.hoist_function(),
                    reference=tr.reference if tr.source is not None else None)
        start = still_start(robot, comp, g, elastic.get("ea"))
        if elastic:
            res = elastic_inverse_dynamics(robot, tr.q, tr.qd, tr.qdd, **args, **elastic,
                                           **start, **{k: v for k, v in cable.items()
                                                       if k == "substeps"})
        else:
            res = inverse_dynamics(robot, tr.q, tr.qd, tr.qdd, **args, **{**start, **cable})
        p = payload_positions(robot, res)
        residual = p - comp.aim
        rel = p - comp.tip
        cosang = np.clip(rel @ down / np.linalg.norm(rel, axis=1), -1.0, 1.0)
        env = envelope(robot, tr.t, tr.q, tr.qd, res.X)
        lift = lift_metrics(res, g)
        runs.append(CompensationRun(
            mode, residual, np.sqrt((residual ** 2).mean(axis=0)),
            np.abs(residual).max(axis=0), float(np.degrees(np.arccos(cosang)).max()),
            lift, worst_utilisation(env.utilisation), lift.winch_utilisation(robot.winch),
            comp.held, res))
    return runs


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
