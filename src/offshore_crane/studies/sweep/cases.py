"""One case of a sweep: its run (inverse dynamics, optional simulation), its envelope as one
row, and the row's schema.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from offshore_crane.errors import OffshoreCraneError
from offshore_crane import progress
from offshore_crane.studies.sweep.grid import Grid, case_id, case_scene, install_hint


#: Columns of a row besides the grid's keys and the envelope (:func:`row_schema`).
CASE_COLUMNS = (("case_id", "string"), ("status", "string"), ("error_type", "string"),
                ("error", "string"), ("warnings", "int64"))


# =========================================================================== one case
@dataclass
class CaseRun:
    """One scene run and its envelope.

    Attributes:
        scene, robot: What ran. trajectory: The scene's record as loaded (the reference of
            a simulation, the sea before a compensation).
        kind: ``"inverse dynamics"`` or ``"simulation"``.
        t, q, qd, X: ``(N,)`` [s], ``(N, 9)`` the motion that ran [m, rad, /s] — the
            simulated motion, the compensated motion under ``[control] compensation`` —
            and the actuator forces [N·m, N] (the simulation's applied forces): what the
            envelope is of.
        result: The :class:`~offshore_crane.dynamics.Result` (condition numbers), of
            the inverse dynamics of the simulated motion for a simulation.
        simulation: The :class:`~offshore_crane.simulation.rigid.SimulationResult`, or None.
        envelope: :class:`~offshore_crane.studies.sizing.Envelope`.
        seconds: Run time of the trajectory and the dynamics (the case's own
            computation) [s].
        compensation: The :class:`~offshore_crane.simulation.compensation.Compensated`
            motion of a scene naming a compensation mode (its aim, tip, held joints), or
            None.
        exposure: The :class:`~offshore_crane.scenes.exposure.ExposurePlan` of a sea
            scene run as an exposure record (the motion, forces and results above are its
            judged window), or None (the scene's own record).
    """

    scene: object
    robot: object
    trajectory: object
    kind: str
    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    X: np.ndarray
    result: object
    simulation: object
    envelope: object
    seconds: float
    compensation: object = None
    exposure: object = None


def record(scene, robot=None, trajectory=None, *, backend: str = "auto", threads: int = 1,
           limits: bool = True, thresholds=None, method: str | None = None) -> CaseRun:
    """Run one scene and take its envelope: the inverse dynamics of its trajectory
    (method ``scene.methods[0]``), or, when the scene has a ``[control]`` section, the
    forward simulation under its controller over the trajectory's span (the envelope is
    of the applied forces; the condition numbers of the inverse dynamics of the
    simulated motion).

    A sea scene runs as an exposure record (:func:`offshore_crane.scenes.exposure.
    exposure_plan`: a spin-up, then the exposure with the operation repeated, under one
    sea) and its envelope is that of the judged window after the spin-up — unless
    ``[extremes] record = "scene"``, a ``[lift]`` event or a ``trajectory`` given here,
    which run as they are.

    With a payload on a cable (``payload.cable_length > 0``) the inverse dynamics is the
    swing's (:func:`offshore_crane.scenes.run_swing`, the scene's ``[cable]`` options, its
    compensation and winch) and the envelope gains the largest sway and the tension range;
    a slack rigid cable fails the case. The envelope is of the motion that ran: the
    compensated arm's speeds and strokes under a compensation.

    Raises:
        The errors of the loaders, of :func:`offshore_crane.dynamics.solve`, of
        :mod:`offshore_crane.dynamics.cable` (:class:`~offshore_crane.errors.SlackCableError`) and
        of :func:`offshore_crane.simulation.rigid.simulate`; the exposure record's
        :class:`~offshore_crane.errors.SceneError` (an operation that cannot repeat).
    """
    from offshore_crane import scenes
    from offshore_crane.dynamics import solve
    from offshore_crane.robot.kinematics.workspace import Thresholds
    from offshore_crane.scenes.exposure import check_own_record, exposure_plan, judged_on_exposure
    from offshore_crane.studies.sizing import conditions, envelope

    thresholds = thresholds or Thresholds()
    robot = robot or scenes.load_robot(scene)
    t0 = time.perf_counter()
    plan = None
    if trajectory is None and judged_on_exposure(scene):
        plan = exposure_plan(scene, robot)
    elif scene.trajectory == "sea" and not scene.lift:
        check_own_record(scene, robot)
    ran_scene = scene if plan is None else plan.scene
    traj = trajectory or scenes.load_trajectory(ran_scene, robot)
    options = dict(limits=limits, thresholds=thresholds, backend=backend, threads=threads)
    simulation = compensation = None
    if scene.simulated:
        simulation = _simulate(ran_scene, robot, traj, limits)
        t, q, qd, X = simulation.t, simulation.q, simulation.qd, simulation.X
        result = solve(robot, q, qd, simulation.qdd, "kane", scene.gravity,
                       outputs=scene.wanted(), t=t, **options)
        kind = "simulation"
    else:
        if robot.hybrid.cable is not None:            # the swing (offshore_crane.dynamics.cable)
            plan_ = scenes.swing_plan(ran_scene, robot, traj)
            result = scenes.run_swing(ran_scene, robot, traj, method or scene.methods[0],
                                      limits=limits, thresholds=thresholds, plan=plan_,
                                      threads=threads)
            compensation, ran = plan_.compensation, result.cable    # the motion that ran
        else:
            result = solve(robot, traj.q, traj.qd, traj.qdd, method or scene.methods[0],
                           scene.gravity, leg_model=scene.leg_model, outputs=scene.wanted(),
                           t=traj.t, **options)
            ran = traj
        t, q, qd, X = ran.t, ran.q, ran.qd, result.X
        kind = "inverse dynamics"
    if plan is not None:                              # the judged window, after the spin-up
        keep = judged(t, plan, ran_scene)
        n = len(t)
        t, q, qd, X, result, simulation, compensation = (
            _window(x, keep, n) for x in (t, q, qd, X, result, simulation, compensation))
    seconds = time.perf_counter() - t0
    wanted = scene.wanted()
    arm = any(n in wanted for n in ("T1", "T2", "Fs"))
    legs = any(n.startswith("Fl") for n in wanted)
    Xw = np.where([n in wanted for n in ("T1", "T2", "Fs", "Fl1", "Fl2", "Fl3", "Fl4",
                                         "Fl5", "Fl6")], X, np.nan)
    env = envelope(robot, t, q, qd, Xw, conditions(result), arm=arm, legs=legs,
                   cable=getattr(result, "cable", None), gravity=scene.gravity)
    return CaseRun(scene, robot, traj, kind, t, q, qd, Xw, result, simulation, env, seconds,
                   compensation, plan)


def judged(t: np.ndarray, plan, ran_scene) -> slice:
    """The samples of ``t (N,)`` [s] in an exposure record's judged window ``[start,
    start + length]`` (:class:`~offshore_crane.scenes.exposure.ExposurePlan`), to half a
    sample interval (the grid's times are ``m / rate`` to round-off)."""
    from offshore_crane.scenes.keys import SEA_RATE

    half = 0.5 / (SEA_RATE if ran_scene.rate is None else float(ran_scene.rate))
    return slice(int(np.searchsorted(t, plan.start - half)),
                 int(np.searchsorted(t, plan.start + plan.length + half)))


def _window(x, keep: slice, n: int):
    """``x`` restricted to the samples ``keep`` of a record of ``n``: an array whose first
    axis has the record's ``n`` samples is sliced, a dataclass field by field (a
    :class:`~offshore_crane.dynamics.Result`, a cable's or a simulation's result, a
    compensated motion and its trajectory), anything else kept."""
    import dataclasses

    if isinstance(x, np.ndarray):
        return x[keep] if x.ndim and x.shape[0] == n else x
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        changed = {f.name: _window(getattr(x, f.name), keep, n)
                   for f in dataclasses.fields(x) if f.init}
        return dataclasses.replace(x, **changed)
    return x


def _simulate(scene, robot, traj, limits: bool):
    """The scene's controlled run over its trajectory's span (as ``offshore-crane
    simulate --scene`` without flags)."""
    from offshore_crane import scenes
    from offshore_crane.simulation.rigid import simulate

    c = scene.control
    q0, qd0, _ = (x[0] for x in traj.reference(traj.t[:1]))
    q0 = q0.copy()
    if c.get("initial_error") is not None:
        q0 += np.asarray(c["initial_error"], dtype=float)
    return simulate(robot, float(traj.t[-1] - traj.t[0]), traj.reference, q0=q0, qd0=qd0,
                    controller=scenes.controller(scene, robot), gravity=scene.gravity,
                    step=c.get("step", 1e-3), integrator=c.get("integrator", "rk4"),
                    limits=limits, t0=float(traj.t[0]))


def _failed_row() -> dict:
    """The envelope columns of a failed case: NaN, 0 and empty strings."""
    from offshore_crane.studies.sizing import row_columns

    row = {}
    for name, kind in row_columns():
        row[name] = math.nan if kind == "float64" else (0 if kind == "int64" else "")
    return row


def fatal(exc: BaseException) -> bool:
    """Whether ``exc`` is the process's failure rather than its case's: out of memory, of
    file descriptors or of processes (every case after it would fail too), or not an
    :class:`Exception` at all (Ctrl-C, SIGTERM, exit). Such an error ends the sweep."""
    import errno

    return (not isinstance(exc, Exception) or isinstance(exc, MemoryError)
            or (isinstance(exc, OSError) and not isinstance(exc, OffshoreCraneError)
                and exc.errno in (errno.ENOMEM, errno.EMFILE, errno.ENFILE)))


def internal_error(exc: BaseException) -> str:
    """One line for an error a case met that is not an
    :class:`~offshore_crane.errors.OffshoreCraneError` (an ``IndexError`` deep in a
    library path: a bug, not the case's input): that it is internal and to report it,
    its message's first 160 characters, and the innermost line of the package it
    passed through."""
    import traceback
    from pathlib import PurePath

    where = ""
    for frame in reversed(traceback.extract_tb(exc.__traceback__)):
        parts = PurePath(frame.filename).parts
        if "offshore_crane" in parts:
            inner = parts[len(parts) - parts[::-1].index("offshore_crane") - 1:]
            where = f" (at {'/'.join(inner)}:{frame.lineno} in {frame.name})"
            break
    text = " ".join(str(exc).split())
    text = (text[:157] + "...") if len(text) > 160 else text or "no message"
    return (f"internal error, a bug: please report it with the scene and this case's "
            f"values: {type(exc).__name__}: {text}{where}")


def run_case(scene, params: dict, backend: str = "auto", timing: dict | None = None,
             cid: str | None = None) -> dict:
    """One case: the row of :func:`row_schema` (``case_id``, the case's values, its
    status, error and envelope). Whatever the case raises is recorded in the row
    (``status = "failed"``, ``error_type``, ``error``) instead of raised, and the row's
    other numbers are then NaN: a library error (workspace, singularity, simulation
    stopped, missing capability) with its message, any other exception as an internal
    error (:func:`internal_error`: a bug to report) — but for the process's own failures
    (:func:`fatal`: out of memory, Ctrl-C, SIGTERM), which propagate and end the sweep.
    ``timing`` (a dict), when given, receives ``compute``: the case's own computation
    (trajectory and dynamics, :attr:`CaseRun.seconds`) [s] — never part of the row, which
    holds only what is reproducible. ``cid``: the case's id when the caller has it
    (:class:`~offshore_crane.studies.sweep.grid.CaseIds`), else computed."""
    import warnings

    row = {"case_id": cid if cid is not None else case_id(scene, params), **params}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            with progress.suspended():          # the sweep's bar counts the cases
                done = record(case_scene(scene, params), backend=backend, threads=1)
        except Exception as exc:
            if fatal(exc):
                raise
            message = str(exc) if isinstance(exc, OffshoreCraneError) else internal_error(exc)
            row.update(status="failed", error_type=type(exc).__name__, error=message,
                       **_failed_row())
            done = None
    if done is not None:
        row.update(status="ok", error_type="", error="", **done.envelope.row())
    if timing is not None:
        timing["compute"] = done.seconds if done is not None else 0.0
    from offshore_crane.robot.kinematics.workspace import OffshoreCraneWarning

    row["warnings"] = sum(issubclass(w.category, OffshoreCraneWarning) for w in caught)
    return row


def run_task(payload):
    """What a worker runs: ``(scene, params, backend, case id)`` → ``(case_id, row,
    seconds, compute seconds)``: the run time of :func:`run_case` whole and of the case's
    own computation [s]."""
    scene, params, backend, cid = payload
    timing: dict = {}
    t0 = time.perf_counter()
    row = run_case(scene, params, backend, timing, cid)
    return row["case_id"], row, time.perf_counter() - t0, timing["compute"]


def row_schema(grid: Grid):
    """The ``pyarrow.Schema`` of a sweep's rows: ``case_id``, the grid's keys (float64,
    ``seed`` int64), ``status``, ``error_type``, ``error``, ``warnings``, then the
    envelope (:func:`offshore_crane.studies.sizing.row_columns`)."""
    pa = install_hint("pyarrow", "A sweep's results (Parquet)")
    from offshore_crane.studies.sizing import row_columns

    types = {"float64": pa.float64(), "int64": pa.int64(), "string": pa.string()}
    cols = [("case_id", "string")] + [(k, "int64" if k == "seed" else "float64")
                                      for k in grid.keys]
    cols += list(CASE_COLUMNS[1:]) + row_columns()
    return pa.schema([(n, types[t]) for n, t in cols])
