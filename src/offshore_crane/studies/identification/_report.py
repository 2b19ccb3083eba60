"""What a log determines and what the prior decided: the identified base parameters with
their σ and meaning, the mass totals the forces see, and the motion a log lacks.

The forces determine only the base parameters ``β = K π`` (:mod:`._base`), and a given
log only those it excites (:attr:`~._fit.Fit.determined`); each body's own parameters are
the consistent split nearest the nominal values (:mod:`._consistent`), decided by the
prior wherever the forces do not reach. A mass total is identifiable when its vector lies
in K's row space: on the shipped robot the slider's mass and the sum of the legs' upper
parts, the platform and the two arm links (the lower parts pivot on the base: only
their first moments act).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from offshore_crane.dynamics.runtime import one_blas_thread

#: A determined base parameter is weak when its σ exceeds this share of its terms'
#: nominal size (the log barely excites it: its value leans on few samples).
WEAK = 0.1
#: Relative size below which a vector counts as in a span (row spaces, mass totals).
IN_SPAN = 1e-8
#: A first moment's scale is at least the body's mass times this length [m].
LENGTH = 1e-2
#: Words for each of a body's ten parameters, in Pinocchio's order.
KINDS = ("mass", "first moment m·c_x", "first moment m·c_y", "first moment m·c_z",
         "inertia Ixx", "product Ixy", "inertia Iyy", "product Ixz", "product Iyz",
         "inertia Izz")
#: The same in general terms.
GENERIC = ("masses",) + ("first moments",) * 3 + ("inertias",) * 6
#: The coordinates (0-based) whose motion moves each kind of body (regressor body name
#: prefix): the legs and the platform move with q1..q6, each arm body with its joint.
MOVERS = (("leg", range(6)), ("platform", range(6)), ("arm_link1", (6,)),
          ("arm_link2", (7,)), ("arm_slider", (8,)))
#: A coordinate whose rate's RMS is below this [m/s, rad/s] is still in a log.
STILL = 1e-6


class BaseRow(NamedTuple):
    """One base parameter as a log identified it.

    Attributes:
        name: ``"β21"``. value: its estimate. sigma: its standard deviation (``inf``:
            the log does not excite it). unit: its unit (its terms' unit).
        combination: ``"leg1_upper.m + … + arm_link2.m"``. meaning: in words.
        status: ``"determined"``, ``"weak"`` (σ above :data:`WEAK` of its size) or
            ``"not excited"``.
    """

    name: str
    value: float
    sigma: float
    unit: str
    combination: str
    meaning: str
    status: str


class MassTotal(NamedTuple):
    """A combination of masses the forces determine.

    Attributes:
        label: the bodies, e.g. ``"leg1_upper + … + arm_link2"``. nominal, identified:
            [kg]. sigma: [kg] (``inf``: this log does not excite it).
    """

    label: str
    nominal: float
    identified: float
    sigma: float


def base_rows(base, fit, R) -> list[BaseRow]:
    """The base parameters of a fit (``fit`` from :func:`~._fit.fit_base` on
    ``base.base_regressor(R.Y)``, ``R`` the log's regressor) as :class:`BaseRow`."""
    size = np.abs(base.K) @ _scales(R)
    rows = []
    for j, line in enumerate(base.describe()):
        name, combination = line.split(" = ", 1)
        status = ("not excited" if not fit.determined[j] else
                  "weak" if fit.sigma[j] > WEAK * size[j] else "determined")
        rows.append(BaseRow(name, float(fit.beta[j]), float(fit.sigma[j]),
                            R.units[base.independent[j]], combination,
                            _meaning(base.K[j], base.independent[j], R.names), status))
    return rows


@one_blas_thread()
def mass_totals(base, fit, R, pi: np.ndarray) -> tuple[list[MassTotal], list[str]]:
    """The mass totals the forces determine (a basis of them in reduced row echelon form,
    so each is a plain sum where one exists), nominal and identified (from ``pi (P,)``)
    with σ; and the bodies whose mass alone is not identifiable."""
    m = [j for j, n in enumerate(R.names) if n.endswith(".m")]
    bodies = [R.names[j].split(".")[0] for j in m]
    V = np.linalg.svd(base.K, full_matrices=False)[2]          # K's row space
    E = np.zeros((len(R.names), len(m)))
    E[m, np.arange(len(m))] = 1.0
    outside = E - V.T @ (V @ E)
    _, s, Vt = np.linalg.svd(outside)
    null = Vt[np.sum(s > IN_SPAN * max(s[0], 1.0)):]          # (d, b): mass totals
    totals = []
    for x in _rref(null):
        c = E @ x
        a = np.linalg.lstsq(base.K.T, c, rcond=None)[0]        # c·π = a·β
        excited = np.linalg.lstsq(fit.root.T, a, rcond=None)[0]
        seen = np.linalg.norm(fit.root.T @ excited - a) <= 1e-6 * np.linalg.norm(a)
        used = [(v, b) for v, b in zip(x, bodies) if abs(v) > 1e-9]
        label = (_bodies([b for _, b in used], " + ") if all(abs(v - 1) <= 1e-9 for v, _ in used)
                 else " + ".join(f"{v:.4g} · {b}" for v, b in used))
        totals.append(MassTotal(label, float(c @ R.pi), float(c @ pi),
                                float(np.sqrt(max(a @ fit.covariance @ a, 0.0)))
                                if seen else float("inf")))
    alone = [b for b, x in zip(bodies, np.eye(len(m)))
             if np.linalg.norm(x - null.T @ (null @ x)) > 1e-6]
    return totals, alone


def unexcited(rows: list[BaseRow], base, names, qd: np.ndarray | None = None) -> str | None:
    """One line naming the base parameters a log does not determine and the motion that
    would: the coordinates moving their bodies that the log keeps still (``qd (N, 9)``
    its rates), or, when it moves them all, the same coordinates more varied. None when
    it excites every one."""
    missing = [k for k, r in enumerate(rows) if r.status == "not excited"]
    if not missing:
        return None
    bodies = {names[j].split(".")[0] for k in missing
              for j in np.flatnonzero(np.abs(base.K[k]) > 1e-9)}
    movers = sorted({c for prefix, cs in MOVERS for c in cs
                     if any(b.startswith(prefix) for b in bodies)})
    still = [] if qd is None else [c for c in movers
                                   if np.sqrt(np.mean(qd[:, c] ** 2)) <= STILL]
    how = (f"move {_coordinates(still)}, which it keeps still" if still else
           f"move {_coordinates(movers)} through more varied speeds and accelerations")
    shown = ", ".join(rows[k].name for k in missing[:12]) + (
        f", … ({len(missing)} in all)" if len(missing) > 12 else "")
    return (f"the log does not determine {len(missing)} of the {len(rows)} base parameters "
            f"({shown}: its motion leaves them unseen or mixed with others, and the prior "
            f"decides what it leaves open): {how} (offshore-crane excite plans a motion "
            "that determines them all)")


def _coordinates(cs: list[int]) -> str:
    """``[0, 1, 2, 3, 4, 5, 6]`` → ``"q1..q6, q7"``."""
    from offshore_crane.conventions import ACTUATORS

    platform = [c for c in cs if c < 6]
    out = (["q1..q6"] if len(platform) == 6 else [f"q{c + 1}" for c in platform])
    return ", ".join(out + [f"q{c + 1} ({ACTUATORS[c - 6]})" for c in cs if c >= 6])


def _scales(R) -> np.ndarray:
    """``(P,)`` each standard parameter's nominal size: its body's mass, first moment
    (at least mass × :data:`LENGTH`) or largest inertia, by kind."""
    out = np.zeros(len(R.pi))
    for k in range(0, len(R.pi), 10):
        p = np.abs(R.pi[k:k + 10])
        out[k] = p[0]
        out[k + 1:k + 4] = max(p[1:4].max(), p[0] * LENGTH)
        out[k + 4:k + 10] = p[[4, 6, 9]].max()
    return out


def _meaning(row: np.ndarray, lead: int, names) -> str:
    """A base parameter's combination in words: its leading parameter's kind and body,
    and what the forces add to it."""
    terms = [j for j in np.flatnonzero(np.abs(row) > 1e-9)]
    kind = {j: KINDS[j % 10] for j in terms}
    body = {j: names[j].split(".")[0] for j in terms}
    others = [j for j in terms if j != lead]
    if not others:
        return f"{kind[lead]} of {body[lead]}"
    if all(kind[j] == kind[lead] and abs(row[j] - 1) < 1e-9 for j in others):
        return f"{kind[lead]} of {_bodies([body[j] for j in terms])} together"
    kinds = [k for k in ("masses", "first moments", "inertias")
             if any(GENERIC[j % 10] == k for j in others)]
    kinds = ", ".join(kinds[:-1]) + (" and " if len(kinds) > 1 else "") + kinds[-1]
    return (f"{kind[lead]} of {body[lead]}, with {kinds} of "
            f"{_bodies([body[j] for j in others])} (the forces see the sum)")


def _bodies(names: list[str], sep: str = ", ") -> str:
    """Bodies in few words: three or more legs' like parts as one ("legs 1, 3, 5
    upper"), joined by ``sep``."""
    names = list(dict.fromkeys(names))
    out = []
    for part in ("lower", "upper"):
        legs = [n for n in names if n.startswith("leg") and n.endswith(part)]
        if len(legs) > 2:
            out.append(f"legs {', '.join(n[3] for n in legs)} {part}")
            names = [n for n in names if n not in legs]
    return sep.join(out + names)


def _rref(A: np.ndarray) -> np.ndarray:
    """The reduced row echelon form of ``A (d, b)`` (partial pivoting), entries below
    1e-12 of a row's largest set to 0."""
    A = np.array(A, dtype=float)
    row = 0
    for col in range(A.shape[1]):
        if row == len(A):
            break
        p = row + int(np.argmax(np.abs(A[row:, col])))
        if abs(A[p, col]) <= 1e-9:
            continue
        A[[row, p]] = A[[p, row]]
        A[row] /= A[row, col]
        for i in range(len(A)):
            if i != row:
                A[i] -= A[i, col] * A[row]
        row += 1
    A[np.abs(A) <= 1e-12 * np.abs(A).max(axis=1, keepdims=True)] = 0.0
    return A
