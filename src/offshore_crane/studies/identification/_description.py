"""The identified robot as a description file: the nominal description with every body's
mass, centre of mass and inertia replaced by the identified ones, so that every other
command runs on the identified robot (``--robot identified.toml``).

Each body of the regressor is one rigid body of the URDF tree: where the URDF welds
bodies together (the arm's column to the platform, a welded payload to the slider), the
forces see only their sum. The file keeps the welded ones at their nominal values and
gives the carrier the identified sum minus them (parameters add: ``π_sum = π_a + π_b``,
in one frame); should that difference not be a physical body, the carrier takes the
whole sum and the welded body's mass is set to 0 (the file says so).

The six legs' parts are written per leg (``[legs.N.lower]``), each as identified.
"""

from __future__ import annotations

import numpy as np

from offshore_crane.studies.identification._consistent import origin_inertia
from offshore_crane.studies.identification._regressor import Regressor

#: The description's table of each regressor body (leg parts: per leg).
_TABLES = {"platform": "platform", "arm_link1": "arm.link1", "arm_link2": "arm.link2",
           "arm_slider": "arm.slider",
           **{f"leg{i}_{p}": f"legs.{i}.{p}" for i in range(1, 7) for p in ("lower", "upper")}}
#: Bodies the URDF welds to a regressor body: carrier -> (welded table, its Body getter).
_WELDED = {"platform": ("arm.column", lambda d: d.arm["column"][2] if d.arm else None),
           "arm_slider": ("payload", lambda d: d.payload)}
_INERTIA = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")


def body_parameters(mass: float, com, inertia) -> np.ndarray:
    """The ten standard parameters ``[m, m cx, m cy, m cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz]``
    (inertia about the frame's origin, Pinocchio's order) of a body given by its mass
    [kg], centre of mass ``(3,)`` [m] and inertia about it ``(3, 3)`` [kg·m²], one frame."""
    c = np.asarray(com, dtype=float)
    I = np.asarray(inertia, dtype=float) + mass * (c @ c * np.eye(3) - np.outer(c, c))
    return np.array([mass, *(mass * c), I[0, 0], I[0, 1], I[1, 1], I[0, 2], I[1, 2],
                     I[2, 2]])


def body_fields(p: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    """``(mass [kg], com (3,) [m], inertia about the com (3, 3) [kg·m²])`` of ten
    standard parameters with ``m > 0`` (inverse of :func:`body_parameters`)."""
    m = float(p[0])
    c = np.asarray(p[1:4]) / m
    return m, c, origin_inertia(p) - m * (c @ c * np.eye(3) - np.outer(c, c))


def physical(p: np.ndarray) -> bool:
    """True when every body of ``p (10 b,)`` is one a description file takes: a mass > 0
    and an inertia about its centre of mass that the description's rule accepts
    (:func:`offshore_crane.robot.description.geometry.inertia_problem`, tolerance
    :data:`~offshore_crane.conventions.INERTIA_RTOL`). The one verdict ``identify``
    prints and the rule its written description is read by; the moments it writes are
    then clipped to :data:`MOMENT_FLOOR` (:func:`clipped`)."""
    from offshore_crane.robot.description.geometry import inertia_problem

    for k in range(0, len(p), 10):
        if not p[k] > 0.0:
            return False
        m, _, I = body_fields(p[k:k + 10])
        if inertia_problem(m, I) is not None:
            return False
    return True


#: The principal moments of inertia written are at least this share of their sum, and
#: meet the triangle inequality: a body the consistent lift leaves on the edge of
#: consistency (a moment of 0, −2e-17 after the conversion to the centre of mass) is
#: written within the description's tolerance (INERTIA_RTOL, 1e-6) as a strict one, which
#: every command, MuJoCo's export included, takes.
MOMENT_FLOOR = 1e-12


def clipped(I: np.ndarray) -> tuple[np.ndarray, bool]:
    """``(I', changed)``: an inertia about the centre of mass ``(3, 3)`` [kg·m²] with its
    principal moments raised to :data:`MOMENT_FLOOR` of their sum and the largest
    lowered to the sum of the others where they are not (the axes kept)."""
    lam, V = np.linalg.eigh(0.5 * (I + I.T))
    new = np.maximum(lam, MOMENT_FLOOR * float(np.abs(lam).sum()))
    new[2] = min(new[2], new[0] + new[1])
    if np.array_equal(new, lam):
        return I, False
    return (V * new) @ V.T, True


def identified_description(robot, R: Regressor, pi: np.ndarray, header: str = "",
                           notes: dict | None = None) -> str:
    """The text of the identified robot's description file.

    Args:
        robot: The nominal robot (its description file and overrides are the base).
        R: A regressor of that robot (its ``names`` and nominal ``pi``).
        pi: ``(P,)`` the identified standard parameters (physically consistent: from
            :func:`~._consistent.consistent_parameters`), in ``R``'s order; friction
            parameters, if any, are not written (the format holds none).
        header: Comment lines for the top of the file.
        notes: ``{body name: text}`` written above the body's table.

    Returns:
        The TOML text; loading it gives a robot whose regressor parameters are ``pi``
        to round-off (tested).

    Raises:
        InputError: a body of ``pi`` that no description takes (:func:`physical`): no
            description is written of it.
    """
    from offshore_crane.errors import InputError
    from offshore_crane.robot.description import read_description, read_toml
    from offshore_crane.robot.description.loading import flat_values
    from offshore_crane.robot.description.writing import description_text

    spec = robot.spec
    raw = dict(flat_values(read_toml(spec.path, read_description(spec.path)), spec.path,
                           spec.overrides).raw)
    comments: dict = {}
    nominal = _nominal_bodies(spec)
    for body, table in _TABLES.items():
        cols = [j for j, n in enumerate(R.names) if n.split(".")[0] == body]
        if not cols:
            continue
        own = pi[cols]
        if not physical(own):
            raise InputError(f"identified description: {body}'s parameters are no rigid "
                             "body a description takes (its mass or its inertia about its "
                             "centre of mass): not written", name="pi")
        lines = [f"{body}: not identifiable alone (nominal mass {nominal[body][0]:.6g} kg): "
                 "the consistent split, nearest the nominal values, of the base "
                 "parameters the header lists"]
        if body in _WELDED:
            welded, get = _WELDED[body]
            part = get(spec)
            if part is not None and part.mass > 0:
                extra = R.pi[cols] - body_parameters(*nominal[body])
                rest = own - extra
                if physical(rest):
                    own = rest
                    lines.append(f"{welded} (welded to it) kept nominal: the forces see "
                                 "the sum")
                else:
                    _set_body(raw, welded, 0.0, np.zeros(3), np.zeros((3, 3)))
                    lines.append(f"{welded} (welded to it) included: the identified sum "
                                 f"minus its nominal values is no physical body; "
                                 f"{welded}.mass set to 0")
        m, c, I = body_fields(own)
        I, changed = clipped(I)
        if changed:
            lines.append(f"principal moments about the centre of mass clipped to at least "
                         f"{MOMENT_FLOOR:g} of their sum (the lift left it on the edge of "
                         "consistency; the change is within the description's tolerance)")
        _set_body(raw, table, m, c, I)
        comments[table] = "\n".join(lines + [(notes or {}).get(body, "")]).rstrip()
    return description_text(raw, comments, header)


def com_bounds(robot, R: Regressor) -> np.ndarray:
    """``(b, 3, 2)`` [m] the bounds the description sets on each body's centre of mass, in
    the order of ``R``'s bodies: a leg part's lies along the leg within the part (lower:
    0..length from P_i, upper: −length..0 from S_i); none elsewhere (``±inf``)."""
    bodies = list(dict.fromkeys(n.split(".")[0] for n in R.names if "." in n
                                and n.split(".")[1] == "m"))
    out = np.tile([-np.inf, np.inf], (len(bodies), 3, 1))
    for k, body in enumerate(bodies):
        if body.startswith("leg"):
            i, part = int(body[3]) - 1, body.split("_")[1]
            L = robot.spec.part_length[i, 0 if part == "lower" else 1]
            out[k, 2] = (0.0, L) if part == "lower" else (-L, 0.0)
    return out


def bounded_bodies(pi: np.ndarray, bounds: np.ndarray, R: Regressor,
                   rtol: float = 1e-6) -> list[str]:
    """The bodies of ``pi`` whose centre of mass lies on one of its ``bounds``
    (:func:`com_bounds`), to ``rtol`` of the bound's span (the lift keeps it strictly
    inside, by the barrier's share)."""
    c = np.stack([pi[k + 1:k + 4] / pi[k] for k in range(0, 10 * len(bounds), 10)])
    finite = np.isfinite(bounds).all(axis=2)
    span = np.where(finite, bounds[..., 1] - bounds[..., 0], 0.0)
    with np.errstate(invalid="ignore"):
        on = finite & ((np.abs(c - bounds[..., 0]) <= rtol * span)
                       | (np.abs(c - bounds[..., 1]) <= rtol * span))
    bodies = list(dict.fromkeys(n.split(".")[0] for n in R.names))
    return [bodies[k] for k in np.flatnonzero(on.any(axis=1))]


def _nominal_bodies(spec) -> dict:
    """``{regressor body: (mass, com, inertia)}`` of the nominal description's own
    values (without welded bodies)."""
    out = {"platform": (spec.platform.mass, spec.platform.com, spec.platform.inertia)}
    for i in range(6):
        for part, bodies in (("lower", spec.lower), ("upper", spec.upper)):
            b = bodies[i]
            out[f"leg{i + 1}_{part}"] = (b.mass, b.com, b.inertia)
    if spec.arm is not None:
        for k in ("link1", "link2", "slider"):
            b = spec.arm[k].body
            out[f"arm_{k}"] = (b.mass, b.com, b.inertia)
    return out


def _set_body(raw: dict, table: str, m: float, c: np.ndarray, I: np.ndarray) -> None:
    """Replace a body's mass, centre of mass and inertia in the flat values."""
    for key in [k for k in raw if k.startswith((f"{table}.com.", f"{table}.inertia."))]:
        del raw[key]
    raw[f"{table}.mass"] = float(m)
    raw.update({f"{table}.com.{a}": float(x) for a, x in zip("xyz", c)})
    entries = (I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[0, 2], I[1, 2])
    raw.update({f"{table}.inertia.{k}": float(v) for k, v in zip(_INERTIA, entries)})
