"""The hanging load's inputs: the robot with its cable, the samples and their uniform
times, and the robot's motion at RK4's stage times (every half step)."""

from __future__ import annotations

import numpy as np

from offshore_crane.errors import InputError, ModelError
from offshore_crane.validation import as_samples, check_memory, uniform_step


def _quintic_basis(s):
    """The quintic Hermite basis at ``s`` in [0, 1]: six (value, d/ds, d²/ds²) triples,
    weighting y0, y0' h, y0'' h², y1'' h², y1' h, y1 in that order."""
    s2, s3, s4, s5 = s ** 2, s ** 3, s ** 4, s ** 5
    H = [(1 - 10 * s3 + 15 * s4 - 6 * s5, -30 * s2 + 60 * s3 - 30 * s4,
          -60 * s + 180 * s2 - 120 * s3),
         (s - 6 * s3 + 8 * s4 - 3 * s5, 1 - 18 * s2 + 32 * s3 - 15 * s4,
          -36 * s + 96 * s2 - 60 * s3),
         (0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5, s - 4.5 * s2 + 6 * s3 - 2.5 * s4,
          1 - 9 * s + 18 * s2 - 10 * s3),
         (0.5 * s3 - s4 + 0.5 * s5, 1.5 * s2 - 4 * s3 + 2.5 * s4, 3 * s - 12 * s2 + 10 * s3),
         (-4 * s3 + 7 * s4 - 3 * s5, -12 * s2 + 28 * s3 - 15 * s4, -24 * s + 84 * s2 - 60 * s3),
         (10 * s3 - 15 * s4 + 6 * s5, 30 * s2 - 60 * s3 + 30 * s4, 60 * s - 180 * s2 + 120 * s3)]
    return H


def quintic_hermite(t, y, yd, ydd, x) -> tuple:
    """The quintic Hermite interpolant of samples ``y, ẏ, ÿ`` ``(N, m)`` at times ``t``
    ``(N,)`` [s], evaluated at ``x`` ``(n,)`` within them: ``(y, ẏ, ÿ)`` each ``(n,)``
    when ``m = 1``, else ``(n, m)`` (error ``O(h⁶)`` in y)."""
    x = np.asarray(x, dtype=float)
    k = np.clip(np.searchsorted(t, x, side="right") - 1, 0, len(t) - 2)
    h = (t[k + 1] - t[k])[:, None]
    s = (x - t[k])[:, None] / h
    H = _quintic_basis(s)
    ends = (y[k], yd[k] * h, ydd[k] * h ** 2, ydd[k + 1] * h ** 2, yd[k + 1] * h, y[k + 1])
    out = tuple(sum(Hk[d] * e for Hk, e in zip(H, ends)) / h ** d for d in range(3))
    return tuple(o[:, 0] for o in out) if y.shape[1] == 1 else out


def _quintic_midpoints(t, q, qd, qdd, sub: int):
    """The motion at the ``2 sub − 1`` interior stage points of each interval (spacing
    ``h / 2``, ``h = Δt / sub``) by quintic Hermite interpolation of ``q, q̇, q̈`` at the
    interval's ends; returns the whole stage grid ``(2 sub (N − 1) + 1, 9)`` × 3."""
    dt = np.diff(t)[:, None, None]                         # (N-1, 1, 1)
    s = (np.arange(1, 2 * sub) / (2 * sub))[None, :, None]    # (1, 2 sub - 1, 1): interior
    H = _quintic_basis(s)
    ends = (q[:-1, None], qd[:-1, None] * dt, qdd[:-1, None] * dt ** 2, qdd[1:, None] * dt ** 2,
            qd[1:, None] * dt, q[1:, None])
    n, m = len(t), q.shape[1]
    out = []
    for d, given in enumerate((q, qd, qdd)):
        grid = np.empty((n - 1, 2 * sub, m))
        grid[:, 0] = given[:-1]                            # the samples themselves, exactly
        grid[:, 1:] = sum(Hk[d] * e for Hk, e in zip(H, ends)) / dt ** d
        out.append(np.ascontiguousarray(np.concatenate([grid.reshape(-1, m), given[-1:]])))
    return out


def uniform_times(t, N: int) -> tuple[np.ndarray, float]:
    """``(t, dt)``: ``N ≥ 2`` uniform times [s] and their spacing, checked.

    Raises:
        InputError: another shape, fewer than 2 samples, non-finite or non-uniform times.
    """
    t = np.asarray(t, dtype=float)
    if t.shape != (N,):
        raise InputError(f"t has shape {t.shape}; expected ({N},), one time per sample of q",
                         name="t")
    if N < 2:
        raise InputError("the swing is integrated over time: give at least 2 samples",
                         name="t")
    if not np.isfinite(t).all():
        k = int(np.argmax(~np.isfinite(t)))
        raise InputError(f"t[{k}] is {t[k]}: every time must be finite", name="t", index=k)
    return t, uniform_step(t, "the motion (the swing's RK4 steps along it)")


def cable_robot(robot, length=None, mass=None):
    """``robot``, or the same description with ``payload.cable_length`` and
    ``payload.mass`` overridden, checked: the robot must carry a payload on a cable.

    Raises:
        InputError: ``length ≤ 0`` or ``mass ≤ 0`` given, or a robot without cable.
    """
    if length is not None or mass is not None:
        over = {}
        if length is not None:
            if not (isinstance(length, (int, float)) and np.isfinite(length) and length > 0):
                raise InputError(f"length = {length!r} m: the cable needs a finite length "
                                 "> 0 (a welded payload is an ordinary robot: use "
                                 "offshore_crane.inverse_dynamics)", name="length")
            over["payload.cable_length"] = float(length)
        if mass is not None:
            if not (isinstance(mass, (int, float)) and np.isfinite(mass) and mass > 0):
                raise InputError(f"mass = {mass!r} kg: the hanging payload needs a finite "
                                 "mass > 0", name="mass")
            over["payload.mass"] = float(mass)
        from offshore_crane.robot import load_robot

        if robot.spec is None:
            raise InputError("length/mass overrides need a robot loaded from a description "
                             "(load_robot), not from URDF text", name="robot")
        robot = load_robot(robot.description_path, {**robot.overrides, **over})
    if robot.hybrid.cable is None:
        raise ModelError("this robot's payload is welded to arm_tip (payload.cable_length = "
                         "0): give payload.cable_length > 0 and payload.mass > 0 "
                         "(--set payload.cable_length=1.5, a scene's [payload]), or length= "
                         "and mass=", element="payload.cable_length")
    return robot


def stage_grid(t, q, qd, qdd, reference, substeps: int):
    """The robot's motion at RK4's stage times (every half step): ``(tt, Q, Qd, Qdd)``
    with ``2 substeps (N − 1) + 1`` rows (see the module docstring); the samples' own rows
    are the given ``q, qd, qdd``, only the points between them are evaluated."""
    N = len(t)
    rows = 2 * substeps * (N - 1) + 1
    check_memory(8.0 * 28 * rows, f"the swing's stage grid ({N} samples × {substeps} "
                 "substeps)", "lower substeps (--substeps) or the sample count",
                 "substeps")
    h = (t[-1] - t[0]) / (N - 1) / substeps
    tt = t[0] + np.arange(2 * substeps * (N - 1) + 1) * (0.5 * h)
    tt[::2 * substeps] = t
    if reference is None:
        return (tt, *_quintic_midpoints(t, q, qd, qdd, substeps))
    full = [np.empty((len(tt), 9)) for _ in range(3)]
    for f, given in zip(full, (q, qd, qdd)):
        f[::2 * substeps] = given                          # the samples themselves
    for j in range(1, 2 * substeps):      # one uniform set of times per stage offset: a
        times = tt[j::2 * substeps]       # sea motion's synthesis stays on its FFT path
        for name, x, f in zip(("q", "qd", "qdd"), reference(times), full):
            x = np.asarray(x, dtype=float)
            if x.shape != (N - 1, 9):
                raise InputError(f"reference(t) returned {name} of shape {x.shape}; "
                                 f"expected ({N - 1}, 9)", name="reference")
            if not np.isfinite(x).all():
                k = int(np.argmax(~np.isfinite(x).all(axis=1)))
                raise InputError(f"reference(t) returned a non-finite {name} at t = "
                                 f"{times[k]:.6g} s", name="reference", index=k)
            f[j:-1:2 * substeps] = x
    return (tt, *full)


def motion_samples(q, qd, qdd, t):
    """``(q, qd, qdd, t, dt)``: the robot's ``(N, 9)`` motion and its ``N`` uniform times
    [s], checked.

    Raises:
        InputError: bad shapes or values, sample counts that differ, non-uniform times.
    """
    q, _ = as_samples("q", q)
    qd, _ = as_samples("qd", qd)
    qdd, _ = as_samples("qdd", qdd)
    N = q.shape[0]
    if qd.shape[0] != N or qdd.shape[0] != N:
        raise InputError(f"q, qd, qdd have {N}, {qd.shape[0]}, {qdd.shape[0]} samples: give "
                         "the same number", name="qd")
    t, dt = uniform_times(t, N)
    return q, qd, qdd, t, dt
