"""A winch on the hanging load: the cable's length ``L(t)`` prescribed, its rate and
acceleration (``offshore_crane.dynamics.cable.inverse_dynamics(hoist=...)``)."""

from __future__ import annotations

import numpy as np

from offshore_crane.errors import InputError
from offshore_crane.motion.operations import Operation


def hoist_grid(hoist, tt: np.ndarray) -> np.ndarray:
    """``(len(tt), 3)`` the winch's ``(L, L̇, L̈)`` at the times ``tt``, checked.

    Raises:
        InputError: ``hoist`` not callable, or returning arrays of another shape, a
            non-finite value or a length ≤ 0 (naming the time).
    """
    if not callable(hoist):
        raise InputError(f"hoist must be a callable hoist(t) -> (L, Ld, Ldd), got "
                         f"{type(hoist).__name__}", name="hoist")
    try:
        out = np.stack([np.asarray(x, dtype=float) for x in hoist(tt)], axis=1)
    except (TypeError, ValueError) as exc:
        raise InputError(f"hoist(t) must return three arrays (L [m], Ld [m/s], Ldd "
                         f"[m/s²]) of the times' length: {exc}", name="hoist") from None
    if out.shape != (len(tt), 3):
        raise InputError(f"hoist(t) returned shape {out.shape} for {len(tt)} times; "
                         f"expected ({len(tt)}, 3): L, Ld, Ldd", name="hoist")
    bad = ~np.isfinite(out).all(axis=1) | ~(out[:, 0] > 0.0)
    if bad.any():
        k = int(np.argmax(bad))
        raise InputError(f"hoist at t = {tt[k]:.6g} s gives L = {out[k, 0]:.6g} m, Ld = "
                         f"{out[k, 1]:.6g} m/s, Ldd = {out[k, 2]:.6g} m/s²: the cable "
                         "length must stay finite and > 0", name="hoist", index=k)
    return np.ascontiguousarray(out)


def hoist_profile(waypoints) -> "callable":
    """A winch's cable length through waypoints ``((t, L), ...)`` [s, m], by the crane
    operations' quintic rest-to-rest moves
    (:class:`~offshore_crane.motion.operations.Operation`: zero rate and acceleration at
    each waypoint, held before the first and after the last): ``hoist(t) -> (L, L̇, L̈)``
    for ``t (n,)``.

    Raises:
        InputError: fewer than one waypoint, times not increasing, a length ≤ 0.
    """
    w = np.asarray(waypoints, dtype=float)
    if w.ndim != 2 or w.shape[1] != 2 or len(w) < 1 or not np.isfinite(w).all():
        raise InputError(f"hoist waypoints must be rows (t [s], L [m]) of finite numbers, "
                         f"got {waypoints!r}", name="hoist")
    if (np.diff(w[:, 0]) <= 0).any() or (w[:, 1] <= 0).any():
        raise InputError("hoist waypoints need increasing times and lengths > 0 m",
                         name="hoist")
    blend = Operation(np.ascontiguousarray(w[:, 0]), np.ascontiguousarray(w[:, 1:2]))

    def hoist(t):
        L, Ld, Ldd = blend(np.asarray(t, dtype=float))
        return L[:, 0], Ld[:, 0], Ldd[:, 0]
    return hoist
