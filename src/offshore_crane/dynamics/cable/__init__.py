"""The hanging load: a payload on a cable at the crane tip, its swing, its pull in X.

Model (docs/cable.md): a point mass m on a massless, inextensible cable of length L from
the frame ``arm_tip`` (the robot description's ``payload.mass`` and
``payload.cable_length``; the URDF then carries the two sway joints). The sway angles
``φ = (φ1, φ2)`` [rad] are measured in the ``arm_tip`` frame: the cable's direction from
the tip to the payload is ``e = R_base_tip · Rx(φ1) · Ry(φ2) · (0, 0, −1)``, regular
around hanging straight down (φ = 0) and singular only where ``cos φ2 = 0`` (the cable
along ``±x`` of the tip frame, horizontal when the tip frame is upright).

Inverse dynamics with the swing (:func:`inverse_dynamics`): the robot's motion ``q(t)`` is
prescribed; the sway obeys Kane's equations of the two sway speeds, exact and nonlinear,
driven by the tip's motion, and is integrated by classical RK4 from a given initial sway;
the cable's pull then enters the actuator forces X through the arm (the payload is the
last body of the arm chain). RK4 needs the robot's motion at its stage times (every half
step): from ``reference`` (an analytic motion: Table 1, sea states, crane operations; a
:class:`~offshore_crane.motion.trajectories.Trajectory`'s ``reference``), else from the samples
by quintic Hermite interpolation of q, q̇, q̈ at both ends of each interval (error
``O(h⁶)`` in q; the derivatives of a CSV are its own columns or finite differences).

Two independent paths, like the rest of the project: ``method="kane"`` (compiled) and
``method="pinocchio"`` (:mod:`offshore_crane.reference.cable`: the sway joints of
Pinocchio's model of the URDF, their accelerations from RNEA and CRBA, X from the RNEA
reference), which share only the URDF. The Kane path writes the pendulum's own equations
by Kane's method on the tip's motion
(:func:`~offshore_crane.dynamics.sway.tip_motion`, ``pendulum``) and X by
``kane_sample`` on the arm chain continued by the sway joints and the payload (the
cable's pull enters through the arm); that pass's rows of the sway speeds must vanish at
the integrated sway, a check between the two (``CableResult.residual``).

A cable cannot push: where the tension the model needs is ≤ 0 the model no longer holds
and :class:`~offshore_crane.errors.SlackCableError` names the time (``slack="warn"``: a
warning, and the samples marked in ``CableResult.slack``).
"""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING

import numpy as np

from offshore_crane import progress
from offshore_crane.lazy import submodule_getattr
from offshore_crane.stops import StopCause
from offshore_crane.conventions import GRAVITY
from offshore_crane.errors import (InputError, NumericalError, SingularConfigurationError,
                                   SlackCableError)
from offshore_crane.robot.kinematics import workspace as ws
from offshore_crane.validation import as_gravity, as_pair, as_samples, thread_count
from offshore_crane.dynamics.cable.hoist import hoist_grid, hoist_profile
from offshore_crane.dynamics.cable.result import CableResult
from offshore_crane.dynamics.cable.grid import (cable_robot, motion_samples, stage_grid,
                                                uniform_times)
from offshore_crane.dynamics.cable.forces import kane_forces
from offshore_crane.dynamics.cable.elastic import ElasticResult, elastic_inverse_dynamics
from offshore_crane.dynamics.cable.lift import LiftMetrics, lift_metrics
from offshore_crane.dynamics.cable.liftoff import LiftOff, SetDown, lift_off, set_down
from offshore_crane.dynamics.cable.modal import Mode, modes

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from offshore_crane.robot import Robot

__all__ = ["CableResult", "METHODS", "SLACK", "cable_robot", "hoist_grid", "hoist_profile",
           "inverse_dynamics", "kane_forces", "stage_grid", "sway_accelerations", "swing",
           "uniform_times", "warm_up", "ElasticResult", "elastic_inverse_dynamics",
           "LiftMetrics", "lift_metrics", "LiftOff", "SetDown", "lift_off", "set_down",
           "Mode", "modes"]

METHODS = ("kane", "pinocchio")
SLACK = ("error", "warn")


# --------------------------------------------------------------------------- helpers
# --------------------------------------------------------------------------- public
def inverse_dynamics(robot: Robot, q: ArrayLike, qd: ArrayLike, qdd: ArrayLike, *,
                     t: ArrayLike, reference=None, gravity: ArrayLike = GRAVITY,
                     initial=(0.0, 0.0), initial_rate=(0.0, 0.0), substeps: int = 1,
                     slack: str = "error", method: str = "kane", limits: bool = True,
                     checks: bool = True, thresholds: ws.Thresholds = ws.Thresholds(),
                     length: float | None = None, mass: float | None = None,
                     hoist=None, threads: int = 1) -> CableResult:
    """Actuator forces of the prescribed motion with the payload swinging on its cable.

    Args:
        robot: From :func:`offshore_crane.load_robot` with ``payload.cable_length > 0``
            (or give ``length`` and ``mass``).
        q, qd, qdd: ``(N, 9)`` the robot's motion [m, rad], rates, accelerations (in the
            order of :func:`offshore_crane.inverse_dynamics`).
        t: ``(N,)`` uniform times [s] (N ≥ 2), keyword: the swing is integrated over
            time, RK4 steps along them.
        reference: Optional ``reference(t (n,)) -> (q, qd, qdd)`` evaluated at RK4's stage
            times (analytic motions); None: quintic Hermite interpolation of the samples.
        gravity: ``(3,)`` [m/s²], base frame.
        initial: ``(2,)`` φ1, φ2 at ``t[0]`` [rad]; initial_rate: ``(2,)`` [rad/s].
        substeps: RK4 steps per sample interval (integer ≥ 1).
        slack: ``"error"``: :class:`SlackCableError` at the first sample whose tension is
            ≤ 0; ``"warn"``: a warning and the samples marked (``CableResult.slack``).
        method: ``"kane"`` (compiled) or ``"pinocchio"`` (the independent reference).
        limits, checks, thresholds: As :func:`offshore_crane.dynamics.solve` (the sway's
            condition ``1/cos²φ2`` follows the same thresholds).
        length, mass: Optional overrides of ``payload.cable_length`` [m] and
            ``payload.mass`` [kg].
        hoist: A winch: ``hoist(t (n,)) -> (L, L̇, L̈)``, each ``(n,)``, the cable's
            length [m] (> 0), its rate [m/s] and acceleration [m/s²] at any times (RK4's
            stage times among them); e.g. :func:`hoist_profile`. None: the fixed
            ``payload.cable_length``.
        threads: Threads for the Kane pass over the integrated sway (chunks of samples;
            from 2 threads on a fixed cable it runs alongside the integration, which
            itself runs in one); the same numbers as one thread. ``method="pinocchio"``
            ignores it. (:func:`swing` also passes them to a sea motion's FFT at the
            stage times.)

    Returns:
        :class:`CableResult`.

    Raises:
        InputError: bad arguments (shapes, NaN, a non-uniform time axis, an initial sway
            on the singular set ``cos φ2 = 0``).
        ModelError: a robot without cable.
        SingularConfigurationError: the sway reaches the singular set, or the robot a
            singular pose (names the time).
        WorkspaceError, NumericalError: as the inverse dynamics; a sway that diverges.
        SlackCableError: the cable goes slack (``slack="error"``).
    """
    if method not in METHODS:
        raise InputError(f"unknown method {method!r}: use one of {', '.join(METHODS)}",
                         name="method")
    if slack not in SLACK:
        raise InputError(f"slack = {slack!r}: use 'error' or 'warn'", name="slack")
    if isinstance(substeps, bool) or not isinstance(substeps, (int, np.integer)) or substeps < 1:
        raise InputError(f"substeps = {substeps!r} must be an integer >= 1", name="substeps")
    if not isinstance(thresholds, ws.Thresholds):
        raise InputError(f"thresholds must be a Thresholds(warn, error), got {thresholds!r}",
                         name="thresholds")
    threads = thread_count(threads)
    robot = cable_robot(robot, length, mass)
    q, qd, qdd, t, dt = motion_samples(q, qd, qdd, t)
    g = as_gravity(gravity)
    phi0 = as_pair(initial, "initial", "rad")
    rate0 = as_pair(initial_rate, "initial_rate", "rad/s")
    c2 = np.cos(phi0[1]) ** 2
    if not c2 * thresholds.error > 1.0:
        raise InputError(f"initial sway phi2 = {phi0[1]:.6g} rad lies on the singular set "
                         "cos(phi2) = 0 (cable along the tip's x axis, phi1 undefined; "
                         f"1/cos^2 = {1 / max(c2, 1e-300):.3g} > {thresholds.error:.3g}): "
                         "start from another sway", name="initial")
    tt, Q, Qd, Qdd = stage_grid(t, q, qd, qdd, reference, int(substeps))
    h = dt / substeps
    y0 = np.concatenate([phi0, rate0])
    length_, mass_ = robot.hybrid.cable_length, float(robot.hybrid.cable.mass[-1])
    Lh = (np.array([[length_, 0.0, 0.0]]) if hoist is None else hoist_grid(hoist, tt))
    done = None
    if method == "kane":
        follow = (None if hoist is not None or threads == 1 else   # the Kane pass
                  lambda Y, ready: kane_forces(                       # alongside
                      robot, t, q, qd, qdd, Y, g, limits, checks, thresholds,
                      threads=threads, rows_ready=ready))
        Y, status, done = _integrate_kane(robot, Q, Qd, Qdd, Lh, g, h, int(substeps), y0,
                                          thresholds, follow)
    else:
        from offshore_crane.reference import cable as ref

        Y, status = ref.integrate(robot, Q, Qd, Qdd, g, h, int(substeps), y0,
                                  1.0 / thresholds.error, None if hoist is None else Lh)
    code, stop, worst = StopCause(int(status[0])), int(status[1]), float(status[2])
    n = len(t) if code == StopCause.NONE else stop
    L = None if hoist is None else np.ascontiguousarray(Lh[::2 * int(substeps)][:n])
    if done is not None:
        X, F, kappa = done
        done = X[:n], F[:n], None if kappa is None else kappa[:, :n]
    res = _forces(robot, t[:n], q[:n], qd[:n], qdd[:n], Y[:n], g, method, limits, checks,
                  thresholds, worst, length_, mass_, h, L, threads, done)
    if code != StopCause.NONE:
        if slack == "error":
            _slack(res, slack)         # a slack cable before the stop is its first cause
        cause = ("the sway reached the singular set cos(phi2) = 0 (1/cos^2 above "
                 f"{thresholds.error:.3g})" if code == StopCause.SINGULAR else "the sway diverged (a "
                 "non-finite state)")
        exc = (SingularConfigurationError(
            f"hanging load: {cause} at sample {stop} (t = {t[stop]:.6g} s); the {n} samples "
            "before it are in error.result", index=stop, time=float(t[stop]),
            condition=worst, kind="sway") if code == StopCause.SINGULAR else NumericalError(
            f"hanging load: {cause} at sample {stop} (t = {t[stop]:.6g} s): shorten the step "
            "(substeps) or check the motion", index=stop, name="sway"))
        exc.result = res
        raise exc
    if checks and worst > thresholds.warn:
        warnings.warn(ws.OffshoreCraneWarning(
            f"the hanging load comes near its singular set cos(phi2) = 0: 1/cos^2 reaches "
            f"{worst:.3g} (above {thresholds.warn:.3g})"), stacklevel=2)
    _slack(res, slack)
    return res


def _integrate_kane(robot, Q, Qd, Qdd, Lh, g, h, sub, y0, thresholds, follow=None):
    """The sway ``Y`` ``(n, 6)`` and the integration's ``status`` (3,), and with
    ``follow(Y, ready)`` its result: run in this thread while the integration runs in
    another, ``ready`` as :func:`~offshore_crane.dynamics.cable.forces.kane_forces`'s
    ``rows_ready`` (None without ``follow``)."""
    from offshore_crane.dynamics.runtime import compiled_kernels
    from offshore_crane.dynamics.cable import kernels as ck
    from offshore_crane.dynamics.constants import cable_arrays

    compiled_kernels()
    arrays = cable_arrays(robot)
    n_out = (Q.shape[0] - 1) // (2 * sub) + 1
    Y = np.full((n_out, 6), np.nan)
    status = np.zeros(3)
    stop = progress.stop_flag()

    def integrate():
        progress.run_polled(
            lambda: ck.integrate(arrays.flat, arrays.layout, arrays.prismatic,
                                 robot.hybrid.sway_damping, float(robot.hybrid.drag), Q, Qd,
                                 Qdd, Lh, g, h, sub, y0, 1.0 / thresholds.error, Y, status,
                                 stop),
            lambda: progress.filled_rows(Y), n_out, "sample", "swing", stop)

    if follow is None:
        integrate()
        return Y, status, None
    return Y, status, _alongside(integrate, lambda ready: follow(Y, ready), Y, status, stop)


#: How often the Kane pass, waiting for the sway's integration, looks again [s].
WAIT = 1e-3


def _alongside(job, follow, Y, status, stop):
    """``follow(ready)`` in this thread while ``job()`` (the sway's integration: writes
    ``Y``'s rows in order over NaN, and ``status`` when it ends) runs in another;
    ``ready(b)`` waits until rows ``< b`` are written (row ``b`` begun) or the job ends,
    and returns how many of them hold the sway: ``b``, fewer when the integration stopped
    early (its stop sample), none when it raised (raised here after ``follow``). An
    exception here (a signal's) sets the integration's flag ``stop`` (1,) and waits for
    it to return before it is raised."""
    import time

    box = progress.in_thread(job, "swing")[1]

    def ready(b: int) -> int:
        while not box["done"].is_set():
            if progress.filled_rows(Y) > b:
                return b
            time.sleep(WAIT)
        if "error" in box:
            return 0
        return b if status[0] == StopCause.NONE else min(b, int(status[1]))

    try:
        out = follow(ready)
    except BaseException:
        progress.halt(stop, box)
        raise
    finally:
        box["done"].wait()
    if "error" in box:
        raise box["error"]
    return out


def _forces(robot, t, q, qd, qdd, Y, g, method, limits, checks, thresholds, worst, length,
            mass, h, L=None, threads=1, done=None) -> CableResult:
    """X, the cable force and the residual at the integrated sway (both paths); ``L``
    ``(n, 3)`` the hoisted length, rate, acceleration, or None; ``done``: Kane's
    ``(X, F, kappa)`` already computed alongside the integration, or None."""
    n = len(t)
    if done is not None:
        X, F, kappa = done
    elif method == "kane":
        X, F, kappa = kane_forces(robot, t, q, qd, qdd, Y, g, limits, checks, thresholds, L,
                                  threads=threads)
    else:
        from offshore_crane.dynamics.constants import cable_arrays
        from offshore_crane.robot.kinematics.workspace import Limits
        from offshore_crane.dynamics.kernels import Options
        from offshore_crane.reference import cable as ref

        r, F = ref.forces(robot, q, qd, qdd, Y, g, conditioning=bool(checks), hoist=L)
        X, kappa, health = r.X, np.empty((3, n)) if checks else None, ws.new_health()
        lim = cable_arrays(robot).limits            # the robot's arm joints, for the checks
        lim = Limits(lim.arm[:robot.hybrid.arm.n], lim.stroke, lim.ujoint)
        if n:                                       # the reference checks nothing
            ws.record_chunk(X, r.condition, r.length, r.cos_theta2, r.height, r.theta, q, 0,
                            Options(legs=True, conditioning=bool(checks), limits=bool(limits),
                                    warn=thresholds.warn, error=thresholds.error),
                            lim, kappa, health)
        ws.enforce(health, (q, qd, qdd), lim if limits else None, kappa, thresholds,
                   (ws.LEG_JACOBIAN, ws.GIMBAL), t)
    return CableResult(
        t=t, q=q, qd=qd, qdd=qdd, X=X, sway=Y[:, 0:2].copy(), sway_rate=Y[:, 2:4].copy(),
        sway_accel=Y[:, 4:6].copy(), tension=F[:, 3].copy(), force_tip=F[:, 0:3].copy(),
        residual=F[:, 4:6].copy(), slack=np.zeros(n, dtype=bool),
        condition=kappa[0] if kappa is not None else np.full(n, np.nan),
        sway_condition=worst, length=length, mass=mass, method=method, step=h, hoist=L)


def _slack(res: CableResult, policy: str) -> None:
    slack = ~(res.tension > 0.0)
    if not slack.any():
        return
    k = int(np.argmax(slack))
    where = f"sample {k} (t = {res.t[k]:.6g} s)"
    if policy == "error":
        raise SlackCableError(
            f"the cable goes slack at {where}: the tension would be {res.tension[k]:.4g} N "
            "(a cable cannot push; docs/cable.md); slack='warn' (CLI --slack warn) marks "
            "such samples and goes on",
            index=k, time=float(res.t[k]), tension=float(res.tension[k]),
            result=res.truncated(k))
    res.slack = slack
    warnings.warn(ws.OffshoreCraneWarning(
        f"the cable is slack at {int(slack.sum())} samples, first at {where} (tension "
        f"{res.tension[k]:.4g} N): the pendulum model does not hold there; they are marked "
        "in the result's slack array"), stacklevel=3)


def sway_accelerations(robot, q, qd, qdd, sway, sway_rate, gravity=GRAVITY,
                       hoist=None) -> np.ndarray:
    """The right-hand side of the swing: ``φ̈`` ``(N, 2)`` [rad/s²] at given states.

    The same formulas the integrator runs compiled
    (:func:`~offshore_crane.dynamics.sway.tip_motion` and ``pendulum``, or
    ``hoisted_pendulum`` with a winch; the payload's drag, ``drag_force`` at
    ``hanging_velocity``), here on NumPy arrays.

    Args:
        robot: With a payload on a cable.
        q, qd, qdd: ``(N, 9)`` the robot's state and accelerations.
        sway, sway_rate: ``(N, 2)`` φ [rad], φ̇ [rad/s].
        gravity: ``(3,)`` [m/s²].
        hoist: ``(N, 3)`` a winch's cable length [m], rate [m/s] and acceleration
            [m/s²], or None for the description's fixed length.
    """
    from offshore_crane.dynamics import backends
    from offshore_crane.dynamics.constants import cable_arrays

    robot = cable_robot(robot)
    q, single = as_samples("q", q)
    qd = as_samples("qd", qd)[0]
    qdd = as_samples("qdd", qdd)[0]
    sway = as_samples("sway", sway, width=2)[0]
    sway_rate = as_samples("sway_rate", sway_rate, width=2)[0]
    g = tuple(float(x) for x in as_gravity(gravity))
    C = cable_arrays(robot).kane
    c1, c2 = (float(c) for c in robot.hybrid.sway_damping)
    F = backends.NUMPY
    if hoist is not None:
        hoist = as_samples("hoist", hoist, width=3)[0]
        if len(hoist) != len(q) or not (hoist[:, 0] > 0).all():
            raise InputError(f"hoist must be ({len(q)}, 3) rows (L > 0 [m], Ld [m/s], Ldd "
                             "[m/s²]), one per sample", name="hoist")
    f = (0.0, 0.0, 0.0)
    if robot.hybrid.drag > 0.0:
        from offshore_crane.dynamics.cable.forces import hanging_drag

        f = tuple(hanging_drag(robot, C, q, qd, qdd, np.hstack([sway, sway_rate]),
                               hoist)[0].T)
    with np.errstate(divide="ignore", invalid="ignore"):
        Rt, w, al, a = F.tip_motion(C, q.T, qd.T, qdd.T)
        if hoist is None:
            a1, a2, _ = F.pendulum(C, Rt, w, al, a, g, sway[:, 0], sway[:, 1],
                                   sway_rate[:, 0], sway_rate[:, 1], c1, c2, f)
        else:
            a1, a2 = F.hoisted_pendulum(C, Rt, w, al, a, g, sway[:, 0], sway[:, 1],
                                        sway_rate[:, 0], sway_rate[:, 1], c1, c2, f,
                                        *hoist.T)[:2]
    out = np.stack([a1, a2], axis=-1)
    return out[0] if single else out


def swing(robot, trajectory, **options) -> CableResult:
    """:func:`inverse_dynamics` of a :class:`~offshore_crane.motion.trajectories.Trajectory`,
    its analytic ``source`` (when it has one) evaluated at RK4's stage times (with the
    ``threads`` of the options, a sea motion shares its FFT among them)."""
    threads = thread_count(options.get("threads", 1))
    reference = (None if trajectory.source is None else
                 lambda t: trajectory.reference(t, threads=threads))
    return inverse_dynamics(robot, trajectory.q, trajectory.qd, trajectory.qdd,
                            reference=reference, **options, t=trajectory.t)


def warm_up(robot=None) -> list[tuple[str, float]]:
    """Compile (or load from the cache) the hanging load's inverse-dynamics kernels
    (the swing integrated along a motion): ``[(name, seconds)]``. The simulation loop
    with a hanging load has its own (:func:`offshore_crane.simulation.swing.warm_up`)."""
    import time

    from offshore_crane.robot import load_robot

    t0 = time.perf_counter()
    robot = robot or load_robot()
    if robot.hybrid.cable is None:
        robot = cable_robot(robot, length=1.0, mass=1.0)
    t = np.array([0.0, 1e-3])
    q = np.repeat(robot.home_pose()[None, :], 2, axis=0)
    inverse_dynamics(robot, q, 0 * q, 0 * q, limits=False, t=t)
    length = robot.hybrid.cable_length
    inverse_dynamics(robot, q, 0 * q, 0 * q, limits=False, t=t,
                     hoist=lambda tt: (np.full(len(tt), length), 0 * tt, 0 * tt))
    elastic_inverse_dynamics(robot, q, 0 * q, 0 * q, limits=False, t=t, ea=1e4)
    return [("hanging-load kernels", time.perf_counter() - t0)]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
