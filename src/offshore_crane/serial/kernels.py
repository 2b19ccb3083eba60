"""The serial chain's Kane inverse dynamics compiled (imports Numba): the arm recursion of
:mod:`offshore_crane.dynamics.formulas` (``arm_forward``, ``arm_backward``, the wrench's
``take``/``put``) inlined into one loop over samples, the same text the NumPy path
(:func:`offshore_crane.serial.core._solve`) runs vectorised.
"""

from __future__ import annotations

import numpy as np

from offshore_crane.dynamics import compiled as c
from offshore_crane.dynamics.formulas import ATT_, F_, STORE_WIDTH, T_, KaneConstants
from offshore_crane.kernel_cache import njit

K = c.K
unpack = c.unpack
arm_forward, arm_backward = K.arm_forward, K.arm_backward
take, put, mv, sub, add, cross = K.take, K.put, K.mv, K.sub, K.add, K.cross


def _helper(stamp):
    """The sample's text, inlined into both loops; made here and kept as a module global
    (not a cell of the loops' closures: a dispatcher in a closure is hashed into Numba's
    cache key with its per-process id, and the loops then compiled in every process)."""

    @njit(inline="always", **c.JIT)
    def sample(C, R, q, qd, qdd, gt, k, lv, Fe, Me, store, rows):
        """One sample into ``rows`` (n,): the forward recursion on a base of attitude
        ``R``, the wrench ``Fe, Me`` on body ``k`` (−1: none) at ``lv`` from its centre
        of mass, the backward accumulation (inlined into both loops: a call a sample
        costs the batch ~30 %)."""
        if len(stamp) == 0:
            return
        arm_forward(C, R, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), q, qd, qdd, 0,
                    gt, store, k >= 0)
        if k >= 0:
            Rk = (take(store, k, ATT_), take(store, k, ATT_ + 3), take(store, k, ATT_ + 6))
            arm = mv(Rk, lv)
            put(store, k, F_, sub(take(store, k, F_), Fe))
            put(store, k, T_, sub(take(store, k, T_), add(Me, cross(arm, Fe))))
        arm_backward(C, store, rows)

    return sample


sample = _helper(c.STAMP)


def _make(stamp):
    """The loops, closed over the formulas' hash (it keys the disk cache: an edited
    formula rebuilds them)."""

    @njit(**c.JIT)
    def kane(flat, lay, prism, q, qd, qdd, g, R_b, k_load, lever, F, M, tau):
        """Samples of ``q, qd, qdd`` ``(N, n)``: the chain (its constants packed in
        ``flat, lay, prism``, :func:`constants`) on a base of attitude ``R_b``
        ``(N, 3, 3)`` or one ``(1, 3, 3)`` (``R_world_base``) under gravity ``g`` (3,)
        [m/s²], an external wrench ``F`` [N], ``M`` [N·m] ``(N, 3)`` or ``(1, 3)`` on
        body ``k_load`` (−1: none) applied at ``lever`` (3,) [m] from its centre of mass
        (body axes); fills ``tau`` ``(N, n)`` [N·m, N]."""
        if len(stamp) == 0:
            return
        C = unpack(flat, lay, prism)[0]
        store = np.empty((C.n_arm, STORE_WIDTH))
        gt = (g[0], g[1], g[2])
        lv = (lever[0], lever[1], lever[2])
        for s in range(q.shape[0]):
            i = s if R_b.shape[0] > 1 else 0                # one rotation for all, or each
            w = s if F.shape[0] > 1 else 0
            R = ((R_b[i, 0, 0], R_b[i, 0, 1], R_b[i, 0, 2]),
                 (R_b[i, 1, 0], R_b[i, 1, 1], R_b[i, 1, 2]),
                 (R_b[i, 2, 0], R_b[i, 2, 1], R_b[i, 2, 2]))
            sample(C, R, q[s], qd[s], qdd[s], gt, k_load, lv, (F[w, 0], F[w, 1], F[w, 2]),
                   (M[w, 0], M[w, 1], M[w, 2]), store, tau[s])

    @njit(**c.JIT)
    def kane_one(flat, lay, prism, q, qd, qdd, g, tau):
        """One sample ``q, qd, qdd`` (n,) on a base at rest in the world's axes, no
        wrench, into ``tau`` (n,); False (``tau`` untouched) when an input is not
        finite."""
        if len(stamp) == 0:
            return False
        total = 0.0
        for j in range(q.shape[0]):
            total += q[j] + qd[j] + qdd[j]
        if not np.isfinite(total):
            return False
        C = unpack(flat, lay, prism)[0]
        zero = (0.0, 0.0, 0.0)
        sample(C, ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)), q, qd, qdd,
               (g[0], g[1], g[2]), -1, zero, zero, zero,
               np.empty((C.n_arm, STORE_WIDTH)), tau)
        return True

    return kane, kane_one


kane, kane_one = _make(c.STAMP)


def constants(chain):
    """The chain's constants packed as the hybrid robot's are
    (:func:`offshore_crane.dynamics.constants.pack`: the kernel rebuilds them from three
    arrays, and the formulas see the one constants type they were compiled for); the
    fields of the hybrid's platform and legs are empty."""
    from offshore_crane.dynamics.constants import pack
    from offshore_crane.robot.kinematics.workspace import Limits

    f = np.ascontiguousarray
    z = np.zeros
    kane = KaneConstants(
        0.0, z(3), z((3, 3)), int(chain.n), f(chain.p_parent_joint, dtype=float),
        f(chain.R_parent_joint, dtype=float), f(chain.axis, dtype=float),
        f(chain.prismatic, dtype=np.bool_), f(chain.mass, dtype=float),
        f(chain.com, dtype=float), f(chain.inertia, dtype=float), z((0, 3)), z((0, 3)),
        z((0, 3)), z((0, 3)), z((0, 3)), z(0), z((0, 3)), z(0), z((0, 3)), z((0, 3, 3)),
        z(0), z(0), z(0), 1.0)
    return pack(kane, Limits(np.column_stack([chain.lower, chain.upper]), z((0, 2)),
                             z((0, 2, 2))))
