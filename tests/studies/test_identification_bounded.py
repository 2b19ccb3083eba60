"""Identification on logs of any length and of any robot it models (issue 36): the fit
block by block equals the fit of the whole record; identify's memory is checked before
it reads a log and stays within its estimate; every input is read before anything is
computed; a platform without the arm is excited and identified; the identified
description is a description like any other (consistent by the one rule the console and
the file share, exported, identified again); a cut-off near the Nyquist frequency and a
pipe are answered.

References: the fit of the whole record (tests/studies/test_identification_logs.py
checks it against 50-digit normal equations), Kane's forces, tracemalloc's count of the
bytes allocated. Every RNG is seeded. The hostile inputs' one-line refusals are in the
catalogue (tests/cli/cases_identify.py).
"""

import re

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.__main__ import main
from offshore_crane.conventions import QD_COLUMNS, QDD_COLUMNS, Q_COLUMNS
from offshore_crane.outputs.visual.motion import FORCE_COLUMNS
from offshore_crane.studies import identification as ident

HS = str(__import__("pathlib").Path(__file__).resolve().parents[2] / "models"
         / "descriptions" / "harib_srinivasan_2003.toml")


@pytest.fixture(scope="module")
def robot():
    return oc.load_robot()


@pytest.fixture(scope="module")
def base(robot):
    return ident.base_parameters(robot)


@pytest.fixture
def shared_base(monkeypatch, base):
    """identify's base parameters computed once for the module (they depend on the robot
    only)."""
    monkeypatch.setattr(ident, "base_parameters", lambda *a, **k: base)


def _write_log(path, robot, duration, rate, rates=True, seed=1, heavy=None):
    """A Fourier excitation's log (t, q [, rates], Kane's X of ``heavy`` or ``robot``) in
    the columns of ``simulate --out``; returns the number of samples."""
    ex = ident.fourier_excitation(robot, duration, rate, harmonics=5, seed=seed)
    X = oc.inverse_dynamics(heavy or robot, ex.q, ex.qd, ex.qdd)
    names = ("t_s",) + Q_COLUMNS + ((QD_COLUMNS + QDD_COLUMNS) if rates else ()) + FORCE_COLUMNS
    cols = [ex.t[:, None], ex.q] + ([ex.qd, ex.qdd] if rates else []) + [X]
    np.savetxt(path, np.hstack(cols), delimiter=",", header=",".join(names), comments="",
               fmt="%.17g")
    return len(ex.t)


def test_a_log_fitted_block_by_block_is_fitted_as_a_whole(robot, base):
    """The per-actuator triangles updated block by block (R of [R_prev; block]) give the
    whole record's fit: β, σ, the noise and the residual RMS to 1e-10 relative (two
    orthogonal factorisations of one matrix: round-off of a condition number ~1e4
    problem, measured ~1e-13), for blocks of 7 samples and for the regressor's blocks of
    a log (fit_log, blocks of 64), against fit_base on the whole regressor."""
    rng = np.random.default_rng(5)
    q, qd, qdd = ident.random_states(robot, 300, seed=4)
    R = ident.regressor(robot, q, qd, qdd)
    Yb = base.base_regressor(R.Y)
    X = R.Y @ R.pi + rng.normal(size=(300, 9)) * 0.1
    whole = ident.fit_base(Yb, X)
    tri = ident.Triangles(base.rank)
    for a in range(0, 300, 7):
        tri.add(Yb[a:a + 7], X[a:a + 7])
    fit = tri.fit()
    logged, head = ident.fit_log(robot, base, q, qd, qdd, X, block=64)
    for f in (fit, logged):
        assert np.allclose(f.beta, whole.beta, rtol=0, atol=1e-10 * np.abs(whole.beta).max())
        assert np.allclose(f.sigma, whole.sigma, rtol=1e-10)
        assert np.allclose(f.noise, whole.noise, rtol=1e-10)
        assert np.allclose(f.rms, np.sqrt(np.mean(whole.residual ** 2, axis=0)), rtol=1e-8)
        assert f.residual is None and f.excited == whole.excited
    assert head.names == R.names and head.Y.shape == (0, 9, 160)
    np.testing.assert_array_equal(head.pi, R.pi)
    with pytest.raises(oc.InputError, match=r"fit: X at sample 12 is not finite"):
        bad = X.copy()
        bad[12, 3] = np.nan
        ident.fit_log(robot, base, q, qd, qdd, bad, block=10)


def test_identify_refuses_beyond_the_memory_limit_before_computing(tmp_path, robot,
                                                                   monkeypatch, capsys):
    """OFFSHORE_CRANE_MEMORY_LIMIT below what identify needs: one line naming the size,
    the limit and what to do, exit 2, once the first chunk of the log is read (the fit
    never starts: base_parameters would raise)."""
    log = tmp_path / "log.csv"
    _write_log(log, robot, 1.0, 100.0)

    def never(*a, **k):
        raise AssertionError("computed before the memory check")

    monkeypatch.setattr(ident, "base_parameters", never)
    monkeypatch.setenv("OFFSHORE_CRANE_MEMORY_LIMIT", "1e8")
    out = tmp_path / "id.toml"
    assert main(["identify", "--log", str(log), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and re.search(
        r"--log .*log\.csv \(about 101 rows\) needs 350 MB of memory, over the limit 100 MB "
        r"\(OFFSHORE_CRANE_MEMORY_LIMIT\): give a shorter log", err), err
    assert not out.exists()


def test_identify_stays_within_its_memory_estimate(tmp_path, robot, base, shared_base):
    """identify on a 3 s log at 1 kHz without rates (the filter and the derivatives
    included): the bytes it allocates at their peak (tracemalloc, numpy's arrays counted)
    stay within the estimate its memory check uses (FIXED_BYTES + BYTES_PER_SAMPLE × N);
    and the fit holds one block of the regressor, never the whole: its peak on 3100
    samples exceeds its peak on 1100 by less than a tenth of what the 2000 more samples'
    Y would take (2000 × 9 × 160 doubles, 23 MB; measured 0.7 MB: the workspace check's
    per-sample flags). The 30-minute log's figure is benchmarks/identification_memory.py's."""
    import tracemalloc

    from offshore_crane.cli.logs import BYTES_PER_SAMPLE, FIXED_BYTES

    log = tmp_path / "log.csv"
    n = _write_log(log, robot, 3.0, 1000.0, rates=False)
    tracemalloc.start()
    try:
        assert main(["identify", "--log", str(log)]) == 0
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak <= FIXED_BYTES + BYTES_PER_SAMPLE * n, peak
    peaks = []
    for samples in (1100, 3100):
        ex = ident.fourier_excitation(robot, (samples - 1) / 1000.0, 1000.0, seed=8)
        X = oc.inverse_dynamics(robot, ex.q, ex.qd, ex.qdd)
        tracemalloc.start()
        try:
            ident.fit_log(robot, base, ex.q, ex.qd, ex.qdd, X)
            peaks.append(tracemalloc.get_traced_memory()[1])
        finally:
            tracemalloc.stop()
    assert peaks[1] - peaks[0] < 0.1 * 2000 * 9 * 160 * 8, peaks


def test_every_input_is_read_before_the_fit(tmp_path, robot, monkeypatch, capsys):
    """A missing --validate file, a --validate log of a hanging load and an --excite
    plan that does not span the log are refused before anything is computed (the fit's
    first step, base_parameters, would raise)."""
    log = tmp_path / "log.csv"
    _write_log(log, robot, 1.0, 100.0)
    monkeypatch.setattr(ident, "base_parameters", lambda *a, **k: pytest.fail("computed"))
    short = tmp_path / "plan.csv"
    short.write_text("t_s," + ",".join(Q_COLUMNS) + "\n" + "\n".join(
        f"{k / 100},0,0,0.5,0,0,0,0,0,0" for k in range(10)) + "\n")
    for extra, pattern in ((["--validate", str(tmp_path / "nope.csv")],
                            r"--validate .*nope\.csv: no such file"),
                           (["--excite", str(short)], r"--excite .*plan\.csv: it spans t = "
                            r"0\.\.0\.09 s, the log 0\.\.1 s: give the excitation the log ran")):
        assert main(["identify", "--log", str(log), *extra]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and re.search(pattern, err), err


def test_a_platform_without_the_arm_is_excited_and_identified(tmp_path, capsys):
    """The literature platform (no arm: six leg forces): excite plans an excitation that
    determines its 82 base parameters (q7..q9 kept 0; Table 1 leaves its workspace, so no
    comparison), and identify fits a log of it whose arm columns are nan, as id writes
    them: the six legs' noise, every body consistent, the written description identified
    again."""
    ex = tmp_path / "ex.csv"
    assert main(["excite", "--robot", HS, "--duration", "5", "--seeds", "1",
                 "--iterations", "3", "--out", str(ex)]) == 0
    out = capsys.readouterr().out
    assert "base regressor (82 parameters)" in out and "Table 1 leaves this robot's " \
        "workspace: no comparison" in out
    plan = oc.motion.trajectories.load(str(ex))
    assert np.all(plan.q[:, 6:] == 0.0)
    hs = oc.load_robot(HS)
    X = oc.inverse_dynamics(hs, plan.q, plan.qd, plan.qdd)
    assert np.isnan(X[:, :3]).all()                   # what id writes: no such actuator
    log = tmp_path / "hs.csv"
    names = ("t_s",) + Q_COLUMNS + QD_COLUMNS + QDD_COLUMNS + FORCE_COLUMNS
    np.savetxt(log, np.column_stack([plan.t, plan.q, plan.qd, plan.qdd, X]), delimiter=",",
               header=",".join(names), comments="", fmt="%.17g")
    written = tmp_path / "hs_id.toml"
    assert main(["identify", "--robot", HS, "--log", str(log), "--out", str(written)]) == 0
    out = capsys.readouterr().out
    assert "every body physically consistent: yes" in out
    assert re.search(r"^Fl6 ", out, re.M) and not re.search(r"^T1 ", out, re.M)
    assert main(["identify", "--robot", str(written), "--log", str(log)]) == 0
    assert "every body physically consistent: yes" in capsys.readouterr().out


def test_the_identified_description_is_a_description_like_any_other(tmp_path, robot,
                                                                    capsys, shared_base):
    """identify --out on an exact Table 1 log of a heavier robot: the console's verdict
    is the file's (ident.physical, the description's own inertia rule); the file is
    exported to MuJoCo, identified again (--robot id.toml --out) and exported again. A
    body left on the edge of consistency (arm_link2 a thin rod: a principal moment of 0,
    ±1e-17 once converted, which MuJoCo refuses) is written clipped within the
    description's tolerance: its smallest moment 1e-12 of their sum, the file says so,
    and MuJoCo takes it."""
    from offshore_crane.motion.trajectories import table1, time_grid
    from offshore_crane.studies.identification._description import body_parameters

    pytest.importorskip("mujoco")
    heavy = oc.load_robot(overrides={"platform.mass": 48.0, "arm.link1.mass": 4.6})
    t = time_grid(6.0, 50.0)
    q, qd, qdd = table1(t)
    log = tmp_path / "log.csv"
    names = ("t_s",) + Q_COLUMNS + QD_COLUMNS + QDD_COLUMNS + FORCE_COLUMNS
    np.savetxt(log, np.column_stack([t, q, qd, qdd, oc.inverse_dynamics(heavy, q, qd, qdd)]),
               delimiter=",", header=",".join(names), comments="", fmt="%.17g")
    first, second = tmp_path / "id.toml", tmp_path / "id2.toml"
    for robot_file, out in ((None, first), (first, second)):
        assert main(["identify", "--log", str(log), "--out", str(out)]
                    + (["--robot", str(robot_file)] if robot_file else [])) == 0
        assert "every body physically consistent: yes" in capsys.readouterr().out
        assert main(["export", "--robot", str(out), "--mjcf", str(tmp_path / "x.xml")]) == 0
    R = ident.regressor(robot, q[:1], qd[:1], qdd[:1])
    pi = R.pi.copy()
    cols = [j for j, n in enumerate(R.names) if n.startswith("arm_link2.")]
    link = robot.spec.arm["link2"].body
    a = float(np.abs(link.inertia).max())
    pi[cols] = body_parameters(link.mass, link.com, np.diag([a, a, 0.0]))
    assert ident.physical(pi)                          # within the description's tolerance
    edge = tmp_path / "edge.toml"
    edge.write_text(ident.identified_description(robot, R, pi, "edge"))
    assert "clipped to at least 1e-12 of their sum" in edge.read_text()
    lam = np.linalg.eigvalsh(oc.load_robot(edge).spec.arm["link2"].body.inertia)
    assert lam[0] >= 0.99e-12 * lam.sum() and lam[2] <= lam[0] + lam[1]
    assert main(["export", "--robot", str(edge), "--mjcf", str(tmp_path / "e.xml")]) == 0


def test_a_cutoff_near_nyquist_and_a_pipe_are_answered(tmp_path, robot, capsys,
                                                       shared_base):
    """--cutoff 499.999 on a 1 kHz log: the filter in second-order sections passes the
    positions as they are (the transfer function's polynomials put them 30× off, then
    outside the workspace) and the fit answers; the same log through a named pipe
    (written by a thread) is read once and answered alike."""
    import os
    import threading

    log = tmp_path / "log.csv"
    _write_log(log, robot, 1.5, 1000.0, rates=False,
               heavy=oc.load_robot(overrides={"platform.mass": 48.0}))
    assert main(["identify", "--log", str(log), "--cutoff", "499.999"]) == 0
    out = capsys.readouterr().out
    assert "every body physically consistent: yes" in out
    pipe = tmp_path / "pipe"
    os.mkfifo(pipe)
    writer = threading.Thread(target=lambda: pipe.write_bytes(log.read_bytes()))
    writer.start()
    assert main(["identify", "--log", str(pipe), "--cutoff", "499.999"]) == 0
    writer.join()
    piped = capsys.readouterr().out
    assert piped.split("\n", 1)[1] == out.split("\n", 1)[1]       # all but the file name
