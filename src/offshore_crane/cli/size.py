"""``offshore-crane size``: the envelope of one run against the actuators' capacities.

Runs the scene as ``id`` does (the same flags; a scene with ``[control]`` is simulated),
then prints per actuator the peak push and pull with their times, the RMS, the peak
speed, the peak and mean absolute power and the stroke used, the worst condition
numbers, and the utilisation of every capacity of the robot description (and the
scene's ``[actuators]``). A sea runs ``--seeds`` stationary records as long as the
exposure (3 h full scale; ``[extremes]``) and judges their most probable maximum (Gumbel
fit of their maxima, from 5 seeds). Exit status 1 when a utilisation exceeds 100 % (or
``--method both`` disagrees), 0 otherwise.
"""

from __future__ import annotations

import math

from offshore_crane.errors import InputError


def add_parser(sub) -> None:
    from offshore_crane.cli import id as id_command
    from offshore_crane.cli.common import add_extremes_options

    doc = __doc__.splitlines()
    p = sub.add_parser("size", help="actuator envelope and utilisation of one run",
                       description=doc[0].split(": ", 1)[1] + " " + " ".join(
                           line.strip() for line in doc[2:9]))
    id_command.add_options(p, plot_help="write the per-actuator utilisation chart to this "
                           "figure (PNG, PDF, SVG)")
    p.add_argument("--seeds", type=int, metavar="N",
                   help="sea scenes: run N seeds from the scene's [sea] seed (default: the "
                   "scene's [extremes] seeds, 5); from 5 the verdict rests on the Gumbel "
                   "most probable maximum")
    add_extremes_options(p, "the most probable maximum")
    p.add_argument("--json", action="store_true",
                   help="print the envelopes and the verdict as JSON on standard output "
                   "(instead of the tables)")
    p.set_defaults(run=run)


def _clean(x):
    """JSON-safe: NaN and ±inf become null; NumPy scalars and arrays plain."""
    import numpy as np

    if isinstance(x, dict):
        return {k: _clean(v) for k, v in x.items()}
    if isinstance(x, (list, tuple, np.ndarray)):
        return [_clean(v) for v in x]
    if isinstance(x, (float, np.floating)):
        return float(x) if math.isfinite(x) else None
    if isinstance(x, np.integer):
        return int(x)
    return x


def run(args) -> int:
    import json
    import sys

    from offshore_crane import progress
    from offshore_crane import scenes
    from offshore_crane.studies import sweep
    from offshore_crane.conventions import ACTUATORS
    from offshore_crane.studies.sizing import (CAPACITIES, EXPOSURE, format_envelope,
                                               format_verdict, verdict)
    from offshore_crane.cli.common import plan
    from offshore_crane.cli.common import extremes_scene, id_scene, thresholds
    from offshore_crane.cli.id import RELATIVE_LIMIT
    from offshore_crane.scenes.exposure import extremes_option

    if args.seeds is not None and args.seeds < 1:
        raise InputError(f"--seeds {args.seeds}: must be ≥ 1", name="--seeds")
    scene = extremes_scene(args, id_scene(args))
    sea = scene.trajectory == "sea"
    args.seeds = args.seeds or (extremes_option(scene, "seeds") if sea and not scene.lift
                                else 1)
    if args.seeds > 1 and not sea:
        raise InputError(f"--seeds {args.seeds}: seeds draw random seas, but the trajectory "
                         f"is {scene.trajectory!r} (deterministic): use a sea scene",
                         name="--seeds")
    if args.seeds > 1 and args.out:
        raise InputError("--out writes the forces of one record: give --seeds 1 with it",
                         name="--out")
    outputs, say = plan(args, scene)
    if args.json:
        say = lambda *a: print(*a, file=sys.stderr)     # noqa: E731 (stdout holds JSON)
    robot = scenes.load_robot(scene)
    backend = args.backend or "auto"
    options = dict(backend=backend, threads=args.threads, limits=not args.no_limits,
                   thresholds=thresholds(args))
    first = int(scene.sea.get("seed", 0)) if sea else None
    runs = []
    with progress.bar(args.seeds, "seed", "size") as shown:
        for s in range(args.seeds):
            case = sweep.case_scene(scene, {"seed": first + s}) if sea else scene
            with progress.suspended():          # the bar counts the seeds
                runs.append(sweep.record(case, robot, **options))
            shown.update()
    exposure = extremes_option(scene, "exposure") * 3600.0 if sea else EXPOSURE
    v = verdict([r.envelope for r in runs], scale=scene.sea["scale"] if sea else None,
                exposure=exposure)
    head = runs[0]
    status = 1 if v.exceeded else 0
    compared = []
    if len(scene.methods) > 1 and not scene.simulated:
        done = scenes.run(scene, robot, head.trajectory, limits=options["limits"],
                          thresholds=options["thresholds"], backend=backend,
                          threads=args.threads)
        for m, diff, scale, rel, i, j in scenes.compare_methods(done):
            ok = rel <= RELATIVE_LIMIT
            compared.append({"method": m, "max_abs_diff": diff, "relative": rel,
                             "ok": ok})
            status = status if ok else 1
    env = head.envelope
    if args.json:
        worst, who, cap = v.worst()
        doc = {"scene": scene.name, "kind": head.kind, "samples": env.samples,
               "duration_s": env.duration,
               "seeds": [first + s for s in range(args.seeds)] if sea else None,
               "envelopes": [r.envelope.row() for r in runs],
               "records": None if head.exposure is None else {
                   "describe": head.exposure.describe(),
                   "judged_s": head.exposure.length, "spin_up_s": head.exposure.spin_up,
                   "cycle_s": head.exposure.cycle,
                   "modes": [{"name": m.name, "omega_rad_s": m.omega, "zeta": m.zeta,
                              "decay_time_s": m.decay_time} for m in head.exposure.modes]},
               "verdict": {"basis": v.basis, "describe": v.describe(), "seeds": v.seeds,
                           "exposure_s": v.exposure, "record_s": v.record,
                           "peaks": v.peaks,
                           "utilisation": {a: dict(zip(CAPACITIES, v.utilisation[k]))
                                           for k, a in enumerate(ACTUATORS)
                                           if env.present[k]},
                           "worst": {"utilisation": worst, "actuator": who,
                                     "capacity": cap},
                           "exceeded": v.exceeded,
                           "load": None if v.load is None else {
                               "sway_max_rad": v.load.sway, "sway_max_deg":
                               math.degrees(v.load.sway),
                               "tension_min_N": v.load.tension_min,
                               "tension_max_N": v.load.tension_max,
                               "static_tension_N": v.load.static,
                               "tension_ratio_min": v.load.ratio_min,
                               "observed": v.load.observed,
                               "limits": {"sway_max_deg": math.degrees(
                                   v.load.limits.sway_max),
                                   "tension_ratio_min": v.load.limits.tension_ratio_min,
                                   "tension_max_N": v.load.limits.tension_max},
                               "utilisation": v.load.utilisation,
                               "exceeded": v.load.exceeded}},
               "comparison": compared}
        print(json.dumps(_clean(doc), indent=1, ensure_ascii=False))
    else:
        where = f" ({args.scene})" if args.scene else ""
        say(f"offshore-crane size: scene {scene.name}{where}: {scene.describe()}")
        if head.exposure is not None:
            say(f"records: {head.exposure.describe()}")
        say(f"{head.kind} of {head.trajectory.name}, {env.samples} samples judged, "
            f"t = {head.t[0]:.2f}..{head.t[-1]:.2f} s"
            + (f"; envelope of seed {first} (of {args.seeds}), observed over "
               f"{env.duration:.6g} s ({env.duration * math.sqrt(scene.sea['scale']):.6g} s "
               "full scale)" if sea else "; observed"))
        say(format_envelope(env))
        say()
        say(format_verdict(v, env.present))
        for c in compared:
            say(f"kane vs {c['method']}: relative max |ΔX| = {c['relative']:.3e} "
                f"({'OK' if c['ok'] else 'FAIL'}, limit {RELATIVE_LIMIT:g})")
    if "--out" in outputs:
        from offshore_crane.outputs.report import write_csv

        write_csv(outputs["--out"], head.t, head.X)
        say(f"wrote {args.out}")
    if "--plot" in outputs:
        from offshore_crane.outputs.sizing_plots import utilisation_chart

        utilisation_chart(outputs["--plot"], v.utilisation,
                          title=f"{scene.name}: utilisation ({v.describe()})")
        say(f"wrote {args.plot}")
    return status
