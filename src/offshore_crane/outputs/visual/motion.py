"""The motion to draw: where it comes from, its values at the frames' times, and the
forces and sway that go with it.

Sources:

- a scene or a trajectory (``--scene``, ``--trajectory table1|sea|F.csv``): through
  :func:`offshore_crane.scenes.load_trajectory`; rates and accelerations analytic where
  the source has them;
- a run's CSV (``--from F.csv``): read by :func:`read_run`. Accepted: the CSV of
  ``offshore-crane simulate --out`` (``t_s, q1..q9, q1_ref..q9_ref, T1_Nm..Fl6_N``), a
  trajectory CSV (``t_s, q1..q9`` with optional ``qd1..qd9, qdd1..qdd9``, e.g. from
  ``offshore-crane motion --out``), and either with the hanging load's
  ``phi1_rad, phi2_rad, tension_N``. ``offshore-crane id --out`` writes forces only (no
  q): give its trajectory with ``--trajectory`` instead.

Frames: frame k shows the motion at ``t0 + k · speed / fps`` (speed 2: twice real time),
evaluated exactly where the source is analytic and linearly interpolated between samples
otherwise (positions, forces, sway alike).

The hanging load (issue 14) plugs in at one place, :func:`hanging_load`: when the robot
description's ``payload.cable_length`` is > 0, the sway and the forces come from
``offshore_crane.dynamics.cable.inverse_dynamics`` (or from the run's CSV), never a load drawn
welded.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from offshore_crane.errors import InputError
from offshore_crane.outputs.visual.runs import (FORCE_COLUMNS, KNOWN_COLUMNS,  # noqa: F401
                                                SWAY_COLUMNS)
from offshore_crane.validation import check_memory


@dataclass(frozen=True)
class Motion:
    """A sampled motion with what is known along it.

    Attributes:
        name: Where it comes from (for captions).
        t: ``(N,)`` [s], strictly increasing.
        q: ``(N, 9)`` [m, rad].
        qd, qdd: ``(N, 9)`` rates and accelerations, or None (a run's CSV without them).
        X: ``(N, 9)`` actuator forces [N·m, N], or None.
        sway: ``(N, 2)`` sway angles (φ1, φ2) [rad] of a hanging load, or None.
        source: ``source(t (n,)) -> (q, qd, qdd)`` exact at any time, or None.
        water: Height of the still water line in the base frame [m] (model scale), or
            None (no sea).
        load: ``(N, 3)`` the payload from the tip [m], base axes, of a cable of varying
            length (a winch, an elastic cable), or None.
        slack: ``(N,)`` bool, the cable slack (with ``load``), or None.
        deck: ``(N, 3)`` the centre of a lift's deck under the load [m], or None.
    """

    name: str
    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray | None = None
    qdd: np.ndarray | None = None
    X: np.ndarray | None = None
    sway: np.ndarray | None = None
    source: object = None
    water: float | None = None
    load: np.ndarray | None = None
    slack: np.ndarray | None = None
    deck: np.ndarray | None = None


def from_trajectory(traj) -> Motion:
    """A :class:`~offshore_crane.motion.trajectories.Trajectory` as a :class:`Motion`."""
    return Motion(traj.name, traj.t, traj.q, traj.qd, traj.qdd, source=traj.source)


def read_run(path, option: str = "--from", **kw) -> Motion:
    """Read a run's CSV (see the module docstring for the accepted files) as it streams:
    :func:`offshore_crane.outputs.visual.runs.read_fields` (``option`` is the command-line
    option that named it, for the messages; ``header_check``, ``memory``: see there).

    Raises:
        TrajectoryError: the file is missing, a directory or a device, unreadable, lacks
            ``t_s`` or one of q1..q9 (an ``offshore-crane id`` CSV: named as such), has an
            unknown column, a row of the wrong length, a non-numeric or non-finite cell
            (naming the line and column), or a time that does not increase.
    """
    from offshore_crane.outputs.visual.runs import read_fields

    return Motion(*read_fields(path, option, **kw))


#: Numbers held per frame: its time, and q, q̇, q̈, X, the sway and a varying cable's
#: load, slack and deck (42 columns) interpolated at it with two temporaries each.
FRAME_COLUMNS = 1 + 3 * 42


def frame_times(motion: Motion, fps: float, speed: float = 1.0,
                duration: float | None = None) -> np.ndarray:
    """Times [s] of the motion shown by each frame: ``t0 + k · speed / fps``.

    Args:
        fps: Frames per second of the picture (> 0).
        speed: Motion seconds per picture second (> 0).
        duration: Motion time to show from the start [s] (default: all of it).

    Raises:
        InputError: fps, speed or duration not finite and > 0, a duration longer than
            the motion, or more frames than memory holds
            (:func:`offshore_crane.validation.check_memory`).
    """
    for name, value in (("--fps", fps), ("--speed", speed)):
        if not (isinstance(value, (int, float, np.floating)) and np.isfinite(value)
                and value > 0):
            raise InputError(f"{name} {value!r} must be a finite number > 0", name=name)
    t0, t1 = float(motion.t[0]), float(motion.t[-1])
    if duration is not None:
        if not (np.isfinite(duration) and duration > 0):
            raise InputError(f"--duration {duration!r} s must be a finite number > 0",
                             name="--duration")
        if duration > (t1 - t0) * (1 + 1e-12):
            raise InputError(f"--duration {duration:g} s is longer than the motion "
                             f"({t1 - t0:g} s)", name="--duration")
        t1 = t0 + duration
    frames = np.floor((t1 - t0) * fps / speed * (1 + 1e-12)) + 1.0
    check_memory(8.0 * FRAME_COLUMNS * frames, f"{frames:.15g} frames of {t1 - t0:g} s at "
                 f"--fps {fps:g} and --speed {speed:g}", "raise --speed, lower --fps or "
                 "shorten --duration", "--speed")
    return t0 + np.arange(int(frames)) * (speed / fps)


def _lerp(t: np.ndarray, y: np.ndarray, times: np.ndarray) -> np.ndarray:
    """Linear interpolation of the rows of ``y (N, m)`` at ``times`` (within ``t``)."""
    i = np.clip(np.searchsorted(t, times, side="right") - 1, 0, len(t) - 2)
    s = ((times - t[i]) / (t[i + 1] - t[i]))[:, None]
    return y[i] * (1.0 - s) + y[i + 1] * s


def at(motion: Motion, times: np.ndarray) -> Motion:
    """The motion at ``times`` (within its span): exact with an analytic source, linear
    between samples otherwise."""
    times = np.asarray(times, dtype=float)
    if motion.source is not None:
        q, qd, qdd = motion.source(times)
    else:
        q = _lerp(motion.t, motion.q, times)
        qd = None if motion.qd is None else _lerp(motion.t, motion.qd, times)
        qdd = None if motion.qdd is None else _lerp(motion.t, motion.qdd, times)
    X = None if motion.X is None else _lerp(motion.t, motion.X, times)
    sway = None if motion.sway is None else _lerp(motion.t, motion.sway, times)
    load = None if motion.load is None else _lerp(motion.t, motion.load, times)
    slack = None if motion.slack is None else _held(motion.t, motion.slack, times)
    deck = None if motion.deck is None else _lerp(motion.t, motion.deck, times)
    return Motion(motion.name, times, q, qd, qdd, X, sway, motion.source, motion.water,
                  load, slack, deck)


def _held(t: np.ndarray, flags: np.ndarray, times: np.ndarray) -> np.ndarray:
    """``flags (N,)`` at ``times``: each sample's held over its interval (as
    :func:`offshore_crane.dynamics.cable.lift.time_slack` counts it)."""
    i = np.clip(np.searchsorted(t, times, side="right") - 1, 0, len(t) - 1)
    return np.asarray(flags, dtype=bool)[i]


def with_rates(motion: Motion, order: int = 4) -> Motion:
    """``motion`` with rates and accelerations (finite differences of the samples when it
    has none, :func:`offshore_crane.motion.trajectories.finite_difference`)."""
    if motion.qd is not None and motion.qdd is not None:
        return motion
    from offshore_crane.motion.trajectories import finite_difference

    qd, qdd = finite_difference(motion.t, motion.q, order=order)
    return replace(motion, qd=qd, qdd=qdd)


def cable_length(robot) -> float:
    """The description's ``payload.cable_length`` [m] (0: the payload is welded)."""
    return float(getattr(robot.spec, "cable_length", 0.0) or 0.0) if robot.spec else 0.0


def varying_cable(robot, result, name: str, water: float | None = None,
                  deck=None) -> Motion:
    """The motion of a scene whose cable varies (a winch, an elastic cable, a
    compensation: :func:`offshore_crane.scenes.run_swing`'s ``cable``, a
    :class:`~offshore_crane.dynamics.cable.CableResult` with a hoist or an
    :class:`~offshore_crane.dynamics.cable.ElasticResult`): the robot's motion as run (the
    compensated arm's), X, and the payload from the tip with the slack samples; ``deck``
    a lift's ``deck(t) -> (z, ż, z̈)`` (:func:`offshore_crane.scenes.lift_deck`), drawn
    under the load where it rests (a lift-off's start, a set-down's contact)."""
    from offshore_crane.dynamics.cable.tip import payload_positions, tip_positions

    load = payload_positions(robot, result) - tip_positions(robot, result.q)[0]
    plate = None
    if deck is not None:
        at_rest = getattr(result.event, "t_contact", result.t[0])
        k = 0 if at_rest != at_rest else int(np.searchsorted(result.t, at_rest))
        payload = payload_positions(robot, result)
        plate = np.column_stack([np.full(len(result.t), payload[k, 0]),
                                 np.full(len(result.t), payload[k, 1]),
                                 deck(result.t)[0]])
    return Motion(name, result.t, result.q, result.qd, result.qdd, result.X, water=water,
                  load=load, slack=np.asarray(result.slack, dtype=bool), deck=plate)


def hanging_load(robot, motion: Motion, gravity, options: dict | None = None) -> Motion:
    """The one place where the hanging load (issue 14) enters the pictures.

    Without a cable (``payload.cable_length = 0``) the motion is returned as it is. With
    one, a motion that carries its sway (a run's CSV with ``phi1_rad, phi2_rad``) is kept;
    otherwise the sway and the forces come from
    ``offshore_crane.dynamics.cable.inverse_dynamics(robot, q, qd, qdd, gravity=..., t=t)`` (``.sway
    (N, 2)``, ``.X (N, 9)``), with the motion's analytic source at RK4's stages when it has
    one, and ``options`` (a scene's ``[cable]``: initial sway, substeps, slack policy).

    Raises:
        The errors of :func:`offshore_crane.dynamics.cable.inverse_dynamics` (a slack cable, a
        non-uniform time axis, ...).
    """
    L = cable_length(robot)
    if L <= 0.0 or motion.sway is not None or motion.load is not None:
        return motion
    from offshore_crane.dynamics import cable

    full = with_rates(motion)
    run = cable.inverse_dynamics(robot, full.q, full.qd, full.qdd, gravity=gravity,
                                 reference=motion.source, **(options or {}), t=full.t)
    return replace(motion, sway=np.asarray(run.sway), X=np.asarray(run.X))


def forces(robot, motion: Motion, gravity, leg_model: str = "full") -> Motion:
    """``motion`` with its actuator forces: kept when it has them, else computed by the
    inverse dynamics (:func:`offshore_crane.dynamics.solve`, Kane) on its samples."""
    if motion.X is not None:
        return motion
    from offshore_crane.dynamics import solve

    full = with_rates(motion)
    X = solve(robot, full.q, full.qd, full.qdd, gravity=gravity, leg_model=leg_model,
              t=full.t).X
    return replace(motion, X=np.asarray(X))


#: ``--color-by`` choices.
COLOR_BY = ("force", "utilisation")


def leg_values(robot, X: np.ndarray, color_by: str) -> tuple[np.ndarray, float]:
    """What colours the legs: ``(v (F, 6), scale)``.

    ``force``: ``v = Fl / max |Fl|`` over the frames, in [-1, 1] (pull < 0 < push),
    ``scale = max |Fl|`` [N]. ``utilisation``: ``v = Fl / push_max`` where Fl > 0 and
    ``|Fl| / pull_max`` where Fl < 0 (the robot description's capacities), ``scale`` the
    largest utilisation over the frames.

    Raises:
        InputError: unknown ``color_by``; utilisation without finite capacities for the
            legs.
    """
    Fl = X[:, 3:9]
    if color_by == "force":
        scale = float(np.abs(Fl).max())
        return (Fl / scale if scale > 0 else np.zeros_like(Fl)), scale
    if color_by == "utilisation":
        caps = robot.capacities
        push, pull = np.asarray(caps.push_max)[3:9], np.asarray(caps.pull_max)[3:9]
        if not (np.all(np.isfinite(push)) and np.all(np.isfinite(pull))):
            raise InputError("--color-by utilisation needs the legs' capacities "
                             "(actuators.Fl.push_max and pull_max in the robot description "
                             "or the scene's [actuators]); this robot gives none: use "
                             "--color-by force", name="--color-by")
        with np.errstate(divide="ignore", invalid="ignore"):
            u = np.where(Fl >= 0, Fl / push, -Fl / pull)
        u = np.nan_to_num(u, nan=0.0, posinf=np.inf)
        return u, float(u.max())
    raise InputError(f"--color-by {color_by!r}: choose {' or '.join(COLOR_BY)}",
                     name="--color-by")
