"""Helpers the sub-commands share: robot options (``--robot``, ``--set``) and the scene
they give, the scene and thresholds of the ``id`` options (``id`` and ``size`` take the
same), output planning, comma-separated numbers."""

from __future__ import annotations

import math
import os
import sys

from offshore_crane.conventions import ACTUATORS
from offshore_crane.errors import InputError


def plan(args, scene):
    """Check ``--out`` and ``--plot`` of a scene-driven command before computing.

    Returns:
        ``(outputs, say)``: the :func:`~offshore_crane.io.plan_outputs` targets, and the
        function that prints the command's report (to standard error when an output goes
        to standard output).
    """
    from offshore_crane.io import FIGURE_FORMATS, plan_outputs

    inputs = [args.scene, *scene.inputs()]
    outputs = plan_outputs({"--out": args.out, "--plot": args.plot}, inputs,
                           {"--plot": FIGURE_FORMATS})
    if any(o.kind == "stdout" for o in outputs.values()):
        return outputs, lambda *a: print(*a, file=sys.stderr)
    return outputs, print


def add_robot_options(p) -> None:
    """``--robot PATH`` and ``--set NAME=VALUE`` (one path: :func:`robot_scene`)."""
    p.add_argument("--robot", metavar="FILE.toml",
                   help="robot description file (default: the scene's, else the shipped "
                   "lab design; see docs/robot-description.md)")
    p.add_argument("--set", action="append", metavar="NAME=VALUE",
                   help="override a robot field by its dotted name or alias, e.g. "
                   "legs.lower.mass=3.1, payload.com=[0,0,-0.05], with_arm=0; repeatable; "
                   "an override that contradicts the scene is an error")


def add_parallel_options(p) -> None:
    """``--workers N`` and ``--scheduler local|tcp://HOST:PORT``: where a command's sweep
    cases run (:func:`offshore_crane.studies.sweep.run`)."""
    options = {"--workers": dict(type=int, metavar="N", help=(
                   "parallel worker processes (default 1: serially; with --scheduler local "
                   "the cluster's size, default 2)")),
               "--scheduler": dict(metavar="ADDRESS|local", help=(
                   "run the cases on Dask: 'local' starts a LocalCluster, tcp://HOST:PORT "
                   "connects to a running scheduler"))}
    for flag, how in options.items():
        p.add_argument(flag, **how)


def robot_scene(args, scene):
    """``scene`` with ``--robot`` and ``--set`` applied, both checked like the scene's
    own robot fields (:func:`offshore_crane.scenes.with_robot_overrides`).

    Raises:
        SceneError: ``--robot`` names another description than the scene's, or a
            ``--set`` contradicts the scene.
        DescriptionError: a bad ``--set`` (unknown name, not a number, ...).
    """
    import os
    from dataclasses import replace

    from offshore_crane.errors import SceneError
    from offshore_crane.robot.overrides import parse_set
    from offshore_crane.scenes import with_robot_overrides

    if args.robot is not None:
        given = os.path.abspath(args.robot)
        if not os.path.exists(given) or os.path.isdir(given):     # a file or a pipe
            raise InputError(f"--robot {args.robot}: no such file (a robot description, "
                             "TOML)", name="--robot")
        own = scene.robot_description
        if own is not None and os.path.abspath(own) != given:
            raise SceneError(f"{scene.where()}: --robot {args.robot} contradicts the "
                             f"scene's [robot] description = {own}: give one",
                             path=scene.path, name="robot.description")
        scene = replace(scene, robot_description=args.robot, arm=None, payload=None)
    return with_robot_overrides(scene, parse_set(args.set))


def add_extremes_options(p, what: str) -> None:
    """``--exposure HOURS`` and ``--record exposure|scene``: how a sea scene's extremes
    are judged (the scene's ``[extremes]``, :mod:`offshore_crane.scenes.exposure`)."""
    p.add_argument("--exposure", type=float, metavar="HOURS",
                   help="full-scale exposure [h]: the length of each seed's stationary "
                   f"record and of {what} (default: the scene's [extremes] exposure, 3)")
    p.add_argument("--record", choices=("exposure", "scene"),
                   help="sea scenes: run stationary records as long as the exposure "
                   "(default), or the scene's own record (observed extremes only)")


def extremes_scene(args, scene):
    """``scene`` with ``--exposure`` and ``--record`` in its ``[extremes]``.

    Raises:
        InputError: either flag on a scene without a sea, or a non-positive exposure.
    """
    from offshore_crane.scenes import with_overrides

    given = {k: v for k, v in (("exposure", args.exposure), ("record", args.record))
             if v is not None}
    if not given:
        return scene
    flag = f"--{next(iter(given))}"
    if args.exposure is not None and not (math.isfinite(args.exposure) and args.exposure > 0):
        raise InputError(f"--exposure {args.exposure:g}: must be a positive number of hours",
                         name="--exposure")
    if scene.trajectory != "sea":
        raise InputError(f"{flag}: applies to a random sea, but the trajectory is "
                         f"{scene.trajectory!r} (deterministic): use a sea scene", name=flag)
    where = f"{scene.path or 'the scene'} with the command-line options"
    return with_overrides(scene, where, extremes={**scene.extremes, **given})


def comma_numbers(text: str, n: int, option: str) -> list[float]:
    """``n`` finite numbers from ``"a,b,c"`` (``--pose``, ``--sway``).

    Raises:
        InputError: not ``n`` finite comma-separated numbers (naming the option).
    """
    import math

    try:
        values = [float(x) for x in text.replace(" ", "").split(",")]
    except ValueError:
        values = []
    if len(values) != n or not all(math.isfinite(v) for v in values):
        raise InputError(f"{option} {text}: give {n} finite comma-separated numbers",
                         name=option)
    return values


def thresholds(args):
    """The singularity policy of ``--warn-cond`` and ``--error-cond``."""
    from offshore_crane.robot.kinematics.workspace import Thresholds

    try:
        return Thresholds(warn=args.warn_cond, error=args.error_cond)
    except ValueError as exc:
        raise InputError(str(exc), name="--warn-cond") from None


def id_scene(args):
    """The scene to run: ``--scene`` (or the default one) with the explicit flags applied."""
    from offshore_crane.scenes import Scene, load_scene, with_overrides, with_trajectory

    scene = robot_scene(args, load_scene(args.scene) if args.scene else Scene())
    methods = None
    if args.method:
        methods = ("kane", "rnea") if args.method == "both" else (args.method,)
    outputs = None if not args.outputs else tuple(o.strip() for o in args.outputs.split(","))
    unknown = [o for o in outputs or () if o not in ACTUATORS]
    if unknown:
        raise InputError(f"--outputs: unknown {', '.join(map(repr, unknown))}: choose among "
                         f"{', '.join(ACTUATORS)}", name="--outputs")
    where = f"{args.scene} with the command-line options" if args.scene else "command line"
    scene = with_trajectory(scene, where, args.trajectory)
    scene = with_overrides(scene, where, trajectory=args.trajectory, duration=args.duration,
                           rate=args.rate, fd_order=args.fd_order, methods=methods,
                           leg_model=args.leg_model, outputs=outputs,
                           gravity=None if args.gravity is None else tuple(args.gravity))
    cable = {k: v for k, v in (("initial", args.initial_sway), ("slack", args.slack),
                               ("substeps", args.substeps)) if v is not None}
    if cable:
        if not scene.payload.cable_length > 0:
            flags = ", ".join(f"--{k.replace('initial', 'initial-sway')}" for k in cable)
            raise InputError(f"{flags}: applies to a payload on a cable; set "
                             "payload.cable_length > 0 (--set, or the scene's [payload])",
                             name="--initial-sway")
        if "substeps" in cable and cable["substeps"] < 1:
            raise InputError(f"--substeps {cable['substeps']}: give an integer >= 1",
                             name="--substeps")
        scene = with_overrides(scene, where, cable={**scene.cable, **cable})
    table1 = scene.trajectory == "table1"
    if table1 and args.fd_order is not None:
        raise InputError("--fd-order applies to a CSV trajectory only (table1 has analytic "
                         "derivatives): leave it out", name="--fd-order")
    return scene                    # a CSV with --duration/--rate: trajectories.load says


def plot_dir(given: str | None) -> str | None:
    """``--plot DIR`` of a command that writes several figures: an existing directory,
    or a new one whose parent exists (made after the checks, before the run)."""
    from offshore_crane.errors import OutputError
    from offshore_crane.special_files import what_is

    if given is None:
        return None
    if os.path.exists(given) and not os.path.isdir(given):
        raise OutputError(f"--plot {given}: exists and is not a directory "
                          f"({what_is(given)}): give a directory for the figures",
                          path=given, reason="not a directory")
    parent = os.path.dirname(os.path.abspath(given))
    if not os.path.isdir(parent):
        raise OutputError(f"--plot {given}: directory {os.path.dirname(given) or '.'} does "
                          "not exist: create it first", path=given, reason="no parent")
    return given
