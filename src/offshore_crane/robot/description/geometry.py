"""Small geometric helpers of the description: inertia of solids of uniform density, URDF rpy
angles, and the data the xacro receives.
"""

from __future__ import annotations

import math

import numpy as np


# ==================================================================== small helpers
def solid_inertia(m: float, shape: dict) -> np.ndarray:
    """Central inertia of a solid of uniform density (same arithmetic as the xacro had)."""
    kind = shape["type"]
    if kind == "cylinder":
        r, h = shape["radius"], shape["length"]
        t = m * (3 * r * r + h * h) / 12
        return np.diag([t, t, m * r * r / 2])
    if kind == "box":
        a, b, c = shape["size"]
        return np.diag([m * (b * b + c * c) / 12, m * (a * a + c * c) / 12,
                        m * (a * a + b * b) / 12])
    r = shape["radius"]
    return np.eye(3) * (2.0 * m * r * r / 5.0)


def rpy_angles(R: np.ndarray) -> np.ndarray:
    """URDF rpy of a rotation matrix; for ``Rz(y) Ry(p)`` (roll 0, the historical U-joint
    frames) it returns the angles that built it up to round-off."""
    pitch = math.atan2(-R[2, 0], math.hypot(R[0, 0], R[1, 0]))
    if math.hypot(R[0, 0], R[1, 0]) < 1e-12:                 # pitch = ±pi/2
        return np.array([0.0, pitch, math.atan2(-R[0, 1], R[1, 1])])
    return np.array([math.atan2(R[2, 1], R[2, 2]), pitch, math.atan2(R[1, 0], R[0, 0])])


def floats(x) -> list:
    return [float(v) for v in np.asarray(x, dtype=float).ravel()]


def inertia6(I) -> list:
    return [float(I[0, 0]), float(I[1, 1]), float(I[2, 2]), float(I[0, 1]), float(I[0, 2]),
            float(I[1, 2])]


def visual(v: dict) -> dict:
    out = {"type": v["type"]}
    for key in ("radius", "length"):
        if key in v:
            out[key] = float(v[key])
    if "size" in v:
        out["size"] = floats(v["size"])
    out["xyz"] = floats(v.get("xyz", (0.0, 0.0, 0.0)))
    return out
