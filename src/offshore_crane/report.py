"""Outputs of an inverse-dynamics run: summary table, CSV (docs/conventions.md columns), figure.

Files are written atomically (temporary file, then rename), so a failed run never leaves
a partial output behind.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np

from .errors import InputError, require
from .conventions import ACTUATOR_UNITS, ACTUATORS

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


#: Figure formats offered by --plot (all written by matplotlib's Agg-based backends).
PLOT_FORMATS = ("png", "pdf", "svg", "svgz", "eps", "ps", "jpg", "jpeg", "tif", "tiff", "webp")


def check_output(path, plot: bool = False) -> None:
    """Fail early (before any computation) on an output path that cannot be written.

    Raises:
        InputError: the directory does not exist, or (``plot``) the suffix is not one of
            :data:`PLOT_FORMATS`.
    """
    path = Path(path)
    directory = path.parent if str(path.parent) else Path(".")
    if not directory.is_dir():
        raise InputError(f"cannot write {path}: directory {directory} does not exist",
                         name=str(path))
    if plot and path.suffix.lstrip(".").lower() not in PLOT_FORMATS:
        raise InputError(f"cannot plot to {path}: the file type '{path.suffix}' is not one "
                         f"of {', '.join('.' + f for f in PLOT_FORMATS)}", name=str(path))


def _atomic_write(path: Path, write) -> None:
    path = Path(path)
    directory = path.parent if str(path.parent) else Path(".")
    if not directory.is_dir():
        raise InputError(f"cannot write {path}: directory {directory} does not exist",
                         name=str(path))
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=directory)
    try:
        with os.fdopen(fd, "wb") as fh:
            write(fh)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def write_csv(path, t: np.ndarray, X: np.ndarray) -> None:
    """Write ``t_s,T1_Nm,T2_Nm,Fs_N,Fl1_N,...,Fl6_N`` with 17 significant digits."""
    data = np.column_stack([t, X])
    _atomic_write(path, lambda fh: np.savetxt(fh, data, delimiter=",", fmt="%.17g",
                                              header=CSV_HEADER, comments=""))


def plot(path, t: np.ndarray, X: np.ndarray, title: str = "") -> None:
    """Figure like the paper's Fig. 3: leg forces, arm torques and slider force vs time."""
    matplotlib = require("matplotlib", "matplotlib", "--plot")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 1, figsize=(8, 9), sharex=True, constrained_layout=True)
    for i in range(6):
        axes[0].plot(t, X[:, 3 + i], label=f"Fl{i + 1}")
    axes[0].set_ylabel("leg force [N]")
    axes[1].plot(t, X[:, 0], label="T1")
    axes[1].plot(t, X[:, 1], label="T2")
    axes[1].set_ylabel("arm torque [N·m]")
    axes[2].plot(t, X[:, 2], label="Fs", color="k")
    axes[2].set_ylabel("slider force [N]")
    axes[2].set_xlabel("time [s]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right", ncol=6, fontsize=8)
    if title:
        axes[0].set_title(title)
    suffix = Path(path).suffix.lstrip(".") or "png"
    _atomic_write(path, lambda fh: fig.savefig(fh, format=suffix, dpi=110))
    plt.close(fig)
