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
#: ... on an elastic cable: the payload from the tip, base axes.
ELASTIC_COLUMNS = "rho_x_m,rho_y_m,rho_z_m,tension_N"
#: ... with a winch: the cable's length, its rate, and the winch's line pull Fw.
WINCH_COLUMNS = "L_m,Ld_m_s,Fw_N"


def cable_columns(cable) -> tuple[str, np.ndarray]:
    """``(header, (N, k) values)`` a hanging load adds to the CSV."""
    if hasattr(cable, "sway"):
        head, cols = CABLE_COLUMNS, [cable.sway, cable.tension]
    else:
        head, cols = ELASTIC_COLUMNS, [cable.position, cable.tension]
    if cable.hoist is not None:
        head += "," + WINCH_COLUMNS
        cols += [cable.hoist[:, :2], cable.tension]
    return head, np.column_stack(cols)


def write_csv(target, t: np.ndarray, X: np.ndarray, cable=None) -> None:
    """Write ``t_s,T1_Nm,T2_Nm,Fs_N,Fl1_N,...,Fl6_N`` with 17 significant digits
    (``target``: a path or a :class:`~offshore_crane.io.Target`); with a hanging load the
    columns of :func:`cable_columns` (sway and tension; the payload's position for an
    elastic cable; the winch's L, L̇, Fw)."""
    if cable is None:
        io.write_csv(target, CSV_HEADER, np.column_stack([t, X]))
    else:
        head, values = cable_columns(cable)
        io.write_csv(target, f"{CSV_HEADER},{head}", np.column_stack([t, X, values]))


def lift_lines(cable, winch=None) -> list[str]:
    """The lift's lines: tension against the static tension (slack, snap), time slack,
    and the winch's demand against ``winch`` (:class:`WinchCapacities`) when hoisted."""
    from offshore_crane.dynamics.cable import lift_metrics

    m = lift_metrics(cable)
    lines = [f"lift: tension {m.tension_min:.4g}..{m.tension_max:.4g} N = "
             f"{m.ratio_min:.3g}..{m.ratio_max:.3g} × m g ({m.static_tension:.4g} N); slack "
             f"for {m.time_slack:.3g} s"]
    if cable.hoist is not None:
        use = m.winch_utilisation(winch) if winch is not None else {}

        def of(name, value, unit):
            u = use.get(name, float("nan"))
            return f"{value:.4g} {unit}" + ("" if u != u else f" ({100 * u:.0f} %)")
        lines.append("winch: peak pull " + of("pull", m.winch_pull, "N") + ", speed "
                     + of("speed", m.winch_speed, "m/s") + ", acceleration "
                     + of("acceleration", m.winch_acceleration, "m/s²") + ", power "
                     + of("power", m.winch_power, "W") + " of its capacities")
    return lines


def cable_summary(cable, robot) -> str:
    """Lines on the hanging load: largest sway, smallest and largest tension, and when;
    the lift's figures (:func:`lift_lines`) against the robot's winch."""
    winch = robot.winch
    if not hasattr(cable, "sway"):
        return elastic_summary(cable, robot)
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
    if cable.hoist is not None:
        lines += lift_lines(cable, winch)
    return "\n".join(lines)


def elastic_summary(cable, robot) -> str:
    """Lines on a payload on an elastic cable: its stiffness and step, its largest sway
    (from the tip's vertical: :func:`~offshore_crane.dynamics.cable.tip.sway_angle`) and
    stretch, and the lift's figures (:func:`lift_lines`)."""
    from offshore_crane.dynamics.cable.tip import sway_angle

    t = cable.t
    down = np.degrees(sway_angle(robot, cable))
    k = int(np.argmax(down))
    j = int(np.argmax(cable.stretch))
    lines = [f"hanging load: {cable.mass:g} kg on an elastic cable, EA {cable.ea:.4g} N, "
             f"damping {cable.damping:.4g} N·s/m, {cable.length:g} m unstretched (axial "
             f"period {cable.axial_period * 1e3:.3g} ms, RK4 step {cable.step:.3g} s, "
             f"{cable.refined} slack/taut steps redone)",
             f"payload: max sway {down[k]:.4g}° from the tip's vertical at t = {t[k]:.2f} s "
             f"({np.degrees(cable.plumb_angle).max():.4g}° from the plumb line);"
             f" max stretch {1e3 * cable.stretch[j]:.4g} mm at t = {t[j]:.2f} s"]
    return "\n".join(lines + event_lines(cable.event) + lift_lines(cable, robot.winch))


def event_lines(event) -> list[str]:
    """A ``[lift]`` scene's critical instant: the lift-off (and a re-hit) or the
    set-down, with the relative vertical speeds [m/s]; none without an event."""
    from offshore_crane.dynamics.cable import LiftOff, SetDown

    if isinstance(event, LiftOff):
        if event.t_liftoff != event.t_liftoff:
            return ["lift-off: the load never leaves the deck (the cable never carries "
                    "its weight and the deck's motion)"]
        if event.flight is None:
            return [f"lift-off at t = {event.t_liftoff:.4g} s, at the record's end"]
        return [f"lift-off at t = {event.t_liftoff:.4g} s; " + (
            f"RE-HIT: the deck catches the load again at t = {event.t_rehit:.4g} s, "
            f"closing at {abs(event.rehit_speed):.3g} m/s (after it the deck's contact is "
            "not modelled: the load flies on)" if event.rehit else
            f"no re-hit, least clearance {1e3 * event.clearance_min:.4g} mm above the deck")
            + " (the lift's figures below are from lift-off on)"]
    if isinstance(event, SetDown):
        if event.t_contact != event.t_contact:
            return ["set-down: the load does not reach the deck in the record"]
        after = event.after
        then = ("then resting where it landed" if after is None or after.t_liftoff
                != after.t_liftoff else f"RE-LIFT: the cable lifts it off again at t = "
                f"{after.t_liftoff:.4g} s" + (f", the deck catching it at t = "
                                             f"{after.t_rehit:.4g} s" if after.rehit else ""))
        return [f"set-down: first contact at t = {event.t_contact:.4g} s, landing at "
                f"{abs(event.speed):.3g} m/s relative to the deck; {then} (the lift's "
                "figures below are up to the contact)"]
    return []


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


def plot(path, t: np.ndarray, X: np.ndarray, title: str = "", cable=None,
         robot=None) -> None:
    """Figure like the paper's Fig. 3: leg forces, arm torques and slider force vs time;
    with a :class:`~offshore_crane.dynamics.cable.CableResult`, a panel of the sway angles and one
    of the tension (an elastic cable's sway from the tip's vertical needs its ``robot``)."""
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
    if cable is not None and hasattr(cable, "sway"):
        axes[3].plot(t, np.degrees(cable.sway[:, 0]), label="phi1")
        axes[3].plot(t, np.degrees(cable.sway[:, 1]), label="phi2")
        axes[3].set_ylabel("sway [deg]")
    elif cable is not None:                     # an elastic cable: the payload's angle
        from offshore_crane.dynamics.cable.tip import sway_angle

        axes[3].plot(t, np.degrees(sway_angle(robot, cable)), label="from the tip's vertical")
        axes[3].set_ylabel("sway [deg]")
    if cable is not None:
        axes[4].plot(t, cable.tension, label="tension", color="k")
        axes[4].set_ylabel("cable tension [N]")
    finish_figure(fig, axes, path, title)


def compensation_plot(target, runs, title: str = "", span: float | None = None) -> None:
    """The payload's residual motion x, y, z [mm] against time, one line per mode
    (:func:`offshore_crane.studies.compensation.compare_compensation`'s runs): the first
    ``span`` [s] of each record (None: all of it), the RMS in the legend over all of it."""
    plt = pyplot()
    fig, axes = plt.subplots(3, 1, figsize=(8, 7.5), sharex=True, constrained_layout=True)
    for r in runs:
        t = r.result.t
        keep = slice(None) if span is None else t <= t[0] + span
        for i, axis in enumerate("xyz"):
            axes[i].plot(t[keep], 1e3 * r.residual[keep, i], lw=0.9,
                         label=f"{r.mode} (RMS {1e3 * r.rms[i]:.3g} mm)")
    for i, axis in enumerate("xyz"):
        axes[i].set_ylabel(f"payload {axis} [mm]")
    finish_figure(fig, axes, target, title)


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
