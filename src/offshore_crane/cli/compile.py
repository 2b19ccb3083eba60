"""``offshore-crane compile``: compile the Numba kernels once and cache them.

The compiled kernels are built on their first call (about 20 s each) and cached beside
the package's files (or in ``NUMBA_CACHE_DIR``). Running this once after installing, and
before starting parallel workers, keeps every later process at the cache's load time
(~1 s) and stops several workers from compiling the same kernel at once.
"""

from __future__ import annotations


def add_parser(sub) -> None:
    p = sub.add_parser("compile", help="compile and cache the Numba kernels",
                       description=__doc__.splitlines()[2].strip() + " " + " ".join(
                           line.strip() for line in __doc__.splitlines()[3:6]))
    p.set_defaults(run=run)


def run(args) -> int:
    from offshore_crane.dynamics.cable import warm_up as warm_up_cable
    from offshore_crane.dynamics import warm_up
    from offshore_crane.simulation.rigid import warm_up as warm_up_simulation

    from offshore_crane import progress

    total = 0.0
    groups = (warm_up, warm_up_simulation, warm_up_cable)
    with progress.bar(len(groups), "group", "compile") as shown:
        for group in groups:
            for name, seconds in group():
                total += seconds
                print(f"{name}: {seconds:.1f} s", flush=True)
            shown.update()
    print(f"compiled kernels ready in {total:.1f} s")
    return 0
