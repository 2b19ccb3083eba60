"""Lift-off and set-down: the critical instants of a lift from (or onto) a moving deck.

A payload resting on a deck leaves it when the cable's upward pull exceeds what holds it
there, ``−T u_z ≥ m (g + z̈_deck)`` (the deck's normal force reaches zero; ``u`` the cable's
direction tip → payload, base z up); from then on it flies on the elastic cable
(:func:`~.elastic.elastic_inverse_dynamics`, started with the deck's velocity). The risk
of a **re-hit** is the deck catching the load again: the first later sample where the
payload is at or below the deck. **Set-down** is the first contact of a lowered load, with
its vertical velocity relative to the deck.

The deck's horizontal motion is not modelled: the load rests below the tip's starting
position, and the deck is the height ``z_deck(t)`` under it (base frame).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from offshore_crane.errors import InputError
from offshore_crane.validation import as_gravity


@dataclass
class LiftOff:
    """A lift from a deck (:func:`lift_off`).

    Attributes:
        t_liftoff: The time the load leaves the deck [s] (NaN: it never does).
        rehit: True when the deck catches the load again after lift-off.
        t_rehit: The first such time [s] (NaN: none).
        rehit_speed: The load's vertical velocity relative to the deck there [m/s]
            (negative: closing).
        clearance_min: The smallest height of the load above the deck after lift-off [m].
        flight: The :class:`~.elastic.ElasticResult` from lift-off on (None: no lift-off).
        result: The whole record as one :class:`~.elastic.ElasticResult`: the load
            resting on the deck (its tension from the cable's stretch, X with that pull),
            then the flight.
    """

    t_liftoff: float
    rehit: bool
    t_rehit: float
    rehit_speed: float
    clearance_min: float
    flight: object
    result: object = None


@dataclass
class SetDown:
    """A load lowered onto a deck (:func:`set_down` in a scene).

    Attributes:
        t_contact: The first contact's time [s] (NaN: none).
        speed: The load's vertical velocity relative to the deck there [m/s]
            (negative: landing).
        after: The :class:`LiftOff` of the load from where it landed (its ``t_liftoff``:
            the cable lifting it again, a re-lift; NaN: it stays), or None.
    """

    t_contact: float
    speed: float
    after: object = None


def first_contact(z_load, vz_load, z_deck, vz_deck):
    """``(index, relative vertical speed [m/s])`` of the first sample where the load
    ``z_load`` is at or below the deck ``z_deck`` (arrays ``(N,)`` [m]), or ``(None, NaN)``:
    set-down, or a re-hit after lift-off."""
    below = z_load <= z_deck
    if not below.any():
        return None, float("nan")
    k = int(np.argmax(below))
    return k, float(vz_load[k] - vz_deck[k])


def lift_off(robot, trajectory, deck, *, ea: float, damping: float = 0.0, hoist=None,
             gravity=(0.0, 0.0, -9.81), substeps=None, limits: bool = True,
             checks: bool = True, thresholds=None, xy=None) -> LiftOff:
    """A load lifted off a moving deck by the winch (or the crane's motion).

    Args:
        robot: With a payload on a cable (``payload.mass``; ``cable_length`` the
            unstretched length when no winch).
        trajectory: The robot's motion (uniform times, an analytic source or samples).
        deck: ``deck(t (n,)) -> (z, ż, z̈)`` the deck's height under the load in the base
            frame [m, m/s, m/s²].
        ea, damping: The elastic cable's EA [N] and damping [N·s/m].
        hoist: A winch ``hoist(t) -> (L, L̇, L̈)`` (typically hauling in), or None.
        gravity: ``(3,)`` [m/s²], along −z.
        substeps: The flight's RK4 steps a sample (:func:`~.elastic.elastic_inverse_dynamics`).
        limits, checks, thresholds: As :func:`offshore_crane.inverse_dynamics`.
        xy: ``(2,)`` where the load rests, base frame [m]; None: below the tip's
            starting position.

    Raises:
        InputError: a deck above the tip at the start, a bad deck function; the errors
            of :func:`~.elastic.elastic_inverse_dynamics` (started at lift-off).
    """
    from offshore_crane.dynamics.cable.elastic import elastic_inverse_dynamics
    from offshore_crane.dynamics.cable.grid import cable_robot
    from offshore_crane.dynamics.cable.hoist import hoist_grid
    from offshore_crane.dynamics.cable.tip import tip_positions

    robot = cable_robot(robot)
    t = np.asarray(trajectory.t, dtype=float)
    q, qd = np.asarray(trajectory.q, dtype=float), np.asarray(trajectory.qd, dtype=float)
    m = float(robot.hybrid.cable.mass[-1])
    g = float(np.linalg.norm(gravity))
    p_tip, v_tip = tip_positions(robot, q, qd)
    z, zd, zdd = _deck(deck, t)
    if not z[0] < p_tip[0, 2]:
        raise InputError(f"the deck at {z[0]:.4g} m is not below the tip "
                         f"({p_tip[0, 2]:.4g} m) at t = {t[0]:.4g} s", name="deck")
    L = (np.column_stack([np.full(len(t), robot.hybrid.cable_length), 0 * t, 0 * t])
         if hoist is None else hoist_grid(hoist, t))
    # resting on the deck below the tip's starting point
    rho, rhod, T, s, u = _on_deck(p_tip, v_tip, p_tip[0, :2] if xy is None else xy, z, zd,
                                  L, ea, damping)
    lifting = -T * u[2] >= m * (g + zdd)               # the deck's normal force ≤ 0
    if xy is None:
        _check_resting(s[0], L[0, 0], ea, m, g, z[0], p_tip[0, 2])
    from offshore_crane.robot.kinematics.workspace import Thresholds

    checked = dict(limits=limits, checks=checks, thresholds=thresholds or Thresholds())
    resting = dict(rho=rho, rhod=rhod, T=T, s=s, L=L, gravity=gravity, ea=ea,
                   damping=damping, hoisted=hoist is not None, **checked)
    k = int(np.argmax(lifting)) if lifting.any() else len(t)
    if k >= len(t) - 2:                                 # it rests to the end
        return LiftOff(float(t[k]) if k < len(t) else float("nan"), False, float("nan"),
                       float("nan"), float("nan"), None,
                       replace(_resting(robot, trajectory, len(t), **resting),
                               airborne=(len(t), len(t))))
    rest = _tail(trajectory, k)
    flight = elastic_inverse_dynamics(
        robot, rest.q, rest.qd, rest.qdd, t=rest.t, ea=ea, damping=damping, hoist=hoist,
        reference=rest.reference if rest.source is not None else None,
        initial=rho[k], initial_velocity=rhod[k], gravity=gravity, substeps=substeps,
        **checked)
    zl, vzl = flight.payload[:, 2], flight.payload_velocity[:, 2]
    j, speed = first_contact(zl[1:], vzl[1:], z[k + 1:], zd[k + 1:])
    whole = replace(_joined(_resting(robot, trajectory, k, **resting), flight),
                    airborne=(k, None))
    return LiftOff(float(t[k]), j is not None,
                   float("nan") if j is None else float(rest.t[1 + j]), speed,
                   float((zl[1:] - z[k + 1:]).min()), flight, whole)


def _check_resting(s0: float, L0: float, ea: float, m: float, g: float, z0: float,
                   z_tip: float) -> None:
    """A lift-off starts with the load resting on the deck: the cable's stretch there
    ``s0`` [m] (unstretched length ``L0``) may not exceed its static stretch
    ``m g L0 / EA``, where it would carry the whole weight (the deck below where the load
    hangs, which no deck can hold it at: the cable starts stretched, the load flung).

    Raises:
        InputError: naming the deck's height, by how much it is too low and what to do.
    """
    static = m * g * L0 / float(ea)
    if s0 > static:
        hang = z_tip - L0 - static
        raise InputError(
            f"lift-off: the deck at {z0:.4g} m is {s0 - static:.3g} m below where the load "
            f"hangs ({hang:.4g} m), so the load cannot rest on it: raise deck_height above "
            f"{hang:.4g} m or lengthen the cable", name="deck")


def _on_deck(p_tip, v_tip, xy, z, zd, L, ea, damping):
    """A load resting on the deck at the horizontal position ``xy`` ``(2,)`` [m] (base
    frame), the deck at heights ``z``, rates ``zd`` ``(n,)``, under the tip at ``p_tip``,
    ``v_tip`` ``(n, 3)``: ``(ρ, ρ̇, T, s, u)`` the load from the tip [m] and relative to
    it [m/s], the cable's tension [N] (0 unless taut and pulling), stretch [m] and
    direction (the cable's formulas, :func:`offshore_crane.dynamics.sway.cable_tension`)."""
    from offshore_crane.dynamics import backends

    rho = np.column_stack([xy[0] - p_tip[:, 0], xy[1] - p_tip[:, 1], z - p_tip[:, 2]])
    rhod = np.column_stack([-v_tip[:, 0], -v_tip[:, 1], zd - v_tip[:, 2]])
    with np.errstate(divide="ignore", invalid="ignore"):
        T, s, u = backends.NUMPY.cable_tension(tuple(rho.T), tuple(rhod.T), L[:, 0],
                                               L[:, 1], float(ea), float(damping))
    return rho, rhod, np.where((s > 0) & (T > 0), T, 0.0), s, u


def _resting(robot, trajectory, k: int, *, rho, rhod, T, s, L, gravity, ea, damping,
             hoisted: bool, limits, checks, thresholds):
    """The first ``k`` samples of a lift with the load resting on the deck as an
    :class:`~.elastic.ElasticResult`: the cable's tension from its stretch, its pull
    ``T ρ/|ρ|`` on the tip in X (the kernel of the elastic cable's X); the deck holds the
    load, so no sway damping or drag acts on it there."""
    from offshore_crane.dynamics.cable.elastic import ElasticResult
    from offshore_crane.dynamics.cable.forces import kane_forces
    from offshore_crane.dynamics.cable.tip import tip_positions

    t = np.asarray(trajectory.t, dtype=float)[:k]
    q, qd, qdd = (np.ascontiguousarray(np.asarray(x, dtype=float)[:k])
                  for x in (trajectory.q, trajectory.qd, trajectory.qdd))
    pull = T[:k, None] * rho[:k] / np.linalg.norm(rho[:k], axis=1)[:, None]
    g = as_gravity(gravity)
    X, _, _ = kane_forces(robot, t, q, qd, qdd, np.zeros((k, 6)), g, limits, checks,
                          thresholds, P=pull, at=np.ascontiguousarray(rho[:k]))
    p_tip, v_tip = tip_positions(robot, q, qd)
    m = float(robot.hybrid.cable.mass[-1])
    return ElasticResult(
        t=t, q=q, qd=qd, qdd=qdd, X=X, position=rho[:k].copy(), velocity=rhod[:k].copy(),
        payload=p_tip + rho[:k], payload_velocity=v_tip + rhod[:k], tension=T[:k].copy(),
        stretch=np.asarray(s, dtype=float)[:k].copy(), force_tip=pull,
        hoist=np.ascontiguousarray(L[:k]) if hoisted else None, mass=m,
        length=float(robot.hybrid.cable_length), ea=float(ea), damping=float(damping),
        static_tension=m * float(np.linalg.norm(g)), step=float("nan"), substeps=0,
        refined=0, axial_period=float("nan"), sway_force=np.zeros((k, 3)),
        drag=np.zeros((k, 3)), sway_damping=float(robot.hybrid.sway_damping[0]),
        drag_area=float(robot.hybrid.drag_area), air_density=float(robot.hybrid.air_density))


def head(res, n: int):
    """The first ``n`` samples of an :class:`~.elastic.ElasticResult` (a set-down's
    record up to its contact: beyond it the deck would hold the load)."""
    return replace(res, **{name: getattr(res, name)[:n] for name in _per_sample(res)})


def _per_sample(res) -> list[str]:
    """The fields of an :class:`~.elastic.ElasticResult` that hold one row a sample."""
    from dataclasses import fields

    N = len(res.t)
    return [f.name for f in fields(res) if isinstance(getattr(res, f.name), np.ndarray)
            and getattr(res, f.name).ndim >= 1 and len(getattr(res, f.name)) == N]


def _joined(first, second):
    """Two :class:`~.elastic.ElasticResult` records one after the other: the per-sample
    arrays concatenated, the integration's figures the second's (the first rests)."""
    return replace(second, **{name: np.concatenate([getattr(first, name),
                                                    getattr(second, name)])
                              for name in _per_sample(second)})


def _deck(deck, t):
    try:
        z, zd, zdd = (np.asarray(x, dtype=float).reshape(len(t)) for x in deck(t))
    except (TypeError, ValueError) as exc:
        raise InputError(f"deck(t) must return three arrays (z [m], ż, z̈) of the times' "
                         f"length: {exc}", name="deck") from None
    if not (np.isfinite(z).all() and np.isfinite(zd).all() and np.isfinite(zdd).all()):
        raise InputError("deck(t) returned a non-finite value", name="deck")
    return z, zd, zdd


def set_down(robot, trajectory, deck, *, ea: float, damping: float = 0.0, hoist=None,
             initial=None, initial_velocity=(0.0, 0.0, 0.0), gravity=(0.0, 0.0, -9.81),
             substeps=None, limits: bool = True, checks: bool = True,
             thresholds=None) -> tuple:
    """A hanging load lowered onto a moving deck: ``(t [s], relative vertical speed
    [m/s], result)`` at its first contact (NaN, NaN without contact), the speed the
    load's minus the deck's (negative: landing); ``result`` the whole record: from the
    contact on the load rests where it landed, and :func:`lift_off` from there says
    whether the cable lifts it again (``result.event``: a :class:`SetDown`, also without
    a contact).

    Args:
        As :func:`lift_off`; ``initial``, ``initial_velocity``: the load from the tip and
        relative to it at the start (default: hanging still at its static stretch).
    """
    from offshore_crane.dynamics.cable.elastic import elastic_inverse_dynamics
    from offshore_crane.dynamics.cable.grid import cable_robot
    from offshore_crane.robot.kinematics.workspace import Thresholds

    robot = cable_robot(robot)
    checked = dict(limits=limits, checks=checks, thresholds=thresholds or Thresholds())
    t = np.asarray(trajectory.t, dtype=float)
    z, zd, _ = _deck(deck, t)
    _check_above(robot, trajectory, hoist, initial, ea, gravity, z[0])
    res = elastic_inverse_dynamics(
        robot, trajectory.q, trajectory.qd, trajectory.qdd, t=t, ea=ea, damping=damping,
        hoist=hoist, reference=trajectory.reference if trajectory.source is not None
        else None, initial=initial, initial_velocity=initial_velocity, gravity=gravity,
        substeps=substeps, **checked)
    k, speed = first_contact(res.payload[:, 2], res.payload_velocity[:, 2], z, zd)
    if k is None:
        return float("nan"), speed, replace(res, event=SetDown(float("nan"), speed))
    if k >= len(t) - 2:                      # at the record's end: nothing rests after it
        return float(t[k]), speed, replace(res, airborne=(0, k),
                                           event=SetDown(float(t[k]), speed))
    after = lift_off(robot, _tail(trajectory, k), deck, ea=ea, damping=damping, hoist=hoist,
                     gravity=gravity, substeps=substeps, xy=res.payload[k, :2], **checked)
    whole = replace(_joined(head(res, k), after.result), airborne=(0, k),
                    event=SetDown(float(t[k]), speed, after))
    return float(t[k]), speed, whole


def _check_above(robot, trajectory, hoist, initial, ea, gravity, z0: float) -> None:
    """A set-down lowers the load onto the deck: it starts above it (``initial`` [m]
    from the tip, or hanging at its static stretch; the deck at ``z0`` [m]).

    Raises:
        InputError: the load at or below the deck, naming by how much and what to do.
    """
    from offshore_crane.dynamics.cable.tip import tip_positions

    t0 = float(np.asarray(trajectory.t, dtype=float)[0])
    z_tip = float(tip_positions(robot, np.asarray(trajectory.q, dtype=float)[:1])[0][0, 2])
    if initial is not None:
        z_load = z_tip + float(np.asarray(initial, dtype=float).reshape(3)[2])
    else:
        from offshore_crane.dynamics.cable.hoist import hoist_grid

        L0 = (float(robot.hybrid.cable_length) if hoist is None
              else float(hoist_grid(hoist, np.array([t0]))[0, 0]))
        g = float(np.linalg.norm(gravity))
        z_load = z_tip - L0 * (1.0 + float(robot.hybrid.cable.mass[-1]) * g / float(ea))
    if not z_load > z0:
        raise InputError(
            f"set-down: the load starts {z0 - z_load:.3g} m below the deck (load at "
            f"{z_load:.4g} m, deck at {z0:.4g} m), so it cannot be lowered onto it: lower "
            f"deck_height below {z_load:.4g} m or shorten the cable", name="deck")


def _tail(trajectory, k: int):
    """The trajectory from sample ``k`` on."""
    return replace(trajectory, t=trajectory.t[k:], q=trajectory.q[k:], qd=trajectory.qd[k:],
                   qdd=trajectory.qdd[k:])
