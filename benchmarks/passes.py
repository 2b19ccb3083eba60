"""Benchmark of the per-sample Kane passes as LLVM programs against the same formulas
inlined and compiled by Numba (what the kernels called before), in one run.

For the default robot, each pass the compiled kernels call (the explicit pass with and
without the mass matrix, the fused pass with every leg force, the pass with a pull at
the tip) is timed in a compiled loop over the 20 001 samples of Table 1 (0–60 s), both
ways: through its entry (``dynamics/passes.py``: the program compiled by LLVM from the
formulas' trace, the six legs as the lanes of vectors) and inlined from the formulas
(``compiled.K``, Numba's build). The process runs on one core. Also measured: each
program's compile by LLVM from its text (no cache) and its instruction count, and the
compile of each Numba loop (the formulas inlined, no cache).

    python benchmarks/passes.py [--save]

``--save`` writes ``benchmarks/results/passes.json``, from which ``python
scripts/figures.py`` writes the table of docs/simulation.md.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _saved import benchmark_parser, save, stamp  # noqa: E402

#: The passes: (label, kind, variant) of :mod:`offshore_crane.dynamics.native`.
PASSES = (("explicit, mass matrix", "explicit", 1), ("explicit, no mass matrix", "explicit", 0),
          ("fused, every leg force", "kane", 1), ("with a pull at the tip", "kane_pull", 0))
REPEATS = 7


def _loops():
    """Per pass, the loop through the entry and the loop with the formulas inlined."""
    import numba

    from offshore_crane.dynamics import compiled as c

    Ke, Kk, Kp = c.K.explicit_sample, c.K.kane_sample, c.K.kane_sample_pull
    ce, ck, cp = c.call_explicit, c.call_kane, c.call_kane_pull

    def explicit(call):
        @numba.njit(nogil=True, error_model="numpy")
        def run(C, Q, QD, QDD, g, wm, B, J, Mm, st, Vw, Ww, Vs, d, mc):
            s = 0.0
            for k in range(Q.shape[0]):
                B[:] = 0.0
                Mm[:] = 0.0
                call(C, Q[k], QD[k], QDD[k], g, wm, B, J, Mm, st, Vw, Ww, Vs, d, mc)
                s += B[0] + Mm[3, 2] + J[2, 1]
            return s
        return run

    def fused(call):
        @numba.njit(nogil=True, error_model="numpy")
        def run(C, Q, QD, QDD, g, rows, A, rhs, d, st):
            s = 0.0
            for k in range(Q.shape[0]):
                call(C, Q[k], QD[k], QDD[k], g, False, 0, True, rows, A, rhs, d, st)
                s += rows[0] + A[2, 1] + rhs[3]
            return s
        return run

    def pulled(call):          # as fused, the flags replaced by a pull (Numba calls a
        @numba.njit(nogil=True, error_model="numpy")   # closure with no *args)
        def run(C, Q, QD, QDD, g, rows, A, rhs, d, st):
            s = 0.0
            for k in range(Q.shape[0]):
                call(C, Q[k], QD[k], QDD[k], g, (1.0, 2.0, -30.0), (0.1, 0.0, -0.5), rows, A,
                     rhs, d, st)
                s += rows[0] + A[2, 1] + rhs[3]
            return s
        return run

    return {"explicit": (explicit(ce), explicit(Ke)), "kane": (fused(ck), fused(Kk)),
            "kane_pull": (pulled(cp), pulled(Kp))}


def main() -> int:
    parser = benchmark_parser(__doc__, "passes")
    args = parser.parse_args()
    os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[-1]})
    import offshore_crane as oc
    from offshore_crane.dynamics import compiled as c
    from offshore_crane.dynamics import native
    from offshore_crane.dynamics.constants import robot_arrays
    from offshore_crane.motion.trajectories import table1

    A = robot_arrays(oc.load_robot())
    C = A.kane
    for entry in (c.EXPLICIT, c.KANE, c.KANE_PULL):
        entry.ensure()
    t = np.linspace(0.0, 60.0, 20001)
    Q, QD, QDD = (np.ascontiguousarray(x) for x in table1(t))
    g = (0.0, 0.0, -9.81)
    na = C.n_arm
    explicit_work = (np.zeros(9), np.zeros((6, 6)), np.zeros((9, 9)), np.zeros((na, 27)),
                     np.zeros((9, 3)), np.zeros((9, 3)), np.zeros((9, 3)), np.zeros((7, 6)),
                     np.zeros((1, 3)))
    fused_work = (np.zeros(na), np.zeros((6, 6)), np.zeros(6), np.zeros((7, 6)),
                  np.zeros((na, 27)))
    loops = _loops()
    out = {**stamp(), "samples": len(t), "cpu": "one core", "passes": {}}
    for label, kind, variant in PASSES:
        row = {}
        extra = (bool(variant),) if kind == "explicit" else ()
        work = explicit_work if kind == "explicit" else fused_work
        run_args = (C, Q, QD, QDD, g, *extra, *work)
        sums = {}
        for way, loop in zip(("program", "numba"), loops[kind]):
            t0 = time.perf_counter()
            loop(C, Q[:2], QD[:2], QDD[:2], g, *extra, *work)        # compiled here
            row[f"{way}_first_call_s"] = time.perf_counter() - t0
            best = np.inf
            for _ in range(REPEATS):
                t0 = time.perf_counter()
                sums[way] = loop(*run_args)
                best = min(best, time.perf_counter() - t0)
            row[f"{way}_s"] = best / len(t)
        row["same_numbers"] = bool(sums["program"] == sums["numba"])
        name = f"offshore_crane_{kind}_bench_{variant}"
        text = native.program_ir(kind, C, variant, name)
        with tempfile.TemporaryDirectory() as cold:        # compiled, not read
            t0 = time.perf_counter()
            library = native._library(name, text, Path(cold))
            row["program_compile_s"] = time.perf_counter() - t0
        asm = library.get_asm_str()
        row["instructions"] = sum(1 for line in asm.splitlines()
                                  if line.startswith("\t") and not line.startswith("\t."))
        out["passes"][label] = row
        print(f"{label}: program {row['program_s'] * 1e6:.3f} us a call "
              f"({row['instructions']} instructions, compiled in "
              f"{row['program_compile_s']:.2f} s), Numba's inlined "
              f"{row['numba_s'] * 1e6:.3f} us (its loop compiled in "
              f"{row['numba_first_call_s']:.1f} s); same numbers: {row['same_numbers']}")
    if args.save:
        save("passes", out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
