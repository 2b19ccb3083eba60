"""Figures of runs: a simulation's tracking errors and forces, a sea-state record with
its spectra. Matplotlib is imported when a figure is drawn (:func:`offshore_crane.outputs.report.pyplot`)."""

from __future__ import annotations

import numpy as np

from offshore_crane.conventions import ACTUATORS, COORDINATE_UNITS, COORDINATES
from offshore_crane.outputs.report import finish_figure, pyplot, save_figure

#: Plotted spectra: heave, roll, pitch (columns of q).
SPECTRUM_COLUMNS = (2, 3, 4)
#: Welch segment [model-scale s]: long enough to resolve the wave peak (Tp/√λ ~ 2 s at
#: 1:20) with ~0.05 Hz bins, short enough to average several segments over a minute.
WELCH_SEGMENT_S = 20.48


def simulation_figure(target, res, title: str = "") -> None:
    """Tracking errors (translations, rotations) and applied forces against time."""
    plt = pyplot()
    n = 4 if res.sway is None else 5
    fig, axes = plt.subplots(n, 1, figsize=(8, 2.5 * n), sharex=True, constrained_layout=True)
    for j in (0, 1, 2, 8):
        axes[0].plot(res.t, res.error[:, j] * 1e3, label=COORDINATES[j])
    axes[0].set_ylabel("error [mm]")
    for j in range(3, 8):
        axes[1].plot(res.t, res.error[:, j] * 1e3, label=COORDINATES[j])
    axes[1].set_ylabel("error [mrad]")
    for k in range(3, 9):
        axes[2].plot(res.t, res.X[:, k], label=ACTUATORS[k])
    axes[2].set_ylabel("leg force [N]")
    for k in range(3):
        axes[3].plot(res.t, res.X[:, k], label=ACTUATORS[k])
    axes[3].set_ylabel("arm [N·m, N]")
    if res.sway is not None:
        axes[4].plot(res.t, np.degrees(res.sway[:, 0]), label="phi1")
        axes[4].plot(res.t, np.degrees(res.sway[:, 1]), label="phi2")
        axes[4].set_ylabel("sway [deg]")
    finish_figure(fig, axes, target, title)


def sea_motion_figure(target, scene, traj) -> None:
    """Left: q1..q6 over time; right: for heave, roll and pitch, the Welch estimate of the
    record's spectrum over the target ``S |RAO|²`` (model scale).

    Args:
        target: Path or :class:`~offshore_crane.io.Target` of the figure.
        scene: The ``source = "sea"`` scene. traj: Its trajectory.
    """
    from offshore_crane.motion.sea import response_spectrum, welch
    from offshore_crane.scenes import sea_arguments

    plt = pyplot()
    motion = traj.source
    args = {k: v for k, v in sea_arguments(scene).items()
            if k not in ("operation", "seed", "highpass", "scale")}
    scale = motion.scale
    fig = plt.figure(figsize=(12, 8), constrained_layout=True)
    grid = fig.add_gridspec(6, 2)
    t, q = traj.t, traj.q
    for k in range(6):
        ax = fig.add_subplot(grid[k, 0])
        ax.plot(t, q[:, k], lw=0.8)
        ax.set_ylabel(f"{COORDINATES[k]} [{COORDINATE_UNITS[k]}]")
        ax.grid(True, alpha=0.3)
        if k < 5:
            ax.tick_params(labelbottom=False)
    ax.set_xlabel("time [s] (model scale)")
    segment = int(min(len(t), round(WELCH_SEGMENT_S * motion.rate)))
    segment -= segment % 2
    omega, S = welch(q[:, list(SPECTRUM_COLUMNS)], motion.rate, segment)
    expected = response_spectrum(omega[1:], scale=scale, **args)
    peak = 2.0 * np.pi / (args["tp"] / np.sqrt(scale))     # model-scale peak [rad/s]
    names = ("heave q3 [m²·s/rad]", "roll q4 [rad²·s/rad]", "pitch q5 [rad²·s/rad]")
    for i, (col, name) in enumerate(zip(SPECTRUM_COLUMNS, names)):
        ax = fig.add_subplot(grid[2 * i:2 * i + 2, 1])
        ax.plot(omega[1:], S[1:, i], lw=1.0, label="Welch estimate of the record")
        ax.plot(omega[1:], expected[:, col], lw=1.5, ls="--", color="k",
                label="target S |RAO|² (model scale)")
        ax.set_ylabel(name)
        ax.set_xlim(0.0, 4.0 * peak)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right", fontsize=8)
    ax.set_xlabel("frequency ω [rad/s] (model scale)")
    fig.suptitle(f"offshore-crane: {traj.name}")
    save_figure(fig, target)
