"""The crane tip's position and velocity along a motion (the ``arm_tip`` frame's origin,
base frame): what a free payload, a deck under it and a compensation are measured from."""

from __future__ import annotations

import numpy as np

#: Samples evaluated at once (the vectorised formulas' arrays stay in the caches: a
#: 3-hour record at 100 Hz takes 2.4 × less time in blocks of 2¹⁵ than whole).
BLOCK = 1 << 15


def tip_positions(robot, q: np.ndarray, qd: np.ndarray | None = None) -> tuple:
    """The tip's position [m] and velocity [m/s] ``(N, 3)`` in the base frame for the
    robot's ``q (N, 9)`` (and ``qd``; zero rates by default), by
    :func:`offshore_crane.dynamics.sway.tip_state` on NumPy arrays, in blocks of
    :data:`BLOCK` samples."""
    from offshore_crane.dynamics import backends
    from offshore_crane.dynamics.constants import cable_arrays

    qd = np.zeros_like(q) if qd is None else qd
    C = cable_arrays(robot).kane
    p, v = np.empty((len(q), 3)), np.empty((len(q), 3))
    for a in range(0, len(q), BLOCK):
        b = slice(a, a + BLOCK)
        pb, vb = backends.NUMPY.tip_state(C, q[b].T, qd[b].T)
        p[b], v[b] = np.stack(pb, axis=-1), np.stack(vb, axis=-1)
    return p, v


def payload_positions(robot, res) -> np.ndarray:
    """``(N, 3)`` the payload in the base frame [m] of a rigid or elastic cable's result."""
    if hasattr(res, "payload"):
        return np.asarray(res.payload)
    from offshore_crane.dynamics import backends
    from offshore_crane.dynamics.constants import cable_arrays

    B, C = backends.NUMPY, cable_arrays(robot).kane
    Rt = B.tip_motion(C, res.q.T, res.qd.T, res.qdd.T)[0]
    Rt = np.array([[np.asarray(x) for x in row] for row in Rt])          # (3, 3, N)
    e = np.array(B.sway_direction(res.sway[:, 0], res.sway[:, 1])[0])     # (3, N)
    length = res.length if res.hoist is None else res.hoist[:, 0]
    return tip_positions(robot, res.q)[0] + np.einsum("ijn,jn->ni", Rt, e) * np.reshape(
        length, (-1, 1))


def sway_angle(robot, res) -> np.ndarray:
    """``(N,)`` the cable's angle from the tip's vertical [rad] — between the cable, from
    the tip to the payload, and the ``arm_tip`` frame's −z axis (down when the platform
    is level) — of a rigid or elastic cable's result: the one sway figure that envelopes,
    verdicts, sweeps and ``compensate`` report. A rigid cable's is ``arccos(cos φ1 cos
    φ2)`` (:attr:`~.result.CableResult.sway_angle`); an elastic one's is taken of the
    payload's position ``ρ`` from the tip and the tip's attitude ``R_base_tip`` along the
    motion that ran, in blocks of :data:`BLOCK` samples."""
    if not hasattr(res, "position"):
        return res.sway_angle
    from offshore_crane.dynamics import backends
    from offshore_crane.dynamics.constants import cable_arrays

    B, C = backends.NUMPY, cable_arrays(robot).kane
    rho = np.asarray(res.position, dtype=float)
    out = np.empty(len(rho))
    for a in range(0, len(rho), BLOCK):
        b = slice(a, a + BLOCK)
        Rt = B.tip_motion(C, res.q[b].T, res.qd[b].T, res.qdd[b].T)[0]
        down = -np.stack([np.asarray(Rt[i][2], dtype=float) for i in range(3)], axis=-1)
        r = rho[b]
        cos = np.einsum("ni,ni->n", r, down) / np.linalg.norm(r, axis=1)
        out[b] = np.arccos(np.clip(cos, -1.0, 1.0))
    return out
