"""Tests of offshore_crane.motion.trajectories: Table 1, finite differences, CSV files, load()."""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np
import pytest

from offshore_crane.errors import TrajectoryError
from offshore_crane.motion.trajectories import (
    CSV_COLUMNS,
    DEFAULT_RATE,
    TABLE1_PERIOD,
    Trajectory,
    finite_difference,
    load,
    read_csv,
    table1,
    time_grid,
    write_csv,
)

PI = math.pi
HEADER = "t_s,q1,q2,q3,q4,q5,q6,q7,q8,q9"          # the bare names of earlier versions: read
UNITS_HEADER = "t_s,q1_m,q2_m,q3_m,q4_rad,q5_rad,q6_rad,q7_rad,q8_rad,q9_m"   # written


# --------------------------------------------------------------------------- time_grid

def test_constants():
    assert TABLE1_PERIOD == 10 * PI
    assert DEFAULT_RATE == 100.0
    assert ",".join(CSV_COLUMNS) == UNITS_HEADER


def test_time_grid_default():
    t = time_grid()
    # floor(10*pi*100) + 1 = 3141 + 1 samples, last one at 3141 / 100 s.
    assert t.shape == (3142,)
    assert t[0] == 0.0
    assert t[-1] == pytest.approx(31.41, abs=1e-12)  # arange(n)/rate: one rounding
    assert abs(t[-1] - 10 * PI) < 0.01
    np.testing.assert_allclose(np.diff(t), 0.01, rtol=1e-12)  # float64 division only


def test_time_grid_includes_both_ends_when_integral():
    # 1.0 s * 10 Hz = 10 steps exactly: 11 samples, last one exactly 1.0 s.
    t = time_grid(1.0, 10.0)
    assert t.shape == (11,)
    assert t[-1] == 1.0
    # 0.3 * 10 = 2.9999999999999996 in float64: the 1e-9 slack still gives 4 samples.
    assert time_grid(0.3, 10.0).shape == (4,)
    # 0.35 s at 10 Hz: 3.5 steps -> 4 samples, the last one (0.3 s) before the end.
    assert time_grid(0.35, 10.0)[-1] == pytest.approx(0.3, abs=1e-15)  # one rounding


@pytest.mark.parametrize("kwargs, name", [
    ({"duration": 0.0}, "duration"),
    ({"duration": -1.0}, "duration"),
    ({"duration": math.nan}, "duration"),
    ({"duration": math.inf}, "duration"),
    ({"duration": "long"}, "duration"),
    ({"rate": 0.0}, "rate"),
    ({"rate": -5.0}, "rate"),
    ({"rate": math.inf}, "rate"),
])
def test_time_grid_rejects_bad_arguments(kwargs, name):
    with pytest.raises(TrajectoryError, match=name) as info:
        time_grid(**kwargs)
    assert info.value.name == name


def test_time_grid_rejects_too_many_samples():
    with pytest.raises(TrajectoryError, match="more than the limit") as info:
        time_grid(1e6, 1e3)  # 1e9 samples
    assert info.value.name == "rate"


# ----------------------------------------------------------------------------- table1

def test_table1_at_zero_matches_hand_values():
    q, qd, qdd = table1(0.0)
    # Table 1 transcribed independently of the module's arrays, evaluated at t = 0.
    q_ref = [0.03, 0.02 * math.cos(0.5), 0.5 + 0.035, (PI / 9) * math.cos(0.2),
             (PI / 9) * math.cos(0.3), (PI / 9) * math.cos(0.4), PI, PI / 3, 0.0]
    qd_ref = [0.0, -0.02 * 0.4 * math.sin(0.5), 0.0, -(PI / 9) * 0.2 * math.sin(0.2),
              -(PI / 9) * 0.2 * math.sin(0.3), -(PI / 9) * 0.2 * math.sin(0.4), 0.0, 0.0,
              -0.15 * 0.2]
    qdd_ref = [-0.03 * 0.16, -0.02 * 0.16 * math.cos(0.5), -0.035 * 0.16,
               -(PI / 9) * 0.04 * math.cos(0.2), -(PI / 9) * 0.04 * math.cos(0.3),
               -(PI / 9) * 0.04 * math.cos(0.4), -PI * 0.25, -(PI / 3) * 0.25, 0.0]
    # A few float64 operations on values <= pi: error well below 1e-15 absolute.
    # (q9 = 0.15 cos(pi/2) is 9.2e-18 in float64, not exactly 0.)
    np.testing.assert_allclose(q, q_ref, rtol=0, atol=1e-15)
    np.testing.assert_allclose(qd, qd_ref, rtol=0, atol=1e-15)
    np.testing.assert_allclose(qdd, qdd_ref, rtol=0, atol=1e-15)
    # Some values spelled out as plain numbers, as a check of the transcription itself.
    assert q[2] == pytest.approx(0.535, abs=1e-15)
    assert q[6] == pytest.approx(3.141592653589793, abs=1e-15)
    assert qd[8] == pytest.approx(-0.03, abs=1e-15)
    assert qdd[7] == pytest.approx(-0.2617993877991494, abs=1e-15)


def test_table1_analytic_derivatives_match_central_differences():
    rng = np.random.default_rng(20240601)
    t = rng.uniform(0.0, TABLE1_PERIOD, size=64)
    q, qd, qdd = table1(t)

    def d1(f, d):  # 4th-order central first derivative, truncation d**4/30 * |f^(5)|
        return (f(t - 2 * d) - 8 * f(t - d) + 8 * f(t + d) - f(t + 2 * d)) / (12 * d)

    def d2(f, d):  # 4th-order central second derivative, truncation d**4/90 * |f^(6)|
        return (-f(t - 2 * d) + 16 * f(t - d) - 30 * f(t) + 16 * f(t + d) - f(t + 2 * d)) / (
            12 * d * d)

    def pos(x):
        return table1(x)[0]

    def vel(x):
        return table1(x)[1]

    # d = 1e-3: truncation <= 1e-12/30 * pi*0.5**5 ~ 3e-15, round-off ~ eps*pi*1.5/d ~ 1e-12.
    np.testing.assert_allclose(d1(pos, 1e-3), qd, rtol=0, atol=1e-10)
    np.testing.assert_allclose(d1(vel, 1e-3), qdd, rtol=0, atol=1e-10)
    # d = 1e-2: truncation <= 1e-8/90 * pi*0.5**6 ~ 5e-12, round-off ~ eps*pi*64/12/d**2 ~ 4e-11.
    np.testing.assert_allclose(d2(pos, 1e-2), qdd, rtol=0, atol=1e-9)
    # The derivatives are not trivially small: a sign error would be seen.
    assert np.abs(qd).max() > 1.0 and np.abs(qdd).max() > 0.5


def test_table1_scalar_and_vector_agree():
    rng = np.random.default_rng(7)
    t = np.concatenate([[0.0], rng.uniform(-5.0, 100.0, size=20)])
    q, qd, qdd = table1(t)
    assert q.shape == qd.shape == qdd.shape == (21, 9)
    for k in (0, 5, 20):
        qs, qds, qdds = table1(float(t[k]))
        assert qs.shape == qds.shape == qdds.shape == (9,)
        # Vectorised (SIMD) and scalar cos/sin may differ by an ulp or so: 1e-14 absolute
        # on values <= pi.
        np.testing.assert_allclose(qs, q[k], rtol=0, atol=1e-14)
        np.testing.assert_allclose(qds, qd[k], rtol=0, atol=1e-14)
        np.testing.assert_allclose(qdds, qdd[k], rtol=0, atol=1e-14)
    # A list and a 0-d array are accepted too.
    assert table1([0.0, 1.0])[0].shape == (2, 9)
    assert table1(np.float64(1.0))[0].shape == (9,)


def test_table1_periods():
    # 10 pi s is the period of the 0.2 and 0.4 rad/s columns; q7, q8 (0.5 rad/s) make
    # 2.5 cycles and change sign; the whole table repeats after 20 pi s.
    q0 = table1(0.3)[0]
    q_half = table1(0.3 + TABLE1_PERIOD)[0]
    q_full = table1(0.3 + 2 * TABLE1_PERIOD)[0]
    same = [0, 1, 2, 3, 4, 5, 8]
    # cos of arguments up to ~30 rad: argument rounding ~1e-15 rad, times amplitude <= pi.
    np.testing.assert_allclose(q_half[same], q0[same], rtol=0, atol=1e-13)
    np.testing.assert_allclose(q_half[[6, 7]], -q0[[6, 7]], rtol=0, atol=1e-13)
    np.testing.assert_allclose(q_full, q0, rtol=0, atol=1e-13)


def test_table1_rejects_non_finite_time():
    t = np.array([0.0, 0.1, np.nan, 0.3, np.inf])
    with pytest.raises(TrajectoryError, match="sample 2") as info:
        table1(t)
    assert info.value.index == 2 and info.value.name == "t"
    with pytest.raises(TrajectoryError, match="not finite"):
        table1(math.inf)
    with pytest.raises(TrajectoryError, match="1-D"):
        table1(np.zeros((2, 3)))
    with pytest.raises(TrajectoryError):
        table1("soon")


# ------------------------------------------------------------------ finite_difference

def _window(rate: float):
    """Table 1 on a uniform grid from t0 = pi/2 over about 4 pi s at ``rate`` [Hz].

    t0 = pi/2 puts both ends where sin(0.5 t) and cos(0.5 t) of the largest component
    (q7 = pi cos 0.5t) are both +-0.71, so the leading error term of the one-sided stencils
    does not vanish there (at t = 0 the odd derivatives of cos vanish and the boundary
    error would converge one order faster than the scheme's order).
    """
    n = int(round(4 * PI * rate))
    t = PI / 2 + np.arange(n + 1) / rate
    return (t,) + table1(t)


def _errors(order: int, rate: float):
    """Max |FD - analytic| over interior and boundary samples, for qd and qdd."""
    t, q, qd, qdd = _window(rate)
    fd1, fd2 = finite_difference(t, q, order=order)
    h = order // 2
    out = {}
    for label, fd, exact in (("qd", fd1, qd), ("qdd", fd2, qdd)):
        err = np.abs(fd - exact)
        out[label, "interior"] = err[h:-h].max()
        out[label, "boundary"] = max(err[:h].max(), err[-h:].max())
    return out


# Rates per order: the truncation error at the finer rate must stay far above round-off
# (~eps * |q| * sum|w| / h**2 ~ 1e-11 for qdd at 16 Hz). With Table 1's slow components
# (<= 0.5 rad/s), order 4 and 6 at 200/400 Hz already sit at round-off (1e-12 .. 1e-9)
# and show no convergence, so they are measured at coarser rates where omega*h <= 1/8.
CONVERGENCE_RATES = {2: (200.0, 400.0), 4: (8.0, 16.0), 6: (4.0, 8.0)}


@pytest.mark.parametrize("order", [2, 4, 6])
def test_finite_difference_convergence_order(order):
    coarse_rate, fine_rate = CONVERGENCE_RATES[order]
    coarse, fine = _errors(order, coarse_rate), _errors(order, fine_rate)
    for key in coarse:
        observed = math.log2(coarse[key] / fine[key])
        # Band +-0.3 on the observed order (ratio within 2**order * [0.81, 1.23]): the
        # next error term is O((omega*h)**2) smaller, up to ~0.2 in the exponent for the
        # one-sided stencils at these rates (measured 0.0 .. 0.2). A scheme one order
        # lower or higher is outside the band.
        assert abs(observed - order) <= 0.3, (key, observed)
        # Not round-off dominated: the finer error must be >= 100x the round-off, which is
        # at most eps * pi * sum|w| / h**2 ~ 2.2e-16 * 3.2 * 6 * 64 ~ 3e-13 (qdd, 8 Hz).
        assert fine[key] > 3e-11, (key, fine[key])


def test_finite_difference_exact_on_polynomials():
    # Every stencil of order p differentiates polynomials of degree <= p exactly.
    rng = np.random.default_rng(11)
    t = 0.2 + 0.05 * np.arange(30)
    for order in (2, 4, 6):
        coef = rng.normal(size=(order + 1, 3))  # 3 columns of degree-`order` polynomials
        q = np.stack([np.polyval(coef[:, j], t) for j in range(3)], axis=1)
        qd = np.stack([np.polyval(np.polyder(coef[:, j]), t) for j in range(3)], axis=1)
        qdd = np.stack([np.polyval(np.polyder(coef[:, j], 2), t) for j in range(3)], axis=1)
        fd1, fd2 = finite_difference(t, q, order=order)
        scale = np.abs(q).max()
        # Round-off only: eps * |q| * sum|w| / h**k with sum|w| <= ~300, h = 0.05.
        np.testing.assert_allclose(fd1, qd, rtol=0, atol=1e-11 * scale / 0.05)
        np.testing.assert_allclose(fd2, qdd, rtol=0, atol=1e-11 * scale / 0.05**2)


def test_finite_difference_shapes():
    t = np.arange(10) * 0.1
    q1 = np.sin(t)
    qd, qdd = finite_difference(t, q1, order=2)
    assert qd.shape == qdd.shape == (10,)
    q3 = np.column_stack([np.sin(t), np.cos(t), t])
    qd, qdd = finite_difference(t, q3, order=2)
    assert qd.shape == qdd.shape == (10, 3)
    # Column 2 is linear: derivative 1 and 0 up to round-off (eps * 1 / h**2 ~ 1e-14).
    np.testing.assert_allclose(qd[:, 2], 1.0, atol=1e-12)
    np.testing.assert_allclose(qdd[:, 2], 0.0, atol=1e-11)
    # Column-wise: same result as differentiating one column alone.
    np.testing.assert_array_equal(finite_difference(t, q3[:, 0], order=2)[0], qd[:, 0])


def test_finite_difference_minimum_length():
    t = np.arange(8) * 0.1
    finite_difference(t, t**2, order=6)  # 8 = 6 + 2 samples: enough
    with pytest.raises(TrajectoryError, match="at least 8 samples"):
        finite_difference(t[:7], t[:7] ** 2, order=6)
    with pytest.raises(TrajectoryError, match="at least 4 samples"):
        finite_difference(t[:3], t[:3], order=2)


def test_finite_difference_rejects_non_uniform_grid():
    t = np.arange(20) * 0.1
    finite_difference(t * (1 + 1e-9 * np.sin(np.arange(20))), np.sin(t))  # jitter 1e-9: ok
    t_bad = t.copy()
    t_bad[7] += 1e-4  # steps 6 and 7 are off by 1e-3 relative
    with pytest.raises(TrajectoryError, match="resample") as info:
        finite_difference(t_bad, np.sin(t_bad))
    assert info.value.index == 6 and info.value.name == "t"


def test_finite_difference_rejects_bad_input():
    t = np.arange(20) * 0.1
    q = np.sin(t)
    t_back = t.copy()
    t_back[5] = t_back[4]
    with pytest.raises(TrajectoryError, match="strictly increasing at sample 5") as info:
        finite_difference(t_back, q)
    assert info.value.index == 5
    with pytest.raises(TrajectoryError, match="order") as info:
        finite_difference(t, q, order=3)
    assert info.value.name == "order"
    with pytest.raises(TrajectoryError, match="shape"):
        finite_difference(t, q[:-1])
    with pytest.raises(TrajectoryError, match="1-D"):
        finite_difference(t[:, None], q)
    q_nan = q.copy()
    q_nan[9] = np.nan
    with pytest.raises(TrajectoryError, match="sample 9"):
        finite_difference(t, q_nan)


# ---------------------------------------------------------------------------- CSV files

def _write(tmp_path, text, name="traj.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def _rows(n=3):
    return "".join(f"{0.1 * i},{','.join(['0.5'] * 9)}\n" for i in range(n))


def test_csv_round_trip_is_exact(tmp_path):
    rng = np.random.default_rng(3)
    t = time_grid(2.0, 50.0)
    q = table1(t)[0] + rng.normal(scale=rng.uniform(1e-12, 1e3, size=9), size=(t.size, 9))
    q[0, 0] = 5e-324  # subnormal
    q[1, 1] = -1.7976931348623157e308
    path = tmp_path / "round.csv"
    write_csv(path, t, q)
    assert path.read_text().splitlines()[0] == UNITS_HEADER
    t2, q2 = read_csv(path)
    np.testing.assert_array_equal(t2, t)  # %.17g round-trips float64 exactly
    np.testing.assert_array_equal(q2, q)
    assert q2.shape == (t.size, 9) and q2.dtype == np.float64


def test_csv_tolerates_whitespace_and_blank_lines(tmp_path):
    header = " t_s , q1,q2 ,q3,q4,q5,q6,q7,q8,  q9 \n"
    path = _write(tmp_path, header + "\n0.0, 1,2,3,4,5,6,7,8,9\n\n 0.5 ,1,2,3,4,5,6,7,8, 9 \n\n")
    t, q = read_csv(str(path))
    np.testing.assert_array_equal(t, [0.0, 0.5])
    np.testing.assert_array_equal(q[1], np.arange(1.0, 10.0))


@pytest.mark.parametrize("text, match, name, index", [
    ("", "is empty", None, None),
    ("\n\n", "is empty", None, None),
    ("t_s,q1,q2,q3,q4,q5,q6,q7\n" + _rows(), r"missing column\(s\) q8_rad, q9_m", "q8_rad,q9_m",
     None),
    (HEADER + ",q10\n" + _rows(), r"unknown column\(s\) 'q10'", "q10", None),
    ("t_s,q1,q2,q3,q4,q5,q6,q7,q9,q8\n" + _rows(), "order", None, None),
    ("t_s,q1,q1,q2,q3,q4,q5,q6,q7,q8,q9\n" + _rows(), r"repeated column\(s\) q1_m", "q1_m", None),
    (HEADER + "\n0,1,2,3,4,5,6,7,8,9\n0.1,1,2,3\n", r"line 3: 4 cells, expected 10", None, 1),
    (HEADER + "\n0,1,2,3,4,5,6,7,8,9\n0.1,1,2,abc,4,5,6,7,8,9\n",
     r"line 3, column q3_m: 'abc' is not a number", "q3_m", 1),
    (HEADER + "\n0,1,2,3,4,5,6,7,8,9\n0.1,1,2,3,4,5,6,7,8,\n",
     r"line 3, column q9_m: '' is not a number", "q9_m", 1),
    (HEADER + "\n0,1,2,3,4,5,6,7,8,9\n0.1,1,2,3,4,nan,6,7,8,9\n",
     r"line 3, column q5_rad: 'nan' is not finite", "q5_rad", 1),
    (HEADER + "\n0,1,2,3,4,5,6,7,8,9\n0.1,1,2,3,4,5,6,7,-inf,9\n",
     r"line 3, column q8_rad: '-inf' is not finite", "q8_rad", 1),
    (HEADER + "\n0,1,2,3,4,5,6,7,8,9\n0.2,1,2,3,4,5,6,7,8,9\n0.1,1,2,3,4,5,6,7,8,9\n",
     r"line 4: time t_s = 0.1 s does not increase", "t_s", 2),
    (HEADER + "\n0,1,2,3,4,5,6,7,8,9\n0,1,2,3,4,5,6,7,8,9\n", "does not increase", "t_s", 1),
    (HEADER + "\n0,1,2,3,4,5,6,7,8,9\n", r"1 data row\(s\), at least 2", None, 0),
    (HEADER + "\n", r"0 data row\(s\), at least 2", None, None),
])
def test_read_csv_rejects_bad_files(tmp_path, text, match, name, index):
    path = _write(tmp_path, text)
    with pytest.raises(TrajectoryError, match=match) as info:
        read_csv(path)
    assert str(path) in str(info.value)  # every message names the file
    assert info.value.name == name
    assert info.value.index == index


def test_read_csv_missing_file(tmp_path):
    with pytest.raises(TrajectoryError, match="does not exist"):
        read_csv(tmp_path / "nope.csv")
    with pytest.raises(TrajectoryError, match="not a file"):
        read_csv(tmp_path)


def test_write_csv_rejects_bad_input(tmp_path):
    t = np.arange(3.0)
    with pytest.raises(TrajectoryError, match=r"\(N, 9\)"):
        write_csv(tmp_path / "a.csv", t, np.zeros((3, 8)))
    q = np.zeros((3, 9))
    q[1, 4] = np.inf
    with pytest.raises(TrajectoryError, match="sample 1"):
        write_csv(tmp_path / "a.csv", t, q)


# ------------------------------------------------------------------ Trajectory and load

def test_trajectory_dataclass():
    t = np.arange(4.0)
    z = np.zeros((4, 9))
    traj = Trajectory("x", t, z, z, z)
    assert len(traj) == 4
    with pytest.raises(dataclasses.FrozenInstanceError):
        traj.name = "y"
    with pytest.raises(TrajectoryError, match="qd must have shape"):
        Trajectory("x", t, z, z[:3], z)


def test_load_table1_default():
    traj = load()
    assert traj.name == "table1"
    assert len(traj) == 3142
    q, qd, qdd = table1(traj.t)
    np.testing.assert_array_equal(traj.q, q)
    np.testing.assert_array_equal(traj.qdd, qdd)


def test_load_table1_duration_and_rate():
    traj = load("table1", duration=2.0, rate=10.0)
    assert len(traj) == 21 and traj.t[-1] == 2.0
    assert len(load("table1", rate=50.0)) == math.floor(TABLE1_PERIOD * 50) + 1
    with pytest.raises(TrajectoryError, match="duration"):
        load("table1", duration=0.0)  # 0 is not taken as "default"


def test_load_csv(tmp_path):
    t = time_grid(TABLE1_PERIOD, 20.0)
    q, qd, qdd = table1(t)
    path = tmp_path / "wave.csv"
    write_csv(path, t, q)
    traj = load(str(path), fd_order=6)
    assert traj.name == "wave" and len(traj) == t.size
    np.testing.assert_array_equal(traj.q, q)
    # Order 6 at 20 Hz on Table 1: measured max error 3e-10 (qd) and 2e-9 (qdd, one-sided
    # ends); 1e-7 leaves margin yet fails for order 2 (error ~ 5e-4).
    np.testing.assert_allclose(traj.qd, qd, rtol=0, atol=1e-7)
    np.testing.assert_allclose(traj.qdd, qdd, rtol=0, atol=1e-7)
    assert len(load(path)) == t.size  # a Path works too; default order 4


def test_load_csv_rejects_duration_and_rate(tmp_path):
    path = tmp_path / "w.csv"
    write_csv(path, time_grid(1.0, 10.0), table1(time_grid(1.0, 10.0))[0])
    with pytest.raises(TrajectoryError, match="apply to table1 only"):
        load(path, duration=5.0)
    with pytest.raises(TrajectoryError, match="apply to table1 only"):
        load(path, rate=5.0)


def test_load_unknown_spec(tmp_path):
    message = ("unknown trajectory 'xyz': use 'table1' or the path of a CSV file with "
               "columns t_s,q1..q9")
    with pytest.raises(TrajectoryError, match=re.escape(message)):
        load("xyz")
    with pytest.raises(TrajectoryError, match="unknown trajectory"):
        load(str(tmp_path / "missing.csv"))
    with pytest.raises(TrajectoryError, match="unknown trajectory"):
        load("Table1")


def test_a_csv_with_the_bare_names_of_earlier_versions_reads_the_same(tmp_path):
    """Files written before the units went into the column names (q1..q9, qd1.., qdd1..)
    read to the same arrays as today's (q1_m.., qd1_m_s.., qdd1_m_s2..)."""
    from offshore_crane.motion import trajectories

    t = np.arange(30) / 100.0
    q, qd, qdd = trajectories.table1(t)
    new = tmp_path / "new.csv"
    trajectories.write_csv(new, t, q, qd, qdd)
    lines = new.read_text().splitlines()
    old_header = ",".join(["t_s", *(f"q{i}" for i in range(1, 10)),
                           *(f"qd{i}" for i in range(1, 10)),
                           *(f"qdd{i}" for i in range(1, 10))])
    assert lines[0].startswith("t_s,q1_m,") and "qd4_rad_s" in lines[0]
    old = tmp_path / "old.csv"
    old.write_text("\n".join([old_header, *lines[1:]]) + "\n")
    a, b = trajectories.read_csv(new, derivatives=True), trajectories.read_csv(
        old, derivatives=True)
    for x, y in zip(a, b):
        np.testing.assert_array_equal(x, y)


def _hermite_numpy(tk, qk, qdk, t):
    """The cubic Hermite interpolant as NumPy expressions over all rows at once (the
    text :func:`~offshore_crane.motion.trajectories.hermite` had before it was
    compiled): the reference the compiled rows must equal bit for bit."""
    i = np.clip(np.searchsorted(tk, t, side="right") - 1, 0, len(tk) - 2)
    h = (tk[i + 1] - tk[i])[:, None]
    s = ((t - tk[i])[:, None]) / h
    p0, p1, m0, m1 = qk[i], qk[i + 1], qdk[i] * h, qdk[i + 1] * h
    s2, s3 = s * s, s * s * s
    q = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 + \
        (s3 - s2) * m1
    dq = ((6 * s2 - 6 * s) * p0 + (3 * s2 - 4 * s + 1) * m0 + (-6 * s2 + 6 * s) * p1
          + (3 * s2 - 2 * s) * m1) / h
    ddq = ((12 * s - 6) * p0 + (6 * s - 4) * m0 + (-12 * s + 6) * p1 + (6 * s - 2) * m1) / h**2
    return q, dq, ddq


@pytest.mark.parametrize("m", [1, 9])
def test_hermite_compiled_rows_equal_the_numpy_expressions_bit_for_bit(m):
    """Non-uniform samples, times anywhere in the span (both ends, the samples
    themselves), a Fortran-ordered input: the same numbers; a quadratic in t is
    reproduced (value, rate, acceleration) to round-off; a time outside is refused."""
    from offshore_crane.motion.trajectories import hermite

    rng = np.random.default_rng(7)
    tk = np.cumsum(rng.uniform(0.01, 0.05, 300))
    qk, qdk = rng.normal(size=(300, m)), np.asfortranarray(rng.normal(size=(300, m)))
    t = np.concatenate([tk[[0, -1, 5, 17]], rng.uniform(tk[0], tk[-1], 2000)])
    for got, want in zip(hermite(tk, qk, qdk, t), _hermite_numpy(tk, qk, qdk, t)):
        np.testing.assert_array_equal(got, want)
    a, b, c = 0.3, -1.2, 2.5                        # q = a + b t + c t²: exact in a cubic
    q, qd, qdd = hermite(tk, (a + b * tk + c * tk**2)[:, None], (b + 2 * c * tk)[:, None], t)
    np.testing.assert_allclose(q[:, 0], a + b * t + c * t**2, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(qd[:, 0], b + 2 * c * t, rtol=1e-10, atol=1e-10)
    np.testing.assert_allclose(qdd[:, 0], 2 * c, rtol=1e-7)  # 1/h² amplifies round-off
    with pytest.raises(TrajectoryError, match="reach outside the trajectory"):
        hermite(tk, qk, qdk, np.array([tk[-1] + 1.0]))
