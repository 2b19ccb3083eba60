"""Physically consistent parameters: the identified base parameters lifted to every body's
ten parameters, each body's inertia a real one.

A body's parameters are those of a mass distribution exactly when its 4×4 pseudo-inertia
``J = [[Σ, h], [hᵀ, m]]`` (``Σ = ½ tr(I) 1 − I``, ``h = m c``, I about the frame's origin)
is positive definite (Wensing, Kim, Slotine, "Linear matrix inequalities for physically
consistent inertial parameter identification", IEEE RA-L 3(1), 2018): then ``m > 0`` and
the inertia about the centre of mass satisfies the triangle inequalities. J is linear in
the parameters, so the set of consistent parameters is convex.

The problem, convex: minimise ``½ |S (K π − β̂)|² + ½ λ |(π − π_0) / s|²`` over π with
every body's J positive definite (and each bounded centre of mass within its bounds:
``lo m ≤ h ≤ hi m``, linear). ``Sᵀ S`` is the inverse covariance of β̂, its square root
taken from the fit's factorisation (:attr:`~._fit.Fit.root`: no covariance is inverted,
and what the record does not excite costs nothing); the second term, toward the nominal
parameters (``s`` each parameter's scale in the nominal robot, :data:`PRIOR_WEIGHT` λ),
decides the directions the forces do not see. Solved by a barrier method (Boyd &
Vandenberghe, *Convex Optimization*, 2004, ch. 11) whose barrier is each body's log-det
divergence from its nominal pseudo-inertia, ``μ Σ [tr(J_0⁻¹ J_b) − log det J_b]`` (the
geometric prior of Lee, Wensing & Park, "Geometric robot dynamic identification: a
convex programming approach", IEEE T-RO 36(2), 2020), plus ``− μ Σ log(slack)`` for the
bounds: infinite at the edge of consistency, and for large μ centred on the nominal robot
(a bare ``− log det`` would send the masses the data do not see to thousands of kg).
Newton's method with a line search that stays inside (the cost's change computed with
its quadratic part expanded, so that decreases of 1e-12 of a large cost still count),
μ starting where the barrier weighs as much as the data at the nominal parameters and
divided by :data:`BARRIER_STEP` until ``μ`` × the number of barrier terms is below
:data:`GAP`. Each Newton step is a linear least squares (the three terms stacked as
rows, the barrier's Hessian by its square root ``J^-½ G_i J^-½``) solved by QR: no normal
equations. Measured on the shipped robot: ~110-140 Newton steps, < 1 s; on an exact log
the base parameters are met to ~1e-5 σ (a log-Cholesky Levenberg-Marquardt, used before,
did not converge in 500 evaluations there: it can only approach the edge of consistency,
where the optimum of an exact log lies).
"""

from __future__ import annotations

import numpy as np

from offshore_crane.dynamics.runtime import one_blas_thread

#: λ: the prior toward the nominal parameters, against the base parameters' misfit in
#: standard deviations (small: a 20 % departure costs 0.02 σ a parameter, so the data
#: decide what they see).
PRIOR_WEIGHT = 1e-2
#: The barrier's weight μ is divided by this between centring steps.
BARRIER_STEP = 10.0
#: The barrier method stops when μ × (barrier terms) is below this, in the cost's units
#: (squared standard deviations): the solution's cost is then within it of the optimum.
GAP = 1e-8
#: Newton steps the barrier method may take in all (the progress bar's total). A log
#: that no consistent robot meets within its σ (an exact simulated log differentiated
#: through the filter: misfit ~15 σ) ends its last centrings slowly: measured on such a
#: log, the misfit is 15.5 σ after 300 steps against 15.1 σ after 3000; on the others the
#: method ends in 90-140 steps.
MAX_STEPS = 300
#: A centring stops when the Newton decrement ``λ²/2`` (the model's decrease, cost
#: units) is below this share of μ (the decrement of the self-concordant ``cost / μ``).
CENTRED = 1e-6
#: The identified robot keeps every body's pseudo-inertia at least this share of its
#: nominal one, ``J ⪰ MARGIN · J_0`` (the lift solves for ``π − MARGIN · π_0`` inside the
#: consistent set): an exact log's optimum lies on the edge of consistency, where a
#: principal moment about the centre of mass is 0 and round-off makes it negative (a
#: description no MuJoCo export takes). The forces move by ~MARGIN of a body's own.
MARGIN = 1e-8
#: A decrease of the cost below this [σ²] is nothing (the decrement's round-off floor on
#: an exact log is ~1e-13): a centring stops there whatever μ.
NEGLIGIBLE = 1e-10


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


def consistent(p: np.ndarray) -> bool:
    """True when every body of ``p (10 b,)`` has a positive definite pseudo-inertia
    (tested scaled to a unit diagonal, so that its mixed units, kg, kg·m and kg·m², do
    not decide the verdict; the identified robot is judged as a description file judges
    it: :func:`~._description.physical`)."""
    for k in range(0, len(p), 10):
        J = pseudo_inertia(p[k:k + 10])
        d = np.diag(J)
        if not np.all(d > 0.0):
            return False
        s = 1.0 / np.sqrt(d)
        if not np.linalg.eigvalsh(J * np.outer(s, s))[0] > 0.0:
            return False
    return True


@one_blas_thread()
def consistent_parameters(K: np.ndarray, beta: np.ndarray, root: np.ndarray,
                          pi0: np.ndarray, prior: float = PRIOR_WEIGHT,
                          com_bounds: np.ndarray | None = None, margin: float = MARGIN):
    """The physically consistent parameters closest to identified base parameters (the
    module docstring's convex problem, by a barrier method).

    Args:
        K: ``(r, P)`` base parameters of the inertial ones (``P = 10 b``).
        beta: ``(r,)`` identified.
        root: ``(n, r)`` the square root of their information matrix (``rootᵀ root`` the
            inverse covariance: :attr:`~._fit.Fit.root`, whose rows span only what the
            record excites, ``n ≤ r``); the misfit ``|root (K π − β̂)|`` is in standard
            deviations, and what the record does not excite costs nothing (the prior
            decides it). From a covariance C: ``root = inv(cholesky(C))``.
        pi0: ``(P,)`` the nominal parameters (consistent, each body's pseudo-inertia
            positive definite).
        prior: λ.
        com_bounds: ``(b, 3, 2)`` [m] lower and upper bound of each body's centre of mass
            per axis of its frame (``±inf``: none), e.g. a leg part's along the leg
            (:func:`~._description.com_bounds`), held exactly (the centre of mass stays
            strictly inside). ``pi0`` must lie strictly inside.
        margin: Every body's pseudo-inertia stays at least this share of its nominal
            one (:data:`MARGIN`): the problem is solved for ``π − margin · π_0``.

    Returns:
        ``(pi (P,), misfit)``: the parameters, and ``|root (K π − β̂)|`` per excited
        direction (in standard deviations, RMS).

    Raises:
        InputError: ``pi0`` not consistent or not inside its bounds.
    """
    shift = margin * np.asarray(pi0, dtype=float)
    pi, _ = _lift(K, beta - K @ shift, root, pi0 - shift, prior, com_bounds)
    pi = pi + shift
    misfit = root @ (K @ pi - beta)
    return pi, float(np.sqrt(np.mean(misfit ** 2))) if len(misfit) else 0.0


def _lift(K, beta, root, pi0, prior, com_bounds):
    """:func:`consistent_parameters` without its margin."""
    from offshore_crane import progress
    from offshore_crane.errors import InputError

    P = len(pi0)
    b = P // 10
    d = np.array([max(abs(pi0[k:k + 10]).max(), 1e-6) for k in range(0, P, 10)
                  for _ in range(10)]) / np.sqrt(prior)       # π = π_0 + d u
    A = (root @ K) * d                                         # (n, P) in u
    w = root @ beta - (root @ K) @ pi0
    rows, low = _bound_rows(com_bounds, b, pi0)
    if not consistent(pi0) or (len(rows) and np.any(rows @ pi0 - low <= 0.0)):
        raise InputError("consistent_parameters: the nominal parameters are not a "
                         "physically consistent robot strictly inside the centre-of-mass "
                         "bounds: check the robot description", name="pi0")
    Bd = rows * d                                              # slack = Bd u + (rows π0 − low)
    s0 = rows @ pi0 - low
    G = _scaled_generators(pi0, b)                             # (b, 10, 4, 4)

    def pseudo(p):
        """The bodies' pseudo-inertias scaled by their nominal diagonal ``S J S``: the
        barrier and its derivatives are the same (congruence leaves the log-det
        divergence unchanged), their round-off is each direction's own (a body as thin
        as a rod, J's eigenvalues 1e-13 of its largest, is resolved)."""
        return np.einsum("bn,bnij->bij", p.reshape(b, 10), G)

    inv0 = np.linalg.inv(pseudo(pi0))                          # J_0⁻¹ per body (4 × 4)

    def barrier(u):
        """``−Σ log λ(J_b) − Σ log(slack)`` at ``u``; inf outside (a J not positive
        definite, a centre of mass on or past its bound, anything not finite)."""
        if not np.isfinite(u).all():
            return np.inf
        J = pseudo(pi0 + d * u)
        lam = np.linalg.eigvalsh(J)
        slack = Bd @ u + s0
        if not (lam.min() > 0.0 and np.all(slack > 0.0)):
            return np.inf
        return (np.einsum("bij,bji->", inv0, J) - np.log(lam).sum()
                - np.log(slack).sum())

    def change(u, step, t, mu, before):
        """The cost's change from ``u`` to ``u + t step``, its quadratic part expanded
        (no cancellation between two large costs: a decrease of 1e-12 of the cost shows)."""
        r_, a = A @ u - w, A @ step
        quadratic = t * (r_ @ a + u @ step) + 0.5 * t * t * (a @ a + step @ step)
        return quadratic + mu * (barrier(u + t * step) - before)

    def newton(u, mu):
        """The Newton step at ``u`` and its decrement ``λ²``."""
        lam, Q = np.linalg.eigh(pseudo(pi0 + d * u))
        lam = np.maximum(lam, 1e-300)
        C = np.einsum("bij,bj,bkj->bik", Q, lam ** -0.5, Q)       # J^-½
        H = np.einsum("bij,bj,bkj->bik", Q, lam ** 0.5, Q)        # J^½
        T = np.eye(4) - H @ inv0 @ H          # ⟨C G_i C, T⟩ = −dφ/dπ_i: log det and trace
        M = np.einsum("bij,bnjk,bkl->bnil", C, G, C)              # (b, 10, 4, 4)
        blocks = np.zeros((16 * b, P))
        for k in range(b):
            blocks[16 * k:16 * k + 16, 10 * k:10 * k + 10] = (
                M[k].reshape(10, 16).T * d[10 * k:10 * k + 10])
        sm, slack = np.sqrt(mu), Bd @ u + s0
        return _newton(np.vstack([A, np.eye(P), sm * blocks, sm * Bd / slack[:, None]]),
                       np.concatenate([w - A @ u, -u, sm * T.reshape(-1),
                                       np.full(len(rows), sm)]))

    u = np.zeros(P)                              # the centre for μ → ∞: the nominal robot
    terms = 4 * b + len(rows)
    r0 = A @ u - w
    mu = max(0.5 * (r0 @ r0) / terms, 1.0)       # the central path's start: data ~ barrier
    steps = 0
    with progress.bar(MAX_STEPS, "Newton step", "identify") as shown:
        while steps < MAX_STEPS:
            while steps < MAX_STEPS:                           # centring at this μ
                steps += 1
                shown.update()
                step, decrement = newton(u, mu)
                if not (np.isfinite(decrement) and np.isfinite(step).all()):
                    steps = MAX_STEPS          # a body on the edge to round-off: stop here
                    break
                if decrement / 2.0 <= CENTRED * mu + NEGLIGIBLE:
                    break
                t, before = 1.0, barrier(u)
                while not change(u, step, t, mu, before) <= -0.25 * t * decrement:
                    t *= 0.5
                    if t < 1e-12:
                        break
                if t < 1e-12 or t * np.abs(step).max() <= 1e-12 * (1.0 + np.abs(u).max()):
                    break                      # centred to round-off
                u = u + t * step
            if mu * terms <= GAP:
                break
            mu /= BARRIER_STEP
    pi = pi0 + d * u
    misfit = root @ (K @ pi - beta)
    return pi, float(np.sqrt(np.mean(misfit ** 2))) if len(misfit) else 0.0


def _newton(lhs: np.ndarray, rhs: np.ndarray):
    """The Newton step of a cost whose quadratic model is ``½ |lhs δ − rhs|²`` (plus a
    constant), by QR (no normal equations), and the Newton decrement ``λ²`` (the model's
    decrease is ``λ²/2``)."""
    from scipy.linalg import qr, solve_triangular

    Q, R = qr(lhs, mode="economic", check_finite=False)
    z = Q.T @ rhs
    return solve_triangular(R, z, check_finite=False), float(z @ z)


def _scaled_generators(pi0: np.ndarray, b: int) -> np.ndarray:
    """``(b, 10, 4, 4)`` ``S_b (dJ/dπ_i) S_b``, ``S_b`` the inverse square root of body
    b's nominal pseudo-inertia's diagonal (positive for a consistent ``pi0``)."""
    J0 = np.einsum("bn,nij->bij", pi0.reshape(b, 10), _GENERATORS)
    s = 1.0 / np.sqrt(np.einsum("bii->bi", J0))
    return _GENERATORS[None] * (s[:, None, :, None] * s[:, None, None, :])


def _bound_rows(bounds, b: int, pi0: np.ndarray):
    """The centre-of-mass bounds as linear slacks ``rows π − low > 0`` (``h − lo m``,
    ``hi m − h`` per finite bound): ``(rows (L, 10 b), low (L,))``, ``low`` all 0."""
    out = []
    if bounds is not None:
        for k in range(b):
            for axis in range(3):
                lo, hi = bounds[k, axis]
                for sign, edge in ((1.0, lo), (-1.0, hi)):
                    if np.isfinite(edge):
                        row = np.zeros(10 * b)
                        row[10 * k + 1 + axis] = sign
                        row[10 * k] = -sign * edge
                        out.append(row)
    rows = np.array(out).reshape(-1, 10 * b)
    return rows, np.zeros(len(rows))


def _generators() -> np.ndarray:
    """``(10, 4, 4)`` ``dJ/dπ_i``: J is linear in the ten parameters."""
    return np.stack([pseudo_inertia(e) for e in np.eye(10)])


_GENERATORS = _generators()
