"""From checked values to a :class:`~offshore_crane.robot.description.results.Description`:
anchors, legs, arm, inertias of solids, validated as a whole (geometry, home pose).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from offshore_crane.conventions import AIR_DENSITY
from offshore_crane.errors import DescriptionError
from offshore_crane.io import toml_value
from offshore_crane.robot.description.files import label
from offshore_crane.robot.description.geometry import (inertia_problem, rpy_angles,
                                                        solid_inertia)
from offshore_crane.spatial import attitude_matrix
from offshore_crane.robot.description.capacities import (capacities, load_limits,
                                                        winch_capacities)
from offshore_crane.robot.description.results import ArmJoint, Body, Description
from offshore_crane.robot.description.schema import (ANCHOR_RTOL, ARM_BODIES,
                                                     ARM_DRAW_RATIO, COM_RTOL, DISC_MARGIN,
                                                     DISC_THICKNESS, FORMAT, GIMBAL_LIMIT,
                                                     HOME_CONDITION_LIMIT, INERTIA_KEYS,
                                                     LEG_DRAW_RATIO, N_LEGS, ORTHOGONAL_TOL,
                                                     REVOLUTE_LIMIT, XYZ)
from offshore_crane.robot.description.values import Numbers, Values, overlap


class Resolver:
    def __init__(self, values: Values, path: str, overrides: dict):
        self.v = values
        self.n = Numbers(values)
        self.path = path
        self.overrides = overrides

    def fail(self, name, message, *involved):
        """Error on field ``name``; the overrides that touch it or ``involved`` are shown."""
        fields = [k for k in self.v.raw if any(overlap(k, p) for p in (name, *involved))]
        fields = self.n.depends(fields) | {name, *involved}
        over = [f"{k} = {toml_value(v)}" for k, v in self.overrides.items()
                if any(overlap(k, p) for p in fields)]
        if len(over) > 3:                                   # the first, and how many more
            over = over[:2] + [f"{len(over) - 2} more"]
        where = self.v.path + (f" with {', '.join(over)}" if over else "")
        raise DescriptionError(f"{where}: {name}: {message}", path=self.path, field=name)

    # ------------------------------------------------------------------ build
    def build(self) -> Description:
        fmt = self.v.raw.get("format", FORMAT)
        if fmt != FORMAT:
            self.fail("format", f"{fmt} is not a known format version (this library reads "
                      f"format {FORMAT})")
        for name in list(self.v.raw):                    # every number, evaluated once
            if not isinstance(self.v.raw[name], bool) and not (
                    name in ("name", "source", "format") or name.endswith(".type")):
                self.n(name)
        h = self.n.need("home.height", "home.height = O2's height at the home pose [m]")
        P = self._anchors("base", "P")
        S = self._anchors("platform", "S")
        platform = self._body("platform", "platform")
        if not self.v.has("platform.shape"):              # drawn as a disc at the S_i
            platform = Body(platform.mass, platform.com, platform.inertia,
                            _disc(S, above=True))
        parts, lengths = self._parts()
        stroke = np.array([[self._leg_number(i, "stroke.min", "m"),
                            self._leg_number(i, "stroke.max", "m")] for i in range(N_LEGS)])
        ulim = np.array([self._leg_number(i, "ujoint.limit", "rad") for i in range(N_LEGS)])
        self._check_ranges(stroke, ulim)
        a1, R_U, rpy_U = self._ujoints(P, S, h)
        self._check_home(P, S, h, stroke, R_U, ulim)
        arm = self._arm()
        payload, cable, damping, drag = self._payload(arm is not None)
        caps = capacities(self.v.has, self.n.get, self.fail)
        return Description(
            name=self.v.raw.get("name", Path(self.path).stem), source=self.v.raw.get(
                "source", ""), path=self.path, overrides=self.overrides, home_height=h,
            p_base_P=P, p_platform_S=S, a1=a1, R_base_U=R_U, rpy_U=rpy_U, lower=tuple(p[0] for p in parts),
            upper=tuple(p[1] for p in parts), part_length=lengths, stroke=stroke,
            ujoint_limit=ulim, platform=platform, base_visual=self._base_visual(P),
            arm=arm, payload=payload, cable_length=cable, sway_damping=damping,
            drag_area=drag[0], air_density=drag[1],
            capacities=caps, values=dict(self.n.cache),
            load_limits=load_limits(self.n.get, self.fail),
            winch=winch_capacities(self.n.get, self.fail))

    # ------------------------------------------------------------------ anchors
    def _anchors(self, side: str, letter: str) -> np.ndarray:
        pre = f"{side}.joints"
        points, circle = self.v.has(f"{pre}.points"), [
            k for k in ("radius", "height", "angles_deg", "half_angle_deg", "pair_angles_deg")
            if self.v.has(f"{pre}.{k}")]
        frame = "base" if side == "base" else "platform"
        if points and circle:
            self.fail(pre, f"give either points or the circle ({', '.join(circle)}), not "
                      "both")
        if points:
            X = np.array([self.n.vector(f"{pre}.points.{i}") for i in range(1, 7)])
        elif circle:
            r = self.n.need(f"{pre}.radius", "the circle's radius [m]")
            z = self.n.need(f"{pre}.height", "the circle's height [m]")
            th = self._angles(pre, side)
            X = np.array([[r * math.cos(t), r * math.sin(t), z] for t in th])
        else:
            self.fail(pre, f"missing: give the six {letter}_i ({frame} frame) as "
                      f"{pre}.points = [[x, y, z], ...] or on a circle ({pre}.radius, "
                      "height, angles_deg)")
        self._check_anchors(pre, X, letter)
        return X

    def _angles(self, pre: str, side: str) -> list[float]:
        if self.v.has(f"{pre}.angles_deg"):
            if self.v.has(f"{pre}.half_angle_deg"):
                self.fail(pre, "give either angles_deg or half_angle_deg (pairs), not both")
            return [math.radians(self.n.need(f"{pre}.angles_deg.{i}", "6 angles [deg]"))
                    for i in range(1, 7)]
        a = math.radians(self.n.need(f"{pre}.half_angle_deg",
                                     "angles_deg (6 angles) or half_angle_deg (pairs)"))
        default = (0.0, 120.0, 240.0) if side == "base" else (60.0, 180.0, 300.0)
        c = [self.n.get(f"{pre}.pair_angles_deg.{k}", default[k - 1]) for k in (1, 2, 3)]
        if side == "base":                    # legs 2k-1, 2k around c_k
            return [math.radians(c[k // 2]) + (a if k % 2 else -a) for k in range(6)]
        # platform: legs 2k, 2k+1 around c_k; leg 1 closes the third pair (c3 - 360°)
        th = [math.radians(c[2] - 360.0) + a]
        th += [math.radians(c[k // 2]) + (a if k % 2 else -a) for k in range(5)]
        return th

    def _check_anchors(self, name: str, X: np.ndarray, letter: str):
        centred = X - X.mean(axis=0)
        spread = float(np.abs(centred).max())
        for i in range(N_LEGS):
            for j in range(i + 1, N_LEGS):
                if np.linalg.norm(X[i] - X[j]) <= ANCHOR_RTOL * spread or spread == 0.0:
                    self.fail(name, f"{letter}{i + 1} and {letter}{j + 1} coincide at "
                              f"({', '.join(f'{x:.6g}' for x in X[i])}) m: give each leg "
                              "its own joint centre")
        sv = np.linalg.svd(centred, compute_uv=False)
        if sv[1] <= ANCHOR_RTOL * sv[0]:
            self.fail(name, f"the six {letter}_i lie on one line: the platform could turn "
                      "about it freely (a singular design)")

    # ------------------------------------------------------------------ bodies
    def _inertia(self, name: str, zero_default: bool = False) -> np.ndarray | None:
        """The inertia table ``name``; products default to 0, the moments too when
        ``zero_default`` (a point mass plus the moments given), else they are required."""
        if not self.v.has(name):
            return None
        ixx, iyy, izz = (self.n.get(f"{name}.{k}", 0.0) if zero_default else self.n.need(
            f"{name}.{k}", "ixx, iyy and izz [kg·m²]") for k in ("ixx", "iyy", "izz"))
        ixy, ixz, iyz = (self.n.get(f"{name}.{k}", 0.0) for k in ("ixy", "ixz", "iyz"))
        return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])

    def _shape(self, name: str) -> dict | None:
        if not self.v.has(name):
            return None
        kind = self.v.raw.get(f"{name}.type")
        if kind is None:
            self.fail(f"{name}.type", "missing: give type = \"cylinder\", \"box\", "
                      "\"sphere\" or \"none\"")
        shape = {"type": kind, "xyz": self.n.vector(f"{name}.xyz", (0.0, 0.0, 0.0))}
        need = {"cylinder": ("radius", "length"), "sphere": ("radius",), "box": ("size",),
                "none": ()}[kind]
        for key in ("radius", "length", "size"):
            given = self.v.has(f"{name}.{key}")
            if key in need and not given:
                self.fail(f"{name}.{key}", f"missing: a {kind} needs "
                          f"{' and '.join(need)} [m]")
            if given and key not in need:
                self.fail(f"{name}.{key}", f"does not apply to a {kind}")
            if given:
                value = (self.n.vector(f"{name}.size") if key == "size"
                         else self.n(f"{name}.{key}"))
                if np.any(np.asarray(value) < 0.0):
                    self.fail(f"{name}.{key}", f"{toml_value(np.asarray(value).tolist())} m "
                              "must not be negative")
                shape[key] = value
        return shape

    def _body(self, name: str, label: str, length_hint: float = 0.0) -> Body:
        m = self.n.need(f"{name}.mass", f"the mass of the {label} [kg]")
        if m < 0.0:
            self.fail(f"{name}.mass", f"{m:g} kg is negative; give a mass >= 0")
        shape = self._shape(f"{name}.shape")
        I = self._inertia(f"{name}.inertia")
        com_default = shape["xyz"] if shape is not None else (0.0, 0.0, 0.0)
        com = self.n.vector(f"{name}.com", com_default)
        if I is None:
            if shape is None or shape["type"] == "none":
                self.fail(f"{name}.inertia", f"missing: give the {label}'s inertia about "
                          "its centre of mass, or a shape (a solid of uniform density)")
            I = solid_inertia(m, shape)
        self._check_inertia(f"{name}.inertia", m, I, f"{name}.mass", f"{name}.shape")
        visual = shape if shape is not None else {"type": "sphere", "radius": max(
            length_hint, 0.0) * ARM_DRAW_RATIO, "xyz": com}
        return Body(m, com, I, visual)

    def _check_inertia(self, name: str, m: float, I: np.ndarray, *involved):
        problem = inertia_problem(m, I)
        if problem is not None:
            self.fail(name, problem, *involved)

    def _leg_name(self, i: int, key: str) -> str:
        """``legs.{i+1}.key`` when given for that leg, else ``legs.key``."""
        own = f"legs.{i + 1}.{key}"
        return own if self.v.has(own) else f"legs.{key}"

    def _leg_number(self, i: int, key: str, unit: str) -> float:
        name = self._leg_name(i, key)
        return self.n.need(name, f"legs.{key} [{unit}] (for all legs, or legs.N.{key})")

    def _parts(self):
        parts, lengths = [], []
        for i in range(N_LEGS):
            pair = []
            for part, sign in (("lower", 1.0), ("upper", -1.0)):
                pair.append(self._part(i, part, sign))
            parts.append(tuple(b for b, _ in pair))
            lengths.append([L for _, L in pair])
        return parts, np.array(lengths)

    def _part(self, i: int, part: str, sign: float):
        key = lambda k: self._leg_name(i, f"{part}.{k}")            # noqa: E731
        label = f"leg {i + 1}'s {part} part"
        m = self.n.need(key("mass"), f"the mass of the {part} leg part [kg]")
        L = self.n.need(key("length"), f"the {part} part's length along the leg [m]")
        if m < 0.0:
            self.fail(key("mass"), f"{m:g} kg is negative; give a mass >= 0")
        if not L > 0.0:
            self.fail(key("length"), f"{L:g} m must be positive: links 'leg{{i}}_{part}' "
                      "would have zero length")
        r = self.n.get(key("radius"))
        if r is not None and r < 0.0:
            self.fail(key("radius"), f"{r:g} m must not be negative")
        default_com = (0.0, 0.0, sign * L / 2)
        com = np.array([self.n.get(self._leg_name(i, f"{part}.com.{c}"), default_com[k])
                        for k, c in enumerate(XYZ)])
        names = [self._leg_name(i, f"{part}.inertia.{k}") for k in INERTIA_KEYS]
        if any(self.v.has(n) for n in names):
            ixx, iyy, izz = (self.n.need(n, "ixx, iyy and izz [kg·m²]") for n in names[:3])
            ixy, ixz, iyz = (self.n.get(n, 0.0) for n in names[3:])
            I = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
        elif r is None:
            self.fail(key("inertia"), f"missing: give the {part} part's inertia about its "
                      "centre of mass, or its radius (a solid cylinder)")
        else:
            I = solid_inertia(m, {"type": "cylinder", "radius": r, "length": L})
        self._check_inertia(key("inertia"), m, I, key("mass"), key("radius"), key("length"))
        lo, hi = (0.0, L) if sign > 0 else (-L, 0.0)
        tol = COM_RTOL * L
        if not lo - tol <= com[2] <= hi + tol:
            self.fail(key("com"), f"z = {com[2]:.6g} m lies outside the {part} part "
                      f"({lo:g} to {hi:g} m along the leg from its joint): {label}",
                      key("length"))
        visual = {"type": "cylinder", "radius": r if r is not None else L * LEG_DRAW_RATIO,
                  "length": L, "xyz": np.array([0.0, 0.0, sign * L / 2])}
        return Body(m, com, I, visual), L

    def _check_ranges(self, stroke, ulim):
        for i in range(N_LEGS):
            lo, hi = stroke[i]
            name = self._leg_name(i, "stroke")
            if not lo < hi:
                self.fail(name, f"the stroke [{lo:g}, {hi:g}] m of leg {i + 1} is empty "
                          "(need min < max)")
            if not lo > 0.0:
                self.fail(name, f"min = {lo:g} m: a leg length must be positive")
            name = self._leg_name(i, "ujoint.limit")
            if not 0.0 < ulim[i] <= math.pi / 2:
                hint = (" (degrees given for radians?)" if ulim[i] > math.pi / 2 else "")
                self.fail(name, f"{ulim[i]:g} rad: need 0 < limit <= pi/2 (both U-joint "
                          f"axes turn within ±limit; at pi/2 the joint locks){hint}")

    # ------------------------------------------------------------------ U-joints
    def _axes(self, name: str):
        if not self.v.has(name):
            return None
        A = np.array([self.n.vector(f"{name}.{i}") for i in range(1, 7)])
        norm = np.linalg.norm(A, axis=1)
        for i in range(N_LEGS):
            if not norm[i] > 0.0:
                self.fail(f"{name}.{i + 1}", "a zero vector is no axis")
        return A / norm[:, None]

    def _ujoints(self, P, S, h):
        d = S + np.array([0.0, 0.0, h]) - P                  # S_i − P_i at home
        A1 = self._axes("base.ujoint_axes")
        A2 = self._axes("base.ujoint_axes2")
        a1s, Rs, rpys = [], [], []
        for i in range(N_LEGS):
            dx, dy, dz = (float(x) for x in d[i])
            if A1 is None and A2 is None:      # a1 horizontal, z at S_i: both angles 0
                rpy = np.array([0.0, math.atan2(math.sqrt(dx * dx + dy * dy), dz),
                                math.atan2(dy, dx)])
                R = attitude_matrix(*rpy)
            elif A1 is None:
                self.fail("base.ujoint_axes2", "give ujoint_axes (a1) with ujoint_axes2")
            else:
                a1 = A1[i]
                u = d[i] / np.linalg.norm(d[i])
                kappa = 1.0 / max(math.sqrt(max(1.0 - float(a1 @ u) ** 2, 0.0)), 1e-300)
                if kappa >= GIMBAL_LIMIT:
                    self.fail(f"base.ujoint_axes.{i + 1}", f"a1 of leg {i + 1} is parallel "
                              "to the leg at the home pose (U-joint gimbal lock): turn it "
                              "across the leg")
                if A2 is None:
                    z = u - (u @ a1) * a1
                    z /= np.linalg.norm(z)
                    x = np.cross(a1, z)
                else:
                    x = A2[i]
                    if abs(float(x @ a1)) > ORTHOGONAL_TOL:
                        self.fail(f"base.ujoint_axes2.{i + 1}", f"a2 is not perpendicular "
                                  f"to a1 (cos = {float(x @ a1):.3g}) for leg {i + 1}")
                    x = x - (x @ a1) * a1
                    x /= np.linalg.norm(x)
                    z = np.cross(x, a1)
                R = np.column_stack([x, a1, z])
                rpy = rpy_angles(R)
                R = attitude_matrix(*rpy)          # the frame the URDF will hold
            a1s.append(R[:, 1])
            Rs.append(R)
            rpys.append(rpy)
        return np.array(a1s), np.array(Rs), np.array(rpys)

    def _check_home(self, P, S, h, stroke, R_U, ulim):
        d = S + np.array([0.0, 0.0, h]) - P
        length = np.linalg.norm(d, axis=1)
        for i in range(N_LEGS):
            if d[i, 2] <= 0.0:
                self.fail("home.height", f"at the home pose sphere centre S{i + 1} is "
                          f"{-d[i, 2]:.4g} m below its U-joint (platform below the base)",
                          "base.joints", "platform.joints")
            lo, hi = stroke[i]
            if not lo <= length[i] <= hi:
                self.fail(self._leg_name(i, "stroke"), f"leg {i + 1} cannot reach the home "
                          f"pose: |P{i + 1}S{i + 1}| = {length[i]:.6g} m is outside the "
                          f"stroke [{lo:g}, {hi:g}] m", "home.height", "base.joints",
                          "platform.joints")
            u = R_U[i].T @ (d[i] / length[i])              # (c2 s1, −s2, c2 c1)
            th2 = -math.asin(max(-1.0, min(1.0, float(u[1]))))
            th1 = math.atan2(float(u[0]), float(u[2]))
            for k, th in ((1, th1), (2, th2)):
                if abs(th) > ulim[i]:
                    self.fail(self._leg_name(i, "ujoint.limit"), f"at the home pose the "
                              f"U-joint angle {k} of leg {i + 1} is {th:.4g} rad, outside "
                              f"±{ulim[i]:g} rad: orient the U-joint (base.ujoint_axes) or "
                              "widen the limit", "base.ujoint_axes", "base.ujoint_axes2")
        u = d / length[:, None]
        L = float(np.linalg.norm(S, axis=1).mean())
        A = np.concatenate([u.T, np.cross(S, u).T / L])
        with np.errstate(all="ignore"):
            kappa = float(np.linalg.cond(A, 1)) if np.all(np.isfinite(A)) else np.inf
        if not kappa < HOME_CONDITION_LIMIT:
            self.fail("platform.joints", f"singular legs at the home pose (Stewart matrix "
                      f"condition {kappa:.3g}): move the anchors",
                      "base.joints", "home.height")

    # ------------------------------------------------------------------ arm
    def _arm(self):
        enabled = self.v.raw.get("arm.enabled", self.v.has("arm"))
        if not enabled:
            return None
        arm = {}
        col_origin = self.n.vector("arm.column.origin")
        col_rpy = self.n.vector("arm.column.rpy", (0.0, 0.0, 0.0))
        parents = ["column", *ARM_BODIES]
        origins = {}
        for body in ARM_BODIES:
            origins[body] = self.n.vector(f"arm.{body}.origin")
        tip_origin = self.n.vector("arm.tip.origin")
        tip_rpy = self.n.vector("arm.tip.rpy", (0.0, 0.0, 0.0))
        child_distance = {"column": float(np.linalg.norm(origins["link1"])),
                          "link1": float(np.linalg.norm(origins["link2"])),
                          "link2": float(np.linalg.norm(origins["slider"])),
                          "slider": float(np.linalg.norm(tip_origin))}
        arm["column"] = (col_origin, col_rpy, self._body("arm.column", "arm column",
                                                         child_distance["column"]))
        for k, body in enumerate(ARM_BODIES):
            pre = f"arm.{body}"
            prismatic = body == "slider"
            axis = self.n.vector(f"{pre}.axis", (1.0, 0.0, 0.0) if prismatic else
                                 (0.0, 0.0, 1.0))
            norm = float(np.linalg.norm(axis))
            if not norm > 0.0:
                self.fail(f"{pre}.axis", "a zero vector is no axis")
            lo = self.n.need(f"{pre}.min", f"the joint's lower limit [{'m' if prismatic else 'rad'}]")
            hi = self.n.need(f"{pre}.max", f"the joint's upper limit [{'m' if prismatic else 'rad'}]")
            if not lo < hi:
                self.fail(f"{pre}.min", f"the range [{lo:g}, {hi:g}] is empty (need min < "
                          "max)", f"{pre}.max")
            if not prismatic and max(abs(lo), abs(hi)) > REVOLUTE_LIMIT:
                self.fail(f"{pre}.max", f"[{lo:g}, {hi:g}] rad spans more than two turns "
                          "(degrees given for radians?)", f"{pre}.min")
            arm[body] = ArmJoint(origins[body], self.n.vector(f"{pre}.rpy", (0.0, 0.0, 0.0)),
                                 axis / norm, lo, hi, prismatic,
                                 self._body(pre, f"arm {body}", child_distance[body]))
        self._check_coaxial(arm)
        arm["tip"] = (tip_origin, tip_rpy)
        return arm

    def _check_coaxial(self, arm):
        for parent, child in (("link1", "link2"),):
            pj, cj = arm[parent], arm[child]
            axis = attitude_matrix(*cj.rpy) @ cj.axis            # in the parent body frame
            if (abs(abs(float(axis @ pj.axis)) - 1.0) < 1e-12
                    and np.linalg.norm(np.cross(cj.origin, pj.axis)) <= 1e-12):
                self.fail(f"arm.{child}.origin", f"arm_joint2 lies on arm_joint1's axis: "
                          f"link 'arm_{parent}' would have zero length")

    # ------------------------------------------------------------------ payload
    def _payload(self, has_arm: bool):
        m = self.n.get("payload.mass", 0.0)
        if m < 0.0:
            self.fail("payload.mass", f"{m:g} kg is negative; give a mass >= 0")
        if m > 0.0 and not has_arm:
            self.fail("payload.mass", f"{m:g} kg: the payload hangs from the arm tip, but "
                      "the robot has no arm", "arm.enabled")
        com = self.n.vector("payload.com", (0.0, 0.0, 0.0))
        I = self._inertia("payload.inertia", zero_default=True)
        I = np.zeros((3, 3)) if I is None else I
        self._check_inertia("payload.inertia", m, I, "payload.mass")
        cable = self.n.get("payload.cable_length", 0.0)
        if cable < 0.0:
            self.fail("payload.cable_length", f"{cable:g} m must not be negative (0: the "
                      "payload welded to arm_tip; > 0: hanging on a cable of that length)")
        damping = self.n.get("payload.sway_damping", 0.0)
        if not damping >= 0.0:
            self.fail("payload.sway_damping", f"{damping:g} N·m·s/rad must not be negative")
        if damping > 0.0 and not cable > 0.0:
            self.fail("payload.sway_damping", f"{damping:g} N·m·s/rad damps the swing of a "
                      "payload on a cable, but payload.cable_length = 0 (welded)",
                      "payload.cable_length")
        area = self.n.get("payload.drag_area", 0.0)
        if not area >= 0.0:
            self.fail("payload.drag_area", f"{area:g} m² must not be negative (C_d·A; 0: "
                      "no drag)")
        if area > 0.0 and not cable > 0.0:
            self.fail("payload.drag_area", f"{area:g} m² drags a payload swinging on a "
                      "cable, but payload.cable_length = 0 (welded)", "payload.cable_length")
        rho = self.n.get("payload.air_density", AIR_DENSITY)
        if not rho > 0.0:
            self.fail("payload.air_density", f"{rho:g} kg/m³ must be > 0 (air at sea level: "
                      f"{AIR_DENSITY:g})")
        if cable > 0.0:
            if not m > 0.0:
                self.fail("payload.cable_length", f"{cable:g} m: a cable needs a payload to "
                          "hang from it: give payload.mass > 0, or cable_length = 0",
                          "payload.mass")
            if np.any(com != 0.0) or np.any(I != 0.0):
                self.fail("payload.com" if np.any(com != 0.0) else "payload.inertia",
                          "with a cable (payload.cable_length > 0) the payload is a point "
                          "mass at the cable's end: set payload.com = [0, 0, 0] and "
                          "payload.inertia to zero (the cable length is measured to the "
                          "centre of mass)", "payload.cable_length")
        return Body(m, com, I, {"type": "none"}), cable, damping, (area, rho)

    def _base_visual(self, P):
        shape = self._shape("base.shape")
        return shape if shape is not None else _disc(P, above=False)


def _disc(X: np.ndarray, above: bool) -> dict:
    """Default drawing: a disc just beyond the anchors ``X``, above or below them."""
    r = DISC_MARGIN * float(np.linalg.norm(X[:, :2], axis=1).max())
    t = DISC_THICKNESS * r
    z = float(X[:, 2].max()) + t / 2 if above else float(X[:, 2].min()) - t / 2
    return {"type": "cylinder", "radius": r, "length": t, "xyz": np.array([0.0, 0.0, z])}
