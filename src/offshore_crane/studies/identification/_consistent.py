"""Physically consistent parameters: the identified base parameters lifted to every body's
ten parameters, each body's inertia a real one.

A body's parameters are those of a mass distribution exactly when its 4×4 pseudo-inertia
``J = [[Σ, h], [hᵀ, m]]`` (``Σ = ½ tr(I) 1 − I``, ``h = m c``, I about the frame's origin)
is positive definite (Wensing, Kim, Slotine, "Linear matrix inequalities for physically
consistent inertial parameter identification", IEEE RA-L 3(1), 2018): then ``m > 0`` and
the inertia about the centre of mass satisfies the triangle inequalities. The
log-Cholesky parametrisation ``J = U Uᵀ``, ``U = e^α [[e^d1, s12, s13, t1], [0, e^d2, s23,
t2], [0, 0, e^d3, t3], [0, 0, 0, 1]]`` (Rucker & Wensing, "Smooth parameterization of
rigid-body inertia", IEEE RA-L 7(2), 2022) maps every real θ to a consistent body, and
back: nonlinear least squares on θ (SciPy ``least_squares``) needs no constraint.

The cost: the base parameters' misfit weighted by their covariance, ``|L⁻¹ (K π(θ) −
β̂)|²`` (``L Lᵀ`` the fit's covariance), plus ``λ |(π(θ) − π_0) / s|²`` toward the
nominal parameters, which decides the directions the forces do not see (``s`` each
parameter's scale in the nominal robot, :data:`PRIOR_WEIGHT` λ): why a log-Cholesky
least squares and not an SDP — it needs only SciPy, keeps the unidentifiable
combinations at their drawing values, and its optimum is consistent by construction.
"""

from __future__ import annotations

import numpy as np

#: λ: the prior toward the nominal parameters, against the base parameters' misfit in
#: standard deviations (small: a 20 % departure costs 0.02 σ a parameter, so the data
#: decide what they see; large enough that the unseen directions converge quickly).
PRIOR_WEIGHT = 1e-2
#: Evaluations the least squares (Levenberg–Marquardt) may take: every iterate is
#: consistent by construction, and by then the base parameters fit to ~1e-5 σ on the
#: shipped robot (the prior's flat directions converge slowly; the misfit is reported).
MAX_EVALUATIONS = 500
#: The residual of a trial step that overflows: large, so that the step is refused.
REFUSED = 1e100


def origin_inertia(p: np.ndarray) -> np.ndarray:
    """``(3, 3)`` inertia about the frame's origin [kg·m²] of one body's ten parameters
    ``[m, hx, hy, hz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz]`` (Pinocchio's order)."""
    return np.array([[p[4], p[5], p[7]], [p[5], p[6], p[8]], [p[7], p[8], p[9]]])


def pseudo_inertia(p: np.ndarray) -> np.ndarray:
    """``(4, 4)`` J of one body's ten parameters ``[m, hx, hy, hz, Ixx, Ixy, Iyy, Ixz, Iyz,
    Izz]`` (Pinocchio's order; I about the frame's origin)."""
    m, h = p[0], p[1:4]
    I = origin_inertia(p)
    J = np.empty((4, 4))
    J[:3, :3] = 0.5 * np.trace(I) * np.eye(3) - I
    J[:3, 3] = J[3, :3] = h
    J[3, 3] = m
    return J


def parameters(J: np.ndarray) -> np.ndarray:
    """The ten parameters of a pseudo-inertia (inverse of :func:`pseudo_inertia`)."""
    S = J[:3, :3]
    I = np.trace(S) * np.eye(3) - S
    return np.array([J[3, 3], J[0, 3], J[1, 3], J[2, 3], I[0, 0], I[0, 1], I[1, 1],
                     I[0, 2], I[1, 2], I[2, 2]])


def from_theta(th: np.ndarray) -> np.ndarray:
    """A body's parameters from its log-Cholesky θ ``(10,)``."""
    a, d1, d2, d3, s12, s23, s13, t1, t2, t3 = th
    U = np.exp(a) * np.array([[np.exp(d1), s12, s13, t1], [0.0, np.exp(d2), s23, t2],
                              [0.0, 0.0, np.exp(d3), t3], [0.0, 0.0, 0.0, 1.0]])
    return parameters(U @ U.T)


def to_theta(p: np.ndarray) -> np.ndarray:
    """θ of a physically consistent body (its pseudo-inertia positive definite)."""
    J = pseudo_inertia(p)
    R = np.eye(4)[::-1]
    U = R @ np.linalg.cholesky(R @ J @ R) @ R        # upper triangular, J = U Uᵀ
    e = U[3, 3]
    Un = U / e
    return np.array([np.log(e), np.log(Un[0, 0]), np.log(Un[1, 1]), np.log(Un[2, 2]),
                     Un[0, 1], Un[1, 2], Un[0, 2], Un[0, 3], Un[1, 3], Un[2, 3]])


def consistent(p: np.ndarray, margin: float = 0.0) -> bool:
    """True when every body of ``p (10 b,)`` has a positive definite pseudo-inertia (its
    smallest eigenvalue above ``margin`` times its largest)."""
    for k in range(0, len(p), 10):
        w = np.linalg.eigvalsh(pseudo_inertia(p[k:k + 10]))
        if not w[0] > margin * w[-1]:
            return False
    return True


def consistent_parameters(K: np.ndarray, beta: np.ndarray, covariance: np.ndarray,
                          pi0: np.ndarray, prior: float = PRIOR_WEIGHT,
                          com_bounds: np.ndarray | None = None):
    """The physically consistent parameters closest to identified base parameters.

    Args:
        K: ``(r, P)`` base parameters of the inertial ones (``P = 10 b``).
        beta: ``(r,)`` identified. covariance: ``(r, r)`` their covariance.
        pi0: ``(P,)`` the nominal parameters (consistent).
        prior: λ.
        com_bounds: ``(b, 3, 2)`` [m] lower and upper bound of each body's centre of mass
            per axis of its frame (``±inf``: none), e.g. a leg part's along the leg
            (:func:`~._description.com_bounds`). The centre of mass is θ's ``t`` (``J``'s
            last column over ``m``): a bound on it is a bound on θ. When the
            unbounded solution (Levenberg–Marquardt) breaks a bound, the problem is
            solved again with the bounds held exactly (SciPy's trust-region reflective
            method, ~7× slower: it happens when the log does not decide a part's mass,
            its first moment alone being identifiable). ``pi0`` must lie inside.

    Returns:
        ``(pi (P,), misfit)``: the parameters, and ``|L⁻¹ (K π − β̂)|`` per base
        parameter (in standard deviations, RMS).
    """
    from scipy.optimize import least_squares

    from offshore_crane import progress

    P = len(pi0)
    L = np.linalg.cholesky(covariance + 1e-300 * np.eye(len(beta)))
    scale = np.array([max(abs(pi0[k:k + 10]).max(), 1e-6) for k in range(0, P, 10)
                      for _ in range(10)])

    def pi_of(x):
        return np.concatenate([from_theta(x[k:k + 10]) for k in range(0, P, 10)])

    A = np.linalg.solve(L, K)                       # (r, P): the whitened base map
    w = np.linalg.solve(L, beta)
    prior_rows = np.sqrt(prior) / scale

    def residual(x):
        shown.update()
        with np.errstate(over="ignore", invalid="ignore"):
            pi = pi_of(x)
            r_ = np.concatenate([A @ pi - w, prior_rows * (pi - pi0)])
        # a trial step whose exponentials overflow is refused (the step is shortened)
        return r_ if np.isfinite(r_).all() else np.full(len(r_), REFUSED)

    def jacobian(x):
        D = _theta_jacobian(x)                      # (P, P) block diagonal dπ/dθ
        return np.vstack([A @ D, prior_rows[:, None] * D])

    x0 = np.concatenate([to_theta(pi0[k:k + 10]) for k in range(0, P, 10)])
    with progress.bar(MAX_EVALUATIONS, "evaluation", "identify") as shown:
        out = least_squares(residual, x0, jac=jacobian, method="lm",
                            max_nfev=MAX_EVALUATIONS)
    if com_bounds is not None:
        lo, hi = (np.full(P, -np.inf), np.full(P, np.inf))
        for axis in range(3):
            lo[7 + axis::10], hi[7 + axis::10] = com_bounds[:, axis, 0], com_bounds[:, axis, 1]
        if np.any(out.x < lo) or np.any(out.x > hi):       # held: solved again, bounded
            with progress.bar(MAX_EVALUATIONS, "evaluation", "identify, bounded") as shown:
                out = least_squares(residual, x0, jac=jacobian, method="trf",
                                    bounds=(lo, hi), max_nfev=MAX_EVALUATIONS)
    pi = pi_of(out.x)
    misfit = A @ pi - w
    return pi, float(np.sqrt(np.mean(misfit ** 2)))


#: Central-difference step of dπ/dθ (θ is O(1): logs and normalised entries).
THETA_STEP = 1e-6


def _theta_jacobian(x: np.ndarray) -> np.ndarray:
    """Block-diagonal ``dπ/dθ`` ``(P, P)`` by central differences per body (each block
    10 × 10; π is a quadratic form in U, smooth: error ~1e-12)."""
    P = len(x)
    D = np.zeros((P, P))
    for k in range(0, P, 10):
        th = x[k:k + 10]
        for j in range(10):
            e = np.zeros(10)
            e[j] = THETA_STEP
            D[k:k + 10, k + j] = (from_theta(th + e) - from_theta(th - e)) / (2 * THETA_STEP)
    return D
