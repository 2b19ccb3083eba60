"""Write scenes/harib_srinivasan_2003_motion.csv: a smooth 6-DOF motion of the Harib &
Srinivasan (2003) platform about its home pose (q3 = 0.39 m), used by
scenes/harib_srinivasan_2003.toml.

    q1 = 0.02 sin(pi t)        q4 = 0.05 sin(pi t)            [m], [rad]
    q2 = 0.02 sin(pi t / 2)    q5 = 0.05 sin(pi t / 2 + 1)
    q3 = 0.39 + 0.02 sin(pi t + 0.5)   q6 = 0.08 sin(pi t)
    q7 = q8 = q9 = 0 (no arm), t = 0 ... 4 s at 200 Hz.

Amplitudes: a few centimetres and degrees, so that every leg stays inside the stroke
assumed in the description and the U-joints inside their range.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

DURATION = 4.0          # [s]: two periods of the fastest component
RATE = 200.0            # [Hz]
OUT = Path(__file__).resolve().parents[1] / "scenes" / "harib_srinivasan_2003_motion.csv"


def motion(t: np.ndarray) -> np.ndarray:
    """``(N, 9)`` coordinates at times ``t`` ``(N,)`` [s]."""
    w = np.pi
    q = np.zeros((len(t), 9))
    q[:, 0] = 0.02 * np.sin(w * t)
    q[:, 1] = 0.02 * np.sin(w * t / 2)
    q[:, 2] = 0.39 + 0.02 * np.sin(w * t + 0.5)
    q[:, 3] = 0.05 * np.sin(w * t)
    q[:, 4] = 0.05 * np.sin(w * t / 2 + 1.0)
    q[:, 5] = 0.08 * np.sin(w * t)
    return q


def text() -> str:
    """The CSV file's text."""
    t = np.arange(int(round(DURATION * RATE)) + 1) / RATE
    rows = ["t_s," + ",".join(f"q{k}" for k in range(1, 10))]
    rows += [",".join(repr(float(x)) for x in (ti, *qi)) for ti, qi in zip(t, motion(t))]
    return "\n".join(rows) + "\n"


if __name__ == "__main__":
    OUT.write_text(text())
    sys.stdout.write(f"wrote {OUT}\n")
