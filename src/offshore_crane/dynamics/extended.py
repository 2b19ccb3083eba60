"""Extended-precision reference: the fused Kane formulas evaluated in mpmath.

What it checks, and what it does not:

- It evaluates *the same formulas* as the fused kernel (:mod:`.fused`): it calls the
  kernel's own building blocks ``_platform``, ``_arm``, ``_legs`` and
  ``_platform_wrench`` with ``xp`` = a small shim exposing mpmath's ``cos``, ``sin``,
  ``sqrt``, ``atan2``, ``hypot``, on ``mpf`` inputs (not NumPy arrays, which would
  round every intermediate to float64), and solves the 6x6 leg-force system with
  ``mpmath.lu_solve``. With ``dps = 40`` (about 133 bits) its rounding is ~1e-40, so
  the difference between a float64 result and this one *is the float64 result's
  rounding error* (for the same float64 inputs and model constants, which are
  converted to ``mpf`` exactly).
- It therefore checks **rounding** (the numerical stability of the float64 kernels,
  NumPy and Numba, and of the explicit Kane and RNEA paths, which compute the same
  quantity by other roundings), not the **formulas**: a wrong formula would be wrong
  here too. The formulas are checked by the independent Pinocchio RNEA path
  (``method="rnea"``, agreement to 1e-9 in the tests).

Near a singularity, the float64 error grows like ``κ · ε`` (``ε = 2⁻⁵²``) where ``κ``
is the condition number of the step that loses accuracy: the 6x6 Stewart solve
(leg-Jacobian singularity), the U-joint spin ``1/cos θ2`` (gimbal), or, for the
explicit Kane and RNEA paths only, the attitude partials, which divide by ``cos q5``
(the fused path solves in twist form and does not). The stress tests
(``tests/test_stress.py``) measure the constant ``c`` of ``error ≤ c · κ · ε`` against
this reference; ``docs/numerics.md`` reports it.

Cost: a few milliseconds per sample; meant for tests and studies, not production.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError, require
from ..validation import as_gravity, as_samples, same_length

#: Decimal digits of the reference arithmetic (≈ 133 bits): 1e-40 against float64's 1e-16.
DPS = 40


class _Shim:
    """The ``xp`` namespace the fused building blocks call (mpmath functions)."""

    def __init__(self, mp):
        self.cos, self.sin, self.sqrt = mp.cos, mp.sin, mp.sqrt
        self.atan2, self.hypot = mp.atan2, mp.hypot


@dataclass
class ExtendedResult:
    """Reference actuator forces of one sample, as ``mpf``.

    Attributes:
        X: 9 ``mpf``: ``[T1, T2, Fs, Fl1..Fl6]`` (CONVENTIONS.md order).
        condition: 1-norm condition number of the dimensionless 6x6 Stewart matrix
            (the one the fused kernel solves), computed in extended precision.
        cos_theta2: 6 ``mpf``, ``|cos θ2|`` of each leg's U-joint (gimbal distance).
    """

    X: list
    condition: object
    cos_theta2: list


def _mp():
    return require("mpmath", "mpmath", "The extended-precision reference")


def sample(robot, q, qd, qdd, gravity=(0.0, 0.0, -9.81), *, leg_model: str = "full",
           dps: int = DPS) -> ExtendedResult:
    """Fused Kane formulas on one sample in ``dps``-digit arithmetic.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q, qd, qdd: 9 floats each (converted to ``mpf`` exactly).
        gravity: ``(3,)`` [m/s²].
        leg_model: ``"full"``, ``"thin-rod"`` or ``"massless"`` (as the fused kernel).
        dps: Decimal digits.

    Returns:
        :class:`ExtendedResult`.
    """
    from .fused import _add, _arm, _legs, _platform, _platform_wrench

    mp = _mp()
    fd = robot.fused
    with mp.workdps(dps):
        xp = _Shim(mp)
        q = [mp.mpf(float(x)) for x in q]
        qd = [mp.mpf(float(x)) for x in qd]
        qdd = [mp.mpf(float(x)) for x in qdd]
        g = tuple(mp.mpf(float(x)) for x in gravity)
        R, p, omega, alpha, a = _platform(q, qd, qdd, False, xp)
        v = (qd[0], qd[1], qd[2])
        arm_rows, F, M = _arm(fd, R, omega, alpha, a, q, qd, qdd, g, xp)
        Fp, Mp = _platform_wrench(fd, R, omega, alpha, a, g)
        F, M = _add(F, Fp), _add(M, Mp)
        iL = 1 / mp.mpf(fd.length_scale)
        A = mp.matrix(6, 6)
        cos2 = []
        for i, lc in enumerate(fd.leg_list):
            u, rxu, f_S, m_S, d, length = _legs(lc, R, p, v, omega, alpha, a, g, leg_model,
                                                xp)
            for k in range(3):
                A[k, i] = u[k]
                A[3 + k, i] = rxu[k] * iL
            if f_S is not None:
                F, M = _add(F, f_S), _add(M, m_S)
            dlx = lc.X[0] * d[0] + lc.X[1] * d[1] + lc.X[2] * d[2]
            dlz = lc.Z[0] * d[0] + lc.Z[1] * d[1] + lc.Z[2] * d[2]
            cos2.append(mp.hypot(dlx, dlz) / length)
        zero = (mp.mpf(0), mp.mpf(0), mp.mpf(0))
        F, M = F or zero, M or zero
        rhs = mp.matrix([F[0], F[1], F[2], M[0] * iL, M[1] * iL, M[2] * iL])
        Fl = mp.lu_solve(A, rhs)
        cond = mp.mnorm(A, 1) * mp.mnorm(mp.inverse(A), 1)
        X = [mp.mpf(x) for x in arm_rows] + [Fl[i] for i in range(6)]
    return ExtendedResult(X=X, condition=cond, cos_theta2=cos2)


def reference(robot, q, qd, qdd, gravity=(0.0, 0.0, -9.81), *, leg_model: str = "full",
              dps: int = DPS) -> list[ExtendedResult]:
    """:func:`sample` on every row of ``(N, 9)`` (or ``(9,)``) inputs."""
    q, _ = as_samples("q", q)
    qd, _ = as_samples("qd", qd)
    qdd, _ = as_samples("qdd", qdd)
    same_length(q=q, qd=qd, qdd=qdd)
    g = as_gravity(gravity)
    if leg_model not in ("full", "thin-rod", "massless"):
        raise InputError(f"unknown leg model '{leg_model}'", name="leg_model")
    return [sample(robot, a, b, c, g, leg_model=leg_model, dps=dps)
            for a, b, c in zip(q.tolist(), qd.tolist(), qdd.tolist())]


def relative_errors(X, refs) -> np.ndarray:
    """Normwise relative error of float results against references, per sample.

    ``e_k = max_j |X[k, j] − X_ref[k][j]| / max_j |X_ref[k][j]|``, evaluated in extended
    precision (the float64 values are converted exactly).

    Args:
        X: ``(N, 9)`` float results.
        refs: N :class:`ExtendedResult` (or lists of 9 ``mpf``).

    Returns:
        ``(N,)`` float relative errors.
    """
    mp = _mp()
    X = np.atleast_2d(np.asarray(X, dtype=float))
    out = np.empty(len(refs))
    with mp.workdps(DPS):
        for k, ref in enumerate(refs):
            Xr = ref.X if isinstance(ref, ExtendedResult) else ref
            scale = max(abs(x) for x in Xr)
            err = max(abs(mp.mpf(float(a)) - b) for a, b in zip(X[k], Xr))
            out[k] = float(err / scale) if scale else float(err)
    return out


def to_float(refs) -> np.ndarray:
    """``(N, 9)`` float64 of the references (each value correctly rounded)."""
    return np.array([[float(x) for x in (r.X if isinstance(r, ExtendedResult) else r)]
                     for r in refs])
