"""The same inverse dynamics from Pinocchio's RNEA, for cross-checks (imports pinocchio).

Pinocchio builds the URDF with a fixed base at the root link and merges fixed joints into
their parent body, as :func:`~offshore_crane.serial.load_chain` does. Joints the chain
locked (off the path to its tip) are locked at zero position with
``pin.buildReducedModel``. Continuous joints have ``(cos θ, sin θ)`` in Pinocchio's ``q``
(nq = 2, nv = 1): :func:`pinocchio_q` converts the chain's angles.
"""

from __future__ import annotations

import numpy as np

from offshore_crane.errors import ModelError, require
from offshore_crane.robot.chain import SerialChain
from offshore_crane.serial.core import GRAVITY, read_urdf


def _pin():
    return require("pinocchio", "pin", "The Pinocchio cross-check of a serial chain")


def pinocchio_model(urdf, chain: SerialChain):
    """Pinocchio model of the same URDF with exactly the chain's joints, in its order.

    Args:
        urdf: The path or URDF text ``chain`` was loaded from.
        chain: From :func:`~offshore_crane.serial.load_chain`, based at the root link.

    Returns:
        ``pinocchio.Model`` (fixed base) whose joints are ``chain.joint_names``.

    Raises:
        ModelError: the chain is not based at the root link, or the joints differ.
    """
    pin = _pin()
    desc, text = read_urdf(urdf)
    if text is None:
        raise ModelError("the Pinocchio cross-check needs the URDF path or text, not a "
                         "parsed URDF")
    if chain.base_link != desc.root:
        raise ModelError(f"the Pinocchio cross-check needs a chain based at the root link "
                         f"'{desc.root}', not '{chain.base_link}'", element=chain.base_link)
    model = pin.buildModelFromXML(text)
    keep = set(chain.joint_names)
    lock = [model.getJointId(name) for name in list(model.names)[1:] if name not in keep]
    if lock:
        model = pin.buildReducedModel(model, lock, pin.neutral(model))
    names = tuple(model.names)[1:]
    if names != tuple(chain.joint_names):
        raise ModelError(f"Pinocchio's joints {names} differ from the chain's "
                         f"{chain.joint_names}")
    return model


def pinocchio_q(model, q: np.ndarray) -> np.ndarray:
    """Chain positions ``(N, n)`` [rad, m] to Pinocchio configurations ``(N, nq)``."""
    q = np.atleast_2d(q)
    out = np.empty((q.shape[0], model.nq))
    for jm in list(model.joints)[1:]:
        iq, iv = jm.idx_q, jm.idx_v
        if jm.nq == 2 and jm.nv == 1:  # continuous joint: (cos, sin)
            out[:, iq], out[:, iq + 1] = np.cos(q[:, iv]), np.sin(q[:, iv])
        else:
            out[:, iq:iq + jm.nq] = q[:, iv:iv + jm.nv]
    return out


def rnea(model, q, qd, qdd, gravity=GRAVITY) -> np.ndarray:
    """``pin.rnea`` sample by sample (Python loop).

    Args:
        model: From :func:`pinocchio_model` (not modified: gravity is set on a copy).
        q, qd, qdd: ``(N, n)`` chain positions [rad, m], rates, accelerations.
        gravity: ``(3,)`` [m/s²].

    Returns:
        ``(N, n)`` joint torques and forces [N·m, N].
    """
    pin = _pin()
    model = model.copy()
    model.gravity.linear = np.asarray(gravity, dtype=float)
    data = model.createData()
    Q = pinocchio_q(model, q)
    qd, qdd = np.atleast_2d(qd), np.atleast_2d(qdd)
    return np.array([pin.rnea(model, data, Q[i], qd[i], qdd[i]).copy()
                     for i in range(Q.shape[0])])


def frame_jacobians(model, q, frame: str) -> np.ndarray:
    """``(N, 6, n)`` Jacobians of ``frame`` (LOCAL_WORLD_ALIGNED: linear velocity of the
    frame origin and angular velocity, world axes) at chain positions ``q`` ``(N, n)``."""
    pin = _pin()
    data = model.createData()
    # BODY: a link may share its name with a joint (SO-100's 'gripper').
    if not model.existFrame(frame, pin.FrameType.BODY):
        raise ModelError(f"Pinocchio's model has no link frame '{frame}'", element=frame)
    fid = model.getFrameId(frame, pin.FrameType.BODY)
    Q = pinocchio_q(model, q)
    return np.array([pin.computeFrameJacobian(model, data, Q[i], fid,
                                              pin.ReferenceFrame.LOCAL_WORLD_ALIGNED).copy()
                     for i in range(Q.shape[0])])
