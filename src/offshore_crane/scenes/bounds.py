"""A scene's physical bounds, checked when it is made (each named in its message): the
elastic cable's EA against its payload and the step rule at the scene's rate
(:func:`offshore_crane.dynamics.cable.elastic.check_cable`, :func:`~offshore_crane.
dynamics.cable.elastic.check_steps`), and a compensation's measurement delay against the
sea and the record (:func:`offshore_crane.simulation.compensation.check_delay`).
"""

from __future__ import annotations

import math

from offshore_crane.errors import InputError


def check_bounds(scene, fail) -> None:
    """Every bound that applies to ``scene``; ``fail(key, message)`` raises its
    :class:`~offshore_crane.errors.SceneError`."""
    if "ea" in scene.cable:
        _check_elastic(scene, fail)
    if "delay" in scene.control:
        delay = scene.control["delay"]
        try:
            check_delay(scene, delay, "delay")
        except InputError as exc:
            fail("control.delay", f"[control] {exc}")


def _check_elastic(scene, fail) -> None:
    """``[cable] ea`` against the payload and, where the scene fixes its rate (a sea,
    Table 1), the step rule's bound at the shortest length (the hoist column's)."""
    from offshore_crane.dynamics.cable.elastic import check_cable, check_steps
    from offshore_crane.motion.trajectories import DEFAULT_RATE
    from offshore_crane.scenes.keys import SEA_RATE

    ea, mass, length = scene.cable["ea"], scene.payload.mass, scene.payload.cable_length
    if scene.cable.get("winch") and scene.operation is not None:
        length = min(row[4] for row in scene.operation)
    rate = scene.rate or {"sea": SEA_RATE, "table1": DEFAULT_RATE}.get(scene.trajectory)
    try:
        check_cable(ea, scene.cable.get("damping", 0.0), mass)
        if rate is not None:
            check_steps(float(ea), mass, length, 1.0 / rate)
    except InputError as exc:
        fail("cable.ea", f"[cable] {str(exc).removeprefix('cable ')}")


def check_delay(scene, delay, name: str = "--delay") -> None:
    """A compensation's measurement delay [s] on ``scene``'s sea
    (:func:`offshore_crane.simulation.compensation.check_delay` with the sea's peak period
    at model scale; the record's span is checked where the record is made).

    Raises:
        InputError: naming ``name`` and the bound.
    """
    from offshore_crane.simulation.compensation import check_delay as check

    tp, scale = scene.sea.get("tp"), scene.sea.get("scale", 1.0)
    check(delay, None if tp is None else float(tp) / math.sqrt(float(scale)), name)
