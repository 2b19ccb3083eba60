"""Identification on any log (issue 35, item 4): the fit and its covariance from an
orthogonal factorisation, the consistent lift on exact and noisy logs of an ordinary
motion, what a log determines against what the prior decided, and ``identify`` on many
kinds of log without a traceback.

References: Kane's inverse dynamics of a perturbed "true" robot (shares only the URDF
with the regressor), the covariance by normal equations in 50-digit arithmetic (mpmath),
the true robot's own parameters. Every RNG is seeded.
"""

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.conventions import QD_COLUMNS, QDD_COLUMNS, Q_COLUMNS
from offshore_crane.errors import InputError
from offshore_crane.motion.trajectories import table1, time_grid
from offshore_crane.outputs.visual.motion import FORCE_COLUMNS
from offshore_crane.studies import identification as ident
from problems import true_robot


@pytest.fixture(scope="module")
def robot():
    return oc.load_robot()


@pytest.fixture(scope="module")
def base(robot):
    return ident.base_parameters(robot, n=100, seed=0)


@pytest.fixture(scope="module")
def truth(robot):
    return true_robot(robot)


def _regression(seed, condition, r=6, N=12, m=9):
    """A regressor ``(N, m, r)`` whose stacked matrix has the given condition number
    (singular values log-spaced), and forces with unit noise on its actuators."""
    rng = np.random.default_rng(seed)
    U = np.linalg.qr(rng.normal(size=(N * m, r)))[0]
    V = np.linalg.qr(rng.normal(size=(r, r)))[0]
    W = U @ np.diag(np.logspace(0, -np.log10(condition), r)) @ V.T
    beta = rng.normal(size=r)
    Y = W.reshape(N, m, r)
    return Y, Y @ beta + rng.normal(size=(N, m)) * np.linspace(0.5, 2.0, m), beta


def test_the_fit_and_its_covariance_match_a_50_digit_reference():
    """On a regression of condition number 1e7 (where the normal equations in doubles
    lose 14 digits), β̂ and its covariance equal the weighted normal equations solved
    in 50-digit arithmetic with the fit's own weights, to 1e-7 of each (a factorisation
    loses ~cond · 1e-16 = 1e-9; the bound leaves 100×); the covariance is symmetric
    positive semi-definite (its smallest eigenvalue ≥ −1e-12 of its largest) and
    ``rootᵀ root`` is the reference information matrix ``W_wᵀ W_w`` to 1e-12 of its
    largest entry (a product of the factor: round-off of the largest). The reported
    condition number is the weighted, column-scaled matrix's: within a factor 1.5 of the
    constructed 1e7 (the weights and the scaling move it)."""
    mp = pytest.importorskip("mpmath")
    mp.mp.dps = 50
    Y, X, _ = _regression(0, 1e7)
    fit = ident.fit_base(Y, X)
    w = 1.0 / fit.noise
    W = (Y * w[None, :, None]).reshape(-1, Y.shape[-1])
    y = (X * w).reshape(-1)
    A = mp.matrix(W.tolist())
    info = A.T * A
    cov = info ** -1
    beta = cov * (A.T * mp.matrix(y.tolist()))
    ref_cov = np.array(cov.tolist(), dtype=float)
    ref_beta = np.array(beta.tolist(), dtype=float).ravel()
    assert np.abs(fit.beta - ref_beta).max() <= 1e-7 * np.abs(ref_beta).max()
    assert np.abs(fit.covariance - ref_cov).max() <= 1e-7 * np.abs(ref_cov).max()
    assert np.allclose(fit.sigma, np.sqrt(np.diag(ref_cov)), rtol=1e-7, atol=0)
    lam = np.linalg.eigvalsh(fit.covariance)
    assert lam[0] >= -1e-12 * lam[-1]
    ref_info = np.array(info.tolist(), dtype=float)
    assert np.abs(fit.root.T @ fit.root - ref_info).max() <= 1e-12 * np.abs(ref_info).max()
    assert fit.excited == 6 and fit.determined.all() and np.isclose(
        fit.condition, 1e7, rtol=0.5)


def test_a_record_that_excites_only_some_parameters_is_fitted_along_them():
    """Two base parameters whose columns are zero (not excited) and two whose columns are
    equal (excited only as their sum): the others are fitted as without them (against
    least squares on the excited columns alone, to 1e-10: round-off of a condition
    number 1e3 problem with β ~ 1 is ~1e-13), the four have σ = inf and
    ``determined`` False, the sum of the equal pair is fitted, and nothing raises."""
    Y, X, _ = _regression(1, 1e3, r=6)
    Z = np.concatenate([Y, np.zeros(Y.shape[:2] + (2,)), Y[..., :1], Y[..., :1]], axis=2)
    fit = ident.fit_base(Z, X)
    alone = ident.fit_base(Y, X)
    assert fit.excited == 6
    assert list(fit.determined) == [False] + [True] * 5 + [False] * 4
    assert np.all(np.isinf(fit.sigma[~fit.determined]))
    assert np.allclose(fit.beta[1:6], alone.beta[1:6], rtol=0, atol=1e-10)
    assert np.isclose(fit.beta[0] + fit.beta[8] + fit.beta[9], alone.beta[0], atol=1e-10)
    with pytest.raises(InputError, match="the record excites none of the base parameters"):
        ident.fit_base(np.zeros_like(Y), X)
    bad = X.copy()
    bad[3, 2] = np.inf
    with pytest.raises(InputError, match="X at sample 3 is not finite"):
        ident.fit_base(Y, bad)


def test_an_exact_log_of_an_ordinary_motion_predicts_another_to_1e_6(robot, base, truth,
                                                                      tmp_path):
    """The issue's acceptance: the true robot (±20 % on every body) along Table 1 (the
    paper's smooth motion, not an optimised excitation; 10π s at 20 Hz), its exact q,
    q̇, q̈ and Kane's X: identified, lifted to a consistent robot and written as a
    description, which predicts the forces of a second motion (a 5-harmonic Fourier
    motion, 10 s) within 1e-6 of their peak (measured ~2e-11: the lift's barrier keeps
    the base parameters to ~1e-5 σ of an exact log's round-off σ). The identifiable
    mass totals equal the truth's to 1e-6 (relative), the single masses are reported
    as not identifiable alone."""
    t = time_grid(10 * np.pi, 20.0)
    q, qd, qdd = table1(t)
    X = oc.inverse_dynamics(truth, q, qd, qdd)
    R = ident.regressor(robot, q, qd, qdd)
    fit = ident.fit_base(base.base_regressor(R.Y), X)
    pi, misfit = ident.consistent_parameters(base.K, fit.beta, fit.root, R.pi,
                                             com_bounds=ident.com_bounds(robot, R))
    assert fit.determined.all() and ident.consistent(pi)
    path = tmp_path / "identified.toml"
    path.write_text(ident.identified_description(robot, R, pi, "exact log"))
    identified = oc.load_robot(path)
    other = ident.fourier_excitation(robot, 10.0, 50.0, harmonics=5, seed=2)
    X2 = oc.inverse_dynamics(truth, other.q, other.qd, other.qdd)
    got = oc.inverse_dynamics(identified, other.q, other.qd, other.qdd)
    assert np.abs(got - X2).max() <= 1e-6 * np.abs(X2).max()
    true_pi = ident.regressor(truth, q[:1], qd[:1], qdd[:1]).pi
    totals, alone = ident.mass_totals(base, fit, R, pi)
    assert {m.label for m in totals} == {
        "legs 1, 2, 3, 4, 5, 6 upper + platform + arm_link1 + arm_link2", "arm_slider"}
    masses = {n.split(".")[0]: true_pi[j] for j, n in enumerate(R.names) if n.endswith(".m")}
    for m in totals:
        want = sum(masses[b] for b in masses if b in m.label or (
            "upper" in b and "upper" in m.label))
        assert abs(m.identified - want) <= 1e-6 * want and m.sigma < 1e-6 * want
    assert "arm_slider" not in alone and "platform" in alone and "leg1_lower" in alone


def test_a_noisy_log_of_an_ordinary_motion_predicts_another_within_the_noise(
        robot, base, truth):
    """The issue's acceptance: Table 1 (two of its periods, 20π s, at 100 Hz) with noise
    of 1 % of each actuator's peak force on X and 1e-5 m / rad on q, no rates in the log
    (q̇, q̈ by log_derivatives at 5 Hz); the consistent robot predicts a second noisy log
    (a 5-harmonic Fourier motion, 20 s, the same noise and filtering) with an RMS error
    ≤ 1.2× the noise's per actuator (the issue's bound; measured 0.98-1.03×; the raw β̂,
    without consistency and prior, 1.0-1.4×: the directions Table 1 barely excites
    extrapolate; the nominal robot up to 4.7×). One period at 200 Hz gave up to 1.17×."""
    rng = np.random.default_rng(0)

    def log(q, qd, qdd, t, noise=None):
        X = oc.inverse_dynamics(truth, q, qd, qdd)
        noise = 0.01 * np.abs(X).max(axis=0) if noise is None else noise
        keep, qf, qdf, qddf = ident.log_derivatives(
            t, q + rng.normal(size=q.shape) * 1e-5, 5.0)
        return qf[keep], qdf[keep], qddf[keep], (X + rng.normal(size=X.shape) * noise)[keep], noise

    t = time_grid(20 * np.pi, 100.0)
    *first, X, noise = log(*table1(t), t)
    R = ident.regressor(robot, *first)
    fit = ident.fit_base(base.base_regressor(R.Y), X)
    pi, misfit = ident.consistent_parameters(base.K, fit.beta, fit.root, R.pi,
                                             com_bounds=ident.com_bounds(robot, R))
    assert ident.consistent(pi) and misfit <= 1.0
    other = ident.fourier_excitation(robot, 20.0, 100.0, harmonics=5, seed=2)
    *second, X2, _ = log(other.q, other.qd, other.qdd, other.t, noise)
    R2 = ident.regressor(robot, *second)
    ratio = np.sqrt(np.mean((R2.Y @ pi - X2) ** 2, axis=0)) / noise
    assert (ratio <= 1.2).all(), ratio


# ---------------------------------------------------------------- identify on any log
def _write_log(path, t, q, X, qd=None, qdd=None):
    """A run's CSV: ``t_s``, q1..q9, optionally the rates, and the forces."""
    cols = [t[:, None], q] + ([qd, qdd] if qd is not None else []) + [X]
    names = ("t_s",) + Q_COLUMNS + ((QD_COLUMNS + QDD_COLUMNS) if qd is not None else ()) \
        + FORCE_COLUMNS
    np.savetxt(path, np.hstack(cols), delimiter=",", header=",".join(names), comments="",
               fmt="%.17g")


def _kinds(robot, truth):
    """``{kind: (t, q, qd, qdd, X, rates in the log)}``: the logs the command must take.
    Motions: Table 1 (ordinary), parts of it held still, 4 s at 100 Hz unless said."""
    rng = np.random.default_rng(7)
    t = time_grid(4.0, 100.0)
    q, qd, qdd = table1(t)

    def held(coords):
        a, b, c = q.copy(), qd.copy(), qdd.copy()
        a[:, coords], b[:, coords], c[:, coords] = q[0, coords], 0.0, 0.0
        return a, b, c

    def kane(a, b, c):
        return oc.inverse_dynamics(truth, a, b, c)

    X = kane(q, qd, qdd)
    noise = 0.01 * np.abs(X).max(axis=0)
    fast = time_grid(2.0, 1000.0)
    qf, qdf, qddf = table1(fast)
    out = {
        "exact, rates given": (t, q, qd, qdd, X, True),
        "exact, no rates": (t, q, qd, qdd, X, False),
        "1 % noise, no rates": (t, q + rng.normal(size=q.shape) * 1e-5, qd, qdd,
                                X + rng.normal(size=X.shape) * noise, False),
        "huge noise (10× the forces)": (t, q, qd, qdd,
                                        X + rng.normal(size=X.shape) * 10 * noise * 100, True),
        "1 kHz, no rates": (fast, qf, qdf, qddf, kane(qf, qdf, qddf), False),
        "constant pose": (t, *held(list(range(9))), kane(*held(list(range(9)))), True),
        "single joint (q7) moving": (t, *held([0, 1, 2, 3, 4, 5, 7, 8]),
                                     kane(*held([0, 1, 2, 3, 4, 5, 7, 8])), True),
        "arm only": (t, *held(list(range(6))), kane(*held(list(range(6)))), True),
        "platform only": (t, *held([6, 7, 8]), kane(*held([6, 7, 8])), True),
        "zero forces": (t, q, qd, qdd, np.zeros_like(X), True),
        "very short, rates given": (t[:5], q[:5], qd[:5], qdd[:5], X[:5], True),
        "very short, no rates": (t[:60], q[:60], qd[:60], qdd[:60], X[:60], False),
    }
    return out


#: What each kind of log must give: exit status, then a pattern of its output (stdout
#: on 0, the one line of stderr on 2).
EXPECTED = {
    "exact, rates given": (0, r"every body physically consistent: yes"),
    "exact, no rates": (0, r"every body physically consistent: yes"),
    "1 % noise, no rates": (0, r"every body physically consistent: yes"),
    "huge noise (10× the forces)": (0, r"every body physically consistent: yes"),
    "1 kHz, no rates": (0, r"every body physically consistent: yes"),
    "constant pose": (0, r"does not determine 99 of the 100 base parameters .*: move q1\.\.q6, "
                         r"q7 \(T1\), q8 \(T2\), q9 \(Fs\), which it keeps still"),
    "single joint (q7) moving": (0, r"does not determine .*: move q1\.\.q6, q8 \(T2\), "
                                    r"q9 \(Fs\), which it keeps still"),
    "arm only": (0, r"does not determine .*: move q1\.\.q6, which it keeps still"),
    "platform only": (0, r"does not determine .*: move q7 \(T1\), q8 \(T2\), q9 \(Fs\), "
                         r"which it keeps still"),
    "zero forces": (2, r"every force of the record is 0 .*check the log's force columns"),
    "very short, rates given": (2, r"45 equations for 100 base parameters: give a longer"),
    "very short, no rates": (2, r"60 samples; the filter's ends take \d+ at each end"),
}


def test_identify_answers_every_kind_of_log_in_one_line_or_a_table(robot, truth, tmp_path,
                                                                   capsys, monkeypatch):
    """The issue's "no traceback on ≥ 10 kinds of log": 12 kinds (exact with and
    without rates, 1 % noise, huge noise, 1 kHz, a constant pose, one joint moving, the
    arm only, the platform only, zero forces, very short with and without rates) each
    give an answer (exit 0: the table, and for a log that leaves base parameters
    unexcited the one line naming them and the coordinates it keeps still) or one line
    on stderr (exit 2), never a traceback. The base parameters are computed once for
    the test (the same for every call: they depend on the robot only)."""
    import re

    from offshore_crane.__main__ import main

    shared = ident.base_parameters(robot)
    monkeypatch.setattr(ident, "base_parameters", lambda *a, **k: shared)
    for kind, (t, q, qd, qdd, X, rates) in _kinds(robot, truth).items():
        path = tmp_path / "log.csv"
        _write_log(path, t, q, X, *((qd, qdd) if rates else ()))
        written = kind in ("exact, no rates", "constant pose")   # --out: 2 kinds (~1 s each)
        out_toml = tmp_path / f"{len(kind)}.toml"
        status = main(["identify", "--log", str(path)]
                      + (["--out", str(out_toml)] if written else []))
        out, err = capsys.readouterr()
        want, pattern = EXPECTED[kind]
        assert status == want, (kind, err)
        assert "Traceback" not in out + err
        if status == 0:
            assert re.search(pattern, out), (kind, out)
            assert not written or oc.load_robot(out_toml).spec.platform.mass > 0
        else:
            assert err.count("\n") == 1 and re.search(pattern, err), (kind, err)
    assert len(EXPECTED) >= 10


def test_the_printed_table_separates_what_the_log_determines(tmp_path, capsys, robot,
                                                             truth):
    """The output and the written description say which base parameters the log
    determines (value ± σ, meaning), which mass totals it identifies, and that each
    body's own values are the prior's split ("not identifiable alone"), never a per-body
    mass as identified."""
    from offshore_crane.__main__ import main

    t = time_grid(10 * np.pi, 20.0)
    q, qd, qdd = table1(t)
    path = tmp_path / "log.csv"
    _write_log(path, t, q, oc.inverse_dynamics(truth, q, qd, qdd), qd, qdd)
    out_toml = tmp_path / "id.toml"
    assert main(["identify", "--log", str(path), "--out", str(out_toml)]) == 0
    out = capsys.readouterr().out
    assert "base parameters the log determines (value ± σ" in out
    assert "mass of arm_slider" in out and "inertia Izz of arm_link1, with masses of " \
        "arm_link2 (the forces see the sum)" in out
    assert "legs 1, 2, 3, 4, 5, 6 upper + platform + arm_link1 + arm_link2" in out
    assert "not identifiable alone (the prior's split" in out
    assert "masses [kg], nominal → identified" not in out          # the old per-body table
    text = out_toml.read_text()
    assert "# Determined by the log: 100" in text and "What the prior decided" in text
    assert "# platform: not identifiable alone (nominal mass 40 kg)" in text   # column: 5
