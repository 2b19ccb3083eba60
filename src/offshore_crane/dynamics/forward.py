"""Equations of motion of the closed-loop robot in its independent coordinates.

``M(q) q̈ + h(q, q̇) = A(q) X`` with q the 9 coordinates of ``docs/conventions.md`` (no
constraint drift: the loops are closed by construction), where

- ``M`` ``(N, 9, 9)`` [kg, kg·m, kg·m²] is Kane's generalized inertia, formed directly from
  every body's partial velocities (:func:`.formulas.explicit_sample`):
  ``M_rs = Σ_bodies m v_r · v_s + ω_r · I ω_s``; symmetric positive definite away from the
  attitude-coordinate singularity ``q5 = ±π/2``;
- ``h`` ``(N, 9)`` [N, N·m] gathers the velocity and gravity terms: Kane's ``B`` of the
  inverse dynamics evaluated at ``q̈ = 0`` (so ``M q̈ + h = B``, the right-hand side of the
  paper's ``A X = B``);
- ``A`` ``(N, 9, 9)`` maps the actuator forces X to generalized forces:
  ``A = [[0, Jᵀ], [I3, 0]]`` with ``J`` the leg-length Jacobian (``l̇ = J q̇[:6]``).

Forward dynamics solves ``M q̈ = A X − h`` by Cholesky. For a robot without arm only the
first six coordinates move (q̈7..q̈9 NaN). ``method="pinocchio"`` gives the same
accelerations from Pinocchio's constraint dynamics on the equivalent tree
(:mod:`offshore_crane.reference.constrained`), an independent check.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from offshore_crane.conventions import COORDINATES, GRAVITY
from offshore_crane.errors import InputError, SingularConfigurationError
from offshore_crane.robot.kinematics import workspace as ws
from offshore_crane.validation import as_gravity, as_samples
from offshore_crane.dynamics.constants import robot_arrays
from offshore_crane.dynamics.runtime import compiled_kernels, run_threaded
from offshore_crane.validation import thread_count

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from offshore_crane.robot import Robot

FORWARD_METHODS = ("kane", "pinocchio")


class Terms(NamedTuple):
    """Which parts of ``M q̈ + h = A X`` one pass of the forward kernel writes (the
    kernel's four flags, in its argument order)."""

    qdd: bool = False
    M: bool = False
    h: bool = False
    A: bool = False


ACCELERATIONS = Terms(qdd=True)


@dataclass
class EquationsOfMotion:
    """``M q̈ + h = A X`` at N samples (unrequested parts None).

    Attributes:
        M: ``(N, 9, 9)`` generalized inertia [kg, kg·m, kg·m²].
        h: ``(N, 9)`` velocity and gravity terms [N, N·m].
        A: ``(N, 9, 9)`` actuation matrix (generalized forces per unit X).
        qdd: ``(N, 9)`` accelerations [m/s², rad/s²] for the given X.
        attitude, gimbal: ``(N,)`` condition numbers ``1/|cos q5|`` and worst
            ``1/cos θ2`` (with ``checks``).
    """

    M: np.ndarray | None = None
    h: np.ndarray | None = None
    A: np.ndarray | None = None
    qdd: np.ndarray | None = None
    attitude: np.ndarray | None = None
    gimbal: np.ndarray | None = None


#: Names of q̈'s columns, for messages.
_QDD_NAMES = tuple(f"q̈{c_[1:]}" for c_ in COORDINATES)
_DEFAULT_THRESHOLDS = ws.Thresholds()


def _run(robot, q, qd, X, gravity, terms: Terms, *, checks: bool = True, limits: bool = True,
         thresholds: ws.Thresholds = _DEFAULT_THRESHOLDS, t=None,
         threads: int = 1) -> EquationsOfMotion:
    c = compiled_kernels()
    q, single = as_samples("q", q, finite=False)
    N = q.shape[0]
    qd = np.zeros_like(q) if qd is None else as_samples("qd", qd, finite=False)[0]
    Xa = np.zeros_like(q) if X is None else as_samples("X", X, finite=False)[0]
    for name, arr in (("qd", qd), ("X", Xa)):
        if arr.shape[0] != N:
            raise InputError(f"{name} has {arr.shape[0]} samples, q has {N}", name=name)
    g = as_gravity(gravity)
    arrays = robot_arrays(robot)
    na = robot.hybrid.arm.n
    if X is not None and na < 3:
        Xa = Xa.copy()
        Xa[:, na:3] = 0.0                     # actuators that do not exist
    out = dict(qdd=np.empty((N, 9)) if terms.qdd else np.empty((1, 9)),
               M=np.zeros((N, 9, 9)) if terms.M else np.empty((1, 9, 9)),
               h=np.zeros((N, 9)) if terms.h else np.empty((1, 9)),
               A=np.zeros((N, 9, 9)) if terms.A else np.empty((1, 9, 9)))
    kappa = np.empty((3, N)) if checks else np.empty((3, 1))

    def run(start, stop, health):
        c.forward(arrays.flat, arrays.layout, arrays.prismatic, q, qd, Xa, g, *terms,
                  checks, limits, thresholds.warn, thresholds.error, start, stop, out["qdd"],
                  out["M"], out["h"], out["A"], kappa, health)

    if N == 1:                                    # one sample: no thread machinery
        health = ws.new_health()
        run(0, 1, health)
    else:
        health = run_threaded(run, N, thread_count(threads))
    if ws.is_clean(health):                    # the common case: nothing to report
        return _result(out, terms, kappa if checks else None)
    ws.check_inputs(health, (q, qd, Xa))
    if limits:
        ws.check_limits(health, arrays.limits, q, t)
    att_error = health[ws.KAPPA + 4 * ws.ATTITUDE + 3]
    if att_error >= 0 and not checks:           # M singular (Cholesky) without κ measured
        k = int(att_error)
        value = float(1.0 / abs(np.cos(q[k, 4])))
        raise SingularConfigurationError(
            f"attitude singularity: the mass matrix is singular at sample {k} (q5 = "
            f"{q[k, 4]:.6g} rad, 1/|cos q5| = {value:.3g}); the roll and yaw rates are not "
            "defined there: keep |q5| away from π/2", index=k, condition=value,
            kind="attitude")
    if checks:
        ws.check_singularities(health, kappa, thresholds, t, (ws.GIMBAL, ws.ATTITUDE))
    ws.check_outputs(health, _QDD_NAMES, (q, qd, Xa), t)
    return _result(out, terms, kappa if checks else None)


def _result(out: dict, wanted: Terms, kappa) -> EquationsOfMotion:
    res = EquationsOfMotion(**{k: (v if flag else None)
                               for (k, v), flag in zip(out.items(), wanted)})
    if kappa is not None:
        res.attitude, res.gimbal = kappa[2], kappa[1]
    return res


_G0 = np.asarray(GRAVITY, dtype=float)


_NDARRAY, _SHAPE9, _STRIDES9, _FLOAT64 = np.ndarray, (9,), (8,), np.dtype(np.float64)


def _is_state(x) -> bool:
    """``x`` is a contiguous ``(9,)`` float64 array, what the one-sample kernel takes
    (checked with identities and tuple comparisons, cheaper than ``dtype ==`` and
    ``flags``; an array that fails goes the general way)."""
    return (x.__class__ is _NDARRAY and x.shape == _SHAPE9 and x.strides == _STRIDES9
            and x.dtype is _FLOAT64)


def _lean(robot, q, qd, X, gravity):
    """One sample with the default options and a clean health record, with as little
    Python as possible (a controller's or a user's per-step call: one compiled call of
    ten arguments, :func:`~offshore_crane.dynamics.compiled` ``forward_one``); None when
    anything is unusual (then the general path runs, and reports)."""
    if not (_is_state(q) and _is_state(qd) and _is_state(X)):
        return None
    arrays = robot_arrays(robot)
    if arrays.prismatic.shape[0] != 3:
        return None
    g = _G0 if gravity is GRAVITY else as_gravity(gravity)
    qdd = np.empty(9)
    t = _DEFAULT_THRESHOLDS
    if compiled_kernels().forward_one(arrays.flat, arrays.layout, arrays.prismatic, q, qd, X,
                                      g, t.warn, t.error, qdd):
        return qdd
    return None


def mass_matrix(robot: Robot, q: ArrayLike, **options) -> np.ndarray:
    """Generalized inertia ``M`` ``(N, 9, 9)`` [kg, kg·m, kg·m²] at ``q`` ``(N, 9)``
    [m, rad] (symmetric positive definite; a ``(9,)`` q gives ``(9, 9)``). ``options``:
    ``checks``, ``limits``, ``thresholds``, ``t``, ``threads``."""
    single = np.ndim(q) == 1
    M = _run(robot, q, None, None, GRAVITY, Terms(M=True), **options).M
    return M[0] if single else M


def bias_forces(robot: Robot, q: ArrayLike, qd: ArrayLike, gravity: ArrayLike = GRAVITY,
                **options) -> np.ndarray:
    """Velocity and gravity terms ``h`` ``(N, 9)`` [N, N·m] at ``q``, ``qd`` ``(N, 9)``
    [m, rad, m/s, rad/s] under ``gravity`` ``(3,)`` [m/s²]: ``M q̈ + h = A X``."""
    single = np.ndim(q) == 1
    h = _run(robot, q, qd, None, gravity, Terms(h=True), **options).h
    return h[0] if single else h


def actuation_matrix(robot: Robot, q: ArrayLike, **options) -> np.ndarray:
    """``A`` ``(N, 9, 9)`` at ``q`` ``(N, 9)``: generalized forces per unit actuator force,
    ``[[0, Jᵀ], [I3, 0]]`` (rows q1..q9, columns T1, T2, Fs, Fl1..Fl6; dimensionless or
    [m] / [1/m] as the row and column units require)."""
    single = np.ndim(q) == 1
    A = _run(robot, q, None, None, GRAVITY, Terms(A=True), **options).A
    return A[0] if single else A


def equations_of_motion(robot: Robot, q: ArrayLike, qd: ArrayLike,
                        gravity: ArrayLike = GRAVITY, **options) -> EquationsOfMotion:
    """``M``, ``h`` and ``A`` in one pass (see the module docstring)."""
    return _run(robot, q, qd, None, gravity, Terms(M=True, h=True, A=True), **options)


def forward_dynamics(robot: Robot, q: ArrayLike, qd: ArrayLike, X: ArrayLike,
                     gravity: ArrayLike = GRAVITY, method: str = "kane",
                     **options) -> np.ndarray:
    """Accelerations ``q̈`` ``(N, 9)`` [m/s², rad/s²] under actuator forces X.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q, qd: ``(N, 9)`` (or ``(9,)``) coordinates [m, rad] and rates.
        X: ``(N, 9)`` actuator forces ``[T1, T2 [N·m], Fs, Fl1..Fl6 [N]]``.
        gravity: ``(3,)`` [m/s²] in the base frame.
        method: ``"kane"`` (the equations above) or ``"pinocchio"`` (Pinocchio's
            constraint dynamics on the equivalent tree, an independent check).
        **options: ``checks``, ``limits``, ``thresholds``, ``t``, ``threads`` (kane).

    Returns:
        ``(N, 9)`` (``(9,)`` for one sample); ``inverse_dynamics(q, qd, q̈) = X``.

    Raises:
        InputError, WorkspaceError, SingularConfigurationError, NumericalError.
    """
    if method not in FORWARD_METHODS:
        raise InputError(f"unknown method {method!r}: use one of {', '.join(FORWARD_METHODS)}",
                         name="method")
    if not options and method == "kane":
        qdd = _lean(robot, q, qd, X, gravity)
        if qdd is not None:
            return qdd
    single = np.ndim(q) == 1
    if method == "pinocchio":
        from offshore_crane.reference.constrained import forward_dynamics as pin_fd

        robot_arrays(robot)                 # refuses a payload on a cable, like kane

        out = pin_fd(robot, q, qd, X, gravity=gravity)
        return out
    qdd = _run(robot, q, qd, X, gravity, ACCELERATIONS, **options).qdd
    return qdd[0] if single else qdd
