"""The RNEA reference's forces: ``τ = RNEA(tree state)`` projected on the independent speeds.

With ``G = ∂v_tree/∂u`` (its leg rows ``J⁻¹ ∂v_S/∂u``, from :mod:`.closure`), the virtual
power of the tree equals that of the mechanism: ``Gᵀ S X = Gᵀ τ``, ``S`` placing X on the
actuated joints; so ``(T1, T2, Fs) = τ_arm`` and ``Jlᵀ Fl = (Gᵀ τ)[0:6]`` with ``Jl`` the
leg-length rows of G, solved by a Householder QR of its own (compiled with Numba).

This path checks nothing: it returns X, the leg-force systems' condition numbers and the
legs' raw kinematic diagnostics (:class:`Forces`); the caller applies the workspace limits
and the singularity policy (``offshore_crane.dynamics``).

Frames: the base frame is Pinocchio's world (the URDF root ``base``); units SI.
"""

from __future__ import annotations

import weakref
from typing import Any, NamedTuple

import numpy as np
from offshore_crane.kernel_cache import njit

from offshore_crane.reference.rnea.closure import tree_state
from offshore_crane.reference.rnea.tree import read_tree

#: Samples per block: the tree's Q, V, A, τ arrays (4 x 27 doubles a sample) stay bounded.
#: :func:`actuator_forces` evaluates what it is given at once; callers split long inputs.
BLOCK = 1 << 16

jit = njit(cache=True, nogil=True, error_model="numpy")


class Forces(NamedTuple):
    """What the RNEA reference returns for ``n`` samples, unchecked.

    Attributes:
        X: ``(n, 9)`` actuator forces ``[T1, T2 [N·m], Fs, Fl1..Fl6 [N]]`` (NaN in the arm
            columns of a robot without its arm).
        condition: ``(n,)`` 1-norm condition number of the leg-force system ``Jlᵀ``
            (rotation rows scaled by 1/L); 0 when ``conditioning`` was not asked for.
        length: ``(n, 6)`` leg lengths [m] (the slide joints of the tree state).
        cos_theta2: ``(n, 6)`` ``|cos θ2|`` of each U-joint (gimbal: 0 is singular).
        height: ``(n, 6)`` height of each sphere centre S_i above its U-joint centre P_i,
            along the base's z [m].
        theta: ``(n, 6, 2)`` U-joint angles θ1, θ2 [rad].
    """

    X: np.ndarray
    condition: np.ndarray
    length: np.ndarray
    cos_theta2: np.ndarray
    height: np.ndarray
    theta: np.ndarray


@jit
def qr_solve(A, b, x, Q, R, want_cond):
    """``x = A⁻¹ b`` for a 6x6 ``A`` by Householder QR (``Q``, ``R`` (6, 6) workspaces:
    the reflectors and the triangle); the 1-norm condition number ``‖A‖₁ ‖A⁻¹‖₁`` when
    ``want_cond`` (else 0); inf and a NaN solution for a singular or non-finite A."""
    n = 6
    for i in range(n):
        for j in range(n):
            R[i, j] = A[i, j]
            Q[i, j] = 0.0
    for k in range(n):
        norm = 0.0
        for i in range(k, n):
            norm += R[i, k] * R[i, k]
        norm = np.sqrt(norm)
        if not norm > 0.0:
            for i in range(n):
                x[i] = np.nan
            return np.inf
        alpha = -norm if R[k, k] >= 0.0 else norm
        vnorm = 0.0
        for i in range(k, n):
            Q[i, k] = R[i, k] - (alpha if i == k else 0.0)
            vnorm += Q[i, k] * Q[i, k]
        for j in range(k, n):                 # R ← (I − 2 v vᵀ / vᵀv) R
            dotv = 0.0
            for i in range(k, n):
                dotv += Q[i, k] * R[i, j]
            f = 2.0 * dotv / vnorm
            for i in range(k, n):
                R[i, j] -= f * Q[i, k]
        Q[k, k] = Q[k, k] / np.sqrt(vnorm)    # keep v normalised in Q's column k
        for i in range(k + 1, n):
            Q[i, k] = Q[i, k] / np.sqrt(vnorm)
    cond = 0.0
    if want_cond:
        norm_a = 0.0
        norm_inv = 0.0
        for j in range(n):
            sa = 0.0
            for i in range(n):
                sa += abs(A[i, j])
            norm_a = max(norm_a, sa)
        for j in range(n):
            for i in range(n):
                x[i] = 1.0 if i == j else 0.0
            _qr_apply(Q, R, x)
            si = 0.0
            for i in range(n):
                si += abs(x[i])
            norm_inv = max(norm_inv, si)
        cond = norm_a * norm_inv
    for i in range(n):
        x[i] = b[i]
    _qr_apply(Q, R, x)
    return cond


@jit
def _qr_apply(Q, R, x):
    """``x ← R⁻¹ Qᵀ x`` with the unit reflectors in Q's columns."""
    n = 6
    for k in range(n):
        dotv = 0.0
        for i in range(k, n):
            dotv += Q[i, k] * x[i]
        for i in range(k, n):
            x[i] -= 2.0 * dotv * Q[i, k]
    for i in range(n - 1, -1, -1):
        s_ = x[i]
        for j in range(i + 1, n):
            s_ -= R[i, j] * x[j]
        x[i] = s_ / R[i, i]


@jit
def project(tau: np.ndarray, G: np.ndarray, plat_v: np.ndarray, leg_v: np.ndarray,
            arm_v: np.ndarray, iL: float, want_cond: bool, X: np.ndarray,
            cond: np.ndarray) -> None:
    """``B = Gᵀ τ`` and the actuator forces: ``(T1, T2, Fs) = τ_arm`` and the legs from
    ``Jlᵀ Fl = B[0:6]`` (rows of the rotation coordinates scaled by 1/L), solved by QR;
    ``cond`` receives that system's 1-norm condition number. ``tau`` (N, nv): a sample a
    row (the transpose of the Fortran (nv, N) array Pinocchio fills: C-ordered for any
    N, one compiled signature for every call)."""
    N = tau.shape[0]
    na = arm_v.shape[0]
    A = np.empty((6, 6))
    rhs = np.empty(6)
    x = np.empty(6)
    Q = np.empty((6, 6))
    R = np.empty((6, 6))
    for k in range(N):
        for b in range(3):
            X[k, b] = tau[k, arm_v[b]] if b < na else np.nan
        for r in range(6):
            B = tau[k, plat_v[r]]
            for l in range(6):
                for j in range(3):
                    B += tau[k, leg_v[l, j]] * G[k, l, j, r]
            f = iL if r >= 3 else 1.0
            rhs[r] = B * f
            for l in range(6):
                A[r, l] = G[k, l, 2, r] * f
        c = qr_solve(A, rhs, x, Q, R, want_cond)
        cond[k] = c
        for l in range(6):
            X[k, 3 + l] = x[l]


_POOLS: dict = {}


def pool(robot: Any, gravity: np.ndarray, threads: int) -> Any:
    """A ``pin.ModelPool`` of ``robot.pinocchio_model`` with this gravity [m/s²], reused
    across calls (while the robot lives)."""
    import pinocchio as pin

    key = (id(robot), tuple(float(x) for x in gravity), threads)
    entry = _POOLS.get(key)
    if entry is None or entry[0]() is not robot:
        model = robot.pinocchio_model.copy()
        model.gravity.linear = np.asarray(gravity, dtype=float)
        entry = _POOLS[key] = (weakref.ref(robot), pin.ModelPool(model, threads))
    return entry[1]



def rnea_projected(robot: Any, Q: np.ndarray, V: np.ndarray, A: np.ndarray, G: np.ndarray,
                   gravity: np.ndarray, *, conditioning: bool = False, threads: int = 1,
                   X: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``τ = RNEA(Q, V, A)`` by ``pin.rneaInParallel`` and its projection :func:`project`.

    Args:
        Q, V, A: ``(nv, N)`` Fortran-ordered tree states (:func:`.closure.tree_state`).
        G: ``(N, 6, 3, 6)`` the legs' joint-rate partials on q̇1..q̇6.
        gravity: ``(3,)`` in the base frame [m/s²].
        conditioning: Measure the leg-force systems' condition numbers.
        threads: Threads of ``pin.rneaInParallel``.
        X: ``(N, 9)`` C-ordered array to write the forces into (a new one by default).

    Returns:
        ``(X (N, 9), condition (N,), tau (nv, N))``.
    """
    import pinocchio as pin

    T = read_tree(robot)
    N = Q.shape[1]
    tau = np.empty_like(Q, order="F")
    pin.rneaInParallel(threads, pool(robot, gravity, threads), Q, V, A, tau)
    X = np.empty((N, 9)) if X is None else X
    cond = np.empty(N)
    project(tau.T, G, T.plat_v, T.legs.v_index, T.arm_v, 1.0 / T.L, conditioning, X, cond)
    return X, cond, tau


def actuator_forces(robot: Any, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray,
                    gravity: np.ndarray, *, conditioning: bool = False, threads: int = 1,
                    X: np.ndarray | None = None) -> Forces:
    """Actuator forces by the reference path, with the diagnostics the checks read.

    Evaluates all ``N`` samples at once (about 120 doubles a sample of temporaries):
    callers with long inputs pass blocks of :data:`BLOCK` samples. Nothing is checked
    here: the caller applies limits and thresholds to the returned :class:`Forces`.

    Args:
        robot: Read by attribute only: ``robot.pinocchio_model``.
        q, qd, qdd: ``(N, 9)`` finite float64 coordinates [m, rad], rates, accelerations
            (docs/conventions.md).
        gravity: ``(3,)`` in the base frame [m/s²].
        conditioning: Measure the leg-force systems' condition numbers (else 0).
        threads: Threads of ``pin.rneaInParallel``.
        X: ``(N, 9)`` C-ordered array to write the forces into (a new one by default).

    Raises:
        NumericalError: Newton's method did not close a loop (naming the sample).
    """
    Q, V, A, G, diag = tree_state(robot, q, qd, qdd)
    X, cond, _ = rnea_projected(robot, Q, V, A, G, gravity, conditioning=conditioning,
                                threads=threads, X=X)
    return Forces(X, cond, diag[0], diag[1], diag[2], np.stack([diag[3], diag[4]], -1))
