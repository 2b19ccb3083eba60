"""What a person reads: :mod:`.report` (summaries and force plots), :mod:`.sizing_plots`,
:mod:`.visual` (animations, stills, the browser viewer) and :mod:`.export` (MJCF).
Matplotlib, Pillow, imageio and viser are imported by the functions that use them."""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr

__all__ = ["report", "sizing_plots", "visual", "export"]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
