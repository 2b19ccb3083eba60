"""The benchmark (``offshore-crane bench``) on tiny sizes: files, columns, errors.

Never asserts on speed (machines vary): only that times are finite and positive, and
that the error axis says what it should (exact paths exact, float32 at float32 level,
finite differences converging with their order).
"""

import csv
import math

import numpy as np
import pytest

from offshore_crane import bench

pytest.importorskip("pinocchio")
pytest.importorskip("matplotlib")


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("bench")
    cfg = bench.Config(sizes=(1, 10, 100), target_s=0.0, min_repeats=1, max_repeats=1,
                       error_n=100, extended_n=2, fd_duration=1.0, startup_runs=0,
                       profile=False, out=out)
    return bench.run_bench(cfg, log=lambda *a, **k: None), out


def _read(path):
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        return reader.fieldnames, list(reader)


def test_files_and_timing_columns(run):
    res, out = run
    for name in ("bench.csv", "errors.csv", "pareto.png", "summary.md"):
        assert (out / name).is_file() and (out / name).stat().st_size > 0, name
    assert (out / "pareto.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    columns, rows = _read(out / "bench.csv")
    assert tuple(columns) == bench.BENCH_COLUMNS
    seen = {(r["variant"], int(r["N"])) for r in rows}
    variants = bench.VARIANTS
    for v in variants:
        for n in (v.sizes or (1, 10, 100)):
            assert (v.name, n) in seen, (v.name, n)
    for r in rows:
        assert not r["skipped"]
        for key in ("median_us", "min_us", "max_us", "ratio_to_floor"):
            x = float(r[key])
            assert math.isfinite(x) and x > 0, (r["variant"], r["N"], key, x)
        assert float(r["min_us"]) <= float(r["median_us"]) <= float(r["max_us"])
        if r["variant"] == bench.FLOOR:
            assert float(r["ratio_to_floor"]) == 1.0
    peaks = [float(r["peak_MB"]) for r in rows if r["peak_MB"] != "nan"]
    assert len(peaks) == len(variants) and all(p >= 0 for p in peaks)


def test_error_axis(run):
    res, out = run
    columns, rows = _read(out / "errors.csv")
    assert tuple(columns) == bench.ERROR_COLUMNS
    err = {(r["variant"], r["reference"]): float(r["max_rel_error"]) for r in rows}
    for r in rows:
        assert math.isfinite(float(r["us_per_sample"])) and float(r["us_per_sample"]) > 0
    exact = [v.name for v in bench.VARIANTS if v.group == "exact" and v.name != "rnea path"]
    for name in exact:
        assert err[(name, "rnea path")] <= 1e-9, name
    assert err[("rnea path", "kane-explicit")] <= 1e-9
    assert 1e-9 < err[("kane float32 kernel", "rnea path")] < 1e-3
    assert err[("kane thin-rod", "rnea path")] > 1e-12      # an approximation, not exact
    assert err[("kane massless", "rnea path")] > err[("kane thin-rod", "rnea path")]
    extended = [e for (v, ref), e in err.items() if ref.startswith("extended precision")]
    if extended:                                             # mpmath reference available
        for name in exact:
            ref = next(ref for (v, ref) in err if v == name and ref.startswith("extended"))
            assert err[(name, ref)] <= 1e-12

    def fd(rate, order):
        return err[(f"CSV q @ {rate:g} Hz, FD{order}", "kane, analytic derivatives")]

    # 1 kHz: order 2 is truncation-bound; 4 and 6 reach the round-off floor of the
    # second difference (ε |q| / h² ≈ 1e-9 relative), so only 2 -> 4, 6 must drop.
    assert fd(1000, 2) > 3 * fd(1000, 4) and fd(1000, 2) > 3 * fd(1000, 6)
    assert fd(50, 2) > fd(50, 4) > fd(50, 6)                 # truncation-bound throughout
    points = [r for r in rows if r["primary"] == "True"]
    assert any(r["pareto"] == "True" for r in points)


def test_summary_states_targets(run):
    res, out = run
    text = (out / "summary.md").read_text(encoding="utf-8")
    assert "| target | limit | measured | met |" in text
    assert len(res.targets) == 5
    exact = next(t for t in res.targets if t["target"].startswith("default path exact"))
    assert exact["met"] is True
    startup = next(t for t in res.targets if t["target"] == "start-up")
    assert startup["met"] is None                            # not measured here
    for t in res.targets:
        assert t["met"] in (True, False, None)


def test_streaming_and_floor_equal_direct_calls(robot):
    from offshore_crane.dynamics import solve
    from offshore_crane.dynamics.rnea import tree_state, tree_torques

    ctx = bench.Context(robot, 11, stream=4)            # 11 samples in chunks of 4
    kane = next(v for v in bench.VARIANTS if v.name == "kane").make(ctx)
    X = solve(robot, ctx.q, ctx.qd, ctx.qdd).X
    np.testing.assert_array_equal(kane(11), X)
    floor = next(v for v in bench.VARIANTS if v.name == bench.FLOOR).make(ctx)
    qt, vt, at, _, _ = tree_state(robot, ctx.q, ctx.qd, ctx.qdd)
    np.testing.assert_allclose(floor(11).T, tree_torques(robot, qt, vt, at, bench.GRAVITY),
                               rtol=0, atol=1e-12)


def test_cli_registers_bench(tmp_path):
    from offshore_crane.__main__ import build_parser

    args = build_parser().parse_args(["bench", "--quick", "--out", str(tmp_path),
                                      "--only", "kane,rnea", "--no-startup"])
    assert args.run is bench.run
    cfg = bench.config_from_args(args)
    assert cfg.sizes == bench.QUICK_SIZES and max(cfg.sizes) <= 10_000
    assert cfg.out == tmp_path and cfg.only == ("kane", "rnea") and cfg.startup_runs == 0


def test_startup_measures_cold_processes(tmp_path):
    rows = bench.startup(bench.Config(startup_runs=1, out=tmp_path), log=lambda *a: None)
    assert rows[0]["command"].startswith("python -c")
    assert rows[0]["ratio_to_numpy"] == 1.0
    for r in rows:
        assert math.isfinite(r["median_s"]) and r["median_s"] > 0
