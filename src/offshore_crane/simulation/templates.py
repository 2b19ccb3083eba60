"""The names a template calls that the driver's namespace provides
(:func:`offshore_crane.simulation.loop.instantiate`): the plant's kernels, the law's
functions and where q and q̇ sit in the plant's state. A template imports them from here
so that it reads as complete Python; :func:`~offshore_crane.simulation.loop.instantiate`
gives each template a namespace of its own in which these names are the plant's and the
law's compiled functions. Called as they are here (a template run without being
instantiated), each raises."""

from __future__ import annotations

#: Where q (9) and q̇ (9) start in the plant's state; set by the namespace (None here: a
#: template used uninstantiated fails at its first index).
IQ = IQD = None


def _unbound(name: str):
    def call(*args):
        raise RuntimeError(f"{name}() is a name of the driver's namespace: instantiate the "
                           "template (offshore_crane.simulation.loop.instantiate)")
    call.__name__ = name
    return call


def unowned(x):
    """``x`` itself: in a compiled loop, :func:`offshore_crane.dynamics.views.unowned`
    (the arrays of the loop's argument tuples without their owner)."""
    return x


# the plant's kernels (offshore_crane.simulation.plants: Plant.KERNELS)
rhs, check, keep = _unbound("rhs"), _unbound("check"), _unbound("keep")
prepare = _unbound("prepare")
inverse, gravity = _unbound("inverse"), _unbound("gravity")
coords, payload = _unbound("coords"), _unbound("payload")
arm_tip, winch, winch_to = _unbound("arm_tip"), _unbound("winch"), _unbound("winch_to")
# the law's templates (offshore_crane.simulation.laws: Law.templates)
command, law_rate = _unbound("command"), _unbound("law_rate")
pd_command, ct_command = _unbound("pd_command"), _unbound("ct_command")
arm_command = _unbound("arm_command")
