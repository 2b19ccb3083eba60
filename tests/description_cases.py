"""Robot descriptions built in Python for the tests: a TOML writer, a general platform
(anchors at two heights, off-centre leg CoMs, full inertia tensors, tilted arm axes)
and its transformations (legs permuted, reference point O2 moved), and seeded random
states near its home pose."""

from __future__ import annotations

import copy
import json
import math

import numpy as np

BASE_DEG = (20, 100, 140, 220, 260, 340)
PLATFORM_DEG = (40, 80, 160, 200, 280, 320)
HOME = 0.5


def to_toml(data: dict, prefix: tuple = ()) -> str:
    """A nested dict of tables, lists, numbers, strings and booleans as TOML text."""
    def value(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, int):
            return str(v)
        if isinstance(v, float):
            if math.isnan(v):
                return "nan"
            return repr(float(v)) if math.isfinite(v) else ("inf" if v > 0 else "-inf")
        if isinstance(v, str):
            return json.dumps(v)
        return "[" + ", ".join(value(x) for x in v) + "]"

    scalars = {k: v for k, v in data.items() if not isinstance(v, dict)}
    lines = ["[" + ".".join(prefix) + "]"] if prefix and scalars else []
    lines += [f"{k} = {value(v)}" for k, v in scalars.items()]
    for k, v in data.items():
        if isinstance(v, dict):
            lines.append(to_toml(v, prefix + (k,)))
    return "\n".join(lines)


def write(tmp_path, data: dict, name: str = "robot.toml"):
    path = tmp_path / name
    path.write_text(to_toml(data) + "\n", encoding="utf-8")
    return path


def _rot(axis, angle):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


def tensor(moments, axis, angle) -> dict:
    """A full inertia table: principal ``moments`` turned by ``angle`` about ``axis``."""
    R = _rot(axis, angle)
    I = R @ np.diag(moments) @ R.T
    return {"ixx": I[0, 0], "iyy": I[1, 1], "izz": I[2, 2], "ixy": I[0, 1], "ixz": I[0, 2],
            "iyz": I[1, 2]}


def _points(radius, degrees, heights):
    return [[radius * math.cos(math.radians(a)), radius * math.sin(math.radians(a)), z]
            for a, z in zip(degrees, heights)]


def general() -> dict:
    """A platform with general anchors and mass properties, and a general arm."""
    P = _points(0.6, BASE_DEG, [0.05, 0.09] * 3)                 # two heights
    S = _points(0.35, PLATFORM_DEG, [-0.02, -0.035] * 3)
    d = np.array(S) + [0, 0, HOME] - np.array(P)
    a1, a2 = [], []
    for i in range(6):
        u = d[i] / np.linalg.norm(d[i])
        h = np.cross([0.0, 0.0, 1.0], u)
        v = h / np.linalg.norm(h) + 0.15 * u + 0.05 * np.array([0, 0, 1.0])
        a1.append(list(v / np.linalg.norm(v)))
        w = np.cross(v, u)                            # a2 ⟂ a1, a2 x a1 close to u
        w = w - (w @ a1[-1]) * np.array(a1[-1])
        a2.append(list(w / np.linalg.norm(w)))
    legs = {
        "lower": {"mass": 2.0, "length": 0.42, "com": [0.012, -0.006, 0.15],
                  "inertia": tensor((0.029, 0.028, 0.0015), (1, 2, 0.5), 0.3)},
        "upper": {"mass": 0.8, "length": 0.40, "com": [-0.004, 0.007, -0.12],
                  "inertia": tensor((0.0105, 0.0102, 0.0004), (0.3, -1, 0.2), 0.5)},
        "stroke": {"min": 0.30, "max": 0.90},
        "ujoint": {"limit": 1.2},
    }
    for i in range(1, 7):                              # every leg a little different
        legs[str(i)] = {"lower": {"mass": 2.0 + 0.1 * i, "com": [0.01, 0.002 * i, 0.14]},
                        "upper": {"inertia": tensor((0.0102 + 5e-5 * i, 0.0102, 0.0004),
                                                    (1, i, 0.3), 0.2 * i)}}
    return {
        "format": 1, "name": "general",
        "home": {"height": HOME},
        "base": {"joints": {"points": P}, "ujoint_axes": a1, "ujoint_axes2": a2},
        "platform": {"mass": 40.0, "com": [0.02, -0.01, 0.015],
                     "inertia": tensor((1.6, 1.5, 3.0), (1, -1, 2), 0.4),
                     "joints": {"points": S}},
        "legs": legs,
        "arm": {
            "enabled": True,
            "column": {"origin": [0.04, 0.02, 0.02], "rpy": [0.02, -0.01, 0.1], "mass": 5.0,
                       "com": [0.003, 0.0, 0.15], "inertia": tensor((0.04, 0.041, 0.006),
                                                                    (0, 1, 0.1), 0.2)},
            "link1": {"origin": [0.0, 0.0, 0.33], "rpy": [0.01, 0.0, 0.0],
                      "axis": [0.05, 0.0, 1.0], "min": -3.3, "max": 3.3, "mass": 4.0,
                      "com": [0.25, 0.01, 0.003], "inertia": tensor((0.003, 0.085, 0.086),
                                                                    (1, 0, 0.2), 0.3)},
            "link2": {"origin": [0.5, 0.01, 0.055], "axis": [0.0, 0.03, 1.0], "min": -2.0,
                      "max": 2.0, "mass": 3.0, "com": [0.2, -0.004, 0.0],
                      "inertia": tensor((0.0016, 0.041, 0.041), (0.2, 1, 0), 0.25)},
            "slider": {"origin": [0.25, 0.0, -0.045], "rpy": [0.0, 0.02, 0.0],
                       "axis": [1.0, 0.02, 0.0], "min": -0.2, "max": 0.2, "mass": 1.0,
                       "com": [0.15, 0.0, 0.002], "inertia": tensor((0.0003, 0.0076, 0.0077),
                                                                    (0, 0, 1), 0.1)},
            "tip": {"origin": [0.3, 0.0, 0.0], "rpy": [0.0, 0.1, 0.0]},
        },
        "payload": {"mass": 2.0, "com": [0.01, 0.0, -0.05],
                    "inertia": tensor((0.004, 0.005, 0.006), (1, 1, 1), 0.3)},
        "actuators": {"Fl": {"push_max": 8000.0, "pull_max": 6000.0, "speed_max": 0.4},
                      "Fl3": {"push_max": 9000.0}, "T1": {"push_max": 300.0,
                                                          "pull_max": 300.0, "speed_max": 2.0,
                                                          "power_max": 500.0}},
    }


def permuted(data: dict, order) -> dict:
    """``data`` with the legs renumbered: new leg k is old leg ``order[k]`` (0-based)."""
    out = copy.deepcopy(data)
    for side, key in (("base", "points"), ("platform", "points")):
        pts = data[side]["joints"][key]
        out[side]["joints"][key] = [pts[j] for j in order]
    for key in ("ujoint_axes", "ujoint_axes2"):
        out["base"][key] = [data["base"][key][j] for j in order]
    for k, j in enumerate(order):
        out["legs"][str(k + 1)] = copy.deepcopy(data["legs"][str(j + 1)])
    acts = out["actuators"]
    if "Fl3" in acts:
        acts[f"Fl{order.index(2) + 1}"] = acts.pop("Fl3")
    return out


def moved_reference(data: dict, c) -> dict:
    """``data`` with the platform frame's origin O2 moved by ``c`` (platform frame) and
    the same physical robot: every platform-frame point shifts by −c."""
    out = copy.deepcopy(data)
    c = np.asarray(c, float)
    out["platform"]["joints"]["points"] = [list(np.array(p) - c)
                                           for p in data["platform"]["joints"]["points"]]
    out["platform"]["com"] = list(np.array(data["platform"]["com"]) - c)
    out["arm"]["column"]["origin"] = list(np.array(data["arm"]["column"]["origin"]) - c)
    out["home"]["height"] = data["home"]["height"] + float(c[2])
    return out


def random_states(robot, n: int, seed: int):
    """``n`` seeded (q, qd, qdd) ``(n, 9)`` near the home pose, every leg in its stroke."""
    rng = np.random.default_rng(seed)
    h = robot.spec.home_height
    lo = np.array([-0.04, -0.04, h - 0.04, -0.12, -0.12, -0.12, -3.0, -1.8, -0.18])
    hi = np.array([0.04, 0.04, h + 0.04, 0.12, 0.12, 0.12, 3.0, 1.8, 0.18])
    q = rng.uniform(lo, hi, size=(n, 9))
    length = leg_lengths(robot, q)
    stroke = robot.hybrid.stroke
    assert np.all((length > stroke[:, 0]) & (length < stroke[:, 1]))
    return q, rng.uniform(-1.0, 1.0, size=q.shape), rng.uniform(-5.0, 5.0, size=q.shape)


def attitude(q):
    """``R_base_platform`` ``(N, 3, 3)`` = Rz(q6) Ry(q5) Rx(q4)."""
    r, p, y = q[:, 3], q[:, 4], q[:, 5]
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    return np.stack([np.stack([cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr], -1),
                     np.stack([sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr], -1),
                     np.stack([-sp, cp * sr, cp * cr], -1)], -2)


def leg_lengths(robot, q):
    """``(N, 6)`` |P_i S_i| [m] (closed form, independent of the library's kinematics)."""
    S = np.einsum("nij,lj->nli", attitude(q), robot.hybrid.p_platform_S) + q[:, None, :3]
    return np.linalg.norm(S - robot.hybrid.p_base_P, axis=2)


def angular(q, qd, qdd):
    """Platform angular velocity and acceleration ``(N, 3)`` each, base frame, from the
    attitude rates (docs/conventions.md: ω = q̇4 w4 + q̇5 w5 + q̇6 w6)."""
    p, y = q[:, 4], q[:, 5]
    z = np.array([0.0, 0.0, 1.0])
    w4 = np.stack([np.cos(y) * np.cos(p), np.sin(y) * np.cos(p), -np.sin(p)], -1)
    w5 = np.stack([-np.sin(y), np.cos(y), np.zeros_like(y)], -1)
    w6 = np.broadcast_to(z, w4.shape)
    r4, r5, r6 = qd[:, 3:4], qd[:, 4:5], qd[:, 5:6]
    omega = r4 * w4 + r5 * w5 + r6 * w6
    # w4 turns with Rz(q6) Ry(q5): ẇ4 = (q̇5 w5 + q̇6 z) × w4; ẇ5 = q̇6 z × w5; ẇ6 = 0
    alpha = (qdd[:, 3:4] * w4 + qdd[:, 4:5] * w5 + qdd[:, 5:6] * w6
             + r4 * np.cross(r5 * w5 + r6 * w6, w4) + r5 * r6 * np.cross(w6, w5))
    return omega, alpha
