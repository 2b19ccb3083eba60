"""The regressor of the closed-loop robot: its actuator forces are linear in the bodies'
inertial parameters (and in friction parameters), ``X = Y(q, q̇, q̈) π``.

The inertial columns come from the reference path (Pinocchio's joint-torque regressor of
the equivalent tree projected through the loops:
:mod:`offshore_crane.reference.rnea.regressor`); the friction columns are per actuator
``[v_k, sign(v_k), 1]`` for viscous [N·s/m or N·m·s/rad], Coulomb [N or N·m] and offset
[N or N·m] parameters, ``v_k`` the actuator's joint rate (q̇7, q̇8, q̇9, the leg rates).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from offshore_crane.conventions import ACTUATORS, ACTUATOR_UNITS, GRAVITY
from offshore_crane.dynamics.runtime import one_blas_thread

#: Friction parameters per actuator, in column order.
FRICTION = ("fv", "fc", "f0")
#: Samples a block of the reference regressor holds (its Y is 9 × P doubles a sample).
BLOCK = 1 << 10


class Regressor(NamedTuple):
    """``X = Y @ pi`` at ``N`` samples.

    Attributes:
        Y: ``(N, 9, P)`` [N or N·m per unit of each parameter].
        pi: ``(P,)`` the robot description's values of the parameters (friction: 0).
        names: ``(P,)`` ``"{body}.{m|mcx|…|Izz}"``, then ``"{actuator}.{fv|fc|f0}"``.
        units: ``(P,)`` each parameter's unit.
    """

    Y: np.ndarray
    pi: np.ndarray
    names: tuple
    units: tuple


def actuator_rows(robot) -> np.ndarray:
    """The rows of ``Y`` (and columns of X) of the actuators ``robot`` has: all nine, or
    the six legs' (3..8) for a platform without the crane arm (its T1, T2, Fs rows are
    NaN: no such actuator)."""
    return np.arange(9) if robot.hybrid.has_arm else np.arange(3, 9)


@one_blas_thread()
def regressor(robot, q, qd, qdd, gravity=GRAVITY, friction: bool = False) -> Regressor:
    """The closed-loop regressor ``Y (N, 9, P)`` and the standard parameters ``π (P,)``.

    Args:
        robot: From :func:`offshore_crane.load_robot` (a payload welded to the tip; not
            on a cable). Without the crane arm, the rows of T1, T2 and Fs are NaN
            (:func:`actuator_rows`).
        q, qd, qdd: ``(N, 9)`` [m, rad], rates, accelerations.
        gravity: ``(3,)`` base frame [m/s²].
        friction: Add 3 friction columns per actuator (:data:`FRICTION`).

    Raises:
        InputError: bad shapes or non-finite values (naming the sample); a robot whose
            payload hangs on a cable (identify it welded).
        WorkspaceError: a pose outside the workspace.
    """
    from offshore_crane.robot.kinematics import actuator_motion

    parts = [R for _, R in regressor_blocks(robot, q, qd, qdd, gravity)]
    q = np.asarray(q, dtype=float).reshape(-1, 9)
    Y = np.concatenate([p.Y for p in parts])
    pi, names, units = parts[0].pi, parts[0].names, parts[0].units
    if friction:
        v = actuator_motion(robot, q, np.asarray(qd, dtype=float).reshape(-1, 9))[1]
        F = np.zeros((len(q), 9, 27))
        for k in range(9):
            F[:, k, 3 * k:3 * k + 3] = np.stack([v[:, k], np.sign(v[:, k]),
                                                 np.ones(len(q))], axis=-1)
        Y = np.concatenate([Y, F], axis=2)
        pi = np.concatenate([pi, np.zeros(27)])
        names = names + tuple(f"{a}.{f}" for a in ACTUATORS for f in FRICTION)
        units = units + tuple(u for unit in ACTUATOR_UNITS for u in
                              (f"{unit}·s/{'rad' if unit == 'N·m' else 'm'}", unit, unit))
    return Regressor(Y, pi, names, units)


def identifiable(robot) -> None:
    """Check that ``robot`` is one the regressor models.

    Raises:
        InputError: its payload hangs on a cable (identify it welded).
    """
    from offshore_crane.errors import InputError

    if robot.hybrid.cable is not None:
        raise InputError("regressor: the payload hangs on a cable; identify the robot "
                         "with its payload welded (payload.cable_length = 0)",
                         name="robot")


def regressor_blocks(robot, q, qd, qdd, gravity=GRAVITY, block: int = BLOCK):
    """The regressor of :func:`regressor` (inertial columns) block by block:
    ``(start, Regressor of samples start..start + block)``, so that a long log's
    ``Y`` is never held whole (a block's ``Y`` is ``block × 9 × P`` doubles). The
    samples are checked first (shapes, finite values, the workspace); a progress bar
    counts them.

    Raises:
        As :func:`regressor`.
    """
    from offshore_crane import progress
    from offshore_crane.errors import InputError
    from offshore_crane.reference.rnea.regressor import regressor as tree_regressor
    from offshore_crane.robot.kinematics import check_workspace
    from offshore_crane.validation import as_gravity, as_samples

    identifiable(robot)
    q, _ = as_samples("q", q)
    qd, _ = as_samples("qd", qd)
    qdd, _ = as_samples("qdd", qdd)
    for name, a in (("qd", qd), ("qdd", qdd)):
        if len(a) != len(q):
            raise InputError(f"regressor: {name} has {len(a)} samples and q {len(q)}",
                             name=name)
    check_workspace(robot, q)
    g = as_gravity(gravity)
    with progress.bar(len(q), "sample", "regressor") as shown:
        for a in range(0, len(q), block):
            part = Regressor(*tree_regressor(robot, q[a:a + block], qd[a:a + block],
                                             qdd[a:a + block], g))
            shown.update(len(part.Y))
            yield a, part
            del part                        # before the next block: one alive at a time
