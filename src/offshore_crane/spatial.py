"""Batched 3-D rotation and vector helpers (pure NumPy).

Convention (as in pytransform3d's ``A2B``): ``R_a_b`` maps coordinates in frame ``b`` to
coordinates in frame ``a``; ``p_a_X`` is the position of point ``X`` in frame ``a``.
Every function takes a leading batch axis of ``N`` time samples, or none.
"""

from __future__ import annotations

import numpy as np


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product over the last axis, broadcast over the leading ones.

    Written out component-wise: about 3x faster than :func:`numpy.cross` on ``(N, 3)``.

    Args:
        a: ``(..., 3)``.
        b: ``(..., 3)``.

    Returns:
        ``(..., 3)`` array ``a x b``.
    """
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    out = np.empty(np.broadcast_shapes(a.shape, b.shape), dtype=np.result_type(a, b))
    out[..., 0] = a1 * b2 - a2 * b1
    out[..., 1] = a2 * b0 - a0 * b2
    out[..., 2] = a0 * b1 - a1 * b0
    return out


def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Dot product over the last axis: ``(..., 3), (..., 3) -> (...)``."""
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1] + a[..., 2] * b[..., 2]


def skew(v: np.ndarray) -> np.ndarray:
    """Cross-product matrix: ``skew(v) @ w == cross(v, w)``; ``(..., 3) -> (..., 3, 3)``."""
    out = np.zeros(v.shape[:-1] + (3, 3), dtype=v.dtype)
    out[..., 0, 1] = -v[..., 2]
    out[..., 0, 2] = v[..., 1]
    out[..., 1, 0] = v[..., 2]
    out[..., 1, 2] = -v[..., 0]
    out[..., 2, 0] = -v[..., 1]
    out[..., 2, 1] = v[..., 0]
    return out


def matvec(R: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``R @ v`` for stacks: ``(..., 3, 3), (..., 3) -> (..., 3)``."""
    return np.einsum("...ij,...j->...i", R, v)


def rot_x(angle: np.ndarray) -> np.ndarray:
    """Rotation about x by ``angle`` [rad]; ``(...) -> (..., 3, 3)``."""
    return axis_angle_matrix(np.array([1.0, 0.0, 0.0]), angle)


def rot_y(angle: np.ndarray) -> np.ndarray:
    """Rotation about y by ``angle`` [rad]; ``(...) -> (..., 3, 3)``."""
    return axis_angle_matrix(np.array([0.0, 1.0, 0.0]), angle)


def rot_z(angle: np.ndarray) -> np.ndarray:
    """Rotation about z by ``angle`` [rad]; ``(...) -> (..., 3, 3)``."""
    return axis_angle_matrix(np.array([0.0, 0.0, 1.0]), angle)


def axis_angle_matrix(axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Rodrigues' formula for a fixed unit ``axis`` (3,) and angles ``(...)`` [rad].

    Returns:
        ``(..., 3, 3)`` rotation matrices ``exp(skew(axis) * angle)``.
    """
    axis = np.asarray(axis, dtype=float)
    angle = np.asarray(angle, dtype=float)
    K = skew(axis)
    K2 = K @ K
    s = np.sin(angle)[..., None, None]
    c = np.cos(angle)[..., None, None]
    return np.eye(3) + s * K + (1.0 - c) * K2


def rpy_matrix(rpy) -> np.ndarray:
    """URDF ``rpy`` (roll, pitch, yaw) [rad] to ``Rz(yaw) @ Ry(pitch) @ Rx(roll)``.

    Args:
        rpy: ``(..., 3)``.

    Returns:
        ``(..., 3, 3)``.
    """
    rpy = np.asarray(rpy, dtype=float)
    return rot_z(rpy[..., 2]) @ rot_y(rpy[..., 1]) @ rot_x(rpy[..., 0])


def attitude_matrix(roll: np.ndarray, pitch: np.ndarray, yaw: np.ndarray) -> np.ndarray:
    """Platform attitude ``R_base_platform = Rz(q6) Ry(q5) Rx(q4)`` (docs/conventions.md).

    Args:
        roll: q4 [rad], shape ``(N,)``.
        pitch: q5 [rad], shape ``(N,)``.
        yaw: q6 [rad], shape ``(N,)``.

    Returns:
        ``(N, 3, 3)``, mapping platform coordinates to base coordinates.
    """
    cr, sr = np.cos(roll), np.sin(roll)
    cp, sp = np.cos(pitch), np.sin(pitch)
    cy, sy = np.cos(yaw), np.sin(yaw)
    R = np.empty(np.shape(roll) + (3, 3))
    R[..., 0, 0] = cy * cp
    R[..., 0, 1] = cy * sp * sr - sy * cr
    R[..., 0, 2] = cy * sp * cr + sy * sr
    R[..., 1, 0] = sy * cp
    R[..., 1, 1] = sy * sp * sr + cy * cr
    R[..., 1, 2] = sy * sp * cr - cy * sr
    R[..., 2, 0] = -sp
    R[..., 2, 1] = cp * sr
    R[..., 2, 2] = cp * cr
    return R


def condition_1(A: np.ndarray) -> np.ndarray:
    """1-norm condition numbers of a stack of square matrices ``(N, n, n) -> (N,)``
    (inf for an exactly singular matrix)."""
    try:
        inv = np.linalg.inv(A)
    except np.linalg.LinAlgError:
        inv = np.linalg.pinv(A)
        out = np.abs(A).sum(axis=-2).max(axis=-1) * np.abs(inv).sum(axis=-2).max(axis=-1)
        out[np.linalg.matrix_rank(A) < A.shape[-1]] = np.inf
        return out
    return np.abs(A).sum(axis=-2).max(axis=-1) * np.abs(inv).sum(axis=-2).max(axis=-1)
