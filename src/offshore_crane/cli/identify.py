"""``offshore-crane identify``: the robot's inertial parameters from a logged run.

The log is a run's CSV (``t_s``, q1..q9, optionally their rates and accelerations, and
the actuator forces ``T1_Nm..Fl6_N``: what ``simulate --out`` writes, or a test rig's
record in the same columns). Without rates in the log, or with ``--cutoff``, the
positions are low-passed (zero-phase Butterworth) and differentiated. Fitted: the base
parameters by weighted least squares with their σ, along what the log excites, lifted to
every body's physically consistent parameters (docs/identification.md). Printed: what the
log determines (the base parameters with σ and meaning, the identifiable mass totals)
apart from what the prior decided (each body's own values: not identifiable alone), the
noise and residual per actuator, one line naming what a poorly exciting log leaves
undetermined and the coordinates to move, and with ``--validate`` the prediction error on
a second log. Any log gives this answer or one line saying why not: a log of a run it
cannot model (a hanging or elastic load, a winch, another robot: its columns say so,
:mod:`offshore_crane.cli.logs`) is refused, and every input is read and its memory
checked before anything is computed; the fit runs a block of the log at a time.
"""

from __future__ import annotations

from offshore_crane.errors import InputError


def add_parser(sub) -> None:
    from offshore_crane.cli.common import add_robot_options

    doc = __doc__.splitlines()
    p = sub.add_parser("identify", help="inertial parameters from a logged run",
                       description=doc[0].split(": ", 1)[1])
    p.add_argument("--log", required=True, metavar="RUN.csv",
                   help="the logged run: t_s, q1..q9 [, qd, qdd], T1_Nm..Fl6_N")
    p.add_argument("--validate", metavar="RUN.csv",
                   help="a second log: the identified robot's prediction error on it")
    p.add_argument("--cutoff", type=float, metavar="HZ",
                   help="low-pass the positions at this frequency and differentiate them "
                   "(default: the log's own rates if it has them, else 5 Hz)")
    p.add_argument("--excite", metavar="EXCITE.csv",
                   help="the excitation the log ran (what 'excite' wrote): its base "
                   "regressor's condition number and how closely the log followed it")
    p.add_argument("--out", metavar="IDENTIFIED.toml",
                   help="write the identified robot's description: the nominal one with "
                   "every body's mass, centre of mass and inertia identified (--robot "
                   "IDENTIFIED.toml then runs any command on it)")
    add_robot_options(p)
    p.set_defaults(run=run)


#: Above this RMS misfit [σ] of the consistent robot a line says the log is not a rigid
#: robot's (noise alone gives ~1).
MISFIT = 3.0


def run(args) -> int:
    """The command, its linear algebra on one BLAS thread (dynamics.runtime)."""
    from offshore_crane.dynamics.runtime import one_blas_thread

    with one_blas_thread():
        return _run(args)


def _inputs(args, robot):
    """Every input read and checked before anything is computed: ``(log, validation log
    or None, planned excitation or None)``."""
    from offshore_crane.cli.logs import read_log

    log = read_log(args.log, "--log", robot, args.cutoff)
    other = (read_log(args.validate, "--validate", robot, args.cutoff, held=log.nbytes)
             if args.validate else None)
    plan = None
    if args.excite:
        from offshore_crane.motion.trajectories import load

        plan = load(args.excite)
        t = log.t
        if t[0] < plan.t[0] or t[-1] > plan.t[-1]:
            raise InputError(f"--excite {args.excite}: it spans t = {plan.t[0]:g}.."
                             f"{plan.t[-1]:g} s, the log {t[0]:g}..{t[-1]:g} s: give the "
                             "excitation the log ran", name="--excite")
    return log, other, plan


def _run(args) -> int:
    import numpy as np

    from offshore_crane import scenes
    from offshore_crane.cli.common import robot_scene
    from offshore_crane.conventions import ACTUATOR_UNITS, ACTUATORS
    from offshore_crane.io import plan_outputs
    from offshore_crane.studies import identification as ident

    if args.cutoff is not None and not (args.cutoff > 0 and args.cutoff < float("inf")):
        raise InputError(f"--cutoff {args.cutoff:g}: give a frequency > 0 [Hz]",
                         name="--cutoff")
    scene = robot_scene(args, scenes.Scene())
    read = scene.inputs() + [f for f in (args.log, args.validate, args.excite) if f]
    outputs = plan_outputs({"--out": args.out}, read, {"--out": ("toml",)})
    robot = scenes.load_robot(scene)
    _identifiable(robot)
    log, other, plan = _inputs(args, robot)
    base = ident.base_parameters(robot, gravity=scene.gravity)
    if plan is not None:
        _excitation(args.excite, plan, robot, base, log.t, log.q)
    try:
        fit, R = ident.fit_log(robot, base, log.q, log.qd, log.qdd, log.X,
                               gravity=scene.gravity)
    except InputError as exc:
        raise InputError(f"--log {args.log}: {exc}", name="--log") from None
    bounds = ident.com_bounds(robot, R)
    pi, misfit = ident.consistent_parameters(base.K, fit.beta, fit.root, R.pi,
                                             com_bounds=bounds)
    rows = ident.base_rows(base, fit, R)
    t = log.t
    print(f"offshore-crane identify: {args.log}, {len(t)} samples, t = {t[0]:.2f}.."
          f"{t[-1]:.2f} s; the log determines {int(fit.determined.sum())} of the {base.rank} "
          f"base parameters (of {len(R.pi)} standard ones; it excites {fit.excited} "
          f"independent combinations, condition number {fit.condition:.4g}); every "
          f"body physically consistent: "
          f"{'yes' if ident.physical(pi) else 'NO'} (base misfit "
          f"{misfit:.3g} σ RMS)")
    print(f"{'actuator':<9}{'unit':<6}{'noise σ':>12}{'residual RMS':>14}")
    actuators = ident.actuator_rows(robot)
    for k, j in enumerate(actuators):
        print(f"{ACTUATORS[j]:<9}{ACTUATOR_UNITS[j]:<6}{fit.noise[k]:>12.4g}"
              f"{fit.rms[k]:>14.4g}")
    masses = _masses(*ident.mass_totals(base, fit, R, pi))
    for line in _determined(rows) + masses:
        print(line)
    missing = ident.unexcited(rows, base, R.names, log.qd)
    if missing:
        print(missing)
    if misfit > MISFIT:
        print(f"the consistent robot misses the log's base parameters by {misfit:.3g} σ RMS: "
              "the forces are not all those of a rigid robot of this geometry (the "
              "filter's error on q̈ for a log without rates, friction, a load not in the "
              "description?)")
    held = ident.bounded_bodies(pi, bounds, R)
    if held:
        print(f"centres of mass held at their part's end (the log did not place them "
              f"inside): {', '.join(held)}")
    if other is not None:
        pred = ident.predict(robot, pi, other.q, other.qd, other.qdd, gravity=scene.gravity)
        err = np.sqrt(np.mean((other.X - pred)[:, actuators] ** 2, axis=0))
        print(f"validation on {args.validate} ({len(other.t)} samples): RMS error per "
              "actuator " + ", ".join(f"{ACTUATORS[j]} {e:.4g}" for j, e in zip(actuators,
                                                                                err))
              + f" [N·m, N]; largest {err.max() / np.abs(other.X).max():.3g} of the peak "
              "force")
    if args.out:
        _write(outputs["--out"], args, robot, R, pi, rows, masses + [missing or ""],
               len(t))
    return 0


def _identifiable(robot) -> None:
    """Refuse, before any log is read, a robot the regressor does not model."""
    from offshore_crane.studies import identification as ident

    try:
        ident.identifiable(robot)
    except InputError:
        raise InputError(f"the robot's payload hangs on a {robot.spec.cable_length:g} "
                         "m cable: identify models it welded (--set payload.cable_length=0)",
                         name="--set") from None


def _determined(rows) -> list[str]:
    """The base parameters the log determines (then the weak ones), one line each: name,
    value ± σ with unit, meaning."""
    from offshore_crane.studies.identification import WEAK

    out = []
    for status, title in (("determined", "base parameters the log determines (value ± σ; "
                           "the forces see only these combinations of the bodies' "
                           "parameters)"),
                          ("weak", f"weakly determined (σ above {WEAK:.0%} of its "
                           "terms' nominal size: the log barely excites them)")):
        chosen = [r for r in rows if r.status == status]
        if chosen:
            out.append(f"{title}:")
            out += [f"  {r.name:<6}{r.value:>13.6g} ± {r.sigma:<9.2g}{r.unit:<6} {r.meaning}"
                    for r in chosen]
    return out


def _masses(totals, alone) -> list[str]:
    """The mass totals the forces determine, and the bodies whose mass is not
    identifiable alone."""
    import numpy as np

    out = ["mass totals the forces determine [kg], nominal → identified ± σ (a welded body "
           "counts in its carrier: the arm's column in the platform, a welded payload in "
           "the slider):"]
    out += [f"  {m.label:<58}{m.nominal:>9.4g} → {m.identified:.6g} ± "
            + (f"{m.sigma:.2g}" if np.isfinite(m.sigma) else "? (this log does not "
               "determine it)")
            for m in totals]
    if alone:
        out.append("not identifiable alone (the prior's split, nearest the nominal values: "
                   f"the written description has them): the masses of {', '.join(alone)}")
    return out


def _excitation(path: str, plan, robot, base, t, q) -> None:
    """Print the planned excitation's condition number and the log's departure from it
    (RMS of q − planned at the log's times, the worst coordinate)."""
    import numpy as np

    from offshore_crane.conventions import Q_COLUMNS
    from offshore_crane.studies import identification as ident

    planned = np.column_stack([np.interp(t, plan.t, plan.q[:, j]) for j in range(9)])
    rms = np.sqrt(np.mean((q - planned) ** 2, axis=0))
    j = int(np.argmax(rms))
    print(f"excitation {path}: base regressor condition number "
          f"{ident.excitation_condition(robot, plan, base):.4g} as planned; the log follows "
          f"it within {rms[j]:.3g} RMS (worst coordinate {Q_COLUMNS[j]})")


def _write(target, args, robot, R, pi, rows, notes, n) -> None:
    """Write the identified description, its header saying what the log determines (the
    base parameters with σ, meaning and combination, ``notes``: the mass totals and what
    the log does not excite) and what the prior decided, and check that it loads."""
    from offshore_crane.io import write_text
    from offshore_crane.robot.description import resolve
    from offshore_crane.studies import identification as ident

    spec = robot.spec
    over = "".join(f", {k} = {v}" for k, v in spec.overrides.items())
    header = [f"The robot identified by offshore-crane identify from {args.log} ({n} "
              "samples).", f"Nominal description: {spec.path}{over}.",
              "What the log determines: the base parameters below (value ± σ [SI units",
              "of their terms], their meaning and combination); the forces see nothing",
              "else. What the prior decided: each body's own mass, centre of mass and",
              "inertia in the tables below are not identifiable alone; they are the",
              "physically consistent split, nearest the nominal values, of these",
              "combinations (docs/identification.md)."]
    header += [""] + [w for line in notes if line
                      for w in (_wrapped(line) if len(line) > 100 else [line])]
    titles = {"determined": "Determined by the log", "weak": "Weakly determined (σ above "
              "a tenth of its terms' nominal size)", "not excited": "Not excited by this "
              "log (the prior decided them; the value is the description's)"}
    for status, title in titles.items():
        chosen = [r for r in rows if r.status == status]
        if chosen:
            header += ["", f"{title}: {len(chosen)}"]
            for r in chosen:
                value = (f"{r.value:.10g} ± {r.sigma:.3g}" if status != "not excited" else
                         "(none from the log)")
                header += [*_wrapped(f"{r.name} = {value} {r.unit}: {r.meaning}", "  "),
                           *_wrapped(f"= {r.combination}", "      ")]
    text = ident.identified_description(robot, R, pi, "\n".join(header))
    resolve(args.out, content=text.encode())           # it loads (or says why)
    write_text(target, text)
    print(f"wrote {args.out}: the identified robot (run any command with --robot "
          f"{args.out})")


def _wrapped(text: str, indent: str = "") -> list[str]:
    """``text`` as comment lines of at most 86 characters."""
    import textwrap

    return textwrap.wrap(text, 86, initial_indent=indent, subsequent_indent=indent + "  ",
                         break_on_hyphens=False)
