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


def inertia_problem(m: float, I: np.ndarray) -> str | None:
    """What keeps an inertia about the centre of mass ``I (3, 3)`` [kg·m²] of a body of
    mass ``m`` [kg] from being a rigid body's, for a message, or None: a principal moment
    below ``−tol``, the triangle inequality broken by more than ``tol`` (``tol`` =
    :data:`~offshore_crane.conventions.INERTIA_RTOL` of the moments' sum), an inertia
    without mass. The one rule of description files and of the identified robot."""
    from offshore_crane.conventions import INERTIA_RTOL

    lam = np.linalg.eigvalsh(I)                           # ascending
    tol = INERTIA_RTOL * float(np.abs(lam).sum())
    shown = ", ".join(f"{x:.6g}" for x in lam)
    if lam[0] < -tol:
        return f"not positive definite: principal moments ({shown}) kg·m² include a negative one"
    if lam[2] > lam[0] + lam[1] + tol:
        return (f"principal moments ({shown}) kg·m² break the triangle inequality "
                f"({lam[2]:.6g} > {lam[0]:.6g} + {lam[1]:.6g})")
    if m == 0.0 and lam[2] > 0.0:
        return "an inertia without mass: give the mass too"
    return None


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
