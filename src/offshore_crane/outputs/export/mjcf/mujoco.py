"""Running an exported model in MuJoCo: its state from ours, loading, and forward dynamics for
comparison with ours.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from offshore_crane.conventions import ACTUATORS, ARM_JOINTS, PLATFORM_JOINTS
from offshore_crane.errors import InputError, ModelError
from offshore_crane.outputs.export.mjcf.exporting import joint_values
from offshore_crane.outputs.export.mjcf.settings import MJCF


# --------------------------------------------------------------------------- MuJoCo
def mujoco_state(model: MJCF, robot, q, qd=None, sway=None, sway_rate=None):
    """Our state as MuJoCo's ``(qpos (N, nq), qvel (N, nv))`` for ``model``.

    Args:
        model: From :func:`export` for this robot.
        robot, q, qd, sway, sway_rate: As :func:`joint_values`.
    """
    values = joint_values(robot, q, qd, sway, sway_rate)
    qpos = np.stack([values[j][0] for j in model.joints], axis=1)
    qvel = np.stack([values[j][1] for j in model.joints], axis=1)
    return qpos, qvel


def load(model: MJCF):
    """``(mujoco.MjModel, mujoco.MjData)`` of ``model`` (imports mujoco).

    Raises:
        BackendMissingError: mujoco is not installed (``pip install offshore-crane[mujoco]``).
        ModelError: MuJoCo refuses the model (its message).
    """
    from offshore_crane.errors import require

    mujoco = require("mujoco", "mujoco", "Loading the MJCF model in MuJoCo")
    try:
        m = mujoco.MjModel.from_xml_string(model.xml)
    except ValueError as exc:
        raise ModelError(f"MuJoCo refuses the exported model: {exc}") from None
    return m, mujoco.MjData(m)


@dataclass(frozen=True)
class MujocoForward:
    """MuJoCo's forward dynamics at our states (:func:`forward`).

    Attributes:
        qdd: ``(N, 9)`` accelerations of q1..q9 [m/s², rad/s²] (zeros for an absent arm).
        constraint: ``(N, 9)`` the part of ``qdd`` the loop constraints produce,
            ``qacc - qacc_smooth`` (MuJoCo's unconstrained acceleration) [m/s², rad/s²]:
            the scale of the soft constraints' error.
        qacc: ``(N, nv)`` MuJoCo's ``qacc`` in :attr:`MJCF.joints` order.
        loop: ``(N,)`` largest distance between the two sites of a loop [m].
    """

    qdd: np.ndarray
    constraint: np.ndarray
    qacc: np.ndarray
    loop: np.ndarray

    def agreement(self, qdd_ref) -> np.ndarray:
        """``(9,)`` per coordinate: ``max_n |qdd - qdd_ref| / max_n |constraint|`` (0 where
        the constraints produce nothing), to compare with :data:`AGREEMENT`."""
        err = np.abs(self.qdd - np.asarray(qdd_ref)).max(axis=0)
        scale = np.abs(self.constraint).max(axis=0)
        return np.divide(err, scale, out=np.zeros(9), where=scale > 0)


def forward(model: MJCF, robot, q, qd, X, sway=None, sway_rate=None) -> MujocoForward:
    """MuJoCo's forward dynamics of ``model`` at our states under actuator forces X.

    Sets ``qpos``, ``qvel`` (:func:`mujoco_state`) and ``ctrl`` = X, runs
    ``mujoco.mj_forward`` per sample (MuJoCo has no batched call) and reads ``qacc``.
    ``mj_inverse`` cannot be used instead: it does not route loads through equality
    constraints.

    Args:
        model: From :func:`export`.
        robot, q, qd, sway, sway_rate: As :func:`joint_values`; ``(N, 9)``.
        X: ``(N, 9)`` actuator forces [N·m, N] in the order of ``ACTUATORS`` (the
            columns of absent actuators are ignored).

    Returns:
        :class:`MujocoForward`.
    """
    from offshore_crane.validation import as_samples

    m, d = load(model)
    import mujoco

    X = as_samples("X", X, finite=False)[0]
    qpos, qvel = mujoco_state(model, robot, q, qd, sway, sway_rate)
    if len(X) != len(qpos):
        raise InputError(f"X has {len(X)} samples, q has {len(qpos)}", name="X")
    ctrl = X[:, [ACTUATORS.index(a) for a in model.actuators]]   # absent arm: NaN columns
    as_samples("X of the model's motors", ctrl, width=ctrl.shape[1])
    index = {name: k for k, name in enumerate(model.joints)}
    ours = [index.get(name) for name in PLATFORM_JOINTS + ARM_JOINTS]
    qacc, smooth = np.empty_like(qvel), np.empty_like(qvel)
    loop = np.zeros(len(qpos))
    for n in range(len(qpos)):
        d.qpos[:], d.qvel[:], d.ctrl[:] = qpos[n], qvel[n], ctrl[n]
        mujoco.mj_forward(m, d)
        qacc[n], smooth[n] = d.qacc, d.qacc_smooth
        if d.ne:
            loop[n] = np.linalg.norm(d.efc_pos[:d.ne].reshape(-1, 3), axis=1).max()
    qdd, constraint = np.zeros((len(qpos), 9)), np.zeros((len(qpos), 9))
    for k, i in enumerate(ours):
        if i is not None:
            qdd[:, k], constraint[:, k] = qacc[:, i], qacc[:, i] - smooth[:, i]
    return MujocoForward(qdd, constraint, qacc, loop)
