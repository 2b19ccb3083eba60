"""What a person reads: :mod:`.report` (summaries and force plots), :mod:`.sizing_plots`,
:mod:`.visual` (animations, stills, the browser viewer) and :mod:`.export` (MJCF).
Matplotlib, Pillow, imageio and viser are imported by the functions that use them."""

from __future__ import annotations

import importlib

__all__ = ["report", "sizing_plots", "visual", "export"]


def __getattr__(name: str):
    if name in __all__:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
