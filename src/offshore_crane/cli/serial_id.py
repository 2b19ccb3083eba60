"""``offshore-crane serial-id URDF [--tip FRAME] [--random N] [--seed S] [--check]``.

Prints the joint torques and forces of a serial robot, by Kane's method, for seeded
random joint states; with ``--check`` also the largest difference from Pinocchio's RNEA
on the same URDF, and exits with status 1 when it exceeds ``1e-9 · max(1, max |τ|)``.
The main command line (:mod:`offshore_crane.__main__`) calls :func:`add_parser` and
:func:`run`, and turns :class:`~offshore_crane.errors.OffshoreCraneError` into exit 2.
"""

from __future__ import annotations

import numpy as np

from offshore_crane.errors import InputError

RELATIVE_LIMIT = 1e-9
"""Largest accepted ``max |τ_kane − τ_rnea| / max(1, max |τ_rnea|)``. Both sides are exact
algorithms in float64: their difference is rounding, ~1e-15 relative for the example
robots; 1e-9 leaves room for long chains while catching any modelling error."""


def add_parser(subparsers):
    """Add the ``serial-id`` sub-command to an argparse ``subparsers`` object.

    The parser's defaults carry ``run=run``, for a main program that dispatches on it.
    """
    p = subparsers.add_parser(
        "serial-id", help="Kane inverse dynamics of a serial robot given by a URDF",
        description="Joint torques [N·m] and forces [N] of a fixed-base serial robot read "
                    "from a URDF, by Kane's method, for seeded random joint states "
                    "(positions uniform within the joint limits, or ±π rad / ±1 m without "
                    "limits; rates and accelerations uniform in [-2, 2]). Gravity "
                    "(0, 0, -9.81) m/s² in the root link's axes.")
    p.add_argument("urdf", metavar="URDF", help="URDF file (meshes are not needed)")
    p.add_argument("--tip", metavar="FRAME",
                   help="link to end the chain at; movable joints off the root→tip path "
                        "(grippers, fingers, mimic joints) are locked at zero")
    p.add_argument("--random", type=int, default=5, metavar="N",
                   help="number of random states (default 5)")
    p.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    p.add_argument("--check", action="store_true",
                   help="compare with Pinocchio's RNEA on the same URDF; exit status 1 when "
                        f"the difference exceeds {RELATIVE_LIMIT:g} · max(1, max |τ|)")
    p.set_defaults(run=run)
    return p


def _table(names, units, values) -> str:
    heads = [f"{name} [{unit}]" for name, unit in zip(names, units)]
    widths = [max(len(h), 13) for h in heads]
    lines = ["sample  " + "  ".join(h.rjust(w) for h, w in zip(heads, widths))]
    for i, row in enumerate(values):
        lines.append(f"{i:>6d}  " + "  ".join(f"{v:>{w}.6f}" for v, w in zip(row, widths)))
    return "\n".join(lines)


def run(args) -> int:
    """Run ``serial-id`` with parsed ``args``; return the exit status (0 ok, 1 check failed).

    Raises:
        InputError: ``--random`` below 1, unreadable file.
        ModelError: the URDF is not a serial chain (naming the joint), unknown tip.
        BackendMissingError: ``--check`` without pinocchio.
    """
    from offshore_crane.serial import GRAVITY, inverse_dynamics, load_chain, random_states

    if args.random < 1:
        raise InputError(f"--random must be at least 1, got {args.random}", name="--random")
    chain = load_chain(args.urdf, tip=args.tip)
    q, qd, qdd = random_states(chain, args.random, seed=args.seed)
    from offshore_crane.dynamics import quick_backend

    tau = inverse_dynamics(chain, q, qd, qdd, gravity=GRAVITY,   # no wait for a few samples
                           backend=quick_backend(len(q)))
    units = ["N" if p else "N·m" for p in chain.prismatic]
    end = f" -> tip '{chain.tip}'" if chain.tip else ""
    print(f"chain: base '{chain.base_link}'{end}, {chain.n} joints"
          + (f" (locked at 0: {', '.join(chain.locked)})" if chain.locked else ""))
    print(f"{args.random} random states, seed {args.seed}; gravity {GRAVITY} m/s²")
    print("Kane inverse dynamics:")
    print(_table(chain.joint_names, units, tau))
    if not args.check:
        return 0

    from offshore_crane.serial.reference import pinocchio_model, rnea

    ref = rnea(pinocchio_model(args.urdf, chain), q, qd, qdd, gravity=GRAVITY)
    diff = float(np.abs(tau - ref).max())
    scale = max(1.0, float(np.abs(ref).max()))
    ok = diff <= RELATIVE_LIMIT * scale
    print(f"check against Pinocchio RNEA: max |τ_kane − τ_rnea| = {diff:.3e} "
          f"(relative {diff / scale:.3e}, limit {RELATIVE_LIMIT:g}): "
          + ("OK" if ok else "FAILED"))
    return 0 if ok else 1
