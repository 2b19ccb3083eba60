"""The constrained reference's loop closure: tree states by Newton on Pinocchio's frames.

Newton on the 18 residuals ``r = p_base_tip_i − p_base_anchor_i`` [m] over the passive
joints, with the Jacobian ``∂r/∂q_tree = J_tip − J_anchor`` (linear rows of Pinocchio's
frame Jacobians in LOCAL_WORLD_ALIGNED, i.e. derivatives of the frame origins in R1),
independent joints held fixed, each sample warm-started from the previous one. The passive
speeds follow from the same Jacobian: ``J_p v_p = −J_i v_i``.

Frames: the base frame R1 is Pinocchio's world (the URDF root ``base``); units SI.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from offshore_crane.errors import ConstraintResidualError, InputError, WorkspaceError
from offshore_crane.reference.constrained.model import LoopTree, loop_tree
from offshore_crane.validation import as_samples, same_length

#: Newton tolerance on the loop closure, max |p_tip − p_anchor| [m]. The robot spans
#: about 1 m, where one ulp is 2.2e-16 m; a chain of ~10 rigid transforms accumulates a
#: few ulp, so 1e-13 m (~500 ulp) is reachable and is far below any physical tolerance.
NEWTON_TOLERANCE = 1e-13
#: Newton iteration cap per sample. Measured: 2 steps per sample along Table 1 at 1 kHz
#: (3 at 100 Hz), 4–6 from an unrelated previous sample (random states) or from the
#: neutral legs; 30 steps leave a wide margin while a diverging solve still fails fast.
NEWTON_MAX_ITER = 30
#: Bound on the velocity residual max |v_tip − v_anchor| relative to the largest anchor
#: speed [m/s]: the passive speeds come from one 18x18 solve whose condition number is
#: <= 2.8 on 1000 random states (legs far from singular), so the round-off is ~1e-15
#: relative (measured <= 7e-16 m/s); 1e-10 flags a broken solve while tolerating
#: condition numbers up to ~1e5.
VELOCITY_RESIDUAL_BOUND = 1e-10


@dataclass(frozen=True)
class TreeStates:
    """Equivalent-tree states that close the six loops.

    Attributes:
        q: ``(N, nq)`` tree configuration in Pinocchio's order (nq = 27 with the arm,
            24 without) [m, rad].
        v: ``(N, nv)`` tree velocity [m/s, rad/s].
        position_residual: ``(N,)`` max over loops and axes of |p_tip − p_anchor| in R1 [m].
        velocity_residual: ``(N,)`` max over loops and axes of |v_tip − v_anchor| [m/s].
        iterations: ``(N,)`` Newton steps taken for each sample.
    """

    q: np.ndarray
    v: np.ndarray
    position_residual: np.ndarray
    velocity_residual: np.ndarray
    iterations: np.ndarray


def _samples(name: str, x, ignored: np.ndarray) -> tuple[np.ndarray, bool]:
    """``x`` as ``(N, 9)`` floats; columns ``ignored`` may hold anything (they are unused)."""
    try:
        arr = np.array(x, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be an array of numbers", name=name) from None
    if ignored.size and arr.ndim in (1, 2) and arr.shape[-1] == 9:
        arr[..., ignored] = 0.0
    return as_samples(name, arr)


def positive(name: str, value: Any, integer: bool = False) -> float | int:
    """``value`` as a positive finite float (or integer), else :class:`InputError`."""
    try:
        ok = (not isinstance(value, bool) and np.ndim(value) == 0 and bool(np.isfinite(value))
              and value > 0 and (not integer or float(value) == int(value)))
    except (TypeError, ValueError):
        ok = False
    if not ok:
        kind = "a positive integer" if integer else "a positive finite number"
        raise InputError(f"{name} must be {kind}, got {value!r}", name=name)
    return int(value) if integer else float(value)


def solve_tree(tree: LoopTree, q: np.ndarray, qd: np.ndarray, tolerance: float,
                max_iter: int, limits: bool) -> TreeStates:
    """Newton loop closure and passive speeds for every sample (see :func:`tree_states`)."""
    n, cols = len(q), tree.columns
    Q = np.empty((n, tree.model.nq))
    V = np.zeros((n, tree.model.nv))
    pos = np.empty(n)
    vel = np.empty(n)
    steps = np.empty(n, dtype=int)
    x = tree.start.copy()
    for k in range(n):
        x[tree.indep] = q[k, cols]
        for it in range(max_iter + 1):
            r, J = tree.loop_residual(x)
            err = np.abs(r).max()
            if err <= tolerance:
                break
            if it == max_iter or not np.isfinite(err):
                raise ConstraintResidualError(
                    f"loop closure did not converge at sample {k}: max |p_tip - p_anchor| = "
                    f"{err:.3g} m after {it} Newton steps (tolerance {tolerance:.3g} m); the "
                    "pose may be outside the legs' reach or at a leg singularity",
                    index=k, kind="position", residual=float(err), bound=tolerance)
            x[tree.passive] -= np.linalg.solve(J[:, tree.passive], r)
        Q[k], pos[k], steps[k] = x, err, it
        v_indep = qd[k, cols]
        V[k, tree.indep] = v_indep
        drive = J[:, tree.indep] @ v_indep             # anchor-relative speeds [m/s]
        V[k, tree.passive] = np.linalg.solve(J[:, tree.passive], -drive)
        vel[k] = np.abs(J @ V[k]).max()
        scale = np.abs(drive).max()
        if not vel[k] <= VELOCITY_RESIDUAL_BOUND * scale:
            raise ConstraintResidualError(
                f"velocity loop residual {vel[k]:.3g} m/s at sample {k} exceeds "
                f"{VELOCITY_RESIDUAL_BOUND:.0e} x {scale:.3g} m/s: the leg Jacobian is "
                "(nearly) singular there", index=k, kind="velocity", residual=float(vel[k]),
                bound=float(VELOCITY_RESIDUAL_BOUND * scale))
    if limits:
        _check_limits(tree, Q)
    return TreeStates(q=Q, v=V, position_residual=pos, velocity_residual=vel, iterations=steps)


def _check_limits(tree: LoopTree, Q: np.ndarray) -> None:
    """Every tree joint inside its URDF limits (leg strokes, U-joint and arm ranges)."""
    bad = (Q < tree.lower) | (Q > tree.upper)
    if bad.any():
        k, j = np.argwhere(bad)[0]
        joint = next(name for name, jm in zip(tree.model.names, tree.model.joints)
                     if jm.idx_q == j and jm.nq > 0)
        raise WorkspaceError(
            f"{joint} = {Q[k, j]:.6g} at sample {k} is outside its URDF limits "
            f"[{tree.lower[j]:.6g}, {tree.upper[j]:.6g}]; change the state, or pass "
            "limits=False to study it anyway", joint=joint, index=int(k), value=float(Q[k, j]))


def tree_states(robot: Any, q: np.ndarray, qd: np.ndarray,
                tolerance: float = NEWTON_TOLERANCE, max_iter: int = NEWTON_MAX_ITER,
                limits: bool = True) -> TreeStates:
    """Tree configurations and velocities that close the six loops, by Pinocchio alone.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q: ``(N, 9)`` or ``(9,)`` independent coordinates (docs/conventions.md) [m, rad].
        qd: Same shape, their rates [m/s, rad/s].
        tolerance: Newton stops when max |p_tip − p_anchor| <= tolerance [m].
        max_iter: Newton steps allowed per sample.
        limits: Check every tree joint (leg lengths, U-joint angles, arm joints) against
            its URDF limits.

    Returns:
        :class:`TreeStates` with ``(N, ·)`` arrays (also for one sample).

    Raises:
        InputError: bad shapes, NaN/inf, non-positive tolerance or max_iter.
        ConstraintResidualError: Newton did not converge within ``max_iter`` steps, or the
            velocity residual exceeds its bound (the message names the sample).
        WorkspaceError: a tree joint outside its URDF limits (``limits=True``).
        ModelError: the URDF lacks a joint or frame named in docs/conventions.md.
    """
    tree = loop_tree(robot)
    q, qd = validated_inputs(tree, q=q, qd=qd)
    return solve_tree(tree, q, qd, positive("tolerance", tolerance),
                       positive("max_iter", max_iter, integer=True), bool(limits))


def validated_inputs(tree: LoopTree, **arrays: Any) -> list[np.ndarray]:
    """Validated ``(N, 9)`` arrays; the columns a robot without its arm does not use (q7..q9
    of q and qd, T1, T2, Fs of X) are not looked at."""
    used = {"X": tree.act_columns}
    out = {name: _samples(name, x, np.setdiff1d(np.arange(9), used.get(name, tree.columns)))[0]
           for name, x in arrays.items()}
    same_length(**out)
    return list(out.values())


