"""The layout of a robot's constants packed in one buffer
(:attr:`~offshore_crane.dynamics.constants.RobotArrays.flat`): the fields' order and the
view of one field. Apart from :mod:`.constants` so that the tracer (:mod:`.tracing`),
which reads the layout, does not import what packs (and loads the compiled passes)."""

from __future__ import annotations

import numpy as np

from offshore_crane.dynamics.formulas import KaneConstants

#: The float fields packed in ``RobotArrays.flat``, in order: KaneConstants' fields but
#: ``n_arm`` and ``arm_prism``, then the limits.
FIELDS = tuple(f for f in KaneConstants._fields if f not in ("n_arm", "arm_prism")) + (
    "lim_arm", "lim_stroke", "lim_ujoint")


def field_view(buffer, offset: int, shape: tuple, scalar=float):
    """A field of :data:`FIELDS` in ``buffer``, laid out as ``RobotArrays.flat``
    (:class:`~offshore_crane.dynamics.constants.RobotArrays`; ``offset``: the field's row
    of its ``layout``, ``shape`` its own): ``scalar(buffer[offset])`` for a scalar, else
    the view of that shape."""
    if not shape:
        return scalar(buffer[offset])
    return buffer[offset:offset + int(np.prod(shape))].reshape(shape)
