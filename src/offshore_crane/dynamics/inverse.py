"""Inverse dynamics of the hybrid robot: Kane (fused, default), explicit Kane, RNEA.

- ``"kane"``: Kane's method with factored partial velocities (:func:`.formulas.kane_sample`);
  the only method offering the leg-model approximations and output pruning.
- ``"kane-explicit"``: Kane's method with every body's partial velocities formed, as the
  paper writes them (:func:`.formulas.explicit_sample`); it checks the fused factoring.
- ``"rnea"``: Pinocchio's RNEA on the equivalent tree with loop-closing tree states of its
  own (:mod:`offshore_crane.reference.rnea`): shares only the URDF with the Kane paths.

Each (method, backend) pair is an entry of :data:`REGISTRY` returning the same triple
``(X, kappa, health)``; :func:`solve` validates, picks the entry and applies the checks.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import TYPE_CHECKING, Sequence

import numpy as np

from offshore_crane.conventions import ACTUATORS, GRAVITY, LANES
from offshore_crane.errors import InputError
from offshore_crane.robot.kinematics import workspace as ws
from offshore_crane.robot.kinematics.formulas import LEG_MODEL_CODES
from offshore_crane.validation import as_gravity, as_samples, same_length
from offshore_crane.dynamics.constants import robot_arrays
from offshore_crane.dynamics.kernels import Options, allocate, run_numpy, run_python
from offshore_crane.dynamics.runtime import compiled_kernels, resolve_backend, run_threaded
from offshore_crane.validation import thread_count

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from offshore_crane.robot import Robot

METHODS = ("kane", "kane-explicit", "rnea")
LEG_MODELS = tuple(LEG_MODEL_CODES)
APPROXIMATIONS = {"thin-rod": "thin-rod legs (axial inertia and U-joint spin dropped)",
                  "massless": "massless legs (no inertia, no weight)"}
#: Up to this many samples the NumPy backend evaluates the text on Python floats (no
#: NumPy per-call cost, ~150 µs a sample) instead of arrays (~1.5 ms for any n ≤ 4096).
PYTHON_MAX = 8
#: The platform-at-rest pruning is looked for from this many samples: below, the test
#: (three reductions, ~3 µs) costs more than the terms it can save (~0.1 µs a sample).
STATIC_MIN = 64


@dataclass
class Result:
    """Actuator forces and what was checked along the way.

    Attributes:
        X: ``(N, 9)`` actuator forces ``[T1, T2 [N·m], Fs, Fl1..Fl6 [N]]``. The arm
            columns are NaN without an arm; the leg columns are NaN when no leg force was
            asked for (``outputs``), since the legs were then not evaluated.
        method: ``"kane"``, ``"kane-explicit"`` or ``"rnea"``.
        leg_model: ``"full"``, ``"thin-rod"`` or ``"massless"``.
        outputs: Names of the actuators asked for.
        condition: ``(N,)`` condition number of the leg-force system, or None.
        gimbal: ``(N,)`` worst ``1/cos θ2`` over the legs (U-joint gimbal), or None.
        attitude: ``(N,)`` ``1/|cos q5|`` (attitude-coordinate singularity), or None.
        approximations: Labels of the approximations used (empty: exact).
        pruned: What was skipped because the result does not depend on it.
        backend: ``"numpy"`` or ``"numba"``: what ran.
        cable: With a payload on a cable, the
            :class:`~offshore_crane.dynamics.cable.CableResult` (sway, tension, cable force), else
            None.
    """

    X: np.ndarray
    method: str
    leg_model: str
    outputs: tuple
    condition: np.ndarray | None
    gimbal: np.ndarray | None
    attitude: np.ndarray | None
    approximations: tuple = ()
    pruned: tuple = field(default_factory=tuple)
    backend: str = "numpy"
    cable: object = None

    def worst(self) -> list[tuple[str, float, int]]:
        """``[(kind, worst condition number, sample index), ...]`` of what was measured."""
        out = []
        for kind, kappa in (("leg-Jacobian", self.condition), ("U-joint gimbal", self.gimbal),
                            ("attitude", self.attitude)):
            if kappa is not None and kappa.size and not np.isnan(kappa).all():
                k = int(np.nanargmax(kappa))
                out.append((kind, float(kappa[k]), k))
        return out


# --------------------------------------------------------------------------- entries
def _kane_numba(robot, q, qd, qdd, g, opts: Options, threads: int):
    """The fused Kane pass compiled: on blocks of samples vectorised across them
    (:mod:`.lanes`) when there are enough samples, the platform moves and every leg
    force is wanted; else one sample at a time. The same numbers either way."""
    c = compiled_kernels()
    arrays = robot_arrays(robot)
    X, kappa = allocate(len(q), opts)
    kap = kappa if kappa is not None else np.empty((3, 1))
    block = None
    if opts.legs and not opts.static and len(q) >= LANES:
        from offshore_crane.dynamics.lanes import kane_kernel

        block = kane_kernel(arrays, opts.leg_model)

    def run(start, stop, health):
        if block is not None:
            block(arrays.flat, arrays.layout, arrays.prismatic, q, qd, qdd, g,
                  opts.conditioning, opts.limits, opts.warn, opts.error, start, stop, X, kap,
                  health)
        else:
            c.kane(arrays.flat, arrays.layout, arrays.prismatic, q, qd, qdd, g, opts.static,
                   opts.leg_model, opts.legs, opts.conditioning, opts.limits, opts.warn,
                   opts.error, start, stop, X, kap, health)

    return X, kappa, run_threaded(run, len(q), threads)


def _explicit_numba(robot, q, qd, qdd, g, opts: Options, threads: int):
    c = compiled_kernels()
    arrays = robot_arrays(robot)
    X, kappa = allocate(len(q), opts)
    kap = kappa if kappa is not None else np.empty((3, 1))

    def run(start, stop, health):
        c.explicit(arrays.flat, arrays.layout, arrays.prismatic, q, qd, qdd, g,
                   opts.conditioning, opts.limits, opts.warn, opts.error, start, stop, X, kap,
                   health)

    return X, kappa, run_threaded(run, len(q), threads)


def _kane_numpy(robot, q, qd, qdd, g, opts: Options, threads: int):
    arrays = robot_arrays(robot)
    X, kappa = allocate(len(q), opts)
    health = ws.new_health()
    if len(q) > PYTHON_MAX or not run_python(arrays, q, qd, qdd, g, opts, X, kappa, health):
        health = ws.new_health()
        run_numpy(arrays, q, qd, qdd, g, opts, X, kappa, health)
    return X, kappa, health


def _explicit_numpy(robot, q, qd, qdd, g, opts: Options, threads: int):
    from offshore_crane.dynamics.kernels import run_explicit_numpy

    arrays = robot_arrays(robot)
    X, kappa = allocate(len(q), opts)
    health = ws.new_health()
    run_explicit_numpy(arrays, q, qd, qdd, g, opts, X, kappa, health)
    return X, kappa, health


def _rnea(robot, q, qd, qdd, g, opts: Options, threads: int):
    from offshore_crane.reference import rnea

    limits = robot_arrays(robot).limits
    X, kappa = allocate(len(q), opts)
    health = ws.new_health()
    for start in range(0, len(q), rnea.BLOCK):          # the reference checks nothing
        sl = slice(start, min(start + rnea.BLOCK, len(q)))
        ws.check_finite((q[sl], qd[sl], qdd[sl]), start, health)
        if health[0] >= 0:
            break
        r = rnea.actuator_forces(robot, q[sl], qd[sl], qdd[sl], g, X=X[sl], threads=threads,
                                 conditioning=opts.conditioning)
        ws.record_chunk(X[sl], r.condition, r.length, r.cos_theta2, r.height, r.theta, q[sl],
                        start, opts, limits, None if kappa is None else kappa[:, sl], health)
    return X, kappa, health


#: (method, backend) -> entry(robot, q, qd, qdd, g, options, threads) -> (X, kappa, health).
#: The RNEA reference has one implementation (Numba closure, Pinocchio's RNEA): both of
#: its backends run it.
REGISTRY = {
    ("kane", "numba"): _kane_numba, ("kane", "numpy"): _kane_numpy,
    ("kane-explicit", "numba"): _explicit_numba, ("kane-explicit", "numpy"): _explicit_numpy,
    ("rnea", "numba"): _rnea, ("rnea", "numpy"): _rnea,
}


# --------------------------------------------------------------------------- solve
def _outputs(outputs, available: tuple) -> tuple:
    """Actuators asked for, in the order of X; all those of the robot by default."""
    if outputs is None:
        return available
    if isinstance(outputs, str):
        outputs = (outputs,)
    try:
        names = tuple(outputs)
    except TypeError:
        raise InputError(f"outputs must be a list of actuator names out of "
                         f"{', '.join(ACTUATORS)}, got {outputs!r}", name="outputs") from None
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


@lru_cache(maxsize=256)
def _options(*args) -> Options:
    return Options(*args)


def solve(robot: Robot, q: ArrayLike, qd: ArrayLike, qdd: ArrayLike, method: str = "kane",
          gravity: ArrayLike = GRAVITY, *, leg_model: str = "full",
          outputs: str | Sequence[str] | None = None, t: ArrayLike | None = None,
          limits: bool = True, checks: bool = True,
          thresholds: ws.Thresholds = ws.Thresholds(), backend: str = "auto",
          threads: int = 1) -> Result:
    """Inverse dynamics with validation, workspace limits and the singularity policy.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q, qd, qdd: ``(N, 9)`` coordinates [m, rad], rates, accelerations
            (``docs/conventions.md``).
        method: One of :data:`METHODS`.
        gravity: ``(3,)`` in the base frame [m/s²].
        leg_model: ``"full"`` (exact) or the approximations ``"thin-rod"``,
            ``"massless"`` (method ``"kane"`` only).
        outputs: Actuator names wanted (default all those the robot has). Without any leg
            force, method ``"kane"`` skips the legs entirely (exact for T1, T2, Fs), and
            no method checks the legs' limits or conditioning.
        t: ``(N,)`` times [s], only used in messages.
        limits: Check leg strokes, U-joint and arm joint limits.
        checks: Measure the condition numbers and apply ``thresholds``.
        thresholds: Warning and error thresholds of the singularity policy.
        backend: ``"auto"`` (compiled when Numba is installed), ``"numpy"`` or
            ``"numba"``.
        threads: Threads for large N (compiled backend): samples are split into
            contiguous blocks; results are bit-identical to one thread.

    Returns:
        :class:`Result`.

    Raises:
        InputError, WorkspaceError, SingularConfigurationError, NumericalError.
    """
    if method not in METHODS:
        raise InputError(f"unknown method {method!r}: use one of {', '.join(METHODS)}",
                         name="method")
    if leg_model not in LEG_MODELS:
        raise InputError(f"unknown leg model {leg_model!r}: use one of {', '.join(LEG_MODELS)}",
                         name="leg_model")
    if leg_model != "full" and method != "kane":
        raise InputError(f"leg model '{leg_model}' is an approximation offered by method "
                         "'kane' only", name="leg_model")
    if not isinstance(thresholds, ws.Thresholds):
        raise InputError(f"thresholds must be a Thresholds(warn, error), got {thresholds!r}",
                         name="thresholds")
    backend = resolve_backend(backend)
    threads = thread_count(threads)
    q, _ = as_samples("q", q, finite=False)
    qd, _ = as_samples("qd", qd, finite=False)
    qdd, _ = as_samples("qdd", qdd, finite=False)
    N = q.shape[0]
    if qd.shape[0] != N or qdd.shape[0] != N:
        same_length(q=q, qd=qd, qdd=qdd)
    if t is not None:
        t = np.asarray(t, dtype=float)
        if t.shape != (N,):
            raise InputError(f"t has shape {t.shape}; expected ({N},)", name="t")
    g = as_gravity(gravity)
    model = robot.hybrid
    names = model.actuators if outputs is None else _outputs(outputs, model.actuators)
    want_legs = names[-1].startswith("Fl")          # names are in the order of X
    pruned = []
    kernel_legs = leg_model
    static = False
    if method == "kane":
        static = N >= STATIC_MIN and bool(not qd[:, :6].any() and not qdd[:, :6].any()
                                          and (q[:, :6] == q[0, :6]).all())
        if static:
            pruned.append("platform velocity and acceleration terms (static platform)")
        if not want_legs:
            pruned.append("leg kinematics and dynamics (no leg force wanted)")
        elif leg_model != "massless" and model.massless_legs:
            kernel_legs = "massless"          # exact: every leg inertia term is zero
            pruned.append("leg inertia and weight terms (the legs have no mass)")
    opts = _options(LEG_MODEL_CODES[kernel_legs], want_legs or method != "kane", static,
                    bool(checks), bool(limits), thresholds.warn, thresholds.error)
    X, kappa, health = REGISTRY[(method, backend)](robot, q, qd, qdd, g, opts, threads)
    ws.enforce(health, (q, qd, qdd), robot_arrays(robot).limits if limits else None,
               kappa if checks else None, thresholds,
               (ws.LEG_JACOBIAN, ws.GIMBAL) if want_legs else (), t)
    if not want_legs:
        X[:, 3:] = np.nan          # not computed
        if kappa is not None:
            kappa[:2] = np.nan
    approx = (APPROXIMATIONS[leg_model],) if leg_model != "full" else ()
    return Result(X=X, method=method, leg_model=leg_model, outputs=names,
                  condition=None if kappa is None or not want_legs else kappa[0],
                  gimbal=None if kappa is None or not want_legs else kappa[1],
                  attitude=None if kappa is None else kappa[2], approximations=approx,
                  pruned=tuple(pruned), backend=backend)


def inverse_dynamics(robot: Robot, q: ArrayLike, qd: ArrayLike, qdd: ArrayLike,
                     method: str = "kane", gravity: ArrayLike = GRAVITY,
                     **options) -> np.ndarray:
    """Actuator forces that produce the motion ``(q, qd, qdd)``.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q: ``(N, 9)`` or ``(9,)`` coordinates (``docs/conventions.md``): q1..q3 [m] the
            platform's reference point O2 in the base frame, q4..q6 [rad] roll, pitch, yaw,
            q7, q8 [rad] arm joint angles, q9 [m] slider displacement.
        qd: Same shape, rates [m/s, rad/s].
        qdd: Same shape, accelerations [m/s², rad/s²].
        method: ``"kane"`` (default), ``"kane-explicit"`` or ``"rnea"``.
        gravity: ``(3,)`` gravity in the base frame [m/s²].
        **options: Keyword options of :func:`solve` (``leg_model``, ``outputs``, ``t``,
            ``limits``, ``checks``, ``thresholds``, ``backend``, ``threads``).

    Returns:
        X ``(N, 9)`` (or ``(9,)``): ``[T1, T2 [N·m], Fs, Fl1..Fl6 [N]]``, signed along
        the joint directions (positive Fl extends the leg).

    Raises:
        InputError, WorkspaceError, SingularConfigurationError, NumericalError.
    """
    single = np.ndim(q) == 1
    X = solve(robot, q, qd, qdd, method, gravity, **options).X
    return X[0] if single else X
