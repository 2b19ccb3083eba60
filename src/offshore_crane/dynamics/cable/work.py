"""The scratch of the hanging load's one-state kernels (:func:`~offshore_crane.dynamics.
cable.kernels.accelerations`, :func:`~offshore_crane.dynamics.cable.kernels.
computed_torque`, the hanging plant's tension): one buffer of :data:`WORK` floats, cut
into views at each call instead of some twenty small arrays allocated at every RK4 stage
(imports Numba).

Each kernel has a region of its own (the law and the plant run at the same stage), laid
out for the longest chain (:data:`N` coordinates: the platform's 6, an arm of 3 joints
and the 2 sway joints); a view takes the caller's sizes (``n = 6 + na``, ``na`` the
chain's bodies) at the start of its slot. The views are made without an owner
(:func:`~offshore_crane.dynamics.views.c_view`): the buffer must be an argument of the
kernel that carves it."""

from __future__ import annotations

from offshore_crane.dynamics.formulas import STORE_WIDTH
from offshore_crane.dynamics.jit import JIT
from offshore_crane.dynamics.views import c_view
from offshore_crane.kernel_cache import njit

#: The most bodies of the chain (an arm of 3 joints and the 2 sway joints) and its
#: coordinates.
NA = 5
N = 6 + NA
#: :func:`carve_accelerations`'s slots, in order: B, J, M, its Cholesky factor, the partials
#: Vw, Ww, Vs, the diagnostics, the arm store, Σ m c, the right-hand side, zeros and a
#: unit vector (each ``(capacity,)``).
_ACCEL = (N, 36, N * N, N * N, 3 * N, 3 * N, 3 * N, 42, NA * STORE_WIDTH, 3, N, N, N)
#: :func:`carve_law`'s: q̈, the arm rows, the Stewart matrix, its right-hand side, the
#: diagnostics, the arm store, the leg forces, the Gauss–Jordan scratch and zeros.
_LAW = (N, NA, 36, 6, 42, NA * STORE_WIDTH, 6, 78, N)
#: :func:`carve_tension`'s: the Kane pass's arm rows, Stewart matrix, right-hand side,
#: diagnostics and arm store.
_TENSION = (NA, 36, 6, 42, NA * STORE_WIDTH)
_ALL = _ACCEL + _LAW + _TENSION
_STARTS = tuple(sum(_ALL[:i]) for i in range(len(_ALL) + 1))
(_B, _J, _M, _L, _VW, _WW, _VS, _DIAG, _STORE, _MC, _RHS, _ZERO, _UNIT, _QDD, _ROWS, _A,
 _RHS6, _LDIAG, _LSTORE, _X, _M13, _LZERO, _TROWS, _TA, _TRHS6, _TDIAG, _TSTORE,
 WORK) = _STARTS


@njit(**JIT)
def carve_accelerations(w, na):
    """The views of :func:`~offshore_crane.dynamics.cable.kernels.accelerations` for a
    chain of ``na`` bodies: ``(B, J, M, L, Vw, Ww, Vs, diag, store, mc, rhs, zero,
    unit)``."""
    n = 6 + na
    return (c_view(w, _B, (n,)), c_view(w, _J, (6, 6)), c_view(w, _M, (n, n)),
            c_view(w, _L, (n, n)), c_view(w, _VW, (n, 3)), c_view(w, _WW, (n, 3)),
            c_view(w, _VS, (n, 3)), c_view(w, _DIAG, (7, 6)),
            c_view(w, _STORE, (na, STORE_WIDTH)), c_view(w, _MC, (1, 3)),
            c_view(w, _RHS, (n,)), c_view(w, _ZERO, (n,)), c_view(w, _UNIT, (n,)))


@njit(**JIT)
def carve_law(w, na):
    """The views of :func:`~offshore_crane.dynamics.cable.kernels.computed_torque` for a
    chain of ``na`` bodies: ``(qdd, rows, A, rhs6, diag, store, x, M13, zero)``."""
    n = 6 + na
    return (c_view(w, _QDD, (n,)), c_view(w, _ROWS, (na,)), c_view(w, _A, (6, 6)),
            c_view(w, _RHS6, (6,)), c_view(w, _LDIAG, (7, 6)),
            c_view(w, _LSTORE, (na, STORE_WIDTH)), c_view(w, _X, (6,)),
            c_view(w, _M13, (6, 13)), c_view(w, _LZERO, (n,)))


@njit(**JIT)
def carve_tension(w, na):
    """The views of the hanging plant's tension (its Kane pass at a recorded sample) for a
    chain of ``na`` bodies: ``(rows, A, rhs6, diag, store)``."""
    return (c_view(w, _TROWS, (na,)), c_view(w, _TA, (6, 6)), c_view(w, _TRHS6, (6,)),
            c_view(w, _TDIAG, (7, 6)), c_view(w, _TSTORE, (na, STORE_WIDTH)))
