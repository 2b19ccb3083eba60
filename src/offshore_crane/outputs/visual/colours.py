"""The legs coloured by their actuator force or utilisation: the colour scales that
animate, its legend, the GIF palette and the browser viewer share."""

from __future__ import annotations

import numpy as np

#: Leg links coloured by force or utilisation.
LEG_LINKS = tuple((f"leg{i}_lower", f"leg{i}_upper") for i in range(1, 7))


def diverging(x: np.ndarray) -> np.ndarray:
    """``x`` in [-1, 1] to RGB 0..1: blue (-1, pull) - light grey (0) - red (+1, push)."""
    x = np.clip(x, -1.0, 1.0)[..., None]
    grey, blue, red = np.array([0.85, 0.85, 0.85]), np.array([0.1, 0.3, 0.9]), \
        np.array([0.9, 0.15, 0.1])
    return np.where(x < 0, grey + (blue - grey) * -x, grey + (red - grey) * x)


def sequential(x: np.ndarray) -> np.ndarray:
    """``x`` in [0, 1] to RGB 0..1: grey (0) - yellow (0.5) - red (1); above 1 dark red
    (beyond capacity)."""
    x = np.asarray(x, dtype=float)[..., None]
    grey, yellow, red = np.array([0.8, 0.8, 0.8]), np.array([0.98, 0.85, 0.1]), \
        np.array([0.9, 0.1, 0.05])
    lo = grey + (yellow - grey) * np.clip(2 * x, 0, 1)
    hi = yellow + (red - yellow) * np.clip(2 * x - 1, 0, 1)
    out = np.where(x <= 0.5, lo, hi)
    return np.where(x > 1.0, np.array([0.45, 0.0, 0.0]), out)


def colour_scale(color_by: str):
    """The legs' colour map and its domain: ``"force"`` → :func:`diverging` on [-1, 1],
    ``"utilisation"`` → :func:`sequential` on [0, 1] (the one choice animate, its legend,
    the GIF palette and the viewer share)."""
    return (diverging, (-1.0, 1.0)) if color_by == "force" else (sequential, (0.0, 1.0))


#: Leg index 0..5 of each leg link.
LEG_OF_LINK = {link: i for i, pair in enumerate(LEG_LINKS) for link in pair}


def leg_face_colours(geo, leg_rgb: np.ndarray) -> np.ndarray:
    """``(nf, 3)`` face colours of a :class:`~.render.Geometry` with the faces of leg i
    painted ``leg_rgb[i]`` ``(6, 3)``."""
    out = geo.rgb.copy()
    for i, pair in enumerate(LEG_LINKS):
        out[geo.faces_of(pair)] = leg_rgb[i]
    return out
