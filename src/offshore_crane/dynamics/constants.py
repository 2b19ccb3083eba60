"""The arrays Kane's formulas read, derived once per robot from its URDF.

Owned by the dynamics package (the robot object stays immutable): :func:`kane_constants`
keeps them in a per-robot cache.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass

import numpy as np

from offshore_crane.dynamics import native
from offshore_crane.dynamics.formulas import KaneConstants
from offshore_crane.dynamics.layout import FIELDS, field_view  # noqa: F401 (re-exported)
from offshore_crane.robot.kinematics.workspace import Limits, limits_of

_CACHE: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()
_CABLE_CACHE: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


@dataclass(frozen=True)
class RobotArrays:
    """What the kernels read of one robot.

    Attributes:
        kane: The formulas' constants (views into ``flat``).
        limits: The workspace limits (views into ``flat``).
        flat: Every float constant, in :data:`FIELDS` order, in one buffer: the compiled
            kernels receive ``(flat, layout, prismatic)`` and rebuild the views inside
            (passing three arrays costs ~0.2 µs; unboxing a tuple of 28 arrays ~3 µs).
        layout: ``(len(FIELDS), 4)`` int64: offset in ``flat`` and shape (padded with 1).
        prismatic: ``(na,)`` bool, the arm joints' types.
    """

    kane: KaneConstants
    limits: Limits
    flat: np.ndarray
    layout: np.ndarray
    prismatic: np.ndarray


def build(model) -> RobotArrays:
    """Constants of :class:`~offshore_crane.robot.hybrid.HybridModel` ``model``.

    The leg links share the leg's angular velocity and acceleration (the joint between
    them is prismatic), so their central inertias are summed in the leg frame
    (``leg_I``). The thin-rod approximation keeps the transverse inertia
    ``(Ixx + Iyy) / 2`` of that sum (exact for links symmetric about the leg axis) and
    the centres of mass projected on the axis.
    """
    arm = model.arm
    f = np.ascontiguousarray
    leg_I = model.lower_inertia + model.upper_inertia
    RU = model.R_base_U
    kane = KaneConstants(
        plat_m=float(model.platform_mass), plat_c=f(model.platform_com),
        plat_I=f(model.platform_inertia), n_arm=int(arm.n), arm_t=f(arm.p_parent_joint),
        arm_Ro=f(arm.R_parent_joint), arm_axis=f(arm.axis),
        arm_prism=f(arm.prismatic, dtype=np.bool_), arm_m=f(arm.mass), arm_c=f(arm.com),
        arm_I=f(arm.inertia), leg_s=f(model.p_platform_S), leg_P=f(model.p_base_P),
        leg_X=f(RU[:, :, 0]), leg_Y=f(RU[:, :, 1]), leg_Z=f(RU[:, :, 2]),
        lo_m=f(model.lower_mass), lo_c=f(model.lower_com), up_m=f(model.upper_mass),
        up_c=f(model.upper_com), leg_I=f(leg_I),
        thin_It=f(0.5 * (leg_I[:, 0, 0] + leg_I[:, 1, 1])), lo_cz=f(model.lower_com[:, 2]),
        up_cz=f(model.upper_com[:, 2]),
        L=float(np.linalg.norm(model.p_platform_S, axis=1).mean()))
    return pack(kane, limits_of(model))


def pack(kane: KaneConstants, limits: Limits) -> RobotArrays:
    """``kane`` and ``limits`` packed into one buffer (:attr:`RobotArrays.flat`, its
    ``layout``), the constants then views into it: what the compiled kernels receive."""
    values = {**kane._asdict(), "lim_arm": limits.arm, "lim_stroke": limits.stroke,
              "lim_ujoint": limits.ujoint}
    parts = [np.asarray(values[name], dtype=float) for name in FIELDS]
    layout = np.zeros((len(FIELDS), 4), dtype=np.int64)
    offset = 0
    for i, x in enumerate(parts):
        shape = x.shape + (1,) * (3 - x.ndim)
        layout[i] = (offset, *shape)
        offset += x.size
    flat = np.concatenate([x.ravel() for x in parts])
    views = {name: field_view(flat, o, x.shape)
             for name, x, (o, *_) in zip(FIELDS, parts, layout)}
    kane = kane._replace(**{k: v for k, v in views.items() if k in KaneConstants._fields})
    limits = Limits(views["lim_arm"], views["lim_stroke"], views["lim_ujoint"])
    native.remember(kane)            # its structure's template for the compiled passes
    return RobotArrays(kane, limits, flat, layout, kane.arm_prism)


def robot_arrays(robot) -> RobotArrays:
    """:func:`build` of ``robot.hybrid``, cached per robot.

    Raises:
        ModelError: the robot's payload hangs on a cable: its forces depend on the sway
            state, which these arrays (the robot without its payload) cannot give.
    """
    out = _CACHE.get(robot)
    if out is None:
        if robot.hybrid.cable is not None:
            from offshore_crane.errors import ModelError

            raise ModelError(
                f"this robot's payload hangs on a cable (payload.cable_length = "
                f"{robot.hybrid.cable_length:g} m): its forces depend on the swing, so "
                "the rigid-robot solvers do not apply; use offshore_crane.dynamics.cable "
                "(inverse_dynamics; the command line's id does it), or cable_length = 0 "
                "for a welded payload", element="payload.cable_length")
        out = _CACHE[robot] = build(robot.hybrid)
    return out


def cable_arrays(robot) -> RobotArrays:
    """:func:`build` of the robot with its hanging payload: the arm chain continued by the
    two sway joints and the payload (``robot.hybrid.cable``, 5 joints), cached per robot.
    The sway joints are unlimited (the URDF gives them ±π only because URDF needs limits).

    Raises:
        ModelError: the robot has no payload on a cable.
    """
    from dataclasses import replace

    out = _CABLE_CACHE.get(robot)
    if out is None:
        model = robot.hybrid
        if model.cable is None:
            from offshore_crane.errors import ModelError

            raise ModelError("the robot has no payload on a cable (payload.cable_length = 0)",
                             element="payload.cable_length")
        chain = model.cable
        n = chain.n
        free = np.arange(n) >= model.arm.n
        chain = replace(chain, lower=np.where(free, -np.inf, chain.lower),
                        upper=np.where(free, np.inf, chain.upper))
        out = _CABLE_CACHE[robot] = build(replace(model, arm=chain))
    return out


def as_mpf(C: KaneConstants) -> KaneConstants:
    """The constants as object arrays of ``mpf`` (exact conversions), for the mpmath
    backend; integers and booleans unchanged."""
    import mpmath as mp

    def conv(x):
        if isinstance(x, np.ndarray) and x.dtype.kind == "f":
            out = np.empty(x.shape, dtype=object)
            for idx, v in np.ndenumerate(x):
                out[idx] = mp.mpf(float(v))
            return out
        if isinstance(x, float):
            return mp.mpf(x)
        return x

    return KaneConstants(*(conv(x) for x in C))
