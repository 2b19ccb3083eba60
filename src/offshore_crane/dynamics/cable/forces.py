"""X of the robot with its hanging load by the compiled Kane pass
(:func:`offshore_crane.dynamics.cable.kernels.kane`'s block form vectorised across
samples, :mod:`offshore_crane.dynamics.lanes`: the same numbers; the per-sample kernel when
the formulas cannot be traced)."""

from __future__ import annotations

import numpy as np

from offshore_crane.robot.kinematics import workspace as ws
from offshore_crane.robot.kinematics.formulas import FULL


#: Samples per chunk of the Kane pass: its 11-column rows are formed a chunk at a time,
#: right before the kernel reads them (still in cache), and a chunk is the unit the
#: threads take and what waits for the sway's integration when it runs alongside.
CHUNK = 1 << 14


def kane_forces(robot, t, q, qd, qdd, Y, g, limits, checks, thresholds, L=None, P=None,
                at=None, *, threads: int = 1, rows_ready=None):
    """X ``(n, 9)``, the cable's ``F`` ``(n, 6)`` and the condition numbers, by the
    compiled ``kernels.kane``: the payload on the chain (``L`` and ``P`` None), or
    ``kernels.kane_pulled`` with the pull on the robot of the hoisted pendulum (``L``
    ``(n, 3)``: the winch's length, rate, acceleration) or given (``P`` ``(n, 3)`` [N]:
    an elastic cable), acting at ``at`` ``(n, 3)`` [m] from the tip (base axes; the
    payload's place; None: at the tip); chunks of :data:`CHUNK` samples shared by
    ``threads`` (checked by the caller, :func:`~offshore_crane.validation.thread_count`).
    ``F`` holds the pull (3) [N], the tension [N] and the residual of the two sway
    equations [N·m] (zero for a given pull).

    With the payload's drag (``robot.hybrid.drag`` > 0) on the chain, the chain's pass
    gives the sway equations' residual (less the drag's ``v_r · f``) and ``m (g − a_p)``;
    X then comes from a second pass with the pull ``m (g − a_p) + f`` at the payload
    (the chain's payload body carries no external force).

    ``rows_ready(b)``: None when the sway ``Y`` is complete; else called before a chunk
    ending at sample ``b`` is read, it waits until the rows before ``b`` are written
    (an integration still running) and returns how many of them hold the sway (< b when
    the integration stopped early); samples past that are not computed (their rows of
    X, F and the condition numbers are undefined)."""
    from concurrent.futures import ThreadPoolExecutor

    from offshore_crane.dynamics.runtime import compiled_kernels
    from offshore_crane.dynamics.cable import kernels as ck
    from offshore_crane.dynamics.constants import cable_arrays

    compiled_kernels()
    arrays = cable_arrays(robot)
    n = len(t)
    q11, qd11, qdd11 = (np.empty((n, 11)) for _ in range(3))
    X = np.empty((n, 9))
    F = np.empty((n, 6))
    kappa = np.empty((3, n)) if checks else np.empty((3, 1))
    if n == 0:
        return X, F, kappa if checks else None
    if L is not None:                # the hoisted pendulum's pull, vectorised
        P, at, F[:] = hoisted_pull(robot, arrays.kane, q, qd, qdd, Y, L, g)
    elif P is not None:              # an elastic cable's: its tension is the pull's part
        P = np.ascontiguousarray(P)  # along the cable (at the tip: all of it)
        F[:, 0:3], F[:, 4:6] = P, 0.0
        if at is None:
            at, F[:, 3] = np.zeros_like(P), np.linalg.norm(P, axis=1)
        else:
            at = np.ascontiguousarray(at)
            F[:, 3] = np.einsum("ij,ij->i", P, at) / np.linalg.norm(at, axis=1)
    chunks = [(a, min(a + CHUNK, n)) for a in range(0, n, CHUNK)]
    records = [ws.new_health() for _ in chunks]
    kane = ck.kane
    if P is None:
        # blocks of samples vectorised across them, whatever the count (a swing's few
        # samples cost microseconds more); the per-sample kernel, 15 s to compile, is
        # then compiled only when the formulas cannot be traced
        from offshore_crane.dynamics.lanes import kane_kernel

        kane = kane_kernel(arrays, FULL, cable=True) or ck.kane

    def run(i, pulled):
        start, stop = chunks[i]
        if rows_ready is not None:
            stop = min(stop, rows_ready(stop))
        if stop <= start:
            return
        for out, given, col in ((q11, q, 0), (qd11, qd, 2), (qdd11, qdd, 4)):
            out[start:stop, :9] = given[start:stop]
            out[start:stop, 9:] = Y[start:stop, col:col + 2]
        if not pulled:
            kane(arrays.flat, arrays.layout, arrays.prismatic, robot.hybrid.sway_damping,
                 q11, qd11, qdd11, g, checks, limits, thresholds.warn, thresholds.error,
                 start, stop, X, kappa, records[i], F)
        else:
            ck.kane_pulled(arrays.flat, arrays.layout, arrays.prismatic, q11, qd11, qdd11, P,
                           at, g, checks, limits, thresholds.warn, thresholds.error, start,
                           stop, X, kappa, records[i])

    def passes(pulled):
        if threads == 1 or len(chunks) == 1:
            for i in range(len(chunks)):
                run(i, pulled)
        else:
            pool = ThreadPoolExecutor(threads)
            try:
                list(pool.map(lambda i: run(i, pulled), range(len(chunks))))
            except BaseException:   # a signal's: chunks not begun cancelled; those waiting
                pool.shutdown(wait=False, cancel_futures=True)  # for the integration end
                raise               # with it (the caller stops it), not before
            pool.shutdown()

    passes(P is not None)
    if P is None and robot.hybrid.drag > 0.0:           # the chain's pull, and the drag
        f, at, v1, v2, e = hanging_drag(robot, arrays.kane, q, qd, qdd, Y, None)
        P = np.ascontiguousarray(F[:, 0:3] + f)
        F[:, 0:3], F[:, 3] = P, np.einsum("ij,ij->i", P, e)
        F[:, 4] -= np.einsum("ij,ij->i", v1, f)
        F[:, 5] -= np.einsum("ij,ij->i", v2, f)
        records = [ws.new_health() for _ in chunks]
        rows_ready = None
        passes(True)
    health = ws.merge(records)
    ws.enforce(health, (q, qd, qdd), arrays.limits if limits else None,
               kappa if checks else None, thresholds, (ws.LEG_JACOBIAN, ws.GIMBAL), t)
    return X, F, kappa if checks else None


def hanging_drag(robot, C, q, qd, qdd, Y, L):
    """The payload's drag on a rigid cable at the sway ``Y`` and the cable's ``L``
    ``(n, 3)`` (length [m], rate [m/s], acceleration; None: the fixed length), on NumPy
    arrays (:func:`~offshore_crane.dynamics.sway.hanging_velocity`, ``drag_force``):
    ``(f, ρ, v1, v2, e)`` each ``(n, 3)``: the drag [N], the payload from the tip [m],
    its partial velocities of the sway rates ``L Rt ∂e/∂φ_r`` [m/rad] and the cable's
    direction, base axes."""
    from offshore_crane.dynamics import backends

    B = backends.NUMPY
    length = np.full(len(q), robot.hybrid.cable_length) if L is None else L[:, 0]
    rate = np.zeros(len(q)) if L is None else L[:, 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        Rt, w = B.tip_motion(C, q.T, qd.T, qdd.T)[:2]
        v_tip = B.tip_state(C, q.T, qd.T)[1]
        v = B.hanging_velocity(Rt, w, v_tip, Y[:, 0], Y[:, 1], Y[:, 2], Y[:, 3], length, rate)
        f = B.drag_force(v, robot.hybrid.drag)
        e, e1, e2 = B.sway_direction(Y[:, 0], Y[:, 1])
        base = [B.mv(Rt, x) for x in (e, e1, e2)]
    e, e1, e2 = (np.stack(x, axis=-1) for x in base)
    return (np.stack(f, axis=-1), e * length[:, None], e1 * length[:, None],
            e2 * length[:, None], e)


def hoisted_pull(robot, C, q, qd, qdd, Y, L, g):
    """``(pull (n, 3), at (n, 3), F (n, 6))`` of the hoisted pendulum
    (:func:`~offshore_crane.dynamics.sway.hoisted_pendulum` on NumPy arrays) at the sway
    ``Y`` and the winch's ``L`` ``(n, 3)``: the pull [N] and where it acts (the payload,
    from the tip [m]), the tension [N] and the residual of the sway equations at Y's φ̈
    [N·m]."""
    from offshore_crane.dynamics import backends

    B = backends.NUMPY
    c1, c2 = (float(c) for c in robot.hybrid.sway_damping)
    gt = tuple(float(x) for x in g)
    f, at = (0.0, 0.0, 0.0), None
    if robot.hybrid.drag > 0.0:
        f, at = hanging_drag(robot, C, q, qd, qdd, Y, L)[:2]
        f = tuple(f.T)
    with np.errstate(divide="ignore", invalid="ignore"):
        Rt, w, al, a_t = B.tip_motion(C, q.T, qd.T, qdd.T)
        a1, a2, cos2, pull, tension = B.hoisted_pendulum(
            C, Rt, w, al, a_t, gt, Y[:, 0], Y[:, 1], Y[:, 2], Y[:, 3], c1, c2, f, *L.T)
        if at is None:
            e = B.sway_direction(Y[:, 0], Y[:, 1])[0]
            at = np.stack(B.mv(Rt, e), axis=-1) * L[:, 0:1]
    m = float(C.arm_m[C.n_arm - 1])
    mL2 = m * L[:, 0] ** 2
    P = np.ascontiguousarray(np.stack(pull, axis=-1))
    F = np.column_stack([P, tension, mL2 * cos2 * (Y[:, 4] - a1), mL2 * (Y[:, 5] - a2)])
    return P, np.ascontiguousarray(at), F
