"""What motion compensation buys on the shipped lifts, as ``offshore-crane compensate``
reports it: the payload's residual motion per mode, its sway and tension, the actuators
and the winch, over the default stationary 3-hour record.

    python benchmarks/compensation.py [--save]

``scenes/compensated_lift.toml`` (supply vessel, Hs 2.5 m, Tp 8 s, beam seas, 1:20;
2.5 kg on 1 m of elastic cable with 2 % sway damping; 20 ms measurement delay) under each
mode (``studies.compensation.compare_compensation``, the scene's seed), and without delay
on the same cable made rigid with and without its sway damping (what limits the law);
``scenes/ship_to_ship.toml``'s arm + winch against none. ``--save`` writes
``benchmarks/results/compensation.json`` (rendered into README.md and docs/cable.md by
``scripts/figures.py``) and draws ``docs/compensation.png`` (the first cycle of each
mode's record, as ``compensate --plot`` draws it).
"""

from __future__ import annotations

import math
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from _saved import benchmark_parser, save, stamp  # noqa: E402
from offshore_crane import scenes  # noqa: E402
from offshore_crane.studies.compensation import compare_compensation  # noqa: E402


def _figures(run) -> dict:
    """One mode's figures: residual RMS and largest [m] per axis, sway [deg], tension
    range over m g, the worst actuator and the winch's worst utilisation."""
    u, who, cap = run.worst
    winch = {k: v for k, v in run.winch.items() if v == v}
    return {"rms": run.rms.tolist(), "peak": run.peak.tolist(),
            "sway_deg": run.sway_max_deg, "ratio": [run.lift.ratio_min, run.lift.ratio_max],
            "worst": [u, who, cap], "winch": winch}


def main(argv=None) -> int:
    parser = benchmark_parser(__doc__, "compensation")
    args = parser.parse_args(argv)
    lift = scenes.load_scene(ROOT / "scenes" / "compensated_lift.toml")
    ship = scenes.load_scene(ROOT / "scenes" / "ship_to_ship.toml")
    t0 = time.perf_counter()
    runs = compare_compensation(lift)
    plan = runs[0].run.exposure
    undamped = replace(lift, robot={**lift.robot, "payload.sway_damping": 0.0}, payload=None,
                       arm=None)
    exact = {name: compare_compensation(replace(s, cable={}), modes=("arm+winch",),
                                        delay=0.0)[0]
             for name, s in (("damped", lift), ("undamped", undamped))}
    ships = compare_compensation(ship, modes=("none", "arm+winch"))
    seconds = time.perf_counter() - t0
    figures = {**stamp(), "seconds": seconds, "record": plan.describe(),
               "judged_s": plan.length, "scale": plan.scale,
               "modes": {r.mode: _figures(r) for r in runs},
               "exact_peak": {k: float(np.abs(r.residual).max()) for k, r in exact.items()},
               "exact_rms_across": float(np.sqrt((exact["damped"].residual[:, :2] ** 2)
                                                 .sum(axis=1).mean())),
               "ship": {r.mode: _figures(r) for r in ships}}
    base = np.array(figures["modes"]["none"]["rms"])
    for mode, f in figures["modes"].items():
        gain = base / np.array(f["rms"])
        print(f"{mode:10s} RMS {', '.join(f'{1e3 * x:.3g}' for x in f['rms'])} mm, sway "
              f"{f['sway_deg']:.3g}°, T/mg {f['ratio'][0]:.3g}..{f['ratio'][1]:.3g}, worst "
              f"{100 * f['worst'][0]:.1f} % {f['worst'][1]} {f['worst'][2]}, reduction "
              f"{', '.join(f'{g:.3g}' for g in gain)}")
    print(f"no delay, rigid cable: largest residual {figures['exact_peak']} m")
    print(f"{len(runs) + 2 + len(ships)} records in {seconds:.1f} s")
    if args.save:
        save("compensation", figures)
        from offshore_crane.outputs.report import compensation_plot

        compensation_plot(ROOT / "docs" / "compensation.png", runs, span=plan.cycle,
                          title=f"{lift.name}: payload motion, delay "
                          f"{lift.control['delay']:g} s (first {plan.cycle:g} s of "
                          f"{plan.length * math.sqrt(plan.scale) / 3600:g} h full scale)")
        print("wrote docs/compensation.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
