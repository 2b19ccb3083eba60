"""Inverse dynamics of the hybrid robot: Kane (fused, default), explicit Kane, RNEA.

- ``"kane"``: Kane's method with factored partial velocities (:mod:`.fused`), NumPy,
  chunked; the only method offering the leg-model approximations and output pruning.
- ``"kane-explicit"``: Kane's method with every body's partial velocities formed as
  ``(N, 9, 3)`` arrays, as the paper writes it (:mod:`.kane_hybrid`); a reference.
- ``"rnea"``: Pinocchio's RNEA on the equivalent tree, projected on the independent
  speeds (:mod:`.rnea`); the independent reference.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..checks import Thresholds, apply_policy, check_limits, condition_1
from ..errors import InputError
from ..model.hybrid import ACTUATORS
from ..validation import as_gravity, as_samples, same_length

METHODS = ("kane", "kane-explicit", "rnea")
LEG_MODELS = ("full", "thin-rod", "massless")
GRAVITY = (0.0, 0.0, -9.81)
APPROXIMATIONS = {"thin-rod": "thin-rod legs (axial inertia and U-joint spin dropped)",
                  "massless": "massless legs (no inertia, no weight)"}


@dataclass
class Result:
    """Actuator forces and what was checked along the way.

    Attributes:
        X: ``(N, 9)`` actuator forces ``[T1, T2 [N·m], Fs, Fl1..Fl6 [N]]``. The arm
            columns are computed whenever the robot has an arm (NaN without one); the
            leg columns are NaN when no leg force was asked for (``outputs``), since the
            legs were then not evaluated.
        method: ``"kane"``, ``"kane-explicit"`` or ``"rnea"``.
        leg_model: ``"full"``, ``"thin-rod"`` or ``"massless"``.
        outputs: Names of the actuators asked for.
        condition: ``(N,)`` condition number of the leg-force system, or None.
        gimbal: ``(N,)`` worst ``1/cos θ2`` over the legs (U-joint gimbal), or None.
        attitude: ``(N,)`` ``1/|cos q5|`` (attitude-coordinate singularity).
        approximations: Labels of the approximations used (empty: exact).
        pruned: What was skipped because the result does not depend on it.
    """

    X: np.ndarray
    method: str
    leg_model: str
    outputs: tuple
    condition: np.ndarray | None
    gimbal: np.ndarray | None
    attitude: np.ndarray
    approximations: tuple = ()
    pruned: tuple = field(default_factory=tuple)

    def worst(self) -> list[tuple[str, float, int]]:
        """``[(kind, worst condition number, sample index), ...]`` of what was measured."""
        out = []
        for kind, kappa in (("leg-Jacobian", self.condition), ("U-joint gimbal", self.gimbal),
                            ("attitude", self.attitude)):
            if kappa is not None and kappa.size:
                k = int(np.argmax(kappa))
                out.append((kind, float(kappa[k]), k))
        return out


def _outputs(outputs, available: tuple = ACTUATORS) -> tuple:
    """Actuators asked for, in the order of X; all those of the robot by default."""
    if outputs is None:
        return available
    names = tuple(outputs)
    unknown = [n for n in names if n not in ACTUATORS]
    if unknown or not names:
        raise InputError(f"unknown outputs {unknown}: choose among {', '.join(ACTUATORS)}"
                         if unknown else "outputs is empty: name at least one actuator",
                         name="outputs")
    absent = [n for n in names if n not in available]
    if absent:
        raise InputError(f"outputs {', '.join(absent)} do not exist: the robot has no arm "
                         f"(xacro argument with_arm = 0); choose among {', '.join(available)}",
                         name="outputs")
    return tuple(n for n in ACTUATORS if n in names)


def _massless_legs(model) -> bool:
    """True when no leg link has mass or inertia (their inertia terms are exact zeros)."""
    return not (model.lower_mass.any() or model.upper_mass.any()
                or model.lower_inertia.any() or model.upper_inertia.any())


def solve(robot, q, qd, qdd, method: str = "kane", gravity=GRAVITY, *, leg_model: str = "full",
          outputs=None, t=None, limits: bool = True, checks: bool = True,
          thresholds: Thresholds = Thresholds(), backend: str = "auto") -> Result:
    """Inverse dynamics with validation, workspace limits and the singularity policy.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q, qd, qdd: ``(N, 9)`` coordinates [m, rad], rates, accelerations (CONVENTIONS.md).
        method: One of :data:`METHODS`.
        gravity: ``(3,)`` in the base frame [m/s²].
        leg_model: ``"full"`` (exact) or the approximations ``"thin-rod"``,
            ``"massless"`` (method ``"kane"`` only).
        outputs: Actuator names wanted (default all those the robot has: no T1, T2,
            Fs without arm). Without any leg force, method ``"kane"`` skips the legs
            entirely (exact for T1, T2, Fs), and no method checks the legs' limits or
            conditioning.
        t: ``(N,)`` times [s], only used in messages.
        limits: Check leg strokes, U-joint and arm joint limits (:mod:`..checks`).
        checks: Measure the condition numbers and apply ``thresholds``.
        thresholds: Warning and error thresholds of the singularity policy.
        backend: ``"auto"`` (Numba when installed, else NumPy), ``"numpy"`` or ``"numba"``:
            the compiled or vectorised kernels of methods ``"kane"`` and ``"rnea"``
            (same formulas; ``"kane-explicit"`` is NumPy only).

    Returns:
        :class:`Result`.

    Raises:
        InputError, WorkspaceError, SingularConfigurationError.
    """
    if method not in METHODS:
        raise InputError(f"unknown method '{method}': use one of {', '.join(METHODS)}",
                         name="method")
    if leg_model not in LEG_MODELS:
        raise InputError(f"unknown leg model '{leg_model}': use one of {', '.join(LEG_MODELS)}",
                         name="leg_model")
    if leg_model != "full" and method != "kane":
        raise InputError(f"leg model '{leg_model}' is an approximation offered by method "
                         "'kane' only", name="leg_model")
    q, _ = as_samples("q", q)
    qd, _ = as_samples("qd", qd)
    qdd, _ = as_samples("qdd", qdd)
    N = same_length(q=q, qd=qd, qdd=qdd)
    if t is not None:
        t = np.asarray(t, dtype=float)
        if t.shape != (N,):
            raise InputError(f"t has shape {t.shape}; expected ({N},)", name="t")
    g = as_gravity(gravity)
    names = _outputs(outputs, robot.hybrid.actuators)
    want_legs = any(n.startswith("Fl") for n in names)
    pruned = []
    cond = diag = None
    policy_done = False
    if method == "kane":
        from .fused import Options, fused_inverse_dynamics

        static = bool(not qd[:, :6].any() and not qdd[:, :6].any()
                      and (q[:, :6] == q[0, :6]).all())
        if static:
            pruned.append("platform velocity and acceleration terms (static platform)")
        if not want_legs:
            pruned.append("leg kinematics and dynamics (no leg force wanted)")
        kernel_legs = leg_model
        if want_legs and leg_model != "massless" and _massless_legs(robot.hybrid):
            kernel_legs = "massless"          # exact: every leg inertia term is zero
            pruned.append("leg inertia and weight terms (the legs have no mass)")
        opts = Options(leg_model=kernel_legs, legs=want_legs, platform_static=static,
                       conditioning=checks and want_legs,
                       diagnostics=(checks or limits) and want_legs)
        X, cond, diag = fused_inverse_dynamics(robot.fused, q, qd, qdd, g, opts,
                                               backend=_backend(backend))
    elif method == "rnea" and _backend(backend) == "numba":
        from .tree_numba import rnea_numba

        X, cond, diag = rnea_numba(robot, q, qd, qdd, g)
        if not want_legs:
            cond = diag = None
        elif not checks:
            cond = None
    else:
        from .kane_hybrid import kane_B, solve_actuators

        if method == "kane-explicit":
            B, legs = kane_B(robot.hybrid, q, qd, qdd, g)
        else:
            from .rnea import rnea_B

            B, legs = rnea_B(robot, q, qd, qdd, g)
        if want_legs:
            diag = {"length": legs.length, "theta1": legs.theta[..., 0],
                    "theta2": legs.theta[..., 1], "cos_theta2": np.abs(legs.u_dot_n),
                    "height": legs.p_S[..., 2] - robot.hybrid.p_base_P[:, 2]}
        if checks and want_legs:
            J = legs.J.copy()
            J[:, :, 3:] /= robot.fused.length_scale
            cond = condition_1(np.swapaxes(J, 1, 2))
            apply_policy("leg-Jacobian", cond, thresholds, t)   # before the solve: it
            policy_done = True                                    # would fail if singular
        X = solve_actuators(B, legs.J)
    if limits:
        check_limits(robot, q, diag, t)       # includes the platform-below-base check
    with np.errstate(divide="ignore"):      # exactly singular: κ = inf, reported below
        gimbal = None if diag is None else 1.0 / diag["cos_theta2"].min(axis=1)
        attitude = 1.0 / np.abs(np.cos(q[:, 4]))
    if checks:
        if not policy_done:
            apply_policy("leg-Jacobian", cond, thresholds, t)
        apply_policy("U-joint gimbal", gimbal, thresholds, t)
        apply_policy("attitude", attitude, thresholds, t, error=False)
    if not want_legs:
        X[:, 3:] = np.nan          # not computed
    X[:, robot.hybrid.arm.n:3] = np.nan   # no arm: these actuators do not exist
    approx = (APPROXIMATIONS[leg_model],) if leg_model != "full" else ()
    return Result(X=X, method=method, leg_model=leg_model, outputs=names, condition=cond,
                  gimbal=gimbal, attitude=attitude, approximations=approx,
                  pruned=tuple(pruned))


def _backend(backend: str) -> str:
    """Resolve ``"auto"`` to ``"numba"`` or ``"numpy"``."""
    from .fused import BACKENDS, numba_available

    if backend not in BACKENDS:
        raise InputError(f"unknown backend '{backend}': use one of {', '.join(BACKENDS)}",
                         name="backend")
    if backend == "auto":
        return "numba" if numba_available() else "numpy"
    return backend


def inverse_dynamics(robot, q, qd, qdd, method: str = "kane", gravity=GRAVITY,
                     **options) -> np.ndarray:
    """Actuator forces that produce the motion ``(q, qd, qdd)``.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q: ``(N, 9)`` or ``(9,)`` coordinates (CONVENTIONS.md): q1..q3 [m] position of
            the platform CoM in the base frame, q4..q6 [rad] roll, pitch, yaw, q7, q8 [rad]
            arm joint angles, q9 [m] slider displacement.
        qd: Same shape, rates [m/s, rad/s].
        qdd: Same shape, accelerations [m/s², rad/s²].
        method: ``"kane"`` (default), ``"kane-explicit"`` or ``"rnea"``.
        gravity: ``(3,)`` gravity in the base frame [m/s²].
        **options: Keyword options of :func:`solve` (``leg_model``, ``outputs``, ``t``,
            ``limits``, ``checks``, ``thresholds``).

    Returns:
        X ``(N, 9)`` (or ``(9,)``): ``[T1, T2 [N·m], Fs, Fl1..Fl6 [N]]``, signed along
        the joint directions (positive Fl extends the leg).

    Raises:
        InputError, WorkspaceError, SingularConfigurationError (see :func:`solve`).
    """
    single = np.ndim(q) == 1
    X = solve(robot, q, qd, qdd, method, gravity, **options).X
    return X[0] if single else X
