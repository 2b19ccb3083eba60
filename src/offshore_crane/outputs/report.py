"""Outputs of an inverse-dynamics run: summary table, CSV (docs/conventions.md columns), figure.

Files are written through :mod:`offshore_crane.io` (checked before computing, atomic,
safe with symlinks, FIFOs and devices).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from offshore_crane import io
from offshore_crane.errors import require
from offshore_crane.io import FIGURE_FORMATS
from offshore_crane.conventions import ACTUATOR_UNITS, ACTUATORS

CSV_HEADER = "t_s," + ",".join(f"{a}_{u.replace('·', '')}"
                               for a, u in zip(ACTUATORS, ACTUATOR_UNITS))


def summary_rows(t: np.ndarray, X: np.ndarray, names=ACTUATORS, units=ACTUATOR_UNITS):
    """Per actuator: peak |X|, the time of the peak and the RMS.

    Args:
        t: ``(N,)`` [s].
        X: ``(N, k)`` [N or N·m].

    Returns:
        List of ``(name, unit, peak, t_peak, rms)``.
    """
    k = np.argmax(np.abs(X), axis=0)
    rms = np.sqrt(np.mean(X * X, axis=0))
    return [(n, u, float(abs(X[k[j], j])), float(t[k[j]]), float(rms[j]))
            for j, (n, u) in enumerate(zip(names, units))]


def format_summary(rows) -> str:
    """Fixed-width table of :func:`summary_rows`."""
    lines = [f"{'actuator':<9}{'unit':<6}{'peak |X|':>12}{'at t [s]':>11}{'RMS':>12}"]
    for name, unit, peak, tp, rms in rows:
        lines.append(f"{name:<9}{unit:<6}{peak:>12.4f}{tp:>11.2f}{rms:>12.4f}")
    return "\n".join(lines)


PLOT_FORMATS = FIGURE_FORMATS


#: Columns added when the payload hangs on a cable (docs/cable.md).
CABLE_COLUMNS = "phi1_rad,phi2_rad,tension_N"


def write_csv(target, t: np.ndarray, X: np.ndarray, cable=None) -> None:
    """Write ``t_s,T1_Nm,T2_Nm,Fs_N,Fl1_N,...,Fl6_N`` with 17 significant digits
    (``target``: a path or a :class:`~offshore_crane.io.Target`); with a
    :class:`~offshore_crane.dynamics.cable.CableResult`, also ``phi1_rad,phi2_rad,tension_N``."""
    if cable is None:
        io.write_csv(target, CSV_HEADER, np.column_stack([t, X]))
    else:
        io.write_csv(target, f"{CSV_HEADER},{CABLE_COLUMNS}",
                     np.column_stack([t, X, cable.sway, cable.tension]))


def cable_summary(cable) -> str:
    """Lines on the hanging load: largest sway, smallest and largest tension, and when."""
    t = cable.t
    angle = cable.sway_angle
    k = int(np.argmax(angle))
    lo, hi = int(np.argmin(cable.tension)), int(np.argmax(cable.tension))
    peaks = np.abs(cable.sway).max(axis=0)
    lines = [f"hanging load: {cable.mass:g} kg on a {cable.length:g} m cable "
             f"({cable.method}, RK4 step {cable.step:g} s): max sway "
             f"{np.degrees(angle[k]):.4g}° from the tip's vertical at t = {t[k]:.2f} s "
             f"(max |phi1| {np.degrees(peaks[0]):.4g}°, |phi2| {np.degrees(peaks[1]):.4g}°)",
             f"cable tension: min {cable.tension[lo]:.4g} N at t = {t[lo]:.2f} s, max "
             f"{cable.tension[hi]:.4g} N at t = {t[hi]:.2f} s (m g = "
             f"{cable.mass * 9.81:.4g} N at 9.81 m/s²)"]
    if cable.slack.any():
        lines.append(f"SLACK CABLE at {int(cable.slack.sum())} samples (first t = "
                     f"{t[int(np.argmax(cable.slack))]:.2f} s): the model does not hold there")
    return "\n".join(lines)


def pyplot(purpose: str = "--plot"):
    """``matplotlib.pyplot`` on the non-interactive Agg backend (files only, no display),
    imported on first use; the one matplotlib set-up of the package.

    Raises:
        BackendMissingError: matplotlib is not installed (naming ``purpose``).
    """
    matplotlib = require("matplotlib", "matplotlib", purpose)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot(path, t: np.ndarray, X: np.ndarray, title: str = "", cable=None) -> None:
    """Figure like the paper's Fig. 3: leg forces, arm torques and slider force vs time;
    with a :class:`~offshore_crane.dynamics.cable.CableResult`, a panel of the sway angles and one
    of the tension."""
    plt = pyplot()

    n = 3 if cable is None else 5
    fig, axes = plt.subplots(n, 1, figsize=(8, 3 * n), sharex=True, constrained_layout=True)
    for i in range(6):
        axes[0].plot(t, X[:, 3 + i], label=f"Fl{i + 1}")
    axes[0].set_ylabel("leg force [N]")
    axes[1].plot(t, X[:, 0], label="T1")
    axes[1].plot(t, X[:, 1], label="T2")
    axes[1].set_ylabel("arm torque [N·m]")
    axes[2].plot(t, X[:, 2], label="Fs", color="k")
    axes[2].set_ylabel("slider force [N]")
    if cable is not None:
        axes[3].plot(t, np.degrees(cable.sway[:, 0]), label="phi1")
        axes[3].plot(t, np.degrees(cable.sway[:, 1]), label="phi2")
        axes[3].set_ylabel("sway [deg]")
        axes[4].plot(t, cable.tension, label="tension", color="k")
        axes[4].set_ylabel("cable tension [N]")
    finish_figure(fig, axes, path, title)


def finish_figure(fig, axes, target, title: str = "") -> None:
    """Grid, legends, a time axis label and the title, then :func:`save_figure`."""
    axes[-1].set_xlabel("time [s]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right", ncol=6, fontsize=8)
    if title:
        axes[0].set_title(title)
    save_figure(fig, target)


def save_figure(fig, target) -> None:
    """Save a matplotlib figure through :mod:`offshore_crane.io` (format from the
    suffix) and close it."""
    import matplotlib.pyplot as plt

    suffix = Path(str(target)).suffix.lstrip(".").lower() or "png"
    try:
        with io.open_output(target, "wb") as fh:
            fig.savefig(fh, format=suffix, dpi=110)
    finally:
        plt.close(fig)
