"""A 3-D view of a motion in the browser (viser), with play / pause and a time slider.

The robot is the renderer's tessellation of the URDF's shapes
(:func:`offshore_crane.outputs.visual.render.geometry`), one mesh per link under a scene frame
that :class:`Viewer` moves to the link's pose; the poses of every frame are computed once
(:mod:`offshore_crane.outputs.visual.poses`). The server listens on 127.0.0.1 by default (this
machine only); a port already in use is an error, not a silent move to the next port.
"""

from __future__ import annotations

import socket
import threading
import time

import numpy as np

from offshore_crane.errors import InputError, ViewerError

#: Rate [1/s] at which the motion is sampled for the viewer (motion time).
VIEW_RATE = 30.0


def quaternions(R: np.ndarray) -> np.ndarray:
    """``(..., 3, 3)`` rotation matrices to unit quaternions ``(..., 4)`` (w, x, y, z),
    w >= 0 (Shepperd's method: the largest of the four candidates, stable everywhere)."""
    R = np.asarray(R, dtype=float)
    tr = R[..., 0, 0] + R[..., 1, 1] + R[..., 2, 2]
    cand = np.stack([tr, R[..., 0, 0], R[..., 1, 1], R[..., 2, 2]], axis=-1)
    k = np.argmax(cand, axis=-1)
    q = np.empty(R.shape[:-2] + (4,))
    s = np.sqrt(np.maximum(1.0 + 2.0 * np.take_along_axis(cand, k[..., None], -1)[..., 0]
                           - tr, 0.0)) * 2.0                 # 4 * the largest component
    m = k == 0
    q[m] = np.stack([s[m] / 4, (R[m, 2, 1] - R[m, 1, 2]) / s[m],
                     (R[m, 0, 2] - R[m, 2, 0]) / s[m], (R[m, 1, 0] - R[m, 0, 1]) / s[m]], -1)
    m = k == 1
    q[m] = np.stack([(R[m, 2, 1] - R[m, 1, 2]) / s[m], s[m] / 4,
                     (R[m, 0, 1] + R[m, 1, 0]) / s[m], (R[m, 0, 2] + R[m, 2, 0]) / s[m]], -1)
    m = k == 2
    q[m] = np.stack([(R[m, 0, 2] - R[m, 2, 0]) / s[m], (R[m, 0, 1] + R[m, 1, 0]) / s[m],
                     s[m] / 4, (R[m, 1, 2] + R[m, 2, 1]) / s[m]], -1)
    m = k == 3
    q[m] = np.stack([(R[m, 1, 0] - R[m, 0, 1]) / s[m], (R[m, 0, 2] + R[m, 2, 0]) / s[m],
                     (R[m, 1, 2] + R[m, 2, 1]) / s[m], s[m] / 4], -1)
    return np.where(q[..., :1] < 0, -q, q)


def check_port(host: str, port: int) -> None:
    """Raise :class:`ViewerError` when ``port`` cannot be bound on ``host``."""
    if not isinstance(port, int) or not 0 <= port <= 65535:
        raise ViewerError(f"--port {port!r}: give a port number in 0..65535 (0: any free "
                          "port)", host=host, port=port)
    import errno

    try:
        socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)
    except (socket.gaierror, UnicodeError) as exc:
        raise ViewerError(f"--host {host}: not an address ({getattr(exc, 'strerror', exc)}): "
                          "give an address of this machine (127.0.0.1 for this machine "
                          "only, 0.0.0.0 for every interface)", host=host, port=port) from None
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    with socket.socket(family, socket.SOCK_STREAM) as s:
        try:
            s.bind((host, port))
        except OSError as exc:
            why = {errno.EADDRINUSE: "another program uses it; choose another port with "
                                     "--port",
                   errno.EADDRNOTAVAIL: f"{host} is not an address of this machine; give "
                                        "one of its addresses with --host (127.0.0.1, "
                                        "0.0.0.0)",
                   errno.EACCES: "a port below 1024 needs privileges; choose a port from "
                                 "1024 with --port"}.get(exc.errno, "check --host and --port")
            raise ViewerError(f"--port {port}: cannot listen on {host}:{port} "
                              f"({exc.strerror}): {why}", host=host, port=port) from None


#: The cable's colour, taut and slack (a varying cable: the line drawn paler while slack).
CABLE_RGB, SLACK_RGB = (25, 25, 25), (170, 170, 170)


class Viewer:
    """A viser server showing a motion.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        shown: :class:`~offshore_crane.outputs.visual.motion.Motion` at the frames' times
            (``t (F,)``, ``q (F, 9)``, ``sway`` with a cable).
        host: Address to listen on (default this machine only).
        port: TCP port (0: any free port; read :attr:`port`).
        speed: Motion seconds per second of playback.
        play: Start playing.

    Attributes:
        server: The ``viser.ViserServer``.
        port: The port it listens on.
        url: ``http://host:port/``.
        slider, playing: The GUI handles (time [s], play checkbox).

    Raises:
        ViewerError: the port is in use or out of range.
        BackendMissingError: viser is not installed (install hint).
    """

    def __init__(self, robot, shown, host: str = "127.0.0.1", port: int = 8080,
                 speed: float = 1.0, play: bool = True, title: str = "offshore-crane",
                 color_by: str | None = None):
        from offshore_crane.errors import require
        from offshore_crane.outputs.visual.poses import link_poses
        from offshore_crane.outputs.visual.colours import LEG_OF_LINK
        from offshore_crane.outputs.visual.render import VARYING_HIDDEN, geometry

        viser = require("viser", "offshore-crane[view]", "The browser viewer")
        check_port(host, port)
        self.t = np.asarray(shown.t, dtype=float)
        P = link_poses(robot, shown.q, shown.sway, shown.load)
        self.poses = P
        self.wxyz = quaternions(P.R)                           # (F, L, 4)
        geo = geometry(robot, P.links, () if shown.load is None else VARYING_HIDDEN)
        self.slack = None if shown.slack is None else np.asarray(shown.slack, dtype=bool)
        server = viser.ViserServer(host=host, port=port, label=title, verbose=False)
        self.server = server
        self.port = server.get_port()
        if port != 0 and self.port != port:                    # lost a race for the port
            server.stop()
            raise ViewerError(f"--port {port}: cannot listen on {host}:{port}: another "
                              "program took it; choose another port with --port",
                              host=host, port=port)
        self.url = f"http://{host if ':' not in host else '[' + host + ']'}:{self.port}/"
        server.scene.set_up_direction("+z")
        # the renderer's default view, fitted to the whole motion
        from offshore_crane.outputs.visual.render import Camera, fit_camera

        step = max(1, len(P) // 100)
        pts = (np.einsum("nvij,vj->nvi", P.R[::step][:, geo.vlink], geo.V)
               + P.p[::step][:, geo.vlink]).reshape(-1, 3)
        eye, target = fit_camera(Camera(fov=50.0), pts, 4.0 / 3.0, fill=0.85)
        server.initial_camera.position = tuple(eye)
        server.initial_camera.look_at = tuple(target)
        self._references(geo, P, shown.water)
        self.frames = {}
        self.legs: dict = {}                    # leg index -> its links' mesh handles
        self.leg_rgb = self._leg_colours(robot, shown, color_by)
        for col, link in enumerate(P.links):
            faces = np.flatnonzero(geo.flink == col)
            if not len(faces):
                continue
            handle = server.scene.add_frame(f"/robot/{link}", show_axes=False)
            self.frames[col] = handle
            # one mesh per colour: fan triangles of the link's faces, link-frame vertices
            for c, rgb in enumerate(np.unique(geo.rgb[faces], axis=0)):
                same = [f for f in faces if np.array_equal(geo.rgb[f], rgb)]
                tris = [(fc[0], fc[i], fc[i + 1]) for f in same
                        for fc in [geo.faces[f]] for i in range(1, len(fc) - 1)]
                used = np.unique(np.array(tris).ravel())
                remap = {v: i for i, v in enumerate(used)}
                mesh = server.scene.add_mesh_simple(
                    f"/robot/{link}/mesh{c}", geo.V[used].astype(np.float32),
                    np.array([[remap[v] for v in tri] for tri in tris], dtype=np.uint32),
                    color=tuple(int(255 * x) for x in rgb), flat_shading=True)
                leg = LEG_OF_LINK.get(link)
                if leg is not None:
                    self.legs.setdefault(leg, []).append(mesh)
        self.cable = None
        if geo.cable is not None:
            self.cable = (geo.cable, None)
        self.deck = None
        if shown.deck is not None:                       # a lift's deck: a plate
            self.deck = (np.asarray(shown.deck, dtype=float), self._plate())
        with server.gui.add_folder("motion"):
            self.playing = server.gui.add_checkbox("play", initial_value=play)
            self.slider = server.gui.add_slider(
                "time [s]", min=float(self.t[0]), max=float(max(self.t[-1], self.t[0] + 1e-9)),
                step=float(np.min(np.diff(self.t))) if len(self.t) > 1 else 1.0,
                initial_value=float(self.t[0]))
            self.speed = server.gui.add_number("speed", initial_value=float(speed),
                                               min=0.01, max=100.0, step=0.01)
        self.slider.on_update(lambda _: self.show(self.slider.value))
        self.show(float(self.t[0]))
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._play, daemon=True, name="viewer-play")
        self._thread.start()

    def _plate(self):
        """The lift's deck: a square of ``render.DECK_SIDE`` under a frame that
        :meth:`show` moves."""
        from offshore_crane.outputs.visual.render import DECK_RGB, deck_square

        frame = self.server.scene.add_frame("/deck", show_axes=False)
        self.server.scene.add_mesh_simple("/deck/plate", deck_square().astype(np.float32),
                                          np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32),
                                          color=DECK_RGB, side="double")
        return frame

    def _references(self, geo, P, water) -> None:
        """The floor under the base and, with a sea, the still water line (model
        scale), as the pictures draw them: ``self.references`` holds their handles by
        name."""
        from offshore_crane.outputs.visual.render import (GROUND_LINE_RGB, WATER_RGB,
                                                          floor_square)

        self.references: dict = {}
        found = floor_square(geo, P)
        if found is None:
            return
        z, r = found
        add = self.server.scene.add_grid
        self.references["floor"] = add(
            "/floor", 2 * r, 2 * r, cell_size=r / 4, section_size=r,
            cell_color=GROUND_LINE_RGB, position=(0.0, 0.0, z))
        if water is not None and np.isfinite(water):
            self.references["still_water"] = add(
                "/still_water", 2 * r, 2 * r, cell_size=r, section_size=2 * r,
                cell_color=WATER_RGB, section_color=WATER_RGB, plane_color=WATER_RGB,
                plane_opacity=0.15, shadow_opacity=0.0, position=(0.0, 0.0, float(water)))

    @staticmethod
    def _leg_colours(robot, shown, color_by):
        """``(F, 6, 3)`` leg colours 0..255 per frame (animate's scale), or None."""
        if color_by is None:
            return None
        from offshore_crane.outputs.visual import motion as mo
        from offshore_crane.outputs.visual.colours import colour_scale

        if shown.X is None:
            raise InputError("--color-by needs the actuator forces", name="--color-by")
        values, _ = mo.leg_values(robot, shown.X, color_by)
        cmap = colour_scale(color_by)[0]
        return np.clip(np.round(cmap(values) * 255.0), 0, 255).astype(np.uint8)

    def index(self, time_s: float) -> int:
        """The frame shown at motion time ``time_s`` [s] (the last one at or before it)."""
        return int(np.clip(np.searchsorted(self.t, time_s + 1e-9, side="right") - 1, 0,
                           len(self.t) - 1))

    def show(self, time_s: float) -> int:
        """Move every link to its pose at ``time_s`` [s]; returns the frame index."""
        k = self.index(time_s)
        p, wxyz = self.poses.p[k], self.wxyz[k]
        with self.server.atomic():
            for col, handle in self.frames.items():
                handle.position = p[col]
                handle.wxyz = wxyz[col]
            if self.leg_rgb is not None:                 # as animate paints them
                for leg, meshes in self.legs.items():
                    colour = tuple(int(v) for v in self.leg_rgb[k, leg])
                    for mesh in meshes:
                        mesh.color = colour
            if self.cable is not None:
                (a, b), line = self.cable
                pts = np.array([[p[a], p[b]]], dtype=np.float32)
                slack = self.slack is not None and bool(self.slack[k])
                colours = np.full((1, 2, 3), SLACK_RGB if slack else CABLE_RGB, np.uint8)
                if line is None:
                    line = self.server.scene.add_line_segments(
                        "/cable", pts, colors=colours, **_thin_line(self.server.scene))
                    self.cable = ((a, b), line)
                else:
                    line.points = pts
                    line.colors = colours
            if self.deck is not None:
                self.deck[1].position = tuple(self.deck[0][k])
        return k

    def _play(self) -> None:
        last = time.perf_counter()
        while not self._stop.wait(1.0 / VIEW_RATE):
            now = time.perf_counter()
            if self.playing.value and len(self.t) > 1:
                t = self.slider.value + (now - last) * float(self.speed.value)
                if t > self.t[-1]:
                    t = float(self.t[0])                       # loop
                self.slider.value = float(t)                    # on_update moves the robot
            last = now

    def close(self) -> None:
        """Stop playback and the server."""
        self._stop.set()
        self._thread.join(timeout=2.0)
        self.server.stop()


def _thin_line(scene) -> dict:
    """A 2-pixel line in viser's words: ``thickness`` in screen units from viser 1.1
    (which deprecates ``line_width``), ``line_width`` before it."""
    import inspect

    params = inspect.signature(scene.add_line_segments).parameters
    if "thickness_units" in params:
        return {"thickness": 2.0, "thickness_units": "screen"}
    return {"line_width": 2.0}
