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

from dataclasses import dataclass

import numpy as np

from offshore_crane.errors import InputError


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
    """

    t_liftoff: float
    rehit: bool
    t_rehit: float
    rehit_speed: float
    clearance_min: float
    flight: object


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
             gravity=(0.0, 0.0, -9.81), substeps=None) -> LiftOff:
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

    Raises:
        InputError: a deck above the tip at the start, a bad deck function; the errors
            of :func:`~.elastic.elastic_inverse_dynamics` (started at lift-off).
    """
    from dataclasses import replace

    from offshore_crane.dynamics import backends
    from offshore_crane.dynamics.cable.elastic import elastic_inverse_dynamics
    from offshore_crane.dynamics.cable.grid import cable_robot
    from offshore_crane.dynamics.cable.hoist import hoist_grid
    from offshore_crane.dynamics.cable.tip import tip_positions

    robot = cable_robot(robot)
    t = np.asarray(trajectory.t, dtype=float)
    q, qd = np.asarray(trajectory.q, dtype=float), np.asarray(trajectory.qd, dtype=float)
    m = float(robot.hybrid.cable.mass[-1])
    g = float(np.linalg.norm(gravity))
    B = backends.NUMPY
    p_tip, v_tip = tip_positions(robot, q, qd)
    z, zd, zdd = _deck(deck, t)
    if not z[0] < p_tip[0, 2]:
        raise InputError(f"the deck at {z[0]:.4g} m is not below the tip "
                         f"({p_tip[0, 2]:.4g} m) at t = {t[0]:.4g} s", name="deck")
    L = (np.column_stack([np.full(len(t), robot.hybrid.cable_length), 0 * t, 0 * t])
         if hoist is None else hoist_grid(hoist, t))
    # resting on the deck below the tip's starting point: the load relative to the tip
    rho = np.column_stack([p_tip[0, 0] - p_tip[:, 0], p_tip[0, 1] - p_tip[:, 1],
                           z - p_tip[:, 2]])
    rhod = np.column_stack([-v_tip[:, 0], -v_tip[:, 1], zd - v_tip[:, 2]])
    with np.errstate(divide="ignore", invalid="ignore"):
        T, s, u = B.cable_tension(tuple(rho.T), tuple(rhod.T), L[:, 0], L[:, 1], float(ea),
                                  float(damping))
    T = np.where((s > 0) & (T > 0), T, 0.0)
    lifting = -T * u[2] >= m * (g + zdd)               # the deck's normal force ≤ 0
    if not lifting.any():
        return LiftOff(float("nan"), False, float("nan"), float("nan"), float("nan"), None)
    k = int(np.argmax(lifting))
    if k >= len(t) - 2:
        return LiftOff(float(t[k]), False, float("nan"), float("nan"), float("nan"), None)
    rest = replace(trajectory, t=t[k:], q=trajectory.q[k:], qd=trajectory.qd[k:],
                   qdd=trajectory.qdd[k:])
    flight = elastic_inverse_dynamics(
        robot, rest.q, rest.qd, rest.qdd, t=rest.t, ea=ea, damping=damping, hoist=hoist,
        reference=rest.reference if rest.source is not None else None,
        initial=rho[k], initial_velocity=rhod[k], gravity=gravity, substeps=substeps)
    zl, vzl = flight.payload[:, 2], flight.payload_velocity[:, 2]
    j, speed = first_contact(zl[1:], vzl[1:], z[k + 1:], zd[k + 1:])
    return LiftOff(float(t[k]), j is not None,
                   float("nan") if j is None else float(rest.t[1 + j]), speed,
                   float((zl[1:] - z[k + 1:]).min()), flight)


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
             substeps=None) -> tuple:
    """A hanging load lowered onto a moving deck: ``(t [s], relative vertical speed
    [m/s], result)`` at its first contact (NaN, NaN without contact), the speed the
    load's minus the deck's (negative: landing).

    Args:
        As :func:`lift_off`; ``initial``, ``initial_velocity``: the load from the tip and
        relative to it at the start (default: hanging still at its static stretch).
    """
    from offshore_crane.dynamics.cable.elastic import elastic_inverse_dynamics

    t = np.asarray(trajectory.t, dtype=float)
    z, zd, _ = _deck(deck, t)
    res = elastic_inverse_dynamics(
        robot, trajectory.q, trajectory.qd, trajectory.qdd, t=t, ea=ea, damping=damping,
        hoist=hoist, reference=trajectory.reference if trajectory.source is not None
        else None, initial=initial, initial_velocity=initial_velocity, gravity=gravity,
        substeps=substeps)
    k, speed = first_contact(res.payload[:, 2], res.payload_velocity[:, 2], z, zd)
    return (float("nan") if k is None else float(t[k])), speed, res
