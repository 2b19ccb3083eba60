"""Why a run ends: one :class:`StopCause` for every integrator of the package.

The compiled loops (the simulation's RK4 driver, the hanging load's and the elastic
cable's integrations on a prescribed motion, the reference's) write a cause's value into
their ``status[0]``; Python reads it back with ``StopCause(status[0])`` and words it with
:meth:`StopCause.describe`. The values are plain integers so that a Numba kernel compares
against them as constants (module globals of :data:`CODES`).
"""

from __future__ import annotations

from enum import IntEnum


class StopCause(IntEnum):
    """Why a run stopped before its end (``NONE``: it did not)."""

    #: It ran to its end.
    NONE = 0
    #: A sample left the robot's workspace (a joint, a stroke, a universal joint's cone).
    WORKSPACE = 1
    #: A singular configuration: the mass matrix (the attitude singularity, the sway at
    #: cos φ2 = 0) or the legs' actuation.
    SINGULAR = 2
    #: The state stopped being finite (or beyond any physical magnitude).
    DIVERGED = 3
    #: Asked to stop (a signal; :func:`offshore_crane.progress.run_polled`).
    STOPPED = 4
    #: The cable went slack where the model needs it taut (the rigid pendulum).
    SLACK = 5

    def describe(self) -> str:
        """A short phrase for messages ("left the workspace")."""
        return _WORDS[self]


_WORDS = {
    StopCause.NONE: "ran to its end",
    StopCause.WORKSPACE: "left the workspace",
    StopCause.SINGULAR: "reached a singular configuration",
    StopCause.DIVERGED: "diverged",
    StopCause.STOPPED: "was stopped",
    StopCause.SLACK: "the cable went slack",
}

#: The values as plain ints, for compiled code: ``OK, WORKSPACE, SINGULAR, DIVERGED,
#: STOPPED, SLACK = CODES``.
CODES = tuple(int(c) for c in StopCause)
