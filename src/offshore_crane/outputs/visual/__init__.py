"""Pictures of the robot: every link's pose from q (:mod:`.poses`), a NumPy + Pillow
renderer (:mod:`.render`), GIF / MP4 animations (:mod:`.animate`), the motion to draw and
its forces (:mod:`.motion`) and a browser viewer (:mod:`.viewer`, viser).

Importing this package imports NumPy only; Pillow, imageio(-ffmpeg) and viser are imported
by the functions that need them, with an install hint when they are missing
(``pip install 'offshore-crane[animate]'`` or ``'offshore-crane[view]'``).
"""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr

__all__ = ["poses", "render", "animate", "motion", "viewer"]


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
