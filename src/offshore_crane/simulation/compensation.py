"""Motion compensation: the arm holds the tip over the point the crane operation would
reach on a still ship, the winch holds the payload's height (docs/cable.md).

The platform reproduces the ship; a motion-compensated crane reads that motion and
commands its own joints against it. Here the law is the exact kinematic one (the
measured platform pose, no delay, no noise): at every sample the arm's coordinates
q7, q8, q9 are those that put the tip's horizontal position in the base frame where the
*still-ship* crane puts it (the platform at home, the arm at the operation's pose), and
with a winch the cable's length follows the tip's height so that the payload's height
stays the still ship's:

- the arm has three joints for two horizontal coordinates: Newton's method with the
  minimum-norm step ``J⁺ e`` and the redundant direction pulled to the operation's pose
  (``(I − J⁺ J)(q_op − q)``), all samples at once;
- a joint that would leave its limits is held at the limit (the residual then shows in
  the payload's motion) and reported with the samples and the time it was held;
- the rates and accelerations of the commanded arm and of the cable length come from
  sixth-order finite differences of the solution on the uniform sample grid (the sea
  record at 100 Hz: relative error ~1e-9).

With a moving target (a point on a second vessel's deck, ``deck``: ship-to-ship
transfer) the load's aim moves with the deck, and the load's position is used as the
pendulum's flat output (Fliess, Lévine, Martin, Rouchon, Int. J. Control 61(6), 1995):
the cable must lie along ``u = (a − g)/|a − g|`` for the load to have the deck's
acceleration ``a``, so the tip is aimed at ``p_aim + L u`` and the winch sets
``L = (z_tip − z_aim)/u_z`` (:data:`AIM_PASSES` passes of arm and length).

Compensation of the motion the *arm* introduces (the classic source, after W. Küchler,
O. Sawodny et al., *Active control for an offshore crane using prediction of the
vessel's motion*, IEEE/ASME Trans. Mechatronics 16(2), 2011: the winch compensates the
rope's suspension point's vertical motion; the arm here adds the horizontal).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from offshore_crane.conventions import GRAVITY
from offshore_crane.dynamics.cable.tip import BLOCK, tip_positions
from offshore_crane.errors import InputError

#: The compensation modes: none, the arm (horizontal), the arm and the winch (vertical).
MODES = ("none", "arm", "arm+winch")
#: Newton's tolerance on the tip's horizontal position [m] and its iteration cap.
IK_TOLERANCE, IK_ITERATIONS = 1e-12, 30
#: Order of the finite differences giving the commanded rates and accelerations.
FD_ORDER = 6
#: Passes of the arm's solve and the winch's length when tracking a deck with the winch:
#: the tip's aim moves with the length along the tilted cable (``L u_xy``, |u_xy| ≲ a/g)
#: and the length with the tip's height; each pass shrinks the change by that factor
#: times the platform's tilt (≲ 1e-2): three leave it below 1e-12 m.
AIM_PASSES = 3


@dataclass
class Compensated:
    """A compensated motion (:func:`compensated_motion`).

    Attributes:
        mode: One of :data:`MODES`.
        trajectory: The robot's motion with the arm's commanded q7..q9 (and their rates,
            accelerations).
        target: ``(N, 3)`` where the tip is to be, base frame [m]: its still-ship
            position, plus the target deck's displacement when one is tracked.
        tip: ``(N, 3)`` the tip's position under the compensated motion [m].
        hoist: ``(N, 3)`` the cable length L [m], L̇, L̈ with the winch, else None.
        held: ``{joint: (samples held at a limit, first time [s])}`` for joints that met
            their limits.
        length: The cable's length on the still ship [m].
        deck: ``(N, 3)`` the tracked deck point's displacement [m], base axes, or None.
        aim, aim_velocity: ``(N, 3)`` where the payload is to be [m] and its velocity
            [m/s], base frame: ``length`` below the still-ship tip, moved with the deck.
    """

    mode: str
    trajectory: object
    target: np.ndarray
    tip: np.ndarray
    hoist: np.ndarray | None
    length: float
    held: dict = field(default_factory=dict)
    deck: np.ndarray | None = None
    aim: np.ndarray | None = None
    aim_velocity: np.ndarray | None = None

    def hoist_function(self):
        """The winch's ``hoist(t) -> (L, L̇, L̈)`` at any times of the record (quintic
        Hermite interpolation of the samples), or None."""
        if self.hoist is None:
            return None
        from offshore_crane.dynamics.cable.grid import quintic_hermite

        t, H = self.trajectory.t, self.hoist
        return lambda x: quintic_hermite(t, H[:, 0:1], H[:, 1:2], H[:, 2:3], x)


def still_tip(robot, q, qd, qdd) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Where the tip is on a still ship: its position [m], velocity [m/s] and
    acceleration [m/s²] ``(N, 3)`` each, base frame, with the platform at home and the
    arm on ``q, qd, qdd`` ``(N, 9)``'s q7..q9 (the crane operation), by the formulas on
    NumPy arrays (:func:`~offshore_crane.dynamics.sway.tip_state`, ``tip_motion``)."""
    from offshore_crane.dynamics import backends
    from offshore_crane.dynamics.constants import cable_arrays

    still = [np.array(x, dtype=float) for x in (q, qd, qdd)]
    still[0][:, :6] = robot.home_pose()[:6]
    still[1][:, :6] = 0.0
    still[2][:, :6] = 0.0
    p, v = tip_positions(robot, still[0], still[1])
    a = backends.NUMPY.tip_motion(cable_arrays(robot).kane, *(x.T for x in still))[3]
    return p, v, np.stack([np.broadcast_to(np.asarray(x, dtype=float), (len(p),))
                           for x in a], axis=-1)


#: The shortest measurement delay but none [s]: no measurement chain (motion sensor, bus,
#: controller) answers within a microsecond; shorter, ``t − delay`` is ``t`` to the
#: times' rounding and the delay means nothing.
DELAY_MIN = 1e-6
#: The longest delay as a fraction of the sea's peak period: compensating a motion
#: measured ``τ`` late leaves ``|1 − e^{−iωτ}| = 2 |sin(ωτ/2)|`` of it, which exceeds the
#: uncompensated motion (1) at the peak frequency from ``τ = Tp/6`` on.
DELAY_MAX_PERIOD = 1.0 / 6.0


def check_delay(delay, peak: float | None = None, name: str = "delay") -> float:
    """A measurement delay [s]: 0, or at least :data:`DELAY_MIN`, and (given the sea's
    peak period ``peak`` [s], model scale) at most :data:`DELAY_MAX_PERIOD` of it.

    Raises:
        InputError: naming ``name``, the value and the bound.
    """
    if not (isinstance(delay, (int, float, np.floating)) and not isinstance(delay, bool)
            and np.isfinite(delay) and delay >= 0.0):
        raise InputError(f"{name} = {delay!r} s: give a finite number >= 0 (the "
                         "measurement's delay)", name=name)
    if 0.0 < delay < DELAY_MIN:
        raise InputError(f"{name} = {delay:.3g} s: shorter than any measurement chain's "
                         f"({DELAY_MIN:g} s): give 0 (none) or >= {DELAY_MIN:g} s", name=name)
    if peak is not None and delay > DELAY_MAX_PERIOD * peak:
        raise InputError(f"{name} = {delay:.4g} s: over a sixth of the sea's peak period "
                         f"{peak:.4g} s (model scale), where compensating amplifies the "
                         f"motion: give <= {DELAY_MAX_PERIOD * peak:.4g} s", name=name)
    return float(delay)


def check_compensable(robot) -> None:
    """Raise :class:`InputError` unless the robot has the crane arm and a payload on a
    cable: what a compensation moves and what it holds still."""
    if robot.hybrid.cable is None or robot.hybrid.arm.n != 3:
        raise InputError("compensation needs the crane arm and a payload on a cable "
                         "(payload.cable_length > 0)", name="compensation")


def still_start(robot, comp: Compensated, gravity, ea: float | None = None) -> dict:
    """The payload at the start of a compensated motion ``comp``: at its aim (still
    below the still-ship tip, or moving with the target deck), on the cable's starting
    length (the winch's, else the still ship's) pointing from the tip towards the aim,
    with the aim's velocity as far as the cable allows; uncompensated (``"none"``)
    hanging along g at rest in the base frame.

    Returns:
        Rigid cable: ``{"initial": (φ1, φ2), "initial_rate": (φ̇1, φ̇2)}`` [rad, rad/s]
        (the cable's direction in the tip's axes; the rates that give the payload the
        aim's velocity across the cable). Elastic of stiffness ``ea`` [N]: ``{"initial":
        ρ0, "initial_velocity": v}`` [m, m/s], base axes, ρ0 at the static stretch, v
        the aim's velocity from the tip's across the cable and the winch's rate along
        it (no axial ringing from the start).
    """
    from offshore_crane.dynamics import backends
    from offshore_crane.dynamics.constants import cable_arrays

    trajectory = comp.trajectory
    length = comp.length if comp.hoist is None else float(comp.hoist[0, 0])
    g = np.asarray(gravity, dtype=float)
    q0, qd0, qdd0 = (np.asarray(x, dtype=float)[:1] for x in (trajectory.q, trajectory.qd,
                                                               trajectory.qdd))
    p_tip, v_tip = (x[0] for x in tip_positions(robot, q0, qd0))
    if comp.mode == "none":                              # hanging still below its tip
        toward, v_rel = g / np.linalg.norm(g), -v_tip
    else:
        toward = comp.aim[0] - p_tip
        toward = toward / np.linalg.norm(toward)
        v_rel = comp.aim_velocity[0] - v_tip             # the payload's, from the tip's
    rate = 0.0 if comp.hoist is None else float(comp.hoist[0, 1])
    v_rel = v_rel + (rate - v_rel @ toward) * toward     # along the cable: the winch's
    if ea is not None:
        stretch = 1.0 + float(robot.hybrid.cable.mass[-1]) * np.linalg.norm(g) / ea
        return {"initial": toward * length * stretch, "initial_velocity": v_rel}
    B, C = backends.NUMPY, cable_arrays(robot).kane
    Rt, w = B.tip_motion(C, q0.T, qd0.T, qdd0.T)[:2]
    Rt = np.array([[float(np.asarray(x)[0]) for x in row] for row in Rt])
    w = np.array([float(np.asarray(x)[0]) for x in w])
    e = Rt.T @ toward                                     # the cable, tip axes
    p2 = float(np.arcsin(np.clip(-e[0], -1.0, 1.0)))
    p1 = float(np.arctan2(e[1], -e[2]))
    _, e1, e2 = (np.array(v, dtype=float) for v in B.sway_direction(p1, p2))
    # L ė (tip axes) = Rtᵀ (v_payload − v_tip) − (Rtᵀ ω) × (L e), across the cable
    edot = (Rt.T @ v_rel) / length - np.cross(Rt.T @ w, e)
    return {"initial": (p1, p2),
            "initial_rate": (float(edot @ e1 / (e1 @ e1)), float(edot @ e2))}


def compensated_motion(robot, trajectory, mode: str = "arm+winch",
                       delay: float = 0.0, deck=None, gravity=GRAVITY) -> Compensated:
    """The arm's (and the winch's) commands that cancel the ship's motion at the tip.

    Args:
        robot: With a payload on a cable (its length is the still ship's).
        trajectory: The robot's motion (a sea record: q1..q6 the ship, q7..q9 the crane
            operation), uniform in time.
        mode: ``"none"`` (the operation as given), ``"arm"`` or ``"arm+winch"``.
        delay: The measurement's delay [s] (≥ 0): the commands at t are those that
            cancel the platform's pose at ``t − delay`` (the record's analytic source
            must reach that far back: :func:`measured_from`; without a source the first
            sample is held).
        deck: A moving target (ship-to-ship transfer): ``deck(t) -> (x, v, a)``, the
            displacement of a point on a second vessel's deck, each ``(n, 3)`` [m, m/s,
            m/s²] at model-scale times, base axes
            (:class:`~offshore_crane.motion.sea.DeckMotion`); the tip tracks the still-ship
            point moved with it and the winch the deck's height, both as measured
            ``delay`` late. None: a fixed point.
        gravity: ``(3,)`` [m/s²]: the cable's direction under a moving target.

    Raises:
        InputError: an unknown mode, a robot without arm or cable, a record too short
            for the finite differences; the still-ship target out of the arm's reach
            everywhere (Newton does not converge).
    """
    from offshore_crane.motion.trajectories.differences import finite_difference
    from offshore_crane.robot.kinematics.workspace import limits_of

    if mode not in MODES:
        raise InputError(f"compensation = {mode!r}: use one of {', '.join(MODES)}",
                         name="compensation")
    check_delay(delay)
    check_compensable(robot)
    t, q = trajectory.t, np.array(trajectory.q, dtype=float)
    still = q.copy()
    still[:, :6] = robot.home_pose()[:6]
    still_qd = np.array(trajectory.qd, dtype=float)
    still_qd[:, :6] = 0.0
    length = float(robot.hybrid.cable_length)
    g = np.asarray(gravity, dtype=float)
    down = g / np.linalg.norm(g)
    still_tip, still_v = tip_positions(robot, still, still_qd)
    aim, aim_v = still_tip + length * down, still_v          # the payload's aim
    seen_aim, seen_a, moved = aim, np.zeros_like(aim), None
    if deck is not None:
        moved, moved_v, _ = (np.asarray(x, dtype=float) for x in deck(t))
        seen_x, _, seen_a = (np.asarray(x, dtype=float) for x in deck(t - delay))
        aim, aim_v, seen_aim = aim + moved, aim_v + moved_v, aim + seen_x
    # the cable along the pull that gives the payload the deck's acceleration (flat output)
    up = (seen_a - g) / np.linalg.norm(seen_a - g, axis=1, keepdims=True)
    if mode == "none":
        return Compensated(mode, trajectory, seen_aim + length * up,
                           tip_positions(robot, q)[0], None, length, deck=moved, aim=aim,
                           aim_velocity=aim_v)
    limits = limits_of(robot.hybrid).arm[:3]
    held: dict = {}
    seen = _delayed(trajectory, delay)              # the platform as measured
    L = np.full(len(t), length)
    for _ in range(AIM_PASSES if mode == "arm+winch" and deck is not None else 1):
        target = seen_aim + L[:, None] * up
        solved, stuck = solve_arm(robot, seen, still[:, 6:9], target[:, :2], limits)
        if mode == "arm+winch":                     # the tip's height sets the length
            L = (tip_positions(robot, solved)[0][:, 2] - seen_aim[:, 2]) / up[:, 2]
    q[:, 6:9] = solved[:, 6:9]
    for j, name in enumerate(("arm_joint1", "arm_joint2", "arm_slide")):
        if stuck[:, j].any():
            held[name] = (int(stuck[:, j].sum()), float(t[int(np.argmax(stuck[:, j]))]))
    qd, qdd = np.array(trajectory.qd), np.array(trajectory.qdd)
    qd[:, 6:9], qdd[:, 6:9] = finite_difference(t, q[:, 6:9], FD_ORDER)
    tip = tip_positions(robot, q)[0]
    hoist = None
    if mode == "arm+winch":
        if not (L > 0).all():
            k = int(np.argmax(~(L > 0)))
            where = "the target ([control] target)" if deck is not None else "the aim"
            raise InputError(f"compensation: {where} is out of reach, "
                             f"{seen_aim[k, 2] - tip[k, 2]:.3g} m above the crane tip at t = "
                             f"{t[k]:.4g} s: pick a point that heaves less, a calmer sea, or "
                             "mode \"arm\"", name="compensation", index=k)
        Ld, Ldd = finite_difference(t, L, FD_ORDER)
        hoist = np.column_stack([L, Ld, Ldd])
    traj = replace(trajectory, name=f"{trajectory.name}, compensated ({mode})", q=q, qd=qd,
                   qdd=qdd, source=None)
    return Compensated(mode, traj, target, tip, hoist, length, held, moved, aim, aim_v)


def measured_from(trajectory, delay: float):
    """The record from the time its first measurement has arrived (``t ≥ t0 + delay``):
    a compensation acting ``delay`` [s] late reads the platform there through the
    record's source, which reaches back to ``t0``."""
    if delay <= 0.0:
        return trajectory
    check_delay(delay)
    t = trajectory.t
    if not delay < t[-1] - t[0]:
        raise InputError(f"delay = {delay:.4g} s: not shorter than the record's span "
                         f"{t[-1] - t[0]:.4g} s: give a shorter delay or a longer duration",
                         name="delay")
    k0 = int(np.searchsorted(trajectory.t, trajectory.t[0] + delay - 1e-12))
    return replace(trajectory, t=trajectory.t[k0:], q=trajectory.q[k0:],
                   qd=trajectory.qd[k0:], qdd=trajectory.qdd[k0:])


def _delayed(trajectory, delay: float) -> np.ndarray:
    """``q (N, 9)`` with the platform's q1..q6 as measured ``delay`` [s] late (the
    record's analytic source where it has one, else linear interpolation with the first
    sample held before the start)."""
    q = np.array(trajectory.q, dtype=float)
    if delay == 0.0:
        return q
    if trajectory.source is not None:
        q[:, :6] = np.asarray(trajectory.source(trajectory.t - delay)[0])[:, :6]
    else:
        t = np.maximum(trajectory.t - delay, trajectory.t[0])
        for j in range(6):
            q[:, j] = np.interp(t, trajectory.t, trajectory.q[:, j])
    return q


def solve_arm(robot, q, q_op, xy, limits) -> tuple[np.ndarray, np.ndarray]:
    """Newton on q7..q9 of every sample: the tip's horizontal position at ``xy``
    ``(N, 2)``, the redundant direction towards ``q_op``; joints held inside ``limits``
    ``(3, 2)``. Returns ``(q, held (N, 3) bool)``; in blocks of :data:`BLOCK` samples."""
    out, held = np.empty_like(q), np.zeros((len(q), 3), dtype=bool)
    for a in range(0, len(q), BLOCK):
        b = slice(a, a + BLOCK)
        out[b], held[b] = _solve_block(robot, q[b], q_op[b], xy[b], limits, a)
    return out, held


def _solve_block(robot, q, q_op, xy, limits, first: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`solve_arm` on one block whose first sample is ``first``."""
    from offshore_crane.dynamics import backends
    from offshore_crane.dynamics.constants import cable_arrays

    C = cable_arrays(robot).kane
    q = q.copy()
    lo, hi = limits[:, 0], limits[:, 1]
    held = np.zeros((len(q), 3), dtype=bool)
    active = np.arange(len(q))                  # samples still iterating
    for _ in range(IK_ITERATIONS):
        qa = q[active]
        tip, cols = backends.NUMPY.tip_jacobian(C, qa.T)
        e = xy[active] - np.stack(tip[:2], axis=-1)
        done = (np.abs(e).max(axis=1) <= IK_TOLERANCE) | held[active].any(axis=1)
        keep = ~done
        active, e, qa = active[keep], e[keep], qa[keep]
        if not len(active):
            break
        # rows of the horizontal Jacobian J (2 × 3); the step J⁺ e + (I − J⁺ J) d with
        # d = q_op − q is d + Jᵀ (J Jᵀ)⁻¹ (e − J d), the 2 × 2 inverse written out
        j0 = np.stack([c[0][keep] for c in cols], axis=-1)               # (n, 3)
        j1 = np.stack([c[1][keep] for c in cols], axis=-1)
        d = q_op[active] - qa[:, 6:9]
        r0 = e[:, 0] - (j0 * d).sum(axis=1)
        r1 = e[:, 1] - (j1 * d).sum(axis=1)
        a, b, c = (j0 * j0).sum(axis=1), (j0 * j1).sum(axis=1), (j1 * j1).sum(axis=1)
        det = a * c - b * b
        w0, w1 = (c * r0 - b * r1) / det, (a * r1 - b * r0) / det
        arm = qa[:, 6:9] + d + j0 * w0[:, None] + j1 * w1[:, None]
        held[active] = (arm < lo) | (arm > hi)
        q[active, 6:9] = np.clip(arm, lo, hi)
    else:
        bad = np.abs(xy - tip_positions(robot, q)[0][:, :2]).max(axis=1) > 1e-6
        if (bad & ~held.any(axis=1)).any():
            k = first + int(np.argmax(bad & ~held.any(axis=1)))
            raise InputError(f"compensation: the arm cannot reach the still-ship tip "
                             f"position at sample {k} (Newton did not converge): check "
                             "the operation's pose", name="compensation", index=k)
    return q, held
