"""Benchmark of ``offshore-crane animate``: a 60 s run at 30 fps (1,800 frames), 640 x 480,
MP4 — the issue's target is <= 30 s on the project's 2-core machine.

Times the whole library call (:func:`offshore_crane.outputs.visual.animate.animate`: forces by
inverse dynamics for ``--color-by force``, link poses, drawing, H.264 encoding by ffmpeg
in its own process, atomic write) on the example sea-state scene, with and without the
legs coloured by force, and splits one run into its stages; then writes the GIFs the
documents describe (:data:`GIFS`: the README's picture, the whole run at 10 and 30 fps)
once each, for their time and size. The machine's other load is
read from ``/proc/stat`` (every process's CPU time minus this process's and its
children's), since the load average would count the benchmark itself.

    PYTHONPATH=src python benchmarks/animate.py [--repeat 3] [--out DIR] [--save]

``--save`` writes the figures to ``benchmarks/results/animate.json``, from which
``python scripts/figures.py`` regenerates the tables of README.md and docs/visual.md.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

import numpy as np  # noqa: E402

from _saved import add_save_option, cpu_busy, save  # noqa: E402  (benchmarks/ is on the path)
from offshore_crane import scenes  # noqa: E402
from offshore_crane.outputs.visual import animate as an  # noqa: E402
from offshore_crane.outputs.visual import motion as mo  # noqa: E402

TARGET_S = 30.0
FPS, DURATION, SIZE = 30.0, 60.0, (640, 480)


def mine() -> float:
    """CPU seconds of this process and its finished children (ffmpeg)."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def stages(robot, motion, gravity) -> dict:
    """One run split: forces, poses, drawing alone (no encoding)."""
    from offshore_crane.outputs.visual.poses import link_poses
    from offshore_crane.outputs.visual.render import Renderer

    out = {}
    t0 = time.perf_counter()
    m = mo.forces(robot, motion, gravity)
    out["inverse dynamics (all samples)"] = time.perf_counter() - t0
    times = mo.frame_times(m, FPS, 1.0, DURATION)
    shown = mo.at(m, times)
    t0 = time.perf_counter()
    P = link_poses(robot, shown.q)
    out["link poses (1,800 frames)"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    r = Renderer(robot, P, *SIZE)
    for k in range(len(P)):
        r.frame(k, text="t").tobytes()
    out["drawing (1,800 frames, no encoding)"] = time.perf_counter() - t0
    return out


#: The GIFs the documents describe: name -> (seconds of motion, fps, (width, height)),
#: legs coloured by force. "caption": the README caption's command, which made
#: docs/sea_state_crane.gif; the others: the whole run at the MP4's size.
GIFS = {"caption": (20.0, 10.0, (480, 360)), "60 s at 10 fps": (60.0, 10.0, SIZE),
        "60 s at 30 fps": (60.0, 30.0, SIZE)}


def gifs(robot, motion, gravity, directory, keep: bool) -> dict:
    """Each GIF of :data:`GIFS` written once: ``{name: {"s": wall, "mb": size}}``."""
    out = {}
    for name, (duration, fps, (w, h)) in GIFS.items():
        target = os.path.join(directory, f"bench_{name.replace(' ', '_')}.gif")
        t0 = time.perf_counter()
        an.animate(robot, motion, target, fps=fps, duration=duration, color_by="force",
                   gravity=gravity, width=w, height=h)
        out[name] = {"s": time.perf_counter() - t0, "mb": os.path.getsize(target) / 1e6}
        if not keep:
            os.remove(target)
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--out", help="keep the MP4s in this directory")
    add_save_option(parser, "animate")
    args = parser.parse_args()
    saved: dict = {"date": time.strftime("%Y-%m-%d"), "runs": args.repeat}
    scene = scenes.load_scene(ROOT / "scenes" / "sea_state_crane.toml")
    robot = scenes.load_robot(scene)
    motion = mo.from_trajectory(scenes.load_trajectory(scene, robot))
    mo.forces(robot, motion, scene.gravity)             # compile / load the kernels first
    directory = args.out or tempfile.mkdtemp(prefix="oc-bench-")
    print(f"scene {scene.name}: {motion.t[-1] - motion.t[0]:g} s record, "
          f"{len(motion.t)} samples; {FPS:g} fps x {DURATION:g} s = "
          f"{int(FPS * DURATION)} frames {SIZE[0]} x {SIZE[1]}, MP4 (H.264)")
    for color_by in (None, "force"):
        walls, others = [], []
        for k in range(args.repeat):
            target = os.path.join(directory, f"bench_{color_by or 'plain'}_{k}.mp4")
            w0, m0, a0 = time.perf_counter(), mine(), cpu_busy()
            done = an.animate(robot, motion, target, fps=FPS, duration=DURATION,
                              color_by=color_by, gravity=scene.gravity, width=SIZE[0],
                              height=SIZE[1])
            wall = time.perf_counter() - w0
            others.append(max(0.0, ((cpu_busy() - a0) - (mine() - m0)) / wall))
            walls.append(wall)
            size = os.path.getsize(target)
            if not args.out:
                os.remove(target)
        saved[color_by or "plain"] = {"median_s": statistics.median(walls),
                                       "min_s": min(walls), "max_s": max(walls),
                                       "mb": size / 1e6, "others_core": float(np.mean(others)),
                                       "frames": done.frames}
        print(f"--color-by {color_by or '(none)':<6}: {done.frames} frames in "
              f"median {statistics.median(walls):.1f} s (min {min(walls):.1f}, max "
              f"{max(walls):.1f}; {args.repeat} runs), {size / 1e6:.1f} MB; "
              f"{'MET' if max(walls) <= TARGET_S else 'NOT MET'} (target {TARGET_S:g} s); "
              f"other processes used {np.mean(others):.2f} core meanwhile")
    saved["gifs"] = gifs(robot, motion, scene.gravity, directory, keep=bool(args.out))
    for name, g in saved["gifs"].items():
        print(f"  GIF {name}: {g['s']:.1f} s, {g['mb']:.1f} MB")
    saved["stages"] = stages(robot, motion, scene.gravity)
    for name, seconds in saved["stages"].items():
        print(f"  {name}: {seconds:.2f} s")
    if args.save:
        save("animate", saved)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
