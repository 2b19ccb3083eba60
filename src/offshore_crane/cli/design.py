"""``offshore-crane design``: search robot description fields for the best designs.

NSGA-II (pymoo) searches the space file's variables (description fields) for the designs
that best meet its objectives under its constraints, each candidate run as sweep cases over
its sea states (local workers or Dask; stored in --out, so a rerun resumes). Writes
DIR/pareto.csv (the front) and, with --plot, its figure; --pick N --out-robot D.toml writes
design N of the front as a robot description. Exit 1 when no design is feasible.
"""

from __future__ import annotations

import os

from offshore_crane.errors import InputError

#: The results store of the candidates' cases, inside --out.
CANDIDATES = "candidates"


def add_parser(sub) -> None:
    from offshore_crane.cli.common import (add_extremes_options, add_parallel_options,
                                           add_robot_options)

    summary = " ".join(line.strip() for line in __doc__.split("\n\n")[1].splitlines())
    p = sub.add_parser("design", help="multi-objective search of the robot's design",
                       description=summary)
    p.add_argument("--scene", metavar="FILE.toml", required=True,
                   help="the scene every candidate runs")
    p.add_argument("--space", metavar="SPACE.toml",
                   help="the variables, objectives, constraints and sea states "
                   "(docs/design.md)")
    p.add_argument("--budget", type=int, default=100, metavar="N",
                   help="the most candidates evaluated (default 100)")
    p.add_argument("--seed", type=int, default=0, metavar="K",
                   help="the optimiser's seed (default 0): the same seed, the same front")
    p.add_argument("--population", type=int, metavar="N",
                   help="candidates per generation (default 20, or 5 per variable)")
    add_parallel_options(p)
    p.add_argument("--out", metavar="DIR",
                   help="write DIR/pareto.csv and store every candidate's cases in "
                   f"DIR/{CANDIDATES} (rerun to resume)")
    p.add_argument("--plot", metavar="DIR", help="draw the front into DIR/front.png")
    p.add_argument("--pick", type=int, metavar="N",
                   help="with --out DIR and --out-robot: write design N of DIR/pareto.csv "
                   "as a robot description (no search)")
    p.add_argument("--out-robot", metavar="D.toml",
                   help="the description file --pick writes")
    add_extremes_options(p, "the verdicts' most probable maximum")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    add_robot_options(p)
    p.set_defaults(run=run)


def run(args) -> int:
    import sys

    from offshore_crane import scenes
    from offshore_crane.cli.common import extremes_scene, robot_scene
    from offshore_crane.cli.common import plot_dir as checked_plot_dir
    from offshore_crane.errors import NoFeasibleDesignError
    from offshore_crane.io import refuse_inside
    from offshore_crane.studies import design

    scene = extremes_scene(args, robot_scene(args, scenes.load_scene(args.scene)))
    if args.pick is not None or args.out_robot is not None:
        return _pick(args, scene)
    if args.space is None:
        raise InputError("design: give --space SPACE.toml (or --pick N with --out DIR and "
                         "--out-robot D.toml)", name="--space")
    space = design.check_space(scene, design.load_space(args.space), args.space)
    if args.budget < 1:
        raise InputError(f"--budget {args.budget}: must be ≥ 1 (the most candidates "
                         "evaluated)", name="--budget")
    store = _out_dir(args.out)
    if args.plot is not None:
        refuse_inside({"--plot": args.plot}, store, f"--out {args.out}'s {CANDIDATES}")
    plot_dir = checked_plot_dir(args.plot)
    progress = not args.no_progress and sys.stderr.isatty()
    made = store is not None and not os.path.isdir(args.out)
    if made:
        os.makedirs(args.out)                   # the checks passed: pareto.csv's home
    try:
        result = design.run(scene, space, args.budget, args.seed, args.workers,
                            args.scheduler, store, progress=progress,
                            population=args.population)
    except NoFeasibleDesignError as exc:
        print(f"offshore-crane: {exc}", file=sys.stderr)
        return 1
    except BaseException:
        if made and not os.listdir(args.out):   # refused before anything was written
            os.rmdir(args.out)
        raise
    s = result.stats
    print(f"offshore-crane design: scene {scene.name} ({args.scene}), space {args.space}: "
          f"{s['evaluated']} candidates in {s['generations']} generations of "
          f"{s['population']} (seed {args.seed}), {s['ran']} cases run, {s['stored']} "
          f"read from {store or 'memory'}, {s['seconds']:.1f} s; "
          f"{sum(c.feasible for c in result.candidates)} feasible; front of "
          f"{len(result.front)}:")
    _print_front(result)
    if args.out is not None:
        print(f"wrote {design.write_front(args.out, result)}")
    if plot_dir is not None:
        from offshore_crane.outputs.design_plots import front_figure

        os.makedirs(plot_dir, exist_ok=True)
        path = os.path.join(plot_dir, "front.png")
        front_figure(path, result, title=f"{scene.name}: {s['evaluated']} candidates, "
                     f"seed {args.seed}")
        print(f"wrote {path}")
    return 0


def _out_dir(out: str | None) -> str | None:
    """``--out DIR``: a directory (made when the run starts) for pareto.csv; its
    candidates' store ``DIR/candidates``, or None."""
    from offshore_crane.errors import OutputError
    from offshore_crane.special_files import what_is

    if out is None:
        return None
    if os.path.exists(out) and not os.path.isdir(out):
        raise OutputError(f"--out {out}: exists and is not a directory ({what_is(out)}): "
                          "give a directory for pareto.csv and the candidates",
                          path=out, reason="not a directory")
    parent = os.path.dirname(os.path.abspath(out))
    if not os.path.isdir(parent):
        raise OutputError(f"--out {out}: directory {os.path.dirname(out) or '.'} does not "
                          "exist: create it first", path=out, reason="no parent")
    return os.path.join(out, CANDIDATES)


def _print_front(result) -> None:
    from offshore_crane.studies.design import front_columns, front_rows

    columns = front_columns(result.space)
    width = [max(10, min(len(c), 24)) for c in columns]
    print("  ".join(f"{c[-w:]:>{w}}" for c, w in zip(columns, width)))
    for row in front_rows(result):
        print("  ".join(f"{row[c]:>{w}.6g}" if not isinstance(row[c], int) else
                        f"{row[c]:>{w}}" for c, w in zip(columns, width)))


def _pick(args, scene) -> int:
    from offshore_crane.io import plan_outputs, write_text
    from offshore_crane.studies import design

    if args.pick is None or args.out_robot is None or args.out is None:
        raise InputError("--pick N needs --out DIR (a finished design's directory) and "
                         "--out-robot D.toml (the description to write)", name="--pick")
    source = os.path.join(args.out, design.PARETO)
    if not os.path.isfile(source):
        raise InputError(f"--pick {args.pick}: {source} does not exist: run the design with "
                         f"--out {args.out} first", name="--pick")
    rows = design.read_front(source)
    names = [c for c in (rows[0] if rows else {}) if c != "design"]
    if args.space is not None:
        names = list(design.check_space(scene, design.load_space(args.space),
                                        args.space).names)
    else:
        names = [n for n in names if _is_field(n)]
    values = design.picked(rows, args.pick, names, source)
    planned = plan_outputs({"--out-robot": args.out_robot}, [args.scene, source,
                                                             *scene.inputs()])
    text = design.design_description(scene, values, header=(
        f"design {args.pick} of {source}: "
        + ", ".join(f"{k} = {v:.17g}" for k, v in values.items())))
    write_text(planned["--out-robot"], text)
    print(f"wrote {args.out_robot}: design {args.pick} ("
          + ", ".join(f"{k} = {v:.6g}" for k, v in values.items()) + ")")
    return 0


def _is_field(name: str) -> bool:
    """Whether a front column is a description field (a variable), not a quantity."""
    from offshore_crane.errors import DescriptionError
    from offshore_crane.robot.overrides import normalise

    if " " in name:
        return False
    try:
        normalise({name: 0.0}, "pareto.csv")
    except DescriptionError:
        return False
    return True
