"""Workspace limits and the singularity policy: what the kernels check, and the thresholds.

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

Policy (``Thresholds(warn, error)``, CLI ``--warn-cond``, ``--error-cond``;
``docs/numerics.md`` shows the measured errors): ``κ > warn`` warns once per kind and run
(the first sample and its value, as an :class:`OffshoreCraneWarning`); ``κ > error``
raises :class:`~offshore_crane.errors.SingularConfigurationError` with the sample index,
time and ``κ``. Defaults: warn 1e5 (relative error bound ``κ ε ≈ 2e-11``), error 1e8
(``κ ε ≈ 2e-8``, which no longer meets the 1e-9 agreement the validation promises).

Workspace limits (``limits=True``): each leg's length inside its stroke, the U-joint
angles and the arm joints inside the URDF limits, and the sphere centres above the
U-joint centres (a platform below the base). Violations raise
:class:`~offshore_crane.errors.WorkspaceError` naming the joint, sample and value.

The kernels record what they find in a small float array, the *health record*
(layout below, :func:`new_health`), filled sample by sample in compiled code or chunk by
chunk in NumPy; :func:`merge` combines the records of chunks or threads and
:func:`enforce` turns one into errors and warnings.
"""

from __future__ import annotations

import operator
import warnings
from dataclasses import dataclass

import numpy as np

from offshore_crane.conventions import ACTUATORS, ARM_JOINTS
from offshore_crane.errors import (InputError, NumericalError, SingularConfigurationError,
                      WorkspaceError)


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
        for name in ("warn", "error"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)):
                raise InputError(f"condition-number threshold {name} must be a number, got "
                                 f"{value!r} (CLI --{name}-cond)", name="thresholds")
            object.__setattr__(self, name, float(value))   # one type for the kernels
        if not (1.0 <= self.warn <= self.error):      # also rejects NaN
            raise InputError(
                f"condition-number thresholds need 1 <= warn <= error, got warn={self.warn:g}, "
                f"error={self.error:g} (CLI --warn-cond, --error-cond)", name="thresholds")


# ---------------------------------------------------------------- the health record
#: Workspace categories, in the order they are reported (the most telling first).
CATEGORIES = ("arm", "height", "stroke", "ujoint")
#: Singularity kinds (index into the record's κ blocks).
KINDS = ("leg-Jacobian", "U-joint gimbal", "attitude")
LEG_JACOBIAN, GIMBAL, ATTITUDE = 0, 1, 2
#: Slots: first non-finite input (sample, column, array 0 q / 1 qd / 2 qdd).
BAD_INPUT = 0
#: Slots: per category (sample, code, value); code = arm joint b, or leg l (height,
#: stroke), or 2 l + axis (U-joint).
VIOLATION = 3
#: Slots: first non-finite result (sample, column of X).
BAD_OUTPUT = VIOLATION + 3 * len(CATEGORIES)
#: Slots: per kind (worst κ, its sample, first sample above warn, first above error).
KAPPA = BAD_OUTPUT + 2
SIZE = KAPPA + 4 * len(KINDS)


_EMPTY = np.full(SIZE, -1.0)
_EMPTY[KAPPA::4] = -np.inf
#: The slots that hold a sample index of something found (all -1 in a clean record).
FIRST = np.array([BAD_INPUT, BAD_OUTPUT, *range(VIOLATION, BAD_OUTPUT, 3),
                   *(KAPPA + 4 * k + j for k in range(len(KINDS)) for j in (2, 3))])
#: The ``FIRST`` slots of a record's list (what :func:`is_clean` reads: 0.7 µs, against
#: 1.7 µs for NumPy's fancy indexing of a 29-value array, on every public call).
_first_slots = operator.itemgetter(*FIRST.tolist())


@dataclass(frozen=True)
class Limits:
    """Workspace limits the kernels check, as flat arrays.

    Attributes:
        arm: ``(na, 2)`` lower and upper limit of each arm joint [rad or m].
        stroke: ``(6, 2)`` shortest and longest leg length [m].
        ujoint: ``(6, 2, 2)`` [leg, axis, (lower, upper)] U-joint angles [rad].
    """

    arm: np.ndarray
    stroke: np.ndarray
    ujoint: np.ndarray


def limits_of(model) -> Limits:
    """The :class:`Limits` of a robot's hybrid model (``robot.hybrid``: the URDF's joint
    limits and the legs' strokes), as float64 arrays."""
    arm = model.arm
    return Limits(arm=np.asarray(np.stack([arm.lower, arm.upper], axis=-1), dtype=float
                                 ).reshape(arm.n, 2),
                  stroke=np.asarray(model.stroke, dtype=float),
                  ujoint=np.asarray(model.ujoint_limits, dtype=float))


def new_health() -> np.ndarray:
    """An empty health record: no sample found yet (-1), worst κ −inf."""
    return _EMPTY.copy()


def is_clean(health: np.ndarray) -> bool:
    """True when the record holds nothing to report (no bad input or result, no workspace
    violation, no κ above a threshold): every "first sample" slot still −1."""
    return max(_first_slots(health.tolist())) < 0.0


def enforce(health: np.ndarray, arrays, limits, kappa, thresholds, error_kinds, t=None):
    """Every check of a kernel's health record, in order: inputs, workspace (when
    ``limits`` is given), singularities (when ``kappa`` is given), finite results.

    A clean record (the common case) is recognised with one comparison.
    """
    if is_clean(health):
        return
    h = health.tolist()
    check_inputs(h, arrays)
    if limits is not None:
        check_limits(h, limits, arrays[0], t)
    if kappa is not None:
        check_singularities(h, kappa, thresholds, t, error_kinds)
    check_outputs(h, ACTUATORS, arrays, t)


def merge(records) -> np.ndarray:
    """One record from those of consecutive chunks or threads (any order).

    ``first`` slots keep the smallest sample index found; worst κ the largest value.
    """
    out = new_health()
    groups = [(BAD_INPUT, 3), *((VIOLATION + 3 * c, 3) for c in range(len(CATEGORIES))),
              (BAD_OUTPUT, 2)]
    for h in records:
        for start, width in groups:
            if h[start] >= 0 and (out[start] < 0 or h[start] < out[start]):
                out[start:start + width] = h[start:start + width]
        for kind in range(len(KINDS)):
            s = KAPPA + 4 * kind
            if h[s] > out[s] or (np.isnan(h[s]) and not np.isnan(out[s])):
                out[s:s + 2] = h[s:s + 2]
            for slot in (s + 2, s + 3):
                if h[slot] >= 0 and (out[slot] < 0 or h[slot] < out[slot]):
                    out[slot] = h[slot]
    return out


def _when(index: int, t) -> str:
    return f"sample {index}" + ("" if t is None else f" (t = {t[index]:.4g} s)")


def check_inputs(health: np.ndarray, arrays) -> None:
    """Raise :class:`InputError` for the first non-finite input the kernel met.

    Args:
        arrays: the ``(N, 9)`` arrays ``(q, qd, qdd)`` it read.
    """
    if health[BAD_INPUT] < 0:
        return
    k, j, which = (int(x) for x in health[BAD_INPUT:BAD_INPUT + 3])
    name = ("q", "qd", "qdd")[which]
    raise InputError(f"{name}[{k}, {j}] is {arrays[which][k, j]} (sample {k}, column "
                     f"{j + 1}); every value must be finite", name=name, index=k)


def check_limits(health: np.ndarray, limits: Limits, q: np.ndarray, t=None,
                 pose: str | None = None) -> None:
    """Raise :class:`WorkspaceError` for the first limit violation, category by category
    in :data:`CATEGORIES` order (a platform below the base is named before the U-joint
    angles and leg lengths it distorts).

    Args:
        limits: :class:`Limits` of the robot.
        q: ``(N, 9)`` coordinates (for the arm's messages).
        t: ``(N,)`` times [s] for the message, or None.
        pose: For one pose a user gave (e.g. ``"--pose"``): the message starts with this
            name, names no sample and asks for a pose inside the workspace; None: a
            motion's samples.
    """
    if pose is None:
        head = ""
        hint = "change the trajectory or the robot, or study it with --no-limits (limits=False)"
    else:
        head, hint = f"{pose}: ", "give a pose inside the workspace"

    def when(k: int) -> str:
        return "" if pose is not None else f" at {_when(k, t)}"

    for c, category in enumerate(CATEGORIES):
        s = VIOLATION + 3 * c
        if health[s] < 0:
            continue
        k, code, value = int(health[s]), int(health[s + 1]), float(health[s + 2])
        if category == "height":
            raise WorkspaceError(
                f"{head}sphere centre S{code + 1} is {-value:.4g} m below its U-joint"
                f"{when(k)} (platform below the base); raise q3",
                joint=f"leg{code + 1}_slide", index=k, value=value)
        if category == "arm":
            joint, what, unit = ARM_JOINTS[code], ARM_JOINTS[code], ("rad", "rad", "m")[code]
            lo, hi = limits.arm[code]
        elif category == "stroke":
            joint, what, unit = f"leg{code + 1}_slide", f"leg{code + 1} length", "m"
            lo, hi = limits.stroke[code]
        else:
            leg, axis = divmod(code, 2)
            joint = what = f"leg{leg + 1}_u{axis + 1}"
            unit = "rad"
            lo, hi = limits.ujoint[leg, axis]
        raise WorkspaceError(
            f"{head}{what} = {value:.6g} {unit}{when(k)} is outside [{lo:.6g}, {hi:.6g}] "
            f"{unit}; {hint}", joint=joint, index=None if pose else k, value=value)


def check_singularities(health: np.ndarray, kappa: dict, thresholds: Thresholds, t=None,
                        error_kinds=(LEG_JACOBIAN, GIMBAL)) -> None:
    """Apply the policy: :class:`SingularConfigurationError` for the first sample above
    ``thresholds.error`` (or non-finite κ) of a kind in ``error_kinds``; one warning per
    kind above ``thresholds.warn``.

    Args:
        kappa: ``{kind index: (N,) condition numbers}`` for the messages.
    """
    for kind in error_kinds:
        s = KAPPA + 4 * kind
        if health[s + 3] >= 0:
            k = int(health[s + 3])
            value = float(kappa[kind][k])
            raise SingularConfigurationError(
                f"{KINDS[kind]} singularity: condition number {value:.3g} at {_when(k, t)} "
                f"exceeds {thresholds.error:.3g}: the forces there are unreliable; move the "
                "trajectory away or raise the error threshold",
                index=k, time=None if t is None else float(t[k]), condition=value,
                kind=KINDS[kind])
    for kind in range(len(KINDS)):
        s = KAPPA + 4 * kind
        if health[s + 2] >= 0:
            k = int(health[s + 2])
            warnings.warn(OffshoreCraneWarning(
                f"near a {KINDS[kind]} singularity: condition number {kappa[kind][k]:.3g} at "
                f"{_when(k, t)} (worst {health[s]:.3g}) exceeds {thresholds.warn:.3g}"),
                stacklevel=4)


def check_outputs(health: np.ndarray, names, arrays, t=None) -> None:
    """Raise :class:`NumericalError` for the first non-finite actuator force.

    Args:
        names: Actuator names of X's columns.
        arrays: ``(q, qd, qdd)``, to state the inputs' magnitude.
    """
    if health[BAD_OUTPUT] < 0:
        return
    k, j = int(health[BAD_OUTPUT]), int(health[BAD_OUTPUT + 1])
    scale = max(float(np.abs(x[k]).max()) for x in arrays)
    raise NumericalError(
        f"{names[j]} is not finite at {_when(k, t)}: the dynamics overflowed (largest input "
        f"|q|, |qd|, |qdd| there {scale:.3g}); check the inputs' units and the robot's "
        "parameters", index=k, name=names[j])


# ----------------------------------------------------------- recording, vectorised
# The NumPy drivers (and the RNEA reference) record what a chunk of samples shows in the
# health record with these; the compiled drivers do the same sample by sample.
def _first_hit(mask: np.ndarray):
    """``(row, column)`` of the first True of a 2-D mask (row-major), or None."""
    rows = mask.any(axis=1)
    if not rows.any():
        return None
    k = int(np.argmax(rows))
    return k, int(np.argmax(mask[k]))


def _record(health, slot, offset, hit, values=None):
    """Record the first hit of a 2-D mask in ``health[slot:]`` if none is there yet."""
    if health[slot] >= 0 or hit is None:
        return
    k, j = hit
    health[slot] = offset + k
    health[slot + 1] = j
    if values is not None:
        health[slot + 2] = values[k, j]


def _policy(health, kind, kappa, offset, opts):
    """Worst κ, its sample, first above warn and first above error (or not finite)."""
    s = KAPPA + 4 * kind
    with np.errstate(invalid="ignore"):
        k = int(np.argmax(np.where(np.isnan(kappa), np.inf, kappa)))
        if not health[s] >= kappa[k] or np.isnan(kappa[k]):
            health[s], health[s + 1] = kappa[k], offset + k
        for slot, above in ((s + 2, kappa > opts.warn), (s + 3, ~(kappa <= opts.error))):
            if health[slot] < 0 and above.any():
                health[slot] = offset + int(np.argmax(above))


def check_finite(arrays, offset, health):
    """Record the first non-finite value of the ``(n, 9)`` ``arrays`` (q, qd, qdd)."""
    if health[BAD_INPUT] >= 0:
        return
    for which, x in enumerate(arrays):
        hit = _first_hit(~np.isfinite(x))
        if hit is not None:
            health[BAD_INPUT:BAD_INPUT + 3] = offset + hit[0], hit[1], which
            return


def record_limits(health: np.ndarray, limits: Limits, q: np.ndarray, length, height, theta,
                  offset: int = 0, legs: bool = True) -> None:
    """Record the first violation of each limit category in a chunk of samples: the arm
    joints of ``q`` ``(n, 9)``, and with ``legs`` the sphere heights above the U-joints
    ``height`` ``(n, 6)`` [m] (≤ 0: platform below the base), the leg lengths ``length``
    ``(n, 6)`` [m] and the U-joint angles ``theta`` ``(n, 6, 2)`` [rad]."""
    na = limits.arm.shape[0]
    x = q[:, 6:6 + na]
    _record(health, VIOLATION, offset,
            _first_hit((x < limits.arm[:, 0]) | (x > limits.arm[:, 1])), x)
    if legs:
        c = VIOLATION + 3
        _record(health, c, offset, _first_hit(height <= 0.0), height)
        _record(health, c + 3, offset, _first_hit((length < limits.stroke[:, 0])
                                                  | (length > limits.stroke[:, 1])), length)
        th = theta.reshape(len(q), 12)
        lo, hi = limits.ujoint[..., 0].reshape(12), limits.ujoint[..., 1].reshape(12)
        _record(health, c + 6, offset, _first_hit((th < lo) | (th > hi)), th)


def record_chunk(X, cond, length, cos2, height, theta, q, offset, opts, limits, kappa,
                 health):
    """Record a chunk's condition numbers, workspace violations and non-finite results.

    Args:
        X: ``(n, 9)`` its actuator forces (the absent arm columns NaN).
        cond: ``(n,)`` the leg-force systems' condition numbers, or None.
        length, cos2, height: ``(n, 6)`` leg lengths [m], cos θ2, heights of S above P [m].
        theta: ``(n, 6, 2)`` U-joint angles [rad] (read with ``opts.limits``), or None.
        q: ``(n, 9)`` the chunk's coordinates; ``offset``: index of its first sample.
        opts: with ``legs``, ``conditioning``, ``limits``, ``warn``, ``error``.
        limits: :class:`Limits`.
        kappa: ``(3, n)`` view of the output condition numbers, or None.
    """
    na = limits.arm.shape[0]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if opts.conditioning:
            kappa[2] = 1.0 / np.abs(np.cos(q[:, 4]))
            _policy(health, ATTITUDE, kappa[2], offset, opts)
            if opts.legs:
                kappa[0] = cond
                kappa[1] = 1.0 / cos2.min(axis=1)
                _policy(health, LEG_JACOBIAN, kappa[0], offset, opts)
                _policy(health, GIMBAL, kappa[1], offset, opts)
            else:
                kappa[:2] = np.nan
        if opts.limits:
            record_limits(health, limits, q, length, height, theta, offset, opts.legs)
        cols = list(range(na)) + (list(range(3, 9)) if opts.legs else [])
        hit = _first_hit(~np.isfinite(X[:, cols]))
        _record(health, BAD_OUTPUT, offset, hit and (hit[0], cols[hit[1]]))
