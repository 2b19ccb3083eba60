"""Pictures of the robot: every link's pose from q (:mod:`.poses`), a NumPy + Pillow
renderer (:mod:`.render`), GIF / MP4 animations (:mod:`.animate`), the motion to draw and
its forces (:mod:`.motion`) and a browser viewer (:mod:`.viewer`, viser).

Importing this package imports NumPy only; Pillow, imageio(-ffmpeg) and viser are imported
by the functions that need them, with an install hint when they are missing
(``pip install 'offshore-crane[animate]'`` or ``'offshore-crane[view]'``).
"""

from __future__ import annotations

__all__ = ["poses", "render", "animate", "motion", "viewer"]


def __getattr__(name):
    if name in __all__:
        import importlib

        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'offshore_crane.outputs.visual' has no attribute '{name}'")
