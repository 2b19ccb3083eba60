"""Fidelity of the leg models against the exact one on a scene: forces and run times."""

from __future__ import annotations

import statistics
import time
from dataclasses import dataclass

import numpy as np

from offshore_crane.conventions import ACTUATOR_UNITS, ACTUATORS
from offshore_crane.dynamics import LEG_MODELS
from offshore_crane.errors import SceneError
from offshore_crane.scenes.assembly import load_robot, load_trajectory
from offshore_crane.scenes.keys import FIDELITY_REPEAT
from offshore_crane.scenes.running import solve_scene
from offshore_crane.scenes.scene import Scene


# --------------------------------------------------------------------------- fidelity
@dataclass(frozen=True)
class Fidelity:
    """One leg model against ``full`` (method kane).

    Attributes:
        leg_model: ``"full"``, ``"thin-rod"`` or ``"massless"``.
        seconds: Median run time of :func:`~offshore_crane.dynamics.solve` [s].
        deviation: ``(k,)`` max over time of |X − X_full| per wanted actuator [N·m, N].
        relative: ``(k,)`` ``deviation / max |X_full|`` per actuator.
        approximations: Labels of the approximations used (empty: exact).
        pruned: What the solver skipped.
    """

    leg_model: str
    seconds: float
    deviation: np.ndarray
    relative: np.ndarray
    approximations: tuple
    pruned: tuple


def compare_fidelity(scene: Scene, robot=None, trajectory=None,
                     repeat: int = FIDELITY_REPEAT, **options):
    """Run time and deviation from ``full`` of each leg model (method kane).

    Args:
        scene, robot, trajectory: As :func:`run`.
        repeat: Timed runs per leg model (after one untimed warm-up run); the median is
            reported.
        **options: Options of :func:`offshore_crane.dynamics.solve`.

    Returns:
        ``(names, scale, rows)``: the wanted actuators, ``(k,)`` max |X_full| per
        actuator, and one :class:`Fidelity` per leg model (``full`` first).
    """
    robot = robot or load_robot(scene)
    if robot.hybrid.cable is not None:
        raise SceneError(f"{scene.where()}: the leg models' fidelity is compared on a rigid "
                         "robot; this one's payload hangs on a cable (computed with the full "
                         "leg model only)", path=scene.path, name="payload.cable_length")
    traj = trajectory or load_trajectory(scene, robot)
    names = scene.wanted()
    cols = [ACTUATORS.index(n) for n in names]
    rows, ref = [], None
    for model in LEG_MODELS:
        res = solve_scene(scene, robot, traj, "kane", model, **options)      # warm-up
        times = []
        for _ in range(repeat):
            t0 = time.perf_counter()
            solve_scene(scene, robot, traj, "kane", model, **options)
            times.append(time.perf_counter() - t0)
        X = res.X[:, cols]
        if ref is None:
            ref = X
            scale = np.abs(ref).max(axis=0)
        dev = np.abs(X - ref).max(axis=0)
        rel = np.divide(dev, scale, out=np.zeros_like(dev), where=scale > 0)
        rows.append(Fidelity(model, statistics.median(times), dev, rel,
                             res.approximations, res.pruned))
    return names, scale, rows


def format_fidelity(names, scale, rows, n_samples: int, repeat: int = FIDELITY_REPEAT) -> str:
    """The fidelity report of :func:`compare_fidelity` as two fixed-width tables."""
    full = rows[0].seconds
    lines = [f"fidelity of the leg models against 'full' (method kane, {n_samples} samples, "
             f"run time: median of {repeat} runs)",
             f"{'leg model':<10}{'time [ms]':>11}{'speed-up':>10}{'worst rel. dev.':>17}"
             "  approximation"]
    for r in rows:
        worst = float(r.relative.max()) if r.relative.size else 0.0
        lines.append(f"{r.leg_model:<10}{r.seconds * 1e3:>11.3f}{full / r.seconds:>10.2f}"
                     f"{worst:>17.3e}  {'; '.join(r.approximations) or 'exact'}")
    legs_skipped = any("leg kinematics" in p for p in rows[0].pruned)
    if legs_skipped:
        lines.append("(no leg force wanted: the legs are not evaluated, so the leg model "
                     "changes nothing)")
    units = {n: u for n, u in zip(ACTUATORS, ACTUATOR_UNITS)}
    head = f"{'actuator':<9}{'unit':<5}{'max |X_full|':>14}"
    for r in rows[1:]:
        head += f"{'max |ΔX| ' + r.leg_model:>22}{'relative':>11}"
    lines += ["", head]
    for k, n in enumerate(names):
        line = f"{n:<9}{units[n]:<5}{scale[k]:>14.5g}"
        for r in rows[1:]:
            line += f"{r.deviation[k]:>22.4e}{r.relative[k]:>11.2e}"
        lines.append(line)
    return "\n".join(lines)
