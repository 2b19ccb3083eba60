"""A small headless renderer: the URDF's visual primitives projected with NumPy and
filled with Pillow (painter's algorithm, flat shading, no display, no OpenGL).

What is drawn: every ``<visual>`` box, cylinder and sphere of the URDF
(:attr:`offshore_crane.robot.urdf.URDF.visuals`) in its material colour; a link with
mass but no visual (the payload: the xacro gives it none) as a sphere of that mass at the
density :data:`PAYLOAD_DENSITY`; with a hanging load, the cable as a line from
``arm_tip`` to ``payload``.

How: the shapes are tessellated once into planar faces in their link frames (vertices,
outward normals, centroids). Per frame, :class:`Renderer` moves them with the link poses
(:mod:`offshore_crane.outputs.visual.poses`), culls the faces turned away from the camera,
shades the rest by ``ambient + diffuse · max(0, n · l)`` with the light ``l`` fixed to the
camera, sorts them far to near by their centroids' depth and fills them with one Pillow
``ImageDraw.polygon`` call each (a few hundred per frame). The root link (the base, the
floor the robot stands on) is drawn first whatever its depth. Painter's algorithm sorts
whole faces, so two faces that interpenetrate may be drawn in the wrong order at their
crossing: large caps are cut into sectors to keep such errors small.

Camera: a perspective pinhole looking at ``target`` from the azimuth (about base z, from
+x) and elevation given [deg], fitted by default so that the whole motion stays in view.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from offshore_crane.errors import InputError

#: Density of the sphere that stands for a link with mass and no visual (the payload)
#: [kg/m³]: steel. A drawing convention, never used by the dynamics.
PAYLOAD_DENSITY = 7850.0
#: Colour of a shape whose URDF visual names none, and of the payload sphere (RGB 0..1).
DEFAULT_RGB = (0.6, 0.6, 0.6)
PAYLOAD_RGB = (0.15, 0.35, 0.75)
CABLE_RGB = (0.1, 0.1, 0.1)
#: Flat shading: intensity = AMBIENT + DIFFUSE · max(0, n · l).
AMBIENT, DIFFUSE = 0.45, 0.55
#: Tessellation: segments around a cylinder, latitude x longitude bands of a sphere;
#: a cylinder cap wider than CAP_SECTOR_RADIUS [m] is cut into triangle sectors.
CYLINDER_SEGMENTS = 16
SPHERE_BANDS = (6, 10)
CAP_SECTOR_RADIUS = 0.1
BACKGROUND_TOP, BACKGROUND_BOTTOM = (235, 240, 246), (200, 208, 218)
#: The floor under the base (the lab's, fixed: a reference the platform moves against):
#: a square of GROUND_EXTENT times the base's radius, its grid every quarter of it.
GROUND_RGB, GROUND_LINE_RGB = (214, 219, 226), (188, 195, 205)
GROUND_EXTENT = 1.6
#: The still water line (a scene with a sea): the calm surface at model scale, drawn as
#: the outline of a square of GROUND_EXTENT times the base's radius.
WATER_RGB = (70, 130, 200)


@dataclass(frozen=True)
class Camera:
    """Where the picture is taken from.

    Attributes:
        azimuth: Direction of the eye seen from the target, about base z from +x [deg].
        elevation: Height of the eye above the target's horizontal plane [deg], in
            (-90, 90).
        distance: Eye to target [m]; None: fitted to the motion.
        target: ``(3,)`` point looked at, base frame [m]; None: the centre of the motion.
        fov: Vertical field of view [deg], in (0, 180).
    """

    azimuth: float = 35.0
    elevation: float = 25.0
    distance: float | None = None
    target: tuple | None = None
    fov: float = 35.0

    def __post_init__(self):
        values = [self.azimuth, self.elevation, self.fov]
        values += [] if self.distance is None else [self.distance]
        values += [] if self.target is None else list(self.target)
        if not all(np.isfinite(values)):
            raise InputError(f"camera {self}: every value must be finite", name="camera")
        if not -90.0 < self.elevation < 90.0:
            raise InputError(f"camera elevation {self.elevation:g} deg must lie in (-90, 90)",
                             name="camera")
        if self.distance is not None and self.distance <= 0.0:
            raise InputError(f"camera distance {self.distance:g} m must be > 0",
                             name="camera")
        if not 0.0 < self.fov < 180.0:
            raise InputError(f"camera fov {self.fov:g} deg must lie in (0, 180)",
                             name="camera")
        if self.target is not None and len(self.target) != 3:
            raise InputError(f"camera target {self.target} needs 3 values [m]",
                             name="camera")


def parse_camera(text: str | None) -> Camera:
    """``"AZ,EL[,DIST]"`` [deg, deg, m] (``--camera``) as a :class:`Camera`.

    Raises:
        InputError: not 2 or 3 numbers, or a value out of its domain.
    """
    if text is None:
        return Camera()
    try:
        values = [float(x) for x in text.split(",")]
    except ValueError:
        values = []
    if len(values) not in (2, 3):
        raise InputError(f"--camera {text}: give AZIMUTH,ELEVATION[,DISTANCE] in degrees "
                         "and metres, e.g. 35,25 or 35,25,3", name="--camera")
    return Camera(values[0], values[1], values[2] if len(values) == 3 else None)


# ------------------------------------------------------------------ tessellation
def _box(size):
    a, b, c = np.asarray(size) / 2.0
    V = np.array([[x, y, z] for x in (-a, a) for y in (-b, b) for z in (-c, c)])
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4),
             (1, 5, 7, 3)]
    normals = [(-1, 0, 0), (1, 0, 0), (0, -1, 0), (0, 1, 0), (0, 0, -1), (0, 0, 1)]
    return V, faces, np.array(normals, dtype=float)


def _cylinder(radius, length, n=CYLINDER_SEGMENTS):
    ang = 2.0 * np.pi * np.arange(n) / n
    ring = np.column_stack([radius * np.cos(ang), radius * np.sin(ang)])
    h = length / 2.0
    V = np.vstack([np.column_stack([ring, np.full(n, -h)]),
                   np.column_stack([ring, np.full(n, h)]), [[0, 0, -h], [0, 0, h]]])
    faces, normals = [], []
    mid = ang + np.pi / n
    for k in range(n):
        j = (k + 1) % n
        faces.append((k, j, n + j, n + k))
        normals.append((np.cos(mid[k]), np.sin(mid[k]), 0.0))
    if radius > CAP_SECTOR_RADIUS:                   # sectors: depth sort by sector
        for k in range(n):
            j = (k + 1) % n
            faces += [(2 * n, j, k), (2 * n + 1, n + k, n + j)]
            normals += [(0, 0, -1), (0, 0, 1)]
    else:
        faces += [tuple(range(n - 1, -1, -1)), tuple(range(n, 2 * n))]
        normals += [(0, 0, -1), (0, 0, 1)]
    return V, faces, np.array(normals, dtype=float)


def _sphere(radius, bands=SPHERE_BANDS):
    nlat, nlon = bands
    lat = np.linspace(-np.pi / 2, np.pi / 2, nlat + 1)
    lon = 2.0 * np.pi * np.arange(nlon) / nlon
    V = np.array([[radius * np.cos(a) * np.cos(b), radius * np.cos(a) * np.sin(b),
                   radius * np.sin(a)] for a in lat for b in lon])
    faces, normals = [], []
    for i in range(nlat):
        for k in range(nlon):
            j = (k + 1) % nlon
            quad = (i * nlon + k, i * nlon + j, (i + 1) * nlon + j, (i + 1) * nlon + k)
            c = V[list(quad)].mean(axis=0)
            faces.append(quad)
            normals.append(c / np.linalg.norm(c))
    return V, faces, np.array(normals)


@dataclass
class Geometry:
    """The robot's faces in their link frames (built once per robot).

    Attributes:
        links: Link names, in the order of :class:`~offshore_crane.outputs.visual.poses.Poses`.
        V: ``(nv, 3)`` vertices in their link's frame [m]; ``vlink (nv,)`` their link.
        faces: Vertex indices of each face (a tuple each, 3 or more).
        flink: ``(nf,)`` link of each face; ``normal (nf, 3)``, ``centroid (nf, 3)`` in
            the link frame.
        rgb: ``(nf, 3)`` base colour 0..1.
        cable: ``(arm_tip column, payload column)`` when the URDF hangs the payload on a
            cable, else None.
    """

    links: tuple
    V: np.ndarray
    vlink: np.ndarray
    faces: list
    flink: np.ndarray
    normal: np.ndarray
    centroid: np.ndarray
    rgb: np.ndarray
    cable: tuple | None

    def faces_of(self, links) -> np.ndarray:
        """Boolean mask ``(nf,)`` of the faces that belong to ``links`` (names)."""
        cols = [self.links.index(name) for name in links if name in self.links]
        return np.isin(self.flink, cols)


#: Links whose visuals are not drawn for a cable of varying length: its rod.
VARYING_HIDDEN = ("cable_link2",)
#: A slack cable's dashes and gaps [pixels at supersample 1].
DASH = (6, 5)
#: Side of the square drawn for a lift's deck [m] (drawing only: a plate under the load).
DECK_SIDE = 0.2
DECK_RGB = (70, 110, 120)


def deck_square() -> np.ndarray:
    """``(4, 3)`` the corners of a lift's deck plate around its centre [m]: a horizontal
    square of :data:`DECK_SIDE`, counter-clockwise seen from above."""
    h = DECK_SIDE / 2.0
    return np.array([[-h, -h, 0.0], [h, -h, 0.0], [h, h, 0.0], [-h, h, 0.0]])


def geometry(robot, links: tuple, hidden: tuple = ()) -> Geometry:
    """Tessellate the robot's visuals (see the module docstring), but those of the
    links ``hidden``."""
    from offshore_crane.outputs.visual.poses import has_cable

    desc = robot.description
    Vs, vlinks, faces, flinks, normals, centroids, rgbs = [], [], [], [], [], [], []
    nv = 0
    for col, link in enumerate(links):
        shapes = [] if link in hidden else list(desc.visuals.get(link, []))
        items = []
        for v in shapes:
            if v.shape == "box":
                V, F, N = _box(v.size)
            elif v.shape == "cylinder":
                V, F, N = _cylinder(v.size[0], v.size[2])
            else:
                V, F, N = _sphere(v.size[0])
            rgb = DEFAULT_RGB if v.rgba is None else tuple(v.rgba[:3])
            items.append((V @ v.R.T + v.xyz, F, N @ v.R.T, rgb))
        inertial = desc.inertials.get(link)
        if not shapes and inertial is not None and inertial.mass > 0.0:
            r = (3.0 * inertial.mass / (4.0 * np.pi * PAYLOAD_DENSITY)) ** (1.0 / 3.0)
            V, F, N = _sphere(r)
            items.append((V, F, N, PAYLOAD_RGB))
        for V, F, N, rgb in items:
            Vs.append(V)
            vlinks.append(np.full(len(V), col))
            for f, n in zip(F, N):
                faces.append(tuple(nv + i for i in f))
                centroids.append(V[list(f)].mean(axis=0))
            flinks.append(np.full(len(F), col))
            normals.append(N)
            rgbs.append(np.tile(rgb, (len(F), 1)))
            nv += len(V)
    cable = None
    if has_cable(desc) and "arm_tip" in links and "payload" in links:
        cable = (links.index("arm_tip"), links.index("payload"))
    return Geometry(links, np.vstack(Vs), np.concatenate(vlinks), faces,
                    np.concatenate(flinks), np.vstack(normals), np.array(centroids),
                    np.vstack(rgbs), cable)


# ------------------------------------------------------------------ camera
def _look_at(eye: np.ndarray, target: np.ndarray) -> np.ndarray:
    """``R_camera_base``: rows = camera x (right), y (down), z (forward) in base axes."""
    forward = target - eye
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    down = np.cross(forward, right)
    return np.array([right, down, forward])


def fit_camera(camera: Camera, points: np.ndarray, aspect: float, fill: float = 0.9) -> tuple:
    """Eye position and target [m] for ``camera`` so that ``points`` ``(M, 3)`` (base
    frame) fill the fraction ``fill`` of the picture's width (``aspect`` = width / height)
    or height, centred; a given target or distance is kept as given."""
    az, el = np.radians(camera.azimuth), np.radians(camera.elevation)
    back = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
    lo, hi = points.min(axis=0), points.max(axis=0)
    target = (lo + hi) / 2.0 if camera.target is None else np.asarray(camera.target, float)
    R = _look_at(target + back, target)                    # rows: right, down, forward
    distance = camera.distance
    ty = np.tan(np.radians(camera.fov) / 2.0) * fill
    tx = ty * aspect
    for _ in range(4 if camera.target is None else 1):
        c = (points - target) @ R.T
        if camera.distance is None:
            # |x| <= tx (d + z) and |y| <= ty (d + z) for every point (z along forward)
            distance = float(np.max(np.maximum(np.abs(c[:, 0]) / tx,
                                               np.abs(c[:, 1]) / ty) - c[:, 2]))
            distance = max(distance, float(np.max(-c[:, 2])) + 1e-3)
        if camera.target is None:                # centre the perspective picture
            u = c[:, :2] / (distance + c[:, 2:3])
            mid = (u.min(axis=0) + u.max(axis=0)) / 2.0
            target = target + distance * (R[0] * mid[0] + R[1] * mid[1])
    return target + distance * back, target


def floor_square(geo, poses) -> tuple[float, float] | None:
    """``(height, half side)`` [m] of the floor square under the base (base frame): at
    the base's lowest vertex, GROUND_EXTENT times its largest radius; None for a robot
    drawn without a base."""
    base = geo.vlink == 0
    if not base.any():
        return None
    V = geo.V[base] @ poses.R[0, 0].T + poses.p[0, 0]          # the base is fixed
    r = GROUND_EXTENT * float(np.linalg.norm(V[:, :2], axis=1).max())
    return (float(V[:, 2].min()), r) if r > 0 else None


class Renderer:
    """Draws the robot at the samples of a :class:`~offshore_crane.outputs.visual.poses.Poses`.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        poses: The motion's link poses (the camera is fitted to all its samples).
        width, height: Picture size [pixels], each 16..8192.
        camera: :class:`Camera` (default: azimuth 35°, elevation 25°, fitted).
        supersample: Draw at this multiple of the size and reduce (anti-aliasing; 1 is
            fastest, 2 for stills).
        water: Height of the still water line in the base frame [m] (model scale, a
            scene with a sea: :func:`offshore_crane.scenes.still_water_level`), or None.
        slack: ``(N,)`` bool per sample of a cable of varying length: True draws the
            cable dashed (slack); None: a rigid cable of the URDF's length (its rod
            drawn), or no cable.
        deck: ``(N, 3)`` the centre of a deck the load is lifted from or set onto
            (``[lift]``), or of a ship-to-ship target (the load's moving aim), base frame
            [m], drawn as a square plate of :data:`DECK_SIDE`; or None.

    Raises:
        InputError: a size out of range, a bad camera or supersample.
        BackendMissingError: Pillow is not installed.
    """

    def __init__(self, robot, poses, width: int = 640, height: int = 480,
                 camera: Camera | None = None, supersample: int = 1,
                 water: float | None = None, slack=None, deck=None):
        from offshore_crane.errors import require

        self._pil = require("PIL.Image", "pillow", "Drawing the robot")
        self._draw = require("PIL.ImageDraw", "pillow", "Drawing the robot")
        for name, value in (("width", width), ("height", height)):
            if not isinstance(value, (int, np.integer)) or not 16 <= value <= 8192:
                raise InputError(f"{name} = {value!r} pixels: give an integer in 16..8192",
                                 name=name)
        if supersample not in (1, 2, 3, 4):
            raise InputError(f"supersample = {supersample!r}: give 1, 2, 3 or 4",
                             name="supersample")
        self.width, self.height, self.ss = int(width), int(height), int(supersample)
        self.camera = camera or Camera()
        # a cable of varying length is the line alone (the URDF's rod has one length)
        self.geo = geometry(robot, poses.links, () if slack is None else VARYING_HIDDEN)
        self.poses = poses
        self.slack = None if slack is None else np.asarray(slack, dtype=bool)
        self.deck = None if deck is None else np.asarray(deck, dtype=float)
        g = self.geo
        # every vertex of the whole motion, on a sub-sample of at most 200 frames
        step = max(1, len(poses) // 200)
        Rs, ps = poses.R[::step][:, g.vlink], poses.p[::step][:, g.vlink]
        pts = np.einsum("nvij,vj->nvi", Rs, g.V) + ps
        eye, target = fit_camera(self.camera, pts.reshape(-1, 3), self.width / self.height)
        self.eye, self.target = eye, target
        self.R_cam = _look_at(eye, target)
        W, H = self.width * self.ss, self.height * self.ss
        self.focal = (H / 2.0) / np.tan(np.radians(self.camera.fov) / 2.0)
        self.centre = np.array([W / 2.0, H / 2.0])
        self.light = -self.R_cam[2] + 0.6 * self.R_cam[0] - 0.8 * self.R_cam[1]
        self.light /= np.linalg.norm(self.light)
        self.root = g.flink == 0
        self._faces = [list(f) for f in g.faces]
        self._background = self._gradient(W, H)
        self._floor(water)

    def _floor(self, water: float | None) -> None:
        """Paint the references into the (static) background: the floor, a square at the
        base's lowest point, GROUND_EXTENT times its radius, with a grid (skipped where
        the camera is below it: it would hide the robot); and, given ``water`` [m] (base
        frame), the still water line: the same square's outline at that height."""
        found = floor_square(self.geo, self.poses)
        if found is None:
            return
        z, r = found
        draw = self._draw.Draw(self._background)
        width = max(1, self.ss)

        def square(height):
            xy, depth = self.project(np.array([[-r, -r, height], [r, -r, height],
                                               [r, r, height], [-r, r, height]]))
            return None if (depth <= 1e-6).any() else [tuple(p) for p in xy.tolist()]

        floor = square(z) if self.eye[2] > z else None
        if floor is not None:
            draw.polygon(floor, fill=GROUND_RGB)
            for u in np.linspace(-r, r, 9):
                for a, b in (([u, -r, z], [u, r, z]), ([-r, u, z], [r, u, z])):
                    lxy, _ = self.project(np.array([a, b]))
                    draw.line([tuple(p) for p in lxy.tolist()], fill=GROUND_LINE_RGB,
                              width=width)
        surface = None if water is None or not np.isfinite(water) else square(water)
        if surface is not None:
            draw.line(surface + surface[:1], fill=WATER_RGB, width=2 * width)

    def _gradient(self, W: int, H: int):
        top, bottom = np.array(BACKGROUND_TOP, float), np.array(BACKGROUND_BOTTOM, float)
        s = np.linspace(0.0, 1.0, H)[:, None]
        rows = (top * (1 - s) + bottom * s).astype(np.uint8)
        return self._pil.fromarray(np.ascontiguousarray(
            np.broadcast_to(rows[:, None, :], (H, W, 3))))

    def project(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Pixel coordinates ``(M, 2)`` and depth ``(M,)`` [m] of base-frame points
        ``(M, 3)`` (in the supersampled picture)."""
        c = (points - self.eye) @ self.R_cam.T
        z = c[:, 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            xy = self.focal * c[:, :2] / z[:, None] + self.centre
        return xy, z

    def _plate(self, draw, centre: np.ndarray) -> None:
        """The deck: a horizontal square of :data:`DECK_SIDE` at ``centre`` (base frame)."""
        xy, depth = self.project(centre + deck_square())
        if (depth > 1e-6).all():
            draw.polygon([tuple(p) for p in xy.tolist()], fill=DECK_RGB)

    def _cable(self, draw, xy: list, dashed: bool) -> None:
        """The cable from the tip to the payload: a line, dashed (:data:`DASH`) when
        slack."""
        fill, width = tuple(int(255 * x) for x in CABLE_RGB), max(1, 2 * self.ss)
        if not dashed:
            draw.line(xy, fill=fill, width=width)
            return
        a, b = np.array(xy[:2], dtype=float), np.array(xy[2:], dtype=float)
        length = float(np.linalg.norm(b - a))
        on, off = DASH[0] * self.ss, DASH[1] * self.ss
        for s0 in np.arange(0.0, length, on + off):
            s1 = min(s0 + on, length)
            p0, p1 = a + (b - a) * (s0 / length), a + (b - a) * (s1 / length)
            draw.line([tuple(p0), tuple(p1)], fill=fill, width=width)

    def frame(self, k: int, face_rgb: np.ndarray | None = None, text: str | None = None,
              overlay=None):
        """The picture of sample ``k`` (a ``PIL.Image`` in RGB).

        Args:
            k: Sample index into the poses.
            face_rgb: ``(nf, 3)`` colours 0..1 replacing the URDF's (e.g. legs coloured
                by force), or None.
            text: Drawn top left (e.g. the time stamp).
            overlay: ``overlay(draw, renderer, k)`` draws more on top (labels), in the
                supersampled picture's pixels.
        """
        g, P = self.geo, self.poses
        R, p = P.R[k], P.p[k]
        Vw = np.einsum("vij,vj->vi", R[g.vlink], g.V) + p[g.vlink]
        xy, z = self.project(Vw)
        Rf = R[g.flink]
        n = np.einsum("fij,fj->fi", Rf, g.normal)
        c = np.einsum("fij,fj->fi", Rf, g.centroid) + p[g.flink]
        facing = np.einsum("fi,fi->f", n, self.eye - c) > 0.0
        depth = (c - self.eye) @ self.R_cam[2]
        visible = facing & (depth > 1e-6)
        rgb = g.rgb if face_rgb is None else face_rgb
        shade = AMBIENT + DIFFUSE * np.clip(n @ self.light, 0.0, None)
        colour = np.clip(rgb * shade[:, None] * 255.0, 0, 255).astype(np.uint8)
        key = np.where(self.root, np.inf, depth)              # the floor first
        order = np.flatnonzero(visible)
        order = order[np.argsort(-key[order], kind="stable")]
        image = self._background.copy()
        draw = self._draw.Draw(image)
        pts = xy.tolist()
        cols = [tuple(x) for x in colour.tolist()]
        faces = self._faces
        cable = None
        if g.cable is not None:
            a, b = p[g.cable[0]], p[g.cable[1]]
            (cxy, cz) = self.project(np.array([a, b]))
            cable = (float(cz.mean()), cxy.ravel().tolist())
        dashed = self.slack is not None and bool(self.slack[k])
        if self.deck is not None:
            self._plate(draw, self.deck[k])
        for f in order.tolist():
            if cable is not None and depth[f] < cable[0]:
                self._cable(draw, cable[1], dashed)
                cable = None
            draw.polygon([pts[i] for i in faces[f]], fill=cols[f])
        if cable is not None:
            self._cable(draw, cable[1], dashed)
        if overlay is not None:
            overlay(draw, self, k)
        if text:
            draw.text((8 * self.ss, 6 * self.ss), text, fill=(20, 20, 25),
                      font=self.font(14))
        if self.ss > 1:
            image = image.resize((self.width, self.height), self._pil.Resampling.LANCZOS)
        return image

    def font(self, size: int):
        """Pillow's bundled font at ``size`` points of the final picture."""
        from PIL import ImageFont

        return ImageFont.load_default(size=size * self.ss)
