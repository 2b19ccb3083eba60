"""Relative error of X against the extended-precision reference, versus condition number.

Runs the three singularity families of ``tests/test_stress.py`` (leg Jacobian, U-joint
gimbal, attitude) for several seeded random motions, measures for every sample the
normwise relative error of X (fused Kane and RNEA with both backends, explicit Kane)
against :mod:`offshore_crane.dynamics.extended` (mpmath,
40 digits), prints the worst ``c = error / (κ ε)`` per kind and method with the κ range,
and draws ``docs/error_vs_condition.png`` (log–log, one panel per kind, with the lines
``c κ ε`` of the test bound and of the worst ``c`` observed).

Usage: ``python scripts/stress_plot.py [--seeds 20] [--out docs/error_vs_condition.png]``
(about 1 s per seed).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

import offshore_crane as oc  # noqa: E402
from test_stress import (C, C_FUSED_ATTITUDE, EPS, FAMILIES, METHODS,  # noqa: E402
                         family_errors)

STYLE = {"kane": ("o", "C0", "fused Kane (Numba, default)"),
         "kane-numpy": ("+", "C2", "fused Kane, NumPy kernel"),
         "kane-explicit": ("x", "C1", "explicit Kane"),
         "rnea": ("s", "C3", "RNEA (Pinocchio; Numba tree states, default)"),
         "rnea-numpy": ("^", "C4", "RNEA (Pinocchio; NumPy tree states)")}
DELTA = np.logspace(-1, -13, 13)


def measure(seeds: int):
    """``{kind: {method: (κ (n,), error (n,), κ_Stewart (n,))}}`` over ``seeds`` motions."""
    robot = oc.load_robot()
    out = {}
    for kind, (family, _) in FAMILIES.items():
        acc = {m: ([], [], []) for m in METHODS}
        for seed in range(seeds):
            _, runs = family_errors(robot, kind, METHODS, DELTA, seed=1000 + seed)
            for m, (kappa, err, res) in runs.items():
                acc[m][0].append(kappa)
                acc[m][1].append(err)
                acc[m][2].append(res.condition)
        out[kind] = {m: tuple(np.concatenate(v) for v in acc[m]) for m in METHODS}
    return out


def worst_c(data):
    """Rows ``(kind, method, median c, 99th percentile c, worst c, κ at the worst, κ min,
    κ max, reference κ)``; the fused path at the attitude singularity is measured
    against its own Stewart κ (its error does not follow 1/cos q5)."""
    rows = []
    for kind, runs in data.items():
        for m, (kappa, err, stewart) in runs.items():
            fused_attitude = kind == "attitude" and m in ("kane", "kane-numpy")
            ref = stewart if fused_attitude else kappa
            c = err / (ref * EPS)
            k = int(np.argmax(c))
            rows.append((kind, m, float(np.median(c)), float(np.percentile(c, 99)),
                         float(c[k]), float(ref[k]), float(kappa.min()), float(kappa.max()),
                         "κ_Stewart" if fused_attitude else "κ"))
    return rows


def plot(data, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8), constrained_layout=True)
    for ax, (kind, runs) in zip(axes, data.items()):
        lo, hi = np.inf, 0.0
        worst = 0.0
        for m, (kappa, err, stewart) in runs.items():
            marker, color, label = STYLE[m]
            shown = np.maximum(err, EPS / 10)          # exact zeros drawn at ε/10
            ax.loglog(kappa, shown, marker, color=color, ms=4, alpha=0.6, label=label,
                      mfc="none" if marker in "os^" else None)
            lo, hi = min(lo, kappa.min()), max(hi, kappa.max())
            if not (kind == "attitude" and m in ("kane", "kane-numpy")):  # fused: flat
                worst = max(worst, (err / (kappa * EPS)).max())
        k = np.logspace(np.log10(lo), np.log10(hi), 50)
        ax.loglog(k, C[kind] * k * EPS, "k-", lw=1.2,
                  label=f"bound of the test family {C[kind]:g} κ ε")
        ax.loglog(k, worst * k * EPS, "k--", lw=1,
                  label=f"worst observed {worst:.3g} κ ε")
        if kind == "attitude":
            s = runs["kane"][2].max()
            ax.axhline(C_FUSED_ATTITUDE * s * EPS, color="C0", ls=":", lw=1,
                       label=f"fused bound {C_FUSED_ATTITUDE:g} κ_Stewart ε")
        ax.set_xlabel({"leg-Jacobian": "κ: Stewart matrix, 1-norm condition number",
                       "U-joint gimbal": "κ = 1 / cos θ2 (worst leg)",
                       "attitude": "κ = 1 / |cos q5|"}[kind])
        ax.set_ylabel("relative error of X vs mpmath (40 digits)")
        ax.set_title(f"{kind} singularity")
        ax.axvline(1e5, color="0.6", lw=0.8, ls="-.")
        ax.axvline(1e8, color="0.3", lw=0.8, ls="-.")
        tr = ax.get_xaxis_transform()                  # x in data, y in axes fraction
        ax.text(1e5, 0.02, " warn", fontsize=8, color="0.4", transform=tr)
        ax.text(1e8, 0.02, " error", fontsize=8, color="0.2", transform=tr)
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(fontsize=7, loc="upper left" if kind != "attitude" else "center left")
    fig.suptitle("offshore-crane: float64 error against condition number "
                 "(tests/test_stress.py families, seeded random rates and accelerations)")
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=20, help="random motions per family")
    parser.add_argument("--out", default=str(ROOT / "docs" / "error_vs_condition.png"))
    args = parser.parse_args(argv)
    data = measure(args.seeds)
    n = sum(len(v[0]) for runs in data.values() for v in runs.values())
    print(f"{n} samples ({args.seeds} seeds x {len(DELTA)} poses x 3 families x "
          f"{len(METHODS)} methods)")
    print(f"{'kind':<16}{'method':<15}{'median c':>9}{'p99 c':>9}{'worst c':>9}"
          f"{'at κ':>9}   {'κ range':<17} c = error / (… ε)")
    for kind, m, med, p99, c, at, lo, hi, ref in worst_c(data):
        print(f"{kind:<16}{m:<15}{med:>9.3g}{p99:>9.3g}{c:>9.3g}{at:>9.2g}   "
              f"{f'{lo:.2g} .. {hi:.2g}':<17} {ref}")
    plot(data, Path(args.out))
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
