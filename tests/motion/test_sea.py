"""Sea states (issue 12): spectra, RAO tables, synthesis, Froude scaling, workspace.

Independent references: closed forms (Pierson-Moskowitz, cos-2s moments), numerical
quadrature (scipy), Welch's PSD of the synthesised records, high-order finite
differences, the long-wave limit of a vessel riding the waves, and the same record built
along two routes (FFT and direct summation; two scales of one full-scale record).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.motion import sea
from offshore_crane.errors import InputError, SeaStateError, SeaWorkspaceError

G = 9.81                    # [m/s²], the vessel data's gravity (VERES header: 9.81)
LPP = 82.8                  # [m], supply vessel
REF_AFT_OF_MIDSHIP = 5.386  # [m], its RAO reference point (VERES xmtn, read by MSS)


def write_table(path, omega, headings, rao):
    """Write a RAO CSV; ``rao(dof_index, omega, heading)`` -> complex."""
    lines = [",".join(sea.RAO_COLUMNS)]
    for h in headings:
        for d, dof in enumerate(sea.DOFS):
            for w in omega:
                z = complex(rao(d, w, h))
                lines.append(f"{float(w)!r},{float(h)!r},{dof},{abs(z)!r},"
                             f"{math.atan2(z.imag, z.real)!r}")
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def unit_heave(tmp_path_factory):
    """Heave RAO 1 (phase 0) at every heading, nothing else; 0.02..6 rad/s covers all but
    3.7e-4 of the variance of a Tp = 8 s sea (PM tail 5/4 (ωp/ω)⁴ above 6 rad/s)."""
    path = tmp_path_factory.mktemp("rao") / "unit_heave.csv"
    return write_table(path, np.linspace(0.02, 6.0, 60), np.arange(0.0, 360.0, 30.0),
                       lambda d, w, h: 1.0 if d == 2 else 0.0)


# ------------------------------------------------------------------------------ spectra
@pytest.mark.parametrize("kind,gamma", [("pierson-moskowitz", None), ("jonswap", 1.0),
                                        ("jonswap", 2.0), ("jonswap", 3.3),
                                        ("jonswap", 7.0), ("jonswap", 10.0),
                                        ("jonswap", None)])
def test_zeroth_moment_is_hs2_over_16(kind, gamma):
    """m0 = Hs²/16 by adaptive quadrature to 1e-10 (the normalisation is numerical)."""
    from scipy.integrate import quad

    hs, tp = 3.0, 9.0
    wp = 2 * math.pi / tp
    f = lambda w: float(sea.spectrum(w, hs, tp, kind, gamma))   # noqa: E731
    parts = [quad(f, a, b, limit=400, epsabs=0.0, epsrel=1e-12)[0]
             for a, b in ((0.0, wp), (wp, 3 * wp), (3 * wp, np.inf))]
    assert sum(parts) == pytest.approx(hs * hs / 16.0, rel=1e-10)


def test_pierson_moskowitz_closed_form_and_jonswap_shape():
    hs, tp = 2.5, 8.0
    wp = 2 * math.pi / tp
    w = np.linspace(0.2, 4.0, 500)
    pm = 5 / 16 * hs**2 * wp**4 * w**-5 * np.exp(-1.25 * (wp / w) ** 4)
    np.testing.assert_allclose(sea.spectrum(w, hs, tp, "pierson-moskowitz"), pm, rtol=1e-13)
    for gamma in (2.0, 3.3, 5.0, 7.0):
        sigma = np.where(w <= wp, 0.07, 0.09)
        peak = gamma ** np.exp(-((w - wp) ** 2) / (2 * sigma**2 * wp**2))
        ratio = sea.spectrum(w, hs, tp, gamma=gamma) / (pm * peak)
        np.testing.assert_allclose(ratio, ratio[0], rtol=1e-12)     # a constant factor
        # DNV-RP-C205's approximate factor is within 2 % of the exact one up to gamma 7
        assert ratio[0] == pytest.approx(1 - 0.287 * math.log(gamma), rel=0.02)
    assert sea.jonswap_normalisation(1.0) == 1.0
    s = sea.spectrum(w, hs, tp)
    assert w[np.argmax(s)] == pytest.approx(wp, abs=w[1] - w[0])


def test_default_gamma_rule():
    assert sea.default_gamma(4.0, 7.0) == 5.0                       # Tp/√Hs = 3.5
    assert sea.default_gamma(1.0, 6.0) == 1.0                       # 6 >= 5
    assert sea.default_gamma(1.0, 4.0) == pytest.approx(math.exp(5.75 - 4.6))
    # continuous at 5; at 3.6 the standard's formula gives exp(1.61) = 5.003, not 5
    assert sea.default_gamma(1.0, 5.0 - 1e-9) == pytest.approx(1.0, rel=1e-8)
    assert sea.default_gamma(1.0, 3.6 + 1e-9) == pytest.approx(5.0, rel=1e-3)


# ----------------------------------------------------------------------------- RAO data
def test_shipped_supply_vessel_beam_sea_roll_peak():
    table = sea.vessel_raos("supply")
    assert table.values.shape == (36, 36, 6) and table.periodic
    for heading in (90.0, 270.0):                       # from starboard, from port
        w = np.linspace(table.omega[0], table.omega[-1], 4000)
        roll = np.abs(sea.vessel_raos()(w, [heading])[:, 0, 3])
        assert roll.max() == pytest.approx(0.054, rel=0.02)           # [rad/m]
        assert 2 * math.pi / w[np.argmax(roll)] == pytest.approx(9.5, abs=0.3)   # [s]


def test_shipped_supply_vessel_long_wave_signs():
    """At 0.105 rad/s (wavelength 5.6 km) the vessel rides the surface
    ζ = a cos(ωt − k(x cos β + y sin β)): heave 1; horizontal displacement a quarter
    period ahead along the propagation (surge −i cos β, sway −i sin β); slopes:
    pitch (bow down) = −∂ζ/∂x → +i k cos β, roll (starboard down) = ∂ζ/∂y → −i k sin β."""
    table = sea.vessel_raos("supply")
    w = table.omega[0]
    k = w * w / G
    for beta in (0.0, 90.0, 180.0, 270.0):
        H = table([w], [beta])[0, 0]
        c, s = math.cos(math.radians(beta)), math.sin(math.radians(beta))
        assert abs(H[2] - 1.0) < 0.01
        assert abs(H[0] - (-1j * c)) < 0.01 and abs(H[1] - (-1j * s)) < 0.01
        if abs(c) > 0.5:
            assert (H[4] / k).imag * c > 0.5
        if abs(s) > 0.5:
            assert -(H[3] / k).imag * s > 0.5


@pytest.mark.parametrize("heading,sign", [(180.0, 1), (0.0, -1)])
def test_head_seas_bow_rises_before_stern(heading, sign):
    """Head seas: the crest reaches the bow first, so the bow's vertical motion leads the
    stern's by about Lpp/c (c = g/ωp, 4.4 s at Tp 12 s); following seas: the stern
    leads. Measured by the lag of the cross-correlation's peak."""
    tp, rate = 12.0, 4.0
    bow = (LPP / 2 + REF_AFT_OF_MIDSHIP, 0.0, 0.0)
    stern = (-LPP / 2 + REF_AFT_OF_MIDSHIP, 0.0, 0.0)
    t = np.arange(int(3600 * rate)) / rate
    z_bow = sea.ship_motion(t, 3.0, tp, heading, point=bow, seed=3)[0][:, 2]
    z_stern = sea.ship_motion(t, 3.0, tp, heading, point=stern, seed=3)[0][:, 2]
    lags = np.arange(-60, 61)                                          # ±15 s
    corr = [np.dot(z_bow[60:-60], z_stern[60 + j:len(t) - 60 + j]) for j in lags]
    lag = lags[int(np.argmax(corr))] / rate                            # z_stern(t + lag)
    expected = LPP / (G / (2 * math.pi / tp))
    assert sign * lag > 0.0
    assert abs(lag) == pytest.approx(expected, rel=0.5)


def test_interpolation_real_imaginary_and_headings(tmp_path):
    """Linear in Re and Im (not amplitude and phase): halfway between 1 and −1 is 0;
    zero outside the frequency band; periodic in heading when the table goes round."""
    omega = np.array([0.5, 1.0])
    rao = lambda d, w, h: (1.0 if w == 0.5 else -1.0) * (1 + h / 90.0) if d == 2 else 0.0  # noqa
    full = sea.load_raos(write_table(tmp_path / "full.csv", omega, [0.0, 90.0, 180.0, 270.0],
                                     rao))
    assert full.periodic
    H = full([0.25, 0.75, 1.0, 1.5], [45.0, 315.0, -45.0, 720.0])[..., 2]
    assert H[1, 0] == pytest.approx(0.0) and H[0, 0] == 0.0 and H[3, 0] == 0.0
    assert H[2, 0] == pytest.approx(-1.5)                         # heading 45: between 1, 2
    assert H[2, 1] == pytest.approx(-2.5) and H[2, 2] == pytest.approx(-2.5)  # 270..360
    assert H[2, 3] == pytest.approx(-1.0)                         # 720 = 0
    half = sea.load_raos(write_table(tmp_path / "half.csv", omega, [0.0, 90.0, 180.0], rao))
    assert not half.periodic
    with pytest.raises(SeaStateError, match=r"heading 270 deg is not covered"):
        half([0.7], [270.0])
    with pytest.raises(SeaStateError, match=r"heading 200 deg is not covered"):
        sea.ship_motion(np.arange(100.0), 2.0, 8.0, 200.0, vessel=tmp_path / "half.csv")


GOOD = "omega_rad_s,heading_deg,dof,amplitude,phase_rad\n"


def _rows(omegas=(0.5, 1.0), heading=180, skip=None, amp=1.0, phase=0.0):
    out = []
    for w in omegas:
        for dof in sea.DOFS:
            if (w, dof) != skip:
                out.append(f"{w},{heading},{dof},{amp},{phase}")
    return out


@pytest.mark.parametrize("body,match", [
    (GOOD + "\n".join(_rows(skip=(1.0, "roll"))),
     r"line 12, column dof: missing dof roll for omega 1 rad/s, heading 180"),
    (GOOD + "\n".join(_rows()[:-1] + ["1.0,180,yaw,-0.5,0"]),
     r"line 13, column amplitude: -0.5 is negative"),
    (GOOD + "\n".join(_rows(omegas=(1.0, 0.5))),
     r"line 8, column omega_rad_s: omega 0.5 rad/s does not increase after 1 on line 2"),
    (GOOD + "\n".join(_rows() + ["0.5,180,heave,1,0"]),
     r"line 14: duplicate row: omega 0.5 rad/s, heading 180 deg, dof heave is already on "
     r"line 4"),
    (GOOD + "\n".join(_rows()[:3] + ["0.5,180,roll,abc,0"] + _rows()[4:]),
     r"line 5, column amplitude: 'abc' is not a number"),
    (GOOD + "\n".join(_rows()[:3] + ["0.5,180,roll,1,nan"] + _rows()[4:]),
     r"line 5, column phase_rad: 'nan' is not finite"),
    (GOOD + "\n".join(_rows(heading=180) + _rows(heading=90)[:6]),
     r"line 19: no rows for omega 1 rad/s at heading 90 deg"),
    (GOOD + "\n".join(_rows()[:3] + ["0.5,180,rool,1,0"] + _rows()[4:]),
     r"line 5, column dof: unknown dof 'rool'"),
    (GOOD.replace("phase_rad", "phase") + "\n".join(_rows()), r"line 1: header"),
    (GOOD + "\n".join(_rows()[:2] + ["0.5,180,heave,1"] + _rows()[3:]),
     r"line 4: 4 cells, expected 5"),
    (GOOD + "\n".join(r for r in _rows() if "yaw" not in r),
     r"line 11, column dof: no rows for dof yaw"),
    (GOOD + "\n".join(_rows(omegas=(0.5,))),
     r"line 7, column omega_rad_s: only one frequency"),
    ("", r"line 1: the file is empty"),
    (GOOD, r"line 1: the header has no data rows under it"),     # once an IndexError
])
def test_bad_rao_files(tmp_path, body, match):
    path = tmp_path / "bad.csv"
    path.write_text(body, encoding="utf-8")
    with pytest.raises(SeaStateError, match=str(path).replace("\\", r"\\") + ", " + match):
        sea.load_raos(path)


def test_non_utf8_rao_file(tmp_path):
    path = tmp_path / "latin1.csv"
    path.write_bytes((GOOD + "\n".join(_rows())).encode() + b"\n0.5,180,roll,1,0\xb0\n")
    with pytest.raises(SeaStateError, match=r"line 14, column phase_rad: byte 0xb0 is not "
                       r"UTF-8") as info:
        sea.load_raos(path)
    assert (info.value.line, info.value.column, info.value.path) == (14, "phase_rad",
                                                                      str(path))
    assert isinstance(info.value, InputError)


def test_unknown_vessel_and_missing_file(tmp_path):
    with pytest.raises(SeaStateError, match=r"unknown vessel 'tanker'"):
        sea.vessel_raos("tanker")
    with pytest.raises(SeaStateError, match=r"cannot read the RAO table"):
        sea.load_raos(tmp_path / "nope.csv")


# ---------------------------------------------------------------------------- synthesis
def test_unit_heave_rao_gives_the_wave_elevation(unit_heave):
    ship = sea.sea_state(2.5, 8.0, 150.0, 600.0, 10.0, vessel=unit_heave, seed=4)
    t = np.arange(6001) / 10.0
    heave = ship(t)[0][:, 2]
    eta = ship.elevation(t)
    # same components through two FFT calls: round-off of a sum of M terms
    np.testing.assert_allclose(heave, eta, rtol=0, atol=1e-13 * np.abs(eta).max())
    assert np.abs(ship(t)[0][:, [0, 1, 3, 4, 5]]).max() == 0.0


@pytest.mark.parametrize("kind", ["jonswap", "pierson-moskowitz"])
def test_four_std_of_heave_is_hs(unit_heave, kind):
    """3-hour records, 5 seeds: 4 std(heave) = Hs within 3 % (mean over seeds)."""
    hs, tp, rate = 2.5, 8.0, 2.0
    t = np.arange(int(3 * 3600 * rate)) / rate
    est = [4 * sea.ship_motion(t, hs, tp, 180.0, vessel=unit_heave, seed=s, kind=kind)[0][
        :, 2].std() for s in range(5)]
    assert np.mean(est) == pytest.approx(hs, rel=0.03)


def test_short_crested_sea_keeps_the_variance(unit_heave):
    """cos-2s spreading: weights sum to 1, E[cos θ] = s/(s+1) (closed form of the cos-2s
    distribution; midpoint rule with 360 bins, 1e-6), and with a heading-independent
    unit heave RAO the heave still has 4 std = Hs (mean over seeds, 3 %)."""
    offsets, weights = sea.spreading_directions(4.0, 360)
    assert weights.sum() == pytest.approx(1.0, abs=1e-15)
    assert np.dot(weights, np.cos(np.radians(offsets))) == pytest.approx(4 / 5, abs=1e-6)
    assert np.dot(weights, np.sin(np.radians(offsets))) == pytest.approx(0.0, abs=1e-15)
    t = np.arange(3 * 3600 * 2) / 2.0
    est = [4 * sea.ship_motion(t, 2.5, 8.0, 90.0, vessel=unit_heave, seed=s, spreading=4.0,
                               directions=24)[0][:, 2].std() for s in range(5)]
    assert np.mean(est) == pytest.approx(2.5, rel=0.03)


def test_welch_psd_matches_target_in_bands():
    """Welch (density per Hz, S_f = 2π S_ω(2πf)) of heave, roll, pitch of the supply
    vessel (bow quartering seas, 135 deg) against ∫ S |H|² dω in bands around the peak:
    10 % (a 6-hour record: 21 segments of 1024 s, ~100 bins per band)."""
    from scipy.signal import welch

    hs, tp, heading, rate = 3.0, 9.0, 135.0, 2.0
    t = np.arange(int(6 * 3600 * rate)) / rate
    motion = sea.ship_motion(t, hs, tp, heading, seed=11)[0]
    f, psd = welch(motion, fs=rate, nperseg=2048, axis=0)
    w_psd = 2 * math.pi * f
    psd_w = psd / (2 * math.pi)                        # per rad/s
    table = sea.vessel_raos("supply")
    wp = 2 * math.pi / tp
    grid = np.linspace(0.3 * wp, 3 * wp, 20001)
    target = sea.spectrum(grid, hs, tp)[:, None] * np.abs(table(grid, [heading])[:, 0]) ** 2
    for a, b in ((0.6, 0.9), (0.9, 1.2), (1.2, 1.6)):
        band = (w_psd >= a * wp) & (w_psd < b * wp)
        lo, hi = w_psd[band][0] - np.pi * rate / 2048, w_psd[band][-1] + np.pi * rate / 2048
        inside = (grid >= lo) & (grid <= hi)
        for dof in (2, 3, 4):
            measured = psd_w[band, dof].sum() * (2 * math.pi * rate / 2048)
            expected = np.trapezoid(target[inside, dof], grid[inside])
            assert measured == pytest.approx(expected, rel=0.10), (a, b, sea.DOFS[dof])


def test_response_spectrum_is_the_synthesis_variance_per_band():
    """Long-crested, deterministic amplitudes: |c_j|²/2 = S(ω_j) Δω |H_P(ω_j)|², so the
    Riemann sum of response_spectrum on the components' grid equals the record's
    variance over its period exactly (1e-12); at model scale λ the same sum in ω_m = ω√λ
    gives the translations' variance / λ² and the angles' unchanged."""
    kw = dict(hs=2.5, tp=8.0, heading_deg=110.0, point=(-12.0, 3.0, 9.0))
    ship = sea.sea_state(duration=900.0, rate=4.0, seed=1, **kw)
    target = sea.response_spectrum(ship.omega, **kw).sum(axis=0) * ship.d_omega
    np.testing.assert_allclose(target, ship.variance(), rtol=1e-12)
    lam = 25.0
    model = sea.response_spectrum(ship.omega * 5.0, scale=lam, **kw).sum(axis=0)
    model *= ship.d_omega * 5.0
    np.testing.assert_allclose(model, ship.variance() / np.r_[[lam**2] * 3, [1.0] * 3],
                               rtol=1e-12)


def test_fft_and_direct_paths_agree():
    """Same components, two summations: agree to round-off of ω t (ω ≤ 3.14 rad/s,
    t ≤ 3000 s: phases good to ~1e-12 rad), here 1e-11 of the record's peak; with a
    time offset, spreading, a point, and a sampling rate so low that components alias."""
    for rate, duration in ((10.0, 600.0), (0.4, 3000.0)):
        ship = sea.sea_state(2.5, 8.0, 150.0, duration, rate, point=(20.0, 5.0, 10.0),
                             spreading=4.0, directions=12, start=100.0, seed=2)
        t = 100.0 + np.arange(int(duration * rate) + 1) / rate
        fft = ship(t, method="fft")
        direct = ship(t[::7], method="direct")
        for a, b in zip(fft, direct):
            np.testing.assert_allclose(a[::7], b, rtol=0, atol=1e-11 * np.abs(b).max())
        assert ship.repetition_period > duration


def test_fft_in_threads_is_bit_for_bit_one_thread():
    """Threads share the FFT's 18 channels (each a transform of its own): the same
    numbers as one thread, on a record long enough to take the FFT path, with aliasing
    components; through the model-scale motion and a trajectory's reference too (its
    source takes the threads; a source without them ignores the count)."""
    ship = sea.sea_state(2.5, 8.0, 150.0, 600.0, 2.0, spreading=4.0, directions=12, seed=4)
    t = np.arange(1201) / 2.0
    one = ship(t, method="fft")
    for n in (2, 3, 64):
        assert all(np.array_equal(a, b) for a, b in zip(one, ship(t, method="fft",
                                                                  threads=n)))
    motion = sea.sea_motion(60.0, 50.0, 2.5, 8.0, 90.0, 20.0, oc.load_robot())
    traj = motion.trajectory()
    two = motion.trajectory(threads=2)
    for name in ("q", "qd", "qdd"):
        assert np.array_equal(getattr(traj, name), getattr(two, name)), name
    mid = 0.5 * (traj.t[1:] + traj.t[:-1])
    assert all(np.array_equal(a, b) for a, b in zip(traj.reference(mid),
                                                    traj.reference(mid, threads=2)))
    table = oc.motion.trajectories.load("table1")
    assert all(np.array_equal(a, b) for a, b in zip(table.reference(mid[:50]),
                                                    table.reference(mid[:50], threads=2)))
    with pytest.raises(InputError, match="threads must be a positive integer, got 0"):
        ship(t, method="fft", threads=0)


def test_analytic_derivatives_match_finite_differences():
    """8th-order central differences, h = 0.05 s: truncation (ωh)⁸/630 < 1e-9 for
    ω ≤ 3.14 rad/s, round-off ε/h² ~ 1e-13: agreement to 1e-7 of the peak."""
    ship = sea.sea_state(3.0, 7.0, 120.0, 1000.0, 5.0, point=(-15.0, 4.0, 12.0), seed=5)
    t = np.linspace(50.0, 950.0, 97)
    h = 0.05
    d1 = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])
    d2 = np.array([-1 / 560, 8 / 315, -1 / 5, 8 / 5, -205 / 72, 8 / 5, -1 / 5, 8 / 315,
                   -1 / 560])
    shifts = np.arange(-4, 5) * h
    x = np.stack([ship(t + s, method="direct")[0] for s in shifts])     # (9, n, 6)
    _, v, a = ship(t)
    np.testing.assert_allclose(np.tensordot(d1, x, 1) / h, v, rtol=0,
                               atol=1e-7 * np.abs(v).max())
    np.testing.assert_allclose(np.tensordot(d2, x, 1) / h**2, a, rtol=0,
                               atol=1e-7 * np.abs(a).max())


def test_point_transfer_is_the_small_angle_rigid_body_motion():
    t = np.arange(2000) / 4.0
    r = np.array([-20.0, 6.0, 9.0])
    m0, v0, a0 = sea.ship_motion(t, 2.5, 8.0, 60.0, seed=1)
    mp, vp, ap = sea.ship_motion(t, 2.5, 8.0, 60.0, seed=1, point=r)
    for base, at_p in ((m0, mp), (v0, vp), (a0, ap)):
        np.testing.assert_allclose(at_p[:, :3], base[:, :3] + np.cross(base[:, 3:], r),
                                   rtol=0, atol=1e-12 * np.abs(at_p).max())
        np.testing.assert_array_equal(at_p[:, 3:], base[:, 3:])
    # roll positive = starboard down: a point on the port side rises with roll
    assert np.cross([1.0, 0, 0], [0, 1.0, 0])[2] > 0


def test_seeds_are_reproducible_and_distinct():
    t = np.arange(1000) / 5.0
    a = sea.ship_motion(t, 2.5, 8.0, 90.0, seed=7)
    b = sea.ship_motion(t, 2.5, 8.0, 90.0, seed=7)
    c = sea.ship_motion(t, 2.5, 8.0, 90.0, seed=8)
    for x, y, z in zip(a, b, c):
        np.testing.assert_array_equal(x, y)
        assert np.abs(x - z).max() > 0.1 * np.abs(x).max()


def test_highpass_drops_components_only():
    """The high-pass keeps the other components unchanged (same phases): exact."""
    full = sea.sea_state(2.5, 8.0, 90.0, 1200.0, 5.0, seed=3)
    cut = sea.sea_state(2.5, 8.0, 90.0, 1200.0, 5.0, seed=3, highpass=0.4)
    assert cut.omega.min() >= 0.4 and full.omega.min() < 0.4
    kept = np.isin(full.harmonics, cut.harmonics)
    np.testing.assert_array_equal(full.coefficients[kept], cut.coefficients)
    assert kept.sum() == cut.harmonics.size


def test_record_does_not_repeat_and_times_outside_raise():
    ship = sea.sea_state(2.5, 8.0, 90.0, 100.0, 10.0)
    assert ship.repetition_period > 100.0
    ship(ship.repetition_period - 1e-6)                  # still inside
    with pytest.raises(SeaStateError, match=r"outside .* the span on which this sea does "
                       r"not repeat"):
        ship(ship.repetition_period + 1.0)


def test_sea_motion_refuses_times_beyond_its_record(robot):
    source = sea.sea_motion(10.0, 50.0, 2.5, 8.0, 90.0, 20.0, robot)
    source(10.0)
    with pytest.raises(SeaStateError, match=r"t\[0\] = 20 s is outside \[0, 10.24\] s, the "
                       r"model-scale span"):
        source([20.0])


# ---------------------------------------------------------------- Froude-scaled platform
def test_froude_scaling_law(robot):
    """One full-scale record at two scales (λ = 16 from duration D, rate R; λ = 1 from
    4 D, R/4): lengths / λ, times / √λ, angles equal; linear accelerations equal,
    angular rates × √λ, angular accelerations × λ. Exact up to round-off (1e-12)."""
    kw = dict(hs=2.5, tp=8.0, heading_deg=120.0, robot=robot, seed=9, check=False,
              point=(-10.0, 2.0, 8.0))
    m = sea.platform_trajectory(30.0, 20.0, scale=16.0, **kw)
    f = sea.platform_trajectory(120.0, 5.0, scale=1.0, **kw)
    np.testing.assert_allclose(m.t * 4.0, f.t, rtol=1e-15)
    home = np.array([0, 0, float(robot.parameters["home_height"])])

    def same(a, b):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * np.abs(b).max())

    same((m.q[:, :3] - home) * 16.0, f.q[:, :3] - home)
    same(m.qd[:, :3] * 4.0, f.qd[:, :3])
    same(m.qdd[:, :3], f.qdd[:, :3])
    same(m.q[:, 3:6], f.q[:, 3:6])
    same(m.qd[:, 3:6] / 4.0, f.qd[:, 3:6])
    same(m.qdd[:, 3:6] / 16.0, f.qdd[:, 3:6])
    assert np.abs(m.q[:, 6:]).max() == 0.0


def test_sea_motion_source_at_stage_times(robot):
    """The callable source at arbitrary times (direct summation) equals the record on its
    grid (FFT); the crane operation fills q7..q9."""
    ops = [[0.0, 0.0, 0.0, 0.0], [5.0, 1.0, -0.5, 0.1], [8.0, 1.0, -0.5, 0.1]]
    source = sea.sea_motion(10.0, 50.0, 2.5, 8.0, 90.0, 20.0, robot, operation=ops)
    traj = source.trajectory()
    k = np.array([0, 3, 77, 250, 499])
    q, qd, qdd = source(traj.t[k])
    for a, b in ((q, traj.q[k]), (qd, traj.qd[k]), (qdd, traj.qdd[k])):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * max(1.0, np.abs(b).max()))
    np.testing.assert_allclose(traj.q[:, 6:], oc.motion.operations.operation(traj.t, ops)[0])
    assert source(2.5)[0].shape == (9,)


def test_workspace_error_states_the_smallest_scale_that_fits(robot):
    kw = dict(hs=3.0, tp=8.0, heading_deg=90.0, robot=robot, seed=1)
    duration, rate, scale = 20.0, 20.0, 4.0
    with pytest.raises(SeaWorkspaceError, match=r"at sample \d+ .*; this full-scale record "
                       r"\(\d+.*s\) fits from scale \d") as info:
        sea.platform_trajectory(duration, rate, scale=scale, **kw)
    err = info.value
    assert err.joint.startswith("leg") and err.index >= 0 and err.scale == scale
    assert err.min_scale > scale and not err.rotations_only

    def replay(lam):            # the same full-scale record at scale lam
        f = math.sqrt(scale / lam)
        return sea.platform_trajectory(duration * f, rate / f, scale=lam, **kw)

    replay(err.min_scale)                                     # fits
    with pytest.raises(SeaWorkspaceError):
        replay(err.min_scale * (1 - 2 * sea.SCALE_RTOL))      # just below: does not


def test_workspace_error_when_rotations_alone_leave(robot, tmp_path):
    """A vessel that rolls 0.4 rad per metre of wave: in Hs 5 m the roll alone exceeds
    what the legs can follow, whatever the scale."""
    rolling = write_table(tmp_path / "rolling.csv", np.linspace(0.2, 3.0, 15), [90.0],
                          lambda d, w, h: 0.4 if d == 3 else 0.0)
    with pytest.raises(SeaWorkspaceError, match=r"no scale fits: the rotations alone") as info:
        sea.platform_trajectory(20.0, 20.0, 5.0, 9.0, 90.0, 30.0, robot, seed=1,
                                vessel=rolling)
    assert info.value.rotations_only and info.value.min_scale is None


# ----------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("kwargs,match", [
    (dict(hs=0.0), r"hs = 0.0 m must be > 0"),
    (dict(hs=-1.0), r"hs = -1.0 m must be > 0"),
    (dict(tp=0.0), r"tp = 0.0 s must be > 0"),
    (dict(gamma=0.5), r"gamma = 0.5 - must be >= 1"),
    (dict(hs=float("nan")), r"hs = nan is not finite"),
    (dict(tp=float("inf")), r"tp = inf is not finite"),
    (dict(heading_deg=float("nan")), r"heading = nan is not finite"),
    (dict(gamma=float("nan")), r"gamma = nan is not finite"),
    (dict(point=(0.0, float("nan"), 0.0)), r"point = .* is not finite"),
    (dict(kind="bretschneider"), r"unknown spectrum kind 'bretschneider'"),
    (dict(kind="pierson-moskowitz", gamma=3.3), r"gamma = 3.3 applies to the JONSWAP"),
    (dict(spreading=-2.0), r"spreading = -2.0 - must be > 0"),
    (dict(seed=1.5), r"seed must be an integer"),
    (dict(highpass=-0.1), r"highpass = -0.1 rad/s must be >= 0"),
    (dict(vessel="tanker"), r"unknown vessel 'tanker'"),
    (dict(hs=1e300), r"the spectrum overflows with hs = 1e\+300 m"),
])
def test_bad_sea_arguments(kwargs, match):
    args = dict(t=np.arange(50.0), hs=2.5, tp=8.0, heading_deg=90.0) | kwargs
    with pytest.raises(SeaStateError, match=match):
        sea.ship_motion(**args)


def test_bad_times_and_scales(robot):
    with pytest.raises(SeaStateError, match=r"t\[3\] = nan is not finite"):
        sea.ship_motion([0.0, 1.0, 2.0, float("nan")], 2.5, 8.0, 90.0)
    with pytest.raises(SeaStateError, match=r"not strictly increasing at sample 2"):
        sea.ship_motion([0.0, 1.0, 1.0], 2.5, 8.0, 90.0)
    with pytest.raises(SeaStateError, match=r"at least 2 times"):
        sea.ship_motion(0.0, 2.5, 8.0, 90.0)
    with pytest.raises(SeaStateError, match=r"scale = -20.0 - must be > 0"):
        sea.platform_trajectory(10.0, 50.0, 2.5, 8.0, 90.0, -20.0, robot)
    with pytest.raises(SeaStateError, match=r"scale = nan is not finite"):
        sea.platform_trajectory(10.0, 50.0, 2.5, 8.0, 90.0, float("nan"), robot)
    with pytest.raises(SeaStateError, match=r"omega\[1\] = -1.0 must be finite and >= 0"):
        sea.spectrum([1.0, -1.0], 2.5, 8.0)
    with pytest.raises(SeaStateError, match=r"a record of 1 s has frequency step"):
        sea.sea_state(2.5, 8.0, 90.0, 1.0, 10.0)
    with pytest.raises(SeaStateError, match=r"method 'fft' needs uniform times"):
        sea.sea_state(2.5, 8.0, 90.0, 100.0, 10.0)([0.0, 0.3, 1.0], method="fft")
