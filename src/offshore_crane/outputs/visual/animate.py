"""Animations (GIF through Pillow, MP4 through imageio-ffmpeg) and still pictures of the
robot, headless.

:func:`animate` draws a :class:`~offshore_crane.outputs.visual.motion.Motion` frame by frame
with :class:`~offshore_crane.outputs.visual.render.Renderer` (one camera for the whole run) and
streams the frames to the encoder: MP4 frames go to ffmpeg as they are drawn (memory
stays bounded), GIF frames are reduced to one palette for the whole animation
(:func:`gif_palette`: the legs' colour scale held exactly, the rest from frames sampled over
the run) and kept until Pillow writes the file. The output is written atomically through
:mod:`offshore_crane.io`.

GIF stores frame durations in hundredths of a second: at 30 fps a frame lasts 30 ms
(GIF cannot say 33.3 ms), so a GIF plays 10 % fast at 30 fps; 10, 20, 25 and 50 fps are
exact.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from offshore_crane import progress
from offshore_crane.conventions import GRAVITY
from offshore_crane.errors import InputError

#: Output formats by file suffix.
FORMATS = ("gif", "mp4")
#: Frames per second by format when none is given [Hz]: a GIF at 10 (its frames last
#: whole centiseconds: 10 fps is exact; the README's 60 s animation at 640 x 480 is 7.2 MB,
#: 20.9 MB at 30 fps), an MP4 at 30 (4.5 MB for the same 60 s at 30 fps: the format for
#: long or smooth runs; a GIF for a page that shows it without a player).
DEFAULT_FPS = {"gif": 10.0, "mp4": 30.0}
#: GIF frames are kept in memory (one byte a pixel) until written: refuse beyond this.
GIF_MAX_PIXELS = 1_000_000_000
#: The longest frame a GIF can hold [s]: its delay is two bytes of centiseconds.
GIF_LONGEST_FRAME = 65535 / 100.0
#: The lowest frame rate a GIF can play [Hz] (a frame of :data:`GIF_LONGEST_FRAME`).
GIF_MIN_FPS = 1.0 / GIF_LONGEST_FRAME
#: Colours of a GIF's palette: one palette for every frame (GIF's most), so that a colour
#: reads the same in every frame and unchanged pixels stay unchanged between frames.
GIF_COLOURS = 256
#: Steps of the legs' colour scale held exactly in the palette, at each of
#: :data:`GIF_SCALE_SHADES` (the legend's full colour first, then the shades the flat
#: shading gives the legs' faces).
GIF_SCALE_STEPS = 24
GIF_SCALE_SHADES = (1.0, 0.88, 0.74, 0.6, 0.45)
#: Shades of each body colour of the robot held in the palette, between the flat
#: shading's darkest (ambient) and brightest.
GIF_BODY_SHADES = 6
#: Frames sampled, evenly over the run, for the rest of the palette (median cut).
GIF_SAMPLE_FRAMES = 6
#: The still's frames, drawn as axis triads (x red, y green, z blue) with their names.
LABELLED_FRAMES = ("base", "platform", "arm_link1", "arm_link2", "arm_tip", "payload")


def output_format(path) -> str:
    """``"gif"`` or ``"mp4"`` from the file's suffix.

    Raises:
        InputError: any other suffix.
    """
    suffix = Path(str(path)).suffix.lstrip(".").lower()
    if suffix not in FORMATS:
        raise InputError(f"--out {path}: unknown animation type '.{suffix}': give a file "
                         f"name ending in {' or '.join('.' + f for f in FORMATS)}",
                         name="--out")
    return suffix


@dataclass(frozen=True)
class Written:
    """What :func:`animate` wrote.

    Attributes:
        frames: Number of frames.
        fps: Frames per second of the file.
        size: ``(width, height)`` [pixels].
        seconds: Wall time of drawing and encoding [s].
        scale: With ``color_by``: max |Fl| [N] (force) or the largest utilisation.
    """

    frames: int
    fps: float
    size: tuple
    seconds: float
    scale: float | None = None


def _legend(color_by: str, scale: float):
    """An overlay drawing the legs' colour bar, top right."""
    from offshore_crane.outputs.visual.colours import colour_scale

    def draw(d, r, k):
        ss = r.ss
        W = r.width * ss
        w, h = 120 * ss, 10 * ss
        x0, y0 = W - w - 14 * ss, 22 * ss
        cmap, (lo, hi) = colour_scale(color_by)
        rgb = cmap(np.linspace(lo, hi, w)) * 255
        for i, c in enumerate(rgb.astype(int).tolist()):
            d.line([(x0 + i, y0), (x0 + i, y0 + h)], fill=tuple(c))
        font = r.font(11)
        if color_by == "force":
            left, right, title = f"-{scale:.0f} N", f"+{scale:.0f} N", "leg force: pull / push"
        else:
            left, right, title = "0", "100 %", f"leg utilisation (max {scale:.0%})"
        d.text((x0, y0 - 14 * ss), title, fill=(20, 20, 25), font=font)
        d.text((x0, y0 + h + 2 * ss), left, fill=(20, 20, 25), font=font)
        d.text((x0 + w, y0 + h + 2 * ss), right, fill=(20, 20, 25), font=font, anchor="ra")
    return draw


def frames(robot, shown, *, width: int = 640, height: int = 480, camera=None,
           color_by: str | None = None, supersample: int = 1, caption: str = ""):
    """The pictures of a motion already evaluated at the frames' times (:func:`painter`
    over every frame, with progress).

    Returns:
        ``(renderer, iterator of PIL images, scale)``.
    """
    r, picture, scale = painter(robot, shown, width=width, height=height, camera=camera,
                                color_by=color_by, supersample=supersample, caption=caption)
    return r, _every_frame(r, picture), scale


def _every_frame(r, picture):
    """``picture(k)`` for every frame of the renderer's poses, with progress."""
    with progress.bar(len(r.poses), "frame", "animate") as drawn:
        for k in range(len(r.poses)):
            yield picture(k)
            drawn.update()


def painter(robot, shown, *, width: int = 640, height: int = 480, camera=None,
            color_by: str | None = None, supersample: int = 1, caption: str = ""):
    """What draws the motion's frames: ``(renderer, picture(k) -> PIL image, scale)``.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        shown: :class:`~offshore_crane.outputs.visual.motion.Motion` at the frames' times (its
            ``X`` needed with ``color_by``, its ``sway`` with a cable, or its ``load`` and
            ``slack`` with one of varying length).
        color_by: None, ``"force"`` or ``"utilisation"`` (the legs' colour).
        caption: Printed after the time stamp.

    Returns:
        ``(renderer, picture, scale)``: ``scale`` as :attr:`Written.scale`.
    """
    from offshore_crane.outputs.visual import motion as mo
    from offshore_crane.outputs.visual.poses import link_poses
    from offshore_crane.outputs.visual.colours import colour_scale, leg_face_colours
    from offshore_crane.outputs.visual.render import Renderer

    P = link_poses(robot, shown.q, shown.sway, shown.load)
    r = Renderer(robot, P, width, height, camera, supersample, water=shown.water,
                 slack=shown.slack, deck=shown.deck)
    values, scale, overlay = None, None, None
    if color_by is not None:
        if shown.X is None:
            raise InputError("--color-by needs the actuator forces", name="--color-by")
        values, scale = mo.leg_values(robot, shown.X, color_by)
        overlay = _legend(color_by, scale)
    cmap = colour_scale(color_by)[0]

    def picture(k: int):
        rgb = None if values is None else leg_face_colours(r.geo, cmap(values[k]))
        return r.frame(k, rgb, text=f"t = {shown.t[k]:.2f} s{caption}", overlay=overlay)
    return r, picture, scale


def gif_palette(renderer, picture, n_frames: int, color_by: str | None = None):
    """One palette for a whole GIF (a ``PIL.Image`` in mode "P"): the legs' colour scale
    (:data:`GIF_SCALE_STEPS` steps at each of :data:`GIF_SCALE_SHADES`) exactly, when the
    legs are coloured, each body colour of the robot at :data:`GIF_BODY_SHADES` shades, and
    the rest by median cut of :data:`GIF_SAMPLE_FRAMES` frames spread over the run
    (background, text, edges)."""
    from PIL import Image

    from offshore_crane.outputs.visual.colours import colour_scale

    fixed = []
    if color_by is not None:
        cmap, (lo, hi) = colour_scale(color_by)
        ramp = cmap(np.linspace(lo, hi, GIF_SCALE_STEPS))
        for shade in GIF_SCALE_SHADES:
            fixed += [tuple(int(v) for v in c)
                      for c in np.clip(ramp * shade * 255.0, 0, 255).astype(np.uint8)]
    from offshore_crane.outputs.visual.render import AMBIENT, DIFFUSE

    bodies = np.unique(np.round(renderer.geo.rgb, 6), axis=0)
    for shade in np.linspace(AMBIENT, AMBIENT + DIFFUSE, GIF_BODY_SHADES):
        fixed += [tuple(int(v) for v in c)
                  for c in np.clip(bodies * shade * 255.0, 0, 255).astype(np.uint8)]
    fixed = list(dict.fromkeys(fixed))[:GIF_COLOURS - 32]   # leave room for the rest
    picks = np.unique(np.linspace(0, n_frames - 1, min(GIF_SAMPLE_FRAMES, n_frames))
                      .round().astype(int))
    samples = [picture(int(k)) for k in picks]
    w, h = samples[0].size
    mosaic = Image.new("RGB", (w, h * len(samples)))
    for i, im in enumerate(samples):
        mosaic.paste(im, (0, h * i))
    rest = mosaic.quantize(GIF_COLOURS - len(fixed), method=Image.Quantize.MEDIANCUT,
                           dither=Image.Dither.NONE)
    colours = fixed + [tuple(c) for c in
                       np.array(rest.getpalette()[:3 * (GIF_COLOURS - len(fixed))])
                       .reshape(-1, 3).tolist()]
    palette = Image.new("P", (1, 1))
    palette.putpalette([v for c in colours for v in c] + [0] * (768 - 3 * len(colours)))
    return palette


def write_gif(target, images, fps: float, palette=None) -> int:
    """Write the images as a looping GIF (Pillow) on one ``palette`` (:func:`gif_palette`;
    None: the first frame's median cut); returns the number of frames."""
    from offshore_crane.errors import require
    from offshore_crane.io import open_output

    Image = require("PIL.Image", "pillow", "Writing a GIF")
    kept = []
    for im in images:
        if palette is None:
            palette = im.quantize(GIF_COLOURS, method=Image.Quantize.MEDIANCUT,
                                  dither=Image.Dither.NONE)
        kept.append(im.quantize(palette=palette, dither=Image.Dither.NONE))
    duration = max(20, int(round(1000.0 / fps / 10.0)) * 10)    # [ms], whole centiseconds
    with open_output(target, "wb") as fh:
        kept[0].save(fh, format="GIF", save_all=True, append_images=kept[1:],
                     duration=duration, loop=0, disposal=1, optimize=False)
    return len(kept)


def write_mp4(target, images, fps: float, size: tuple) -> int:
    """Stream the images to ffmpeg (H.264, yuv420p); returns the number of frames."""
    from offshore_crane.errors import require
    from offshore_crane.io import output_path

    iio = require("imageio_ffmpeg", "offshore-crane[animate]", "Writing an MP4")
    n = 0
    with output_path(target, ".mp4") as path:
        writer = iio.write_frames(path, size, fps=fps, codec="libx264", quality=7,
                                  pix_fmt_out="yuv420p", macro_block_size=2,
                                  output_params=["-f", "mp4"], ffmpeg_log_level="error")
        writer.send(None)
        try:
            for im in images:
                writer.send(im.tobytes())
                n += 1
        finally:
            writer.close()
    return n


def animate(robot, motion, target, *, fps: float | None = None, speed: float = 1.0,
            duration: float | None = None, color_by: str | None = None,
            gravity=GRAVITY, leg_model: str = "full", width: int = 640,
            height: int = 480, camera=None, fmt: str | None = None,
            cable: dict | None = None) -> Written:
    """Draw ``motion`` into a GIF or MP4 file.

    Args:
        robot: From :func:`offshore_crane.load_robot`.
        motion: :class:`~offshore_crane.outputs.visual.motion.Motion` (a scene's trajectory, a
            run's CSV).
        target: Output path or :class:`offshore_crane.io.Target`; its suffix (``.gif``,
            ``.mp4``) chooses the format unless ``fmt`` is given.
        fps: Frames per second of the file (> 0; default :data:`DEFAULT_FPS` of the
            format).
        speed: Motion seconds per second of the file (> 0).
        duration: Motion time drawn from its start [s] (default: all).
        color_by: None, ``"force"`` or ``"utilisation"``: the legs coloured by their
            actuator force (computed by inverse dynamics when the motion has none).
        gravity: ``(3,)`` [m/s²], for the forces and the hanging load.
        width, height: [pixels]; MP4 needs them even.
        camera: :class:`~offshore_crane.outputs.visual.render.Camera`.
        cable: Options of the hanging load's swing (a scene's ``[cable]``).

    Returns:
        :class:`Written`.

    Raises:
        InputError: unknown suffix, fps or speed <= 0, odd MP4 size, a GIF too large.
        ModelError: a hanging load without the cable model.
        BackendMissingError: Pillow or imageio-ffmpeg missing (with the install hint).
    """
    from offshore_crane.outputs.visual import motion as mo

    fmt = fmt or output_format(getattr(target, "given", target))
    fps = DEFAULT_FPS[fmt] if fps is None else fps
    times = mo.frame_times(motion, fps, speed, duration)
    if fmt == "mp4" and (width % 2 or height % 2):
        raise InputError(f"an MP4 needs an even width and height, got {width} x {height}",
                         name="--size")
    if fmt == "gif" and fps < GIF_MIN_FPS:
        raise InputError(f"--fps {fps:g}: a GIF frame lasts at most {GIF_LONGEST_FRAME:g} s "
                         f"(two bytes of centiseconds), so a GIF needs --fps >= "
                         f"{GIF_MIN_FPS:.4g}: raise --fps or write an MP4", name="--fps")
    if fmt == "gif" and len(times) * width * height > GIF_MAX_PIXELS:
        raise InputError(f"a GIF of {len(times)} frames of {width} x {height} would hold "
                         f"{len(times) * width * height / 1e9:.1f} G pixels in memory: "
                         "write an MP4, or lower --fps, --duration or the size",
                         name="--out")
    start = time.perf_counter()
    motion = mo.hanging_load(robot, motion, gravity, cable)
    if color_by is not None:
        motion = mo.forces(robot, motion, gravity, leg_model)
    shown = mo.at(motion, times)
    r, picture, scale = painter(robot, shown, width=width, height=height, camera=camera,
                                color_by=color_by)
    images = _every_frame(r, picture)
    if fmt == "gif":
        n = write_gif(target, images, fps, gif_palette(r, picture, len(shown.t), color_by))
    else:
        n = write_mp4(target, images, fps, (width, height))
    return Written(n, fps, (width, height), time.perf_counter() - start, scale)


def _labels(names):
    """An overlay drawing the axis triads of the frames ``names`` with their names."""
    def draw(d, r, k):
        P = r.poses
        ss = r.ss
        font = r.font(12)
        size = 0.08 * np.linalg.norm(r.eye - r.target) / 4.0
        drawn = []
        for name in names:
            if name not in P.links:
                continue
            p, R = P.p[k, P.index(name)], P.R[k, P.index(name)]
            if any(np.abs(p - other).max() < 1e-9 for other in drawn):
                continue                            # welded at a frame already named
            drawn.append(p)
            pts = np.vstack([p, p + size * R.T])
            xy, _ = r.project(pts)
            o = tuple(xy[0])
            for a, colour in enumerate(((220, 30, 30), (30, 160, 30), (30, 60, 220))):
                d.line([o, tuple(xy[a + 1])], fill=colour, width=2 * ss)
            d.text((o[0] + 6 * ss, o[1] - 16 * ss), name, fill=(10, 10, 10), font=font,
                   stroke_width=2 * ss, stroke_fill=(255, 255, 255))
        for i in range(1, 7):                      # leg numbers beside each leg's middle
            lo = f"leg{i}_lower"
            if lo not in P.links:
                continue
            mid = (P.p[k, P.index(lo)] + P.p[k, P.index(f"leg{i}_tip")]) / 2.0
            (x, y), = r.project(mid[None])[0]
            d.text((x + 4 * ss, y), f"leg{i}", fill=(10, 10, 10), font=font,
                   stroke_width=2 * ss, stroke_fill=(255, 255, 255))
    return draw


def still(robot, q, target, *, width: int = 800, height: int = 600, camera=None,
          sway=None, labels: bool = True) -> None:
    """A picture of the robot at one pose ``q (9,)`` (PNG, or any type Pillow writes
    from the suffix), with the main frames drawn and named (``labels``).

    Raises:
        InputError: a bad ``q`` or size; the errors of
            :func:`offshore_crane.outputs.visual.poses.link_poses`.
    """
    from offshore_crane.io import open_output
    from offshore_crane.validation import as_samples
    from offshore_crane.outputs.visual.poses import link_poses
    from offshore_crane.outputs.visual.render import Renderer

    q, _ = as_samples("--pose", q)
    if len(q) != 1:
        raise InputError(f"--pose takes one pose of 9 values, got {len(q)}", name="--pose")
    P = link_poses(robot, q, None if sway is None else np.atleast_2d(sway))
    r = Renderer(robot, P, width, height, camera, supersample=2)
    text = "q = (" + ", ".join(f"{x:.3g}" for x in q[0]) + ")"
    image = r.frame(0, text=text, overlay=_labels(LABELLED_FRAMES) if labels else None)
    fmt = Path(str(getattr(target, "given", target))).suffix.lstrip(".").lower()
    with open_output(target, "wb") as fh:
        image.save(fh, format={"jpg": "JPEG", "tif": "TIFF"}.get(fmt, fmt.upper()))
