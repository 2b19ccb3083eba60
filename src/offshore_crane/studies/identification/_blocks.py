"""A log of any length, block by block: the fit's data and the identified robot's forces
from the regressor of one block at a time, never the whole ``Y (N, 9, P)`` in memory (a
200 s log at 1 kHz held whole took 6.9 GB; a block of :data:`~._regressor.BLOCK` samples
is ~12 MB).
"""

from __future__ import annotations

import numpy as np

from offshore_crane.conventions import GRAVITY
from offshore_crane.dynamics.runtime import one_blas_thread
from offshore_crane.studies.identification._regressor import BLOCK


@one_blas_thread()
def fit_log(robot, base, q, qd, qdd, X, gravity=GRAVITY, block: int = BLOCK):
    """The weighted fit of a log's forces on the base regressor, one block at a time
    (:class:`~._fit.Triangles`), on the actuators the robot has
    (:func:`~._regressor.actuator_rows`).

    Args:
        robot: The nominal robot. base: its :class:`~._base.BaseParameters`.
        q, qd, qdd: ``(N, 9)`` [m, rad], rates, accelerations.
        X: ``(N, 9)`` the logged forces [N·m, N] (the columns of actuators the robot
            lacks are not read).
        gravity: ``(3,)`` [m/s²]. block: samples a block.

    Returns:
        ``(fit, head)``: the :class:`~._fit.Fit` (its ``residual`` None, ``noise`` and
        ``rms`` per actuator the robot has), and the regressor's parameters: a
        :class:`~._regressor.Regressor` whose ``Y`` has no sample ``(0, 9, P)``.

    Raises:
        InputError: X not ``(N, 9)``; the errors of :func:`~._regressor.regressor` and
            :meth:`~._fit.Triangles.fit`.
    """
    from offshore_crane.errors import InputError
    from offshore_crane.studies.identification._fit import Triangles
    from offshore_crane.studies.identification._regressor import (actuator_rows,
                                                                  regressor_blocks)

    X = np.asarray(X, dtype=float)
    if X.shape != (len(q), 9):
        raise InputError(f"fit: X has shape {X.shape}, q {np.shape(q)}: give (N, 9) both",
                         name="X")
    rows = actuator_rows(robot)
    tri = Triangles(base.rank, len(rows))
    head = None
    for a, R in regressor_blocks(robot, q, qd, qdd, gravity, block):
        tri.add(base.base_regressor(R.Y)[:, rows], X[a:a + len(R.Y)][:, rows])
        if head is None:
            head = R._replace(Y=np.empty((0,) + R.Y.shape[1:]))
        del R                               # one block's Y alive at a time, not two
    return tri.fit(), head


def predict(robot, pi: np.ndarray, q, qd, qdd, gravity=GRAVITY,
            block: int = BLOCK) -> np.ndarray:
    """``(N, 9)`` the forces ``Y π`` [N·m, N] of standard parameters ``pi (P,)`` (in the
    regressor's order) along ``q, qd, qdd (N, 9)``, one block at a time (NaN for the
    actuators the robot lacks)."""
    from offshore_crane.studies.identification._regressor import regressor_blocks

    out = np.empty((len(q), 9))
    for a, R in regressor_blocks(robot, q, qd, qdd, gravity, block):
        out[a:a + len(R.Y)] = R.Y @ pi
        del R
    return out
