"""Base parameters: the combinations of the standard parameters that the actuator forces
determine, from a pivoted QR of the regressor stacked over random states.

``W = [Y(s_1); …; Y(s_n)]`` ``(9 n, P)``; ``W Π = Q R`` with column pivoting; the
numerical rank ``r`` is the number of ``|R_ii| > tol |R_11|`` (:data:`RANK_TOLERANCE`),
the first ``r`` pivoted columns the independent parameters, and the others enter them as
``β = π_1 + R_11⁻¹ R_12 π_2``: ``β = K π``, ``Y π = Y_b β`` with ``Y_b`` the independent
columns (exactly, for every state: the dependent columns are combinations of them).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from offshore_crane.conventions import GRAVITY
from offshore_crane.dynamics.runtime import one_blas_thread

#: Relative threshold of the numerical rank on the pivoted R's diagonal (the diagonal
#: falls by > 1e6 between the identifiable and the rest on the shipped robot).
RANK_TOLERANCE = 1e-8
#: Coefficients below this in a base parameter's combination are not written out.
SHOWN = 1e-9


class BaseParameters(NamedTuple):
    """The identifiable combinations of a robot's parameters.

    Attributes:
        K: ``(r, P)``: ``β = K π``.
        independent: ``(r,)`` column indices of the base regressor in the full one.
        names: ``(P,)`` the standard parameters' names (:class:`._regressor.Regressor`).
        diagonal: ``(P,)`` ``|R_ii|`` of the pivoted QR, in pivot order (the gap at the
            rank shows how clear it is).
        tolerance: The relative rank threshold used.
    """

    K: np.ndarray
    independent: np.ndarray
    names: tuple
    diagonal: np.ndarray
    tolerance: float

    @property
    def rank(self) -> int:
        return int(len(self.independent))

    def base_regressor(self, Y: np.ndarray) -> np.ndarray:
        """``Y_b (N, 9, r)`` from a full regressor ``Y (N, 9, P)``."""
        return Y[..., self.independent]

    def describe(self) -> list[str]:
        """Each base parameter as its combination: ``"β3 = leg1_upper.Izz + 0.5 ·
        leg2_upper.m …"`` (coefficients above :data:`SHOWN`)."""
        out = []
        for i, row in enumerate(self.K):
            terms = [(c, self.names[j]) for j, c in enumerate(row) if abs(c) > SHOWN]
            text = " ".join(("+ " if c > 0 else "− ") + (f"{abs(c):.6g} · " if abs(abs(c) - 1)
                                                         > 1e-12 else "") + n
                            for c, n in terms)
            out.append(f"β{i + 1} = {text.removeprefix('+ ')}")
        return out


def random_states(robot, n: int, seed: int = 0, speed: float = 1.0, accel: float = 5.0):
    """``n`` random states ``(q, q̇, q̈)`` ``(n, 9)`` inside the workspace: the platform
    within ±5 cm and ±0.3 rad of home, the arm within its joint limits (±π where none;
    0 with its rates and accelerations for a robot without the arm),
    rates uniform in ±``speed``, accelerations in ±``accel`` (rejection-sampled on the
    workspace checks)."""
    from offshore_crane.errors import WorkspaceError
    from offshore_crane.robot.kinematics import check_workspace
    from offshore_crane.robot.kinematics.workspace import limits_of

    rng = np.random.default_rng(seed)
    home = robot.home_pose()
    arm = (np.clip(limits_of(robot.hybrid).arm[:3], -np.pi, np.pi) if robot.hybrid.has_arm
           else np.zeros((3, 2)))                      # no arm: q7..q9 stay 0
    lo = np.concatenate([home[:3] - 0.05, home[3:6] - 0.3, arm[:, 0]])
    hi = np.concatenate([home[:3] + 0.05, home[3:6] + 0.3, arm[:, 1]])
    kept: list = []
    while sum(len(k) for k in kept) < n:
        q = rng.uniform(lo, hi, size=(2 * n, 9))
        ok = np.ones(len(q), dtype=bool)
        for i in range(len(q)):             # rejection: each candidate checked alone
            try:
                check_workspace(robot, q[i:i + 1])
            except WorkspaceError:
                ok[i] = False
        kept.append(q[ok])
    q = np.concatenate(kept)[:n]
    moving = (hi > lo).astype(float)
    return (q, rng.uniform(-speed, speed, q.shape) * moving,
            rng.uniform(-accel, accel, q.shape) * moving)


@one_blas_thread()
def base_parameters(robot, n: int = 200, seed: int = 0, gravity=GRAVITY,
                    friction: bool = False,
                    tolerance: float = RANK_TOLERANCE) -> BaseParameters:
    """The base parameters from the regressor on ``n`` random states (:func:`random_states`).

    Raises:
        The errors of :func:`._regressor.regressor`.
    """
    from scipy.linalg import qr

    from offshore_crane.studies.identification._regressor import actuator_rows, regressor

    R_ = regressor(robot, *random_states(robot, n, seed), gravity=gravity, friction=friction)
    W = R_.Y[:, actuator_rows(robot)].reshape(-1, R_.Y.shape[-1])
    scale = np.linalg.norm(W, axis=0)
    scale[scale == 0] = 1.0
    _, R, perm = qr(W / scale, mode="economic", pivoting=True)
    d = np.abs(np.diag(R))
    r = int(np.sum(d > tolerance * d[0]))
    R1, R2 = R[:r, :r], R[:r, r:]
    P = W.shape[1]
    K = np.zeros((r, P))
    K[:, perm[:r]] = np.eye(r)
    # the scaled columns: W_s = W / s, β_s = K_s (s π); back to unscaled parameters
    Ks = np.linalg.solve(R1, R2)
    K[:, perm[r:]] = Ks
    K = K * scale[None, :] / scale[perm[:r]][:, None]
    return BaseParameters(K, np.asarray(perm[:r]), R_.names, d, tolerance)
