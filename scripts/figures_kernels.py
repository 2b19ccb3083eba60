"""The renderers of the kernels' and tools' benchmarks (timings, agreement, compile, CI): each
``NAME_rows(saved result) -> {(file, first cell or 'figure KEY'): text}``
(``scripts/figures.py``)."""

from __future__ import annotations

import re

from figures_format import _count, _met, _sci


def animate_rows(r: dict) -> dict:
    """``{(file, first cell): row}`` of benchmarks/animate.py's figures."""
    p, f, s = r["plain"], r["force"], r["stages"]
    drawing = s.get("drawing (1,800 frames, no encoding)", float("nan"))
    visual = "docs/visual.md"
    g = r["gifs"]
    caption, g10, g30 = g["caption"], g["60 s at 10 fps"], g["60 s at 30 fps"]
    return {
        ("README.md", "figure gif-caption"): f"{caption['mb']:.1f} MB, written in "
                                             f"{caption['s']:.1f} s",
        ("README.md", "figure gif-sizes"): f"{g10['mb']:.1f} MB as a GIF, {f['mb']:.1f} MB "
                                           "as a 30 fps MP4",
        (visual, "figure gif-sizes"): f"{g10['mb']:.1f} MB at 10 fps; {g30['mb']:.1f} MB at "
                                      f"30 fps, where an MP4 takes {f['mb']:.1f} MB",
        (visual, "figure gif-caption"): f"is {caption['mb']:.1f} MB and takes "
                                        f"{caption['s']:.1f} s ({r['date']})",
        (visual, "figure animate-load"):
            f"{r['date']}, other processes using {p['others_core']:.2f} and "
            f"{f['others_core']:.2f} core during the plain and coloured runs",
        (visual, "plain"):
            f"| plain | {p['median_s']:.1f} s ({p['min_s']:.1f}–{p['max_s']:.1f}), "
            f"{p['mb']:.1f} MB | ≤ 30 s, {_met(p['max_s'] <= 30)} |",
        (visual, "`--color-by force`"):
            f"| `--color-by force` (inverse dynamics of the 6,001 samples included) | "
            f"{f['median_s']:.1f} s ({f['min_s']:.1f}–{f['max_s']:.1f}), {f['mb']:.1f} MB | "
            f"≤ 30 s, {_met(f['max_s'] <= 30)} |",
        (visual, "stages:"):
            "| stages: " + ", ".join(f"{k.split(' (')[0]} {v:.2f} s" for k, v in s.items())
            + f" ({drawing / 1800 * 1e3:.1f} ms a frame drawn) | | |",
        ("README.md", "a 60 s run at 30 fps"):
            f"| a 60 s run at 30 fps, 640 × 480 MP4 (1,801 frames) | `benchmarks/animate.py` "
            f"| {p['median_s']:.1f} s ({f['median_s']:.1f} s with legs coloured by force; "
            f"other processes using {max(p['others_core'], f['others_core']):.1f} core) | "
            f"≤ 30 s ({_met(max(p['max_s'], f['max_s']) <= 30)}) |",
    }


def cable_swing_rows(r: dict) -> dict:
    """benchmarks/cable_swing.py's figures: one thread, and ``threads`` (the Kane passes,
    the motion's FFTs and check; issue 25's targets: ≤ 2.5 s, ≤ 2× the rigid inverse
    dynamics)."""
    m, s, rigid, n = r["motion_s"], r["swing_s"], r["rigid_s"], r["threads"]
    m2, s2, rigid2 = r["motion_threads_s"], r["swing_threads_s"], r["rigid_threads_s"]
    total, total2 = m + s, m2 + s2
    return {
        ("README.md", "a 3-hour sea state at 100 Hz (1.08 M samples) with"):
            f"| a 3-hour sea state at 100 Hz (1.08 M samples) with the hanging load's swing "
            f"| `benchmarks/cable_swing.py` | {total:.1f} s (motion {m:.1f} s, swing "
            f"{s:.1f} s); {total2:.1f} s in {n} threads | ≤ 10 s "
            f"({_met(total <= 10)}); ≤ 2.5 s and ≤ 2× the rigid inverse dynamics "
            f"({total2 / rigid2:.1f}×: {_met(total2 <= 2.5 and total2 <= 2 * rigid2)}) |",
        ("README.md", "figure cable_swing"): f"**{total:.1f} s** ({total2:.1f} s in {n} "
                                             "threads)",
        ("docs/cable.md", "figure cable_swing"):
            f"the motion {m:.1f} s, the swing {s:.1f} s ({s / r['samples'] * 1e6:.1f} µs a "
            f"sample: stage motion, RK4, Kane with the pull), **{total:.1f} s in all** "
            f"(target ≤ 10 s); the rigid robot's inverse dynamics of the same record takes "
            f"{rigid:.1f} s. In {n} threads (`threads=`, `id --threads`: the Kane pass, the "
            f"sea motion's FFTs and workspace check) the motion takes {m2:.1f} s and the "
            f"swing {s2:.1f} s, **{total2:.1f} s in all**, {total2 / rigid2:.1f}× "
            f"the rigid robot's {rigid2:.2f} s in as many threads (issue 25's target, ≤ 2.5 "
            f"s and ≤ 2×: {_met(total2 <= 2.5 and total2 <= 2 * rigid2)})",
    }


def sea_synthesis_rows(r: dict) -> dict:
    """benchmarks/sea_synthesis.py's figures."""
    per = r["inverse_min"] / r["model_samples"] * 1e6
    sea = "docs/sea.md"
    return {
        (sea, "`ship_motion`, 3 h at 100 Hz"):
            f"| `ship_motion`, 3 h at 100 Hz ({_count(r['samples'])} samples, "
            f"{r['components']} components, 6 DOFs × position, velocity, acceleration) | "
            f"{r['synth_median']:.2f} s | {r['synth_min']:.2f} s |",
        (sea, "reference: bare `irfft`"):
            f"| reference: bare `irfft` of the same size (18 channels) | "
            f"{r['irfft_median']:.2f} s | {r['irfft_min']:.2f} s |",
        (sea, "`platform_trajectory` at λ = 20"):
            f"| `platform_trajectory` at λ = {r['scale']:g} ({_count(r['model_samples'])} "
            f"samples, workspace checked) | {r['build_median']:.2f} s | "
            f"{r['build_min']:.2f} s |",
        (sea, "`inverse_dynamics` (Kane) on it"):
            f"| `inverse_dynamics` (Kane) on it | {r['inverse_median']:.2f} s | "
            f"{r['inverse_min']:.2f} s ({per:.2f} µs/sample; Table 1 at the same size: ratio "
            f"{r['inverse_min'] / r['table1_min']:.2f}) |",
        ("README.md", "figure sea_synthesis"):
            f"a 3-hour record at 100 Hz ({r['samples'] / 1e6:.2f} M samples, "
            f"{r['components']} wave components) in {r['synth_min']:.2f} s (target 2 s; a "
            f"bare inverse FFT of the same size takes {r['irfft_min']:.2f} s); the inverse "
            f"dynamics on the same record at scale {r['scale']:g} "
            f"({_count(r['model_samples'])} samples) in {r['inverse_min']:.2f} s ({per:.2f} µs "
            f"a sample, {r['inverse_min'] / r['table1_min']:.2f} × Table 1's)",
    }


def pinocchio_fd_rows(r: dict) -> dict:
    """benchmarks/pinocchio_fd.py's figures."""
    call, batch, single = r["constraint_call_s"], r["batch_s"], r["single_s"]
    return {
        ("README.md", "forward dynamics, batched N = 10⁴"):
            f"| forward dynamics, batched N = 10⁴ | {batch * 1e6:.1f} µs a sample | "
            f"{call * 1e6:.1f} µs | ≤ 0.5 × ({_met(batch / call <= 0.5)}: "
            f"{batch / call:.2f}) |",
        ("README.md", "forward dynamics, one sample"):
            f"| forward dynamics, one sample | {single * 1e6:.1f} µs | {call * 1e6:.1f} µs | "
            f"≤ 1 × ({_met(single / call <= 1)}: {single / call:.2f}) |",
        ("README.md", "simulate 60 s at 1 kHz"):
            f"| simulate 60 s at 1 kHz, RK4, computed torque | {r['simulate_60s_s']:.2f} s: "
            f"real-time factor {r['rtf']:.0f} | | ≥ 10 ({_met(r['rtf'] >= 10)}) |",
        ("README.md", "the same law as a Python callable"):
            f"| the same law as a Python callable (a user's controller, 10 s) | real-time "
            f"factor {r['rtf_python']:.1f} | | (measured) |",
        ("README.md", "figure pinocchio_fd"):
            f"`benchmarks/pinocchio_fd.py`, {r['date']}, Pinocchio {r['pin']}",
        ("docs/mjcf.md", "figure fd-batch"):
            f"{batch * 1e6:.1f} µs a sample at N = 10⁴ (`benchmarks/pinocchio_fd.py`, "
            f"{r['date']})",
    }


def mjcf_agreement_rows(r: dict) -> dict:
    """benchmarks/mjcf_agreement.py's figures."""
    ratios, bound = r["ratios"], r["agreement"]
    home, worst = ratios["lab, home"], r["worst"]
    labels = {"home": "home", "rotated": "a rotated pose (q4..q6 = 0.04, −0.03, 0.05 rad, "
              "arm moved)", "sample 0": "Table 1's first sample"}
    harib = {"home": "home", "rotated": "a rotated pose", "sample 0": "the first state"}
    out = {
        ("README.md", "MuJoCo against our forward dynamics"):
            f"| MuJoCo against our forward dynamics, Table 1 | `benchmarks/mjcf_agreement.py` "
            f"| {_sci(home)} of the constraint accelerations (worst pose written "
            f"{_sci(worst)}) | ≤ {_sci(bound)} ({_met(worst <= bound)}) |",
        ("docs/mjcf.md", "figure mjcf_agreement"):
            f"The worst, {_sci(worst)}, is {bound / worst:.1f}× below the bound; the model "
            f"written at home (the default) agrees to {_sci(home)}, {bound / home:.0f}× "
            "below.",
    }
    for key, value in ratios.items():
        robot, pose = key.split(", ")
        if robot == "lab":
            states = "Table 1 over 10π s" if pose == "home" else "Table 1"
            first = f"| lab | {labels[pose]} | {states}"
        else:
            states = ("seeded, within 1 cm, 0.05 rad of home" if pose == "home" else "same")
            first = (f"| {robot}{' (no arm)' if pose == 'home' else ''} | {harib[pose]} | "
                     f"{states}")
        out[("docs/mjcf.md", first[2:])] = f"{first} | 200 | {_sci(value)} |"
    return out


def lift_rows(r: dict) -> dict:
    """benchmarks/lift.py's figures."""
    m, s = r["motion_s"], r["lift_s"]
    return {
        ("README.md", "a 3-hour sea state at 100 Hz, the compensated lift"):
            f"| a 3-hour sea state at 100 Hz, the compensated lift (elastic cable, winch, "
            f"arm) | `benchmarks/lift.py` | {m + s:.1f} s (sea {m:.1f} s, lift {s:.1f} s) | "
            f"≤ 20 s ({_met(m + s <= 20)}) |",
        ("docs/cable.md", "figure lift"):
            f"**{m + s:.1f} s** (the sea record {m:.1f} s, the compensated lift {s:.1f} s; "
            f"target ≤ 20 s)",
    }


#: benchmarks/simulation.py's runs as docs/simulation.md names them.
SIMULATION_RUNS = {
    "rigid": "1. rigid robot, built-in computed torque (the driver)",
    "python": "2. the same law as a Python callable (`Controller(function=law)`)",
    "python-1khz": "2b. the same Python law sampled at 1 kHz",
    "hanging": "3. 2 kg hanging on a rigid 0.5 m cable, computed torque",
    "elastic": "4. the elastic lift, `scenes/compensated_lift.toml` (`simulate --scene`)",
}


def simulation_rows(r: dict) -> dict:
    """benchmarks/simulation.py's figures: docs/simulation.md's table of real-time factors
    and issue 37's targets (row 1 ≥ 100, the elastic lift ≥ 0.5 × row 1, one-sample
    forward dynamics ≤ 0.5 × Pinocchio's constraintDynamics call)."""
    runs, fd = r["rows"], r.get("forward_dynamics")
    base = runs["rigid"]["rtf"]
    targets = {"rigid": f"≥ 100 ({_met(base >= 100)})",
               "elastic": f"≥ 0.5 × row 1 ({_met(runs['elastic']['rtf'] / base >= 0.5)})"}
    lines = ["| run | step | law evaluated | simulated | real-time factor (min–max) | "
             "÷ row 1 | target |", "| --- | --- | --- | --- | --- | --- | --- |"]
    for name, x in runs.items():
        law = {"stage": "every RK4 stage", "1 kHz": "at 1 kHz, held"}.get(x["law"], x["law"])
        lines.append(f"| {SIMULATION_RUNS.get(name, name)} | {x['step_s'] * 1e3:g} ms | {law} | "
                     f"{x['seconds']:g} s | {x['rtf']:.3g} ({x['rtf_min']:.3g}–"
                     f"{x['rtf_max']:.3g}) | {x['rtf'] / base:.2g} | {targets.get(name, '')} |")
    e = runs["elastic"]
    rate = ("at the same 1 kHz rate as row 1" if e["step_s"] >= 1e-3 else
            f"at a step finer than 1 ms ({e['step_s'] * 1e3:g} ms), not at row 1's rate")
    others = max(x["others_cores"] for x in runs.values())
    text = [f"Row 4 runs {rate} (the cable's axial period is "
            f"{e['axial_period_s'] * 1e3:.3g} ms)."]
    if fd:
        ratio = fd["ours_s"] / fd["constraint_dynamics_s"]
        pinned = ", the process on one core" if fd.get("pinned") else ""
        text.append(f"One-sample forward dynamics (`oc.forward_dynamics`, one call from "
                    f"Python on {fd['samples']} Table 1 states{pinned}): "
                    f"{fd['ours_s'] * 1e6:.1f} µs "
                    f"a call against {fd['constraint_dynamics_s'] * 1e6:.1f} µs for "
                    f"Pinocchio {fd['pin']}'s `constraintDynamics` ({ratio:.2f} ×; target "
                    f"≤ 0.5 ×: {_met(ratio <= 0.5)}) and {fd['lcaba_s'] * 1e6:.1f} µs for "
                    "`lcaba` (mu = 1e-6).")
    text.append(f"`benchmarks/simulation.py`, {r['date']}, median of {r['repeats']}, on "
                f"{r['cores']} cores with other processes using up to {others:.1f} of them.")
    out = {("docs/simulation.md", "figure simulation"):
           "\n\n" + "\n".join(lines) + "\n\n" + " ".join(text) + "\n\n"}
    pid = r.get("pid")
    if pid:
        pd_, pid_ = pid["pd-gravity"], pid["pid"]
        out[("docs/simulation.md", "figure simulation-pid")] = (
            f"with the controller's model {pid['model_payload_kg']:g} kg in its payload "
            f"for the plant's {pid['payload_kg']:g} kg, over the second half of "
            f"{pid['seconds']:g} s of Table 1, the legs' RMS tracking error is "
            f"{pd_['legs_rms_m']:.2g} m under PD with gravity compensation and "
            f"{pid_['legs_rms_m']:.2g} m under PID ({pd_['legs_rms_m'] / pid_['legs_rms_m']:.2g}"
            f"× smaller), the arm joints' {pd_['arm_rms']:.2g} and {pid_['arm_rms']:.2g} "
            f"(`benchmarks/simulation.py`, {r['date']})")
    return out


def stepper_rows(r: dict) -> dict:
    """benchmarks/stepper.py's figure: the stepper's time over the compiled run's, per
    plant, against issue 38's bound."""
    names = {"rigid": "the rigid robot along Table 1",
             "elastic": "the elastic compensated lift (`scenes/compensated_lift.toml`)"}
    parts = [f"{names.get(k, k)} {x['ratio']:.2f} × ({x['stepper_s'] * 1e3:.0f} ms against "
             f"{x['compiled_s'] * 1e3:.0f} ms for {x['periods']} periods, the same run: "
             f"largest |Δq| {x['dq_max']:.1g})" for k, x in r["rows"].items()]
    worst = max(x["ratio"] for x in r["rows"].values())
    others = max(x["others_cores"] for x in r["rows"].values())
    return {("docs/simulation.md", "figure stepper"):
            f"at {1 / r['period_s']:g} Hz control, the stepper's time over the compiled run "
            f"of the same law and plant (its commands replayed): {'; '.join(parts)}; issue "
            f"38's bound {r['target']:g} × ({_met(worst <= r['target'])}) "
            f"(`benchmarks/stepper.py`, {r['date']}, median of {r['repeats']}, on "
            f"{r['cores']} cores with other processes using up to {others:.1f} of them)"}


def gym_rows(r: dict) -> dict:
    """benchmarks/gym.py's figures: the environment's real-time factor and the vector's
    scaling, against issue 38's targets."""
    e, v, t = r["env"], r["vector"], r["targets"]
    return {("docs/control.md", "figure gym"):
            f"Measured by `benchmarks/gym.py` ({r['date']}, median of {r['repeats']}, on "
            f"{r['cores']} cores with other processes using up to {r['others_cores']:.1f} "
            f"of them): the Gymnasium environment of the elastic compensated lift at "
            f"{1 / r['period_s']:g} Hz control, the default reward included, runs "
            f"{e['rtf']:.1f} × real time on one core ({e['steps']} steps in "
            f"{e['env_s'] * 1e3:.0f} ms; {e['over_stepper']:.2f} × the bare stepper's time; "
            f"the compiled run's commands replayed: the same run, largest |Δq| "
            f"{e['dq_max']:.1g}), issue 38's target ≥ {t['rtf']:g} × "
            f"({_met(e['rtf'] >= t['rtf'])}); {v['envs']} environments of it on 2 workers "
            f"step {v['steps_per_s_2']:.0f} environment-steps per second against "
            f"{v['steps_per_s_1']:.0f} on one, {v['scaling']:.2f} ×, target ≥ "
            f"{t['scaling']:g} × ({_met(v['scaling'] >= t['scaling'])})"}


def roofline_rows(r: dict) -> dict:
    """benchmarks/roofline.py's figures: one row per kernel, the machine in prose."""
    peak, width = r["peak_gflops"], r["vector_width"]
    out = {("README.md", "figure roofline-machine"):
           f"one core's peak {peak:.1f} GFLOP/s (a dense matrix product, one BLAS thread), "
           f"vector width {width} doubles, so {peak / width:.1f} GFLOP/s for scalar code; "
           f"memory copy {r['bandwidth_gbs']:.1f} GB/s; Pinocchio's `rneaInParallel(1)` "
           f"{r['floor_us']:.2f} µs a sample; N = {_count(r['n'])}, run of {r['date']}"}
    per = {k["kernel"]: k for k in r["kernels"]}
    kernels = [k for k in r["kernels"] if not k["kernel"].startswith("legs' geometry")]
    fast = [k for k in kernels if not k["verdict"].startswith("latency")]
    slow = [k for k in kernels if k["verdict"].startswith("latency")]
    scalar = [100 * k["scalar_share"] for k in slow]
    rates = ", ".join(f"{k['kernel']} {k['gflops']:.1f} GFLOP/s" for k in fast)
    lead = (f"{rates}: {fast[0]['verdict'].split(' (')[0]} (blocks of samples vectorised "
            "across them); " if fast else "")
    out[("README.md", "figure roofline-verdict")] = (
        f"{lead}the {len(slow)} others, one sample at a time, latency-bound: scalar code at "
        f"{min(scalar):.0f}–{max(scalar):.0f} % of the scalar roof and under "
        f"{max(100 * k['peak_share'] for k in slow):.0f} % of the machine's peak")
    a, b = per["legs' geometry, per sample"], per["legs' geometry, arrays"]
    out[("README.md", "figure roofline-layout")] = (
        f"{a['us'] * 1e3:.0f} → {b['us'] * 1e3:.0f} ns a sample ({a['us'] / b['us']:.1f}×, "
        f"{a['gflops']:.1f} → {b['gflops']:.1f} GFLOP/s, {b['verdict'].split(' (')[0]}: "
        "its outputs stream to memory)")
    for k in r["kernels"]:
        out[("README.md", f"roofline, {k['kernel']}")] = (
            f"| roofline, {k['kernel']} | {_count(k['flop'])} (+{k['trig']} sin, cos) | "
            f"{k['us']:.2f} | {k['gflops']:.2f} | {100 * k['peak_share']:.1f} % | "
            f"{100 * k['scalar_share']:.0f} % | {k['intensity']:.0f} | {k['verdict']} |")
    return out


def passes_rows(r: dict) -> dict:
    """benchmarks/passes.py's figures: docs/simulation.md's table of the per-sample Kane
    passes, LLVM programs against the formulas inlined by Numba."""
    lines = ["| pass | program (LLVM, legs as lanes) | formulas inlined by Numba | ÷ | "
             "instructions | compile: program / Numba's loop | same numbers |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    for label, x in r["passes"].items():
        numba = (f"{x['numba_first_call_s']:.1f} s" if x["numba_first_call_s"] > 1.0
                 else "(compiled above)")
        lines.append(f"| {label} | {x['program_s'] * 1e6:.2f} µs | {x['numba_s'] * 1e6:.2f} µs "
                     f"| {x['program_s'] / x['numba_s']:.2f} | {x['instructions']} | "
                     f"{x['program_compile_s']:.2f} s / {numba} | {x['same_numbers']} |")
    text = (f"A call, in a compiled loop over the {r['samples']} samples of Table 1, "
            f"{r['cpu']}; `benchmarks/passes.py`, {r['date']}.")
    return {("docs/simulation.md", "figure passes"):
            "\n\n" + "\n".join(lines) + "\n\n" + text + "\n\n"}


def compile_rows(r: dict) -> dict:
    """benchmarks/compile.py's figures: the cold compile in one process and in parallel."""
    one, par, cores = r["one_process"], r["parallel"], r["cores"]
    load = (f"other processes using {one['others_cores']:.1f} and "
            f"{par['others_cores']:.1f} of the {cores} cores meanwhile")
    kernels = ", ".join(f"{k} {s:.0f} s" for k, s in one["kernels"].items())
    rigid, lift = r["first_simulate"], r["first_simulate_elastic"]
    hanging = r["first_simulate_hanging"]
    waits = [x["wall_s"] for x in (rigid, lift, hanging)]
    first = (f"a first `simulate` on a cold cache waits {rigid['wall_s']:.0f} s (the rigid "
             f"robot along Table 1), {lift['wall_s']:.0f} s (the elastic compensated "
             f"lift) and {hanging['wall_s']:.0f} s (scenes/hanging_load.toml), against "
             f"issue 37's 15 s ({_met(max(waits) <= 15)})")
    return {
        ("README.md", "figure compile-short"):
            f"{one['wall_s']:.0f} s for the whole set in one process, {par['wall_s']:.0f} s "
            f"with `offshore-crane compile`, on {cores} cores with {load} "
            f"(`benchmarks/compile.py`, {r['date']}); {first}",
        ("README.md", "figure compile"):
            f"{one['wall_s']:.0f} s in one process ({one['cpu_s']:.0f} s of CPU), "
            f"{par['wall_s']:.0f} s with `offshore-crane compile`, which runs its groups "
            f"in parallel processes ({par['cpu_s']:.0f} s of CPU), on {cores} cores with "
            f"{load} ({r['date']}), against issue 37's 30 s on 2 cores "
            f"({_met(par['wall_s'] <= 30)}); in one process, kernel by kernel: {kernels}",
        ("README.md", "figure compile-serial"):
            f"{one['kernels']['serial chain kernels']:.0f} s in one process",
    }


def ci_rows(r: dict) -> dict:
    """benchmarks/ci.py's figures: ``bash .ci/run`` on a fresh clone."""
    tests = r["tests"]
    skipped = f", {tests['skipped']} skipped" if tests.get("skipped") else ""
    return {
        ("README.md", "figure ci"):
            f"{r['total_s']} s in all ({r['date']}, commit {r['commit']}: "
            f"{tests.get('passed', 0)} tests passed{skipped}; pytest {r['pytest_s']:.0f} s "
            f"of it, its cold compile {r['compile_s']:.1f} s), on {r['cores']} cores with "
            f"other processes using {r['others_cores']:.1f} of them meanwhile",
    }


def bench_serial_rows(r: dict) -> dict:
    """benchmarks/bench_serial.py's figures: every robot of the tests against Pinocchio."""
    rows = r["rows"]
    one = [x for x in rows if x["N"] == 1]
    big = [x for x in rows if x["N"] >= 10_000]
    ten = [x for x in rows if x["N"] == 10_000]
    panda = {x["N"]: x for x in rows if x["robot"] == "panda"}
    lo1, hi1 = min(x["kane_over_rnea_loop"] for x in one), max(x["kane_over_rnea_loop"]
                                                               for x in one)
    lob, hib = min(x["kane_over_parallel1"] for x in big), max(x["kane_over_parallel1"]
                                                               for x in big)
    numpy_one = sorted(x["kane_numpy_us"] for x in one)[len(one) // 2]
    numpy_one_ratio = sorted(x["kane_numpy_us"] / x["rnea_loop_us"] for x in one)[len(one) // 2]
    numpy_big = sorted(x["kane_numpy_us"] / x["rnea_parallel1_us"] for x in ten)[len(ten) // 2]
    p1, pb = panda[1], panda[max(panda)]
    return {
        ("README.md", "figure bench_serial"):
            f"`python benchmarks/bench_serial.py --save` on this {r['cores']}-core machine "
            f"({r['date']}, Pinocchio {r['pinocchio']}), every robot of the tests: N = 1 in "
            f"{lo1:.2f}–{hi1:.2f} × one `pin.rnea` call (target ≤ 3 ×: {_met(hi1 <= 3)}; "
            f"NumPy: {numpy_one:.0f} µs, {numpy_one_ratio:.0f} ×, medians), N ≥ 10⁴ in "
            f"{lob:.2f}–{hib:.2f} × `rneaInParallel(1)` a sample (target ≤ 1 ×: "
            f"{_met(hib <= 1)}; NumPy {numpy_big:.1f} × at N = 10⁴, median); e.g. the Panda "
            f"{pb['kane_us']:.2f} µs a sample at N = {_count(pb['N'])} against "
            f"{pb['rnea_parallel1_us']:.2f} µs, one sample {p1['kane_us']:.1f} µs against "
            f"{p1['rnea_loop_us']:.1f} µs",
    }


#: The README's rows of benchmarks/bench.py's table: its label -> bench.py's variant.
BENCH_VARIANTS = {
    "floor: `rneaInParallel`, tree states given": "floor: rneaInParallel (1 thread, tree "
                                                  "states given)",
    "`kane` (default: checks, compiled)": "kane (default: checks, compiled)",
    "`kane`, no checks": "kane, no checks",
    "`kane`, NumPy backend": "kane, NumPy backend",
    "`kane`, 2 threads": "kane, 2 threads",
    "`kane`, thin-rod legs": "kane, thin-rod legs",
    "`kane-explicit`": "kane-explicit",
    "`rnea` reference path": "rnea reference path",
}


def read_summary(text: str) -> dict:
    """docs/bench/summary.md (benchmarks/bench.py's output) as ``{"date": ..., "tables":
    [{first cell: [other cells]}, ...]}``, its tables in order."""
    tables, current = [], None
    for line in text.splitlines():
        if not line.startswith("|"):
            current = None
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if current is None:
            current = {"": cells[1:]}
            tables.append(current)
        elif not set(cells[0]) <= set("- "):
            current[cells[0]] = cells[1:]
    date = re.search(r"^# Benchmark (.+)$", text, re.M)
    return {"date": date.group(1) if date else "?", "tables": tables}


def bench_rows(r: dict) -> dict:
    """benchmarks/bench.py's figures (docs/bench/summary.md): the README's table, its
    date, its targets, and docs/numerics.md's per-sample time."""
    times, errors, targets = r["tables"][:3]
    columns = times[""]

    def cell(variant, heading):
        return times[variant][columns.index(heading)]

    out = {("README.md", "figure bench-date"): r["date"]}
    for label, variant in BENCH_VARIANTS.items():
        if variant.startswith("floor"):
            error = "(no loop closure)"
        elif variant.startswith("rnea"):
            error = "—"
        else:
            error = errors[f"{variant} vs RNEA reference"][0]
            error += " (approximation)" if "thin-rod" in variant else ""
        out[("README.md", label)] = (
            f"| {label} | {cell(variant, 'N = 1').split(' (')[0]} | "
            f"{cell(variant, 'N = 10000')} | {cell(variant, 'N = 1e+06')} | "
            f"{cell(variant, '÷ floor (min)')} | {error} |")
    kane = "kane (default: checks, compiled)"
    at_1e5 = float(cell(kane, "÷ floor (min)").split(" / ")[1])
    verdicts = "; ".join(f"{target}: {v[0]} ({_met(v[1] == 'True')})"
                         for target, v in targets.items()
                         if target and v[1] in ("True", "False"))
    mpmath = next(v[0] for k, v in errors.items() if "mpmath" in k)
    out[("README.md", "figure bench-targets")] = (
        f"{verdicts}; issue 25's Kane ≤ 0.2 × floor at N = 10⁵: {at_1e5:.2f} "
        f"({_met(at_1e5 <= 0.2)}); Kane agrees with mpmath at 40 digits to {mpmath}")
    out[("docs/numerics.md", "figure bench-kane")] = (
        f"{cell(kane, 'N = 100000')} µs a sample, median (minimum), with the checks at "
        f"N = 10⁵ (`benchmarks/bench.py`, {r['date']})")
    return out
