"""Extended-precision reference: the Kane formulas evaluated in mpmath.

What it checks, and what it does not:

- It evaluates *the same text* as the float64 kernels: :mod:`.backends` binds the formula
  modules to mpmath's ``sqrt``, ``sin``, ``cos``, ``atan2``, and the robot's constants are
  converted to ``mpf`` exactly; the 6x6 leg-force system is solved with
  ``mpmath.lu_solve``. With ``dps = 40`` (about 133 bits) its rounding is ~1e-40, so the
  difference between a float64 result and this one *is the float64 result's rounding
  error* (for the same float64 inputs and model constants).
- It therefore checks **rounding** (the numerical stability of the float64 paths), not
  the **formulas**: a wrong formula would be wrong here too. The formulas are checked by
  the independent Pinocchio RNEA path (``method="rnea"``, agreement to 1e-9 in the tests).

Near a singularity, the float64 error grows like ``κ · ε`` (``ε = 2⁻⁵²``) where ``κ``
is the condition number of the step that loses accuracy: the 6x6 Stewart solve
(leg-Jacobian singularity), the U-joint spin ``1/cos θ2`` (gimbal), or, for the
explicit Kane and RNEA paths only, the attitude partials, which divide by ``cos q5``.
The stress tests (``tests/test_stress.py``) measure the constant ``c`` of
``error ≤ c · κ · ε`` against this reference; ``docs/numerics.md`` reports it.

Cost: a few milliseconds per sample; meant for tests and studies, not production.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from offshore_crane.conventions import GRAVITY
from offshore_crane.errors import InputError, require
from offshore_crane.robot.kinematics.formulas import LEG_MODEL_CODES
from offshore_crane.validation import as_gravity, as_samples, same_length

#: Decimal digits of the reference arithmetic (≈ 133 bits): 1e-40 against float64's 1e-16.
DPS = 40


@dataclass
class ExtendedResult:
    """Reference actuator forces of one sample, as ``mpf``.

    Attributes:
        X: 9 ``mpf``: ``[T1, T2, Fs, Fl1..Fl6]`` (docs/conventions.md order).
        condition: 1-norm condition number of the dimensionless 6x6 Stewart matrix
            (the one the fused kernel solves), computed in extended precision.
        cos_theta2: 6 ``mpf``, ``|cos θ2|`` of each leg's U-joint (gimbal distance).
    """

    X: list
    condition: object
    cos_theta2: list


def _mp():
    return require("mpmath", "mpmath", "The extended-precision reference")


def sample(robot, q, qd, qdd, gravity=GRAVITY, *, leg_model: str = "full",
           dps: int = DPS) -> ExtendedResult:
    """The fused Kane formulas on one sample in ``dps``-digit arithmetic.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        q, qd, qdd: 9 floats each (converted to ``mpf`` exactly).
        gravity: ``(3,)`` [m/s²].
        leg_model: ``"full"``, ``"thin-rod"`` or ``"massless"`` (as the kernels).
        dps: Decimal digits.

    Returns:
        :class:`ExtendedResult`.
    """
    from offshore_crane.dynamics.backends import mpmath_backend
    from offshore_crane.dynamics.constants import as_mpf, robot_arrays
    from offshore_crane.dynamics.formulas import COS_THETA2, DIAG_ROWS, STORE_WIDTH

    mp = _mp()
    B = mpmath_backend()
    with mp.workdps(dps):
        C = as_mpf(robot_arrays(robot).kane)
        q, qd, qdd = ([mp.mpf(float(x)) for x in v] for v in (q, qd, qdd))
        g = tuple(mp.mpf(float(x)) for x in gravity)
        rows = [mp.mpf(0)] * 3
        A = np.empty((6, 6), dtype=object)
        rhs = np.empty(6, dtype=object)
        diag = np.empty((DIAG_ROWS, 6), dtype=object)
        store = np.empty((C.n_arm, STORE_WIDTH), dtype=object)
        B.kane_sample(C, q, qd, qdd, g, False, LEG_MODEL_CODES[leg_model], True, rows, A, rhs,
                      diag, store)
        Am = mp.matrix(A.tolist())
        Fl = mp.lu_solve(Am, mp.matrix(rhs.tolist()))
        cond = mp.mnorm(Am, 1) * mp.mnorm(mp.inverse(Am), 1)
        X = list(rows[:C.n_arm]) + [Fl[i] for i in range(6)]
    return ExtendedResult(X=X, condition=cond, cos_theta2=list(diag[COS_THETA2]))


def reference(robot, q, qd, qdd, gravity=GRAVITY, *, leg_model: str = "full",
              dps: int = DPS) -> list[ExtendedResult]:
    """:func:`sample` on every row of ``(N, 9)`` (or ``(9,)``) inputs."""
    q, _ = as_samples("q", q)
    qd, _ = as_samples("qd", qd)
    qdd, _ = as_samples("qdd", qdd)
    same_length(q=q, qd=qd, qdd=qdd)
    g = as_gravity(gravity)
    if leg_model not in LEG_MODEL_CODES:
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
