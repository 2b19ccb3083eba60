"""Workspace limits and the singularity policy (what is checked, and the thresholds).

Three kinds of singularity are watched, each by a dimensionless *condition number*
``κ ≥ 1`` whose product with the machine epsilon bounds the relative error it causes:

- **Stewart (leg-Jacobian) singularity**: ``κ`` is the 1-norm condition number of the
  linear system solved for the leg forces (for the fused Kane path the dimensionless
  Stewart Jacobian ``[u_i; r_i × u_i / L]``; for the explicit Kane and RNEA paths the
  leg-length Jacobian in the coordinates' rates, columns 4-6 times ``1/L``).
- **U-joint gimbal**: the leg axis along the first U-joint axis; ``κ = 1/cos θ2`` (the
  leg's spin is ``(ω⊥·n)/(u·n)`` with ``u·n = −cos θ2``).
- **Attitude coordinates** at pitch ``q5 = ±π/2``: ``κ = 1/|cos q5|``. Roll and yaw rates
  are then not defined by the angular velocity. The fused Kane path solves in twist form
  and does not divide by ``cos q5``; the explicit Kane and RNEA paths do, through ``κ``
  of their leg Jacobian.

Policy (thresholds settable per call, ``solve(..., thresholds=Thresholds(warn, error))``,
CLI ``--warn-cond``, ``--error-cond``; ``docs/numerics.md`` shows the measured errors):
``κ > warn`` warns once per run (the first sample and its value, as an
:class:`OffshoreCraneWarning`); ``κ > error`` raises :class:`SingularConfigurationError`
with the sample index, time and ``κ``. Defaults: warn 1e5 (relative error bound
``κ ε ≈ 2e-11``, forces 1e5 times as sensitive to geometry errors as at a well-conditioned
pose), error 1e8 (``κ ε ≈ 2e-8``, which no longer meets the 1e-9 agreement that the
validation promises). Measured against an extended-precision reference
(``docs/numerics.md``), the relative error of X is ``≤ c κ ε`` with worst ``c`` 0.14
(leg Jacobian), 1.24 (attitude, explicit Kane and RNEA) and, for the U-joint gimbal,
median 1.8 but up to 1.6e3 where X nearly cancels. The fused path's error does not grow
at the attitude singularity, so for it only the warning applies there.

Workspace limits (``limits=True``): each leg's length inside its stroke, the U-joint
angles and the arm joints inside the URDF limits, and the sphere centres above the
U-joint centres (a platform below the base, checked first). Violations raise
:class:`WorkspaceError` naming the joint, sample and value; ``limits=False`` (CLI
``--no-limits``) skips them. The robot description itself (masses, inertias, lengths,
strokes, the home pose) is checked on load by :mod:`offshore_crane.model.validate`.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .errors import InputError, SingularConfigurationError, WorkspaceError


class OffshoreCraneWarning(UserWarning):
    """A result computed near a singularity: valid, but check the pose."""


@dataclass(frozen=True)
class Thresholds:
    """Condition-number thresholds of the singularity policy (see module docstring).

    Attributes:
        warn: Warn above this condition number (default 1e5).
        error: Raise :class:`SingularConfigurationError` above it (default 1e8).
    """

    warn: float = 1e5
    error: float = 1e8

    def __post_init__(self):
        if not (1.0 <= self.warn <= self.error):      # also rejects NaN
            raise InputError(
                f"condition-number thresholds need 1 <= warn <= error, got warn={self.warn:g}, "
                f"error={self.error:g} (CLI --warn-cond, --error-cond)", name="thresholds")


def _when(index: int, t) -> str:
    return f"sample {index}" + ("" if t is None else f" (t = {t[index]:.4g} s)")


def check_limits(robot, q: np.ndarray, diag: dict | None, t=None) -> None:
    """Raise :class:`WorkspaceError` for the first sample outside the workspace.

    Args:
        robot: The robot.
        q: ``(N, 9)`` coordinates.
        diag: Leg diagnostics ``{"length", "theta1", "theta2"}`` ``(N, 6)``, or None
            when the legs were not evaluated.
        t: ``(N,)`` times [s] for the messages, or None.
    """
    h = robot.hybrid
    arm = h.arm
    n = arm.n
    if _all_inside(robot, q, diag):      # one vectorised test; details only on failure
        return
    _range_check(q[:, 6:6 + n], arm.lower, arm.upper, arm.joint_names,
                 ["m" if p else "rad" for p in arm.prismatic], t)
    if diag is None:
        return
    if "height" in diag:            # the most telling message first: a U-joint angle or a
        check_below_base(diag, t)   # leg length is only the symptom of an inverted platform
    legs = [f"leg{i + 1}" for i in range(6)]
    _range_check(diag["length"], h.stroke[:, 0], h.stroke[:, 1],
                 [f"{leg}_slide" for leg in legs], ["m"] * 6, t,
                 what=[f"{leg} length" for leg in legs])
    for a, key in enumerate(("theta1", "theta2")):
        _range_check(diag[key], h.ujoint_limits[:, a, 0], h.ujoint_limits[:, a, 1],
                     [f"{leg}_u{a + 1}" for leg in legs], ["rad"] * 6, t)


def _all_inside(robot, q, diag) -> bool:
    """True when every arm joint, leg length and U-joint angle is inside its limits and
    every sphere centre is above its U-joint (a handful of NumPy calls for all checks)."""
    h = robot.hybrid
    n = h.arm.n
    if diag is None:
        x, lo, hi = q[:, 6:6 + n], h.arm.lower, h.arm.upper
    else:
        table = robot.__dict__.get("_limit_table")
        if table is None:
            table = robot.__dict__["_limit_table"] = (
                # the sphere centres' heights must be > 0: smallest positive float
                np.concatenate([h.arm.lower, h.stroke[:, 0], h.ujoint_limits[:, 0, 0],
                                h.ujoint_limits[:, 1, 0], np.full(6, np.nextafter(0.0, 1.0))]),
                np.concatenate([h.arm.upper, h.stroke[:, 1], h.ujoint_limits[:, 0, 1],
                                h.ujoint_limits[:, 1, 1], np.full(6, np.inf)]))
        lo, hi = table
        step = 1 << 16                  # bounded temporaries for very long trajectories
        for a in range(0, len(q), step):
            b = a + step
            x = np.concatenate([q[a:b, 6:6 + n], diag["length"][a:b], diag["theta1"][a:b],
                                diag["theta2"][a:b], diag["height"][a:b]], axis=1)
            if not ((x >= lo) & (x <= hi)).all():
                return False
        return True
    return bool(((x >= lo) & (x <= hi)).all())


def _range_check(x, lo, hi, joints, units, t, what=None):
    """``x (N, m)`` against per-column limits ``lo, hi (m,)``."""
    bad = (x < lo) | (x > hi)
    if bad.any():
        k, j = np.argwhere(bad)[0]
        unit = units[j]
        raise WorkspaceError(
            f"{(what or joints)[j]} = {x[k, j]:.6g} {unit} at {_when(k, t)} is outside "
            f"[{lo[j]:.6g}, {hi[j]:.6g}] {unit}; change the trajectory or the robot "
            "parameters, or pass limits=False (CLI --no-limits) to study it anyway",
            joint=joints[j], index=int(k), value=float(x[k, j]))


def check_below_base(diag: dict, t=None) -> None:
    """A sphere centre at or below its U-joint centre: the platform is below the base."""
    dz = diag["height"]
    bad = dz <= 0.0
    if bad.any():
        k, i = np.argwhere(bad)[0]
        raise WorkspaceError(
            f"sphere centre S{i + 1} is {-dz[k, i]:.4g} m below its U-joint at "
            f"{_when(k, t)} (platform below the base); raise q3",
            joint=f"leg{i + 1}_slide", index=int(k), value=float(dz[k, i]))


def apply_policy(kind: str, kappa: np.ndarray, thresholds: Thresholds, t=None,
                 error: bool = True) -> None:
    """Warn once / raise for condition numbers ``kappa`` ``(N,)`` of one kind."""
    if kappa is None:
        return
    worst = kappa.max()
    if worst <= thresholds.warn:      # also False for NaN: falls through to the checks
        return
    if error and (worst > thresholds.error or not np.all(np.isfinite(kappa))):
        k = int(np.argmax(~(kappa <= thresholds.error)))
        raise SingularConfigurationError(
            f"{kind} singularity: condition number {kappa[k]:.3g} at {_when(k, t)} exceeds "
            f"{thresholds.error:.3g}; the forces there are unreliable (move the trajectory "
            "away from the singularity or raise the error threshold)",
            index=k, time=None if t is None else float(t[k]), condition=float(kappa[k]),
            kind=kind)
    if worst > thresholds.warn:
        k = int(np.argmax(kappa > thresholds.warn))
        warnings.warn(OffshoreCraneWarning(
            f"near a {kind} singularity: condition number {kappa[k]:.3g} at {_when(k, t)} "
            f"(worst {worst:.3g}) exceeds {thresholds.warn:.3g}"), stacklevel=3)


def condition_1(A: np.ndarray) -> np.ndarray:
    """1-norm condition numbers of a stack of square matrices ``(N, n, n) -> (N,)``."""
    try:
        inv = np.linalg.inv(A)
    except np.linalg.LinAlgError:
        inv = np.linalg.pinv(A)
        out = np.abs(A).sum(axis=-2).max(axis=-1) * np.abs(inv).sum(axis=-2).max(axis=-1)
        singular = np.abs(np.linalg.det(A)) == 0.0
        out[singular] = np.inf
        return out
    return np.abs(A).sum(axis=-2).max(axis=-1) * np.abs(inv).sum(axis=-2).max(axis=-1)
