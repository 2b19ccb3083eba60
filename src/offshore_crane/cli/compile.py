"""``offshore-crane compile``: compile the Numba kernels once and cache them.

The compiled kernels are built on their first call and cached beside the package's files
(or in ``NUMBA_CACHE_DIR``). Running this once after installing, and before starting
parallel workers, keeps every later process at the cache's load time (~1 s). The kernel
groups compile in parallel processes (``--jobs``, default one per core): Numba compiles
under one lock per process, so processes are what uses the cores.
"""

from __future__ import annotations

import os

#: The kernel groups: name -> (warm-up calls, each ``(module, function, keyword
#: arguments)``, run in order in one process; cold compile seconds). The seconds,
#: measured on this project's 2-core machine (one process, 2026-11-28), order the groups
#: longest first (a longest-first schedule on the workers). Groups share no big kernel:
#: two processes compiling one kernel at once both pay for it (the hanging load's
#: kernels and its simulation loop share the cable's kernels: one group; apart, they
#: took longer, measured). The driver's loops (:mod:`offshore_crane.simulation.loop`)
#: of ``simulate --scene``'s plants under computed torque are warmed; another law's loop
#: compiles on its first use (~5 s).
PARTS = {
    "hanging load": ((("offshore_crane.dynamics.cable", "warm_up", {}),
                      ("offshore_crane.simulation.swing", "warm_up", {})), 22),
    "elastic cable": ((("offshore_crane.simulation.elastic", "warm_up", {}),), 11),
    "simulation loop": ((("offshore_crane.simulation.rigid", "warm_up", {"swing": False}),),
                        9),
    "rnea kernels": ((("offshore_crane.dynamics", "warm_up",
                       {"methods": ("rnea",), "forward": False}),), 6),
    "kane kernels": ((("offshore_crane.dynamics", "warm_up",
                       {"methods": ("kane",), "forward": False}),), 2),
    "serial chain kernels": ((("offshore_crane.serial.core", "warm_up", {}),), 2),
    "kane-explicit kernels and forward dynamics": (
        (("offshore_crane.dynamics", "warm_up", {"methods": ("kane-explicit",)}),), 2),
}


def add_parser(sub) -> None:
    doc = __doc__.splitlines()
    p = sub.add_parser("compile", help="compile and cache the Numba kernels",
                       description=doc[2].strip() + " " + " ".join(
                           line.strip() for line in doc[3:8]))
    p.add_argument("--jobs", type=int, default=None, metavar="N",
                   help="processes compiling at once (default: one per core)")
    p.set_defaults(run=run)


def _part(name: str) -> list[tuple[str, float]]:
    """Compile (or load) one group in this process: ``[(name, seconds), ...]``."""
    import importlib

    return [item for module, function, kwargs in PARTS[name][0]
            for item in getattr(importlib.import_module(module), function)(**kwargs)]


def compile_all(jobs: int | None = None, report=None) -> list[tuple[str, float]]:
    """Compile (or load) every kernel group, ``jobs`` processes at once (default: one
    per core; 1: in this process): ``[(name, seconds), ...]`` in completion order.

    Args:
        jobs: Worker processes (spawned: they import nothing of this process).
        report: Called with each group's ``[(name, seconds), ...]`` as it completes.

    Raises:
        InputError: ``jobs`` < 1.
    """
    from offshore_crane.errors import InputError

    jobs = (os.cpu_count() or 1) if jobs is None else jobs
    if jobs < 1:
        raise InputError(f"--jobs {jobs}: give at least 1", name="--jobs")
    out: list = []
    order = sorted(PARTS, key=lambda n: -PARTS[n][1])

    def done(items):
        out.extend(items)
        if report:
            report(items)

    from offshore_crane import compile_beside

    with compile_beside.off():          # the groups' processes are all there are
        if jobs == 1:
            for name in order:
                done(_part(name))
            return out
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor, as_completed

        with ProcessPoolExecutor(min(jobs, len(order)),
                                 mp_context=multiprocessing.get_context("spawn")) as pool:
            for f in as_completed([pool.submit(_part, name) for name in order]):
                done(f.result())
    return out


def run(args) -> int:
    import time

    from offshore_crane import progress

    t0 = time.perf_counter()
    with progress.bar(len(PARTS), "group", "compile") as shown:
        def report(items):
            for name, seconds in items:
                print(f"{name}: {seconds:.1f} s", flush=True)
            shown.update()

        compile_all(args.jobs, report)
    print(f"compiled kernels ready in {time.perf_counter() - t0:.1f} s")
    return 0
