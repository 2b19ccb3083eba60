"""Pictures of sizing and operability (matplotlib, imported when drawing).

- :func:`utilisation_chart`: one case, per actuator the utilisation of each capacity
  (push, pull, speed, power, stroke) as grouped bars against the 100 % line.
- :func:`operability_diagram`: per heading, Hs over Tp coloured by the worst utilisation
  over actuators (:func:`offshore_crane.studies.sweep.verdicts`), the 100 % contour, and at every
  swept sea state the governing actuator (failed cases marked ``×``).

Figures are written through :mod:`offshore_crane.io` (atomic; the format from the suffix).
"""

from __future__ import annotations

import math

import numpy as np

from offshore_crane.conventions import ACTUATORS
from offshore_crane.outputs.report import pyplot
from offshore_crane.studies.sizing import CAPACITIES


def utilisation_chart(target, utilisation, title: str = "") -> None:
    """Grouped bars of a ``(9, 5)`` utilisation (1 = 100 %) over :data:`CAPACITIES`;
    actuators without any utilisation (absent) are left out, a capacity not given (NaN)
    has no bar."""
    from offshore_crane.outputs.report import save_figure

    plt = pyplot()
    util = np.asarray(utilisation, dtype=float)
    rows = [k for k in range(9) if not np.isnan(util[k]).all()]
    fig, ax = plt.subplots(figsize=(9, 4.2), constrained_layout=True)
    width = 0.8 / len(CAPACITIES)
    x = np.arange(len(rows))
    for c, cap in enumerate(CAPACITIES):
        values = 100.0 * util[rows, c]
        ax.bar(x + (c - 2) * width, np.nan_to_num(values, nan=0.0), width, label=cap)
    ax.axhline(100.0, color="k", lw=1.2, ls="--", label="capacity (100 %)")
    ax.set_xticks(x, [ACTUATORS[k] for k in rows])
    ax.set_ylabel("utilisation [%]")
    top = np.nanmax(100.0 * util[rows]) if not np.isnan(util[rows]).all() else 100.0
    ax.set_ylim(0.0, 1.25 * max(100.0, top))
    ax.grid(True, axis="y", alpha=0.3)
    ax.legend(ncol=6, fontsize=8, loc="upper center")
    ax.set_title(_wrapped(title, fig), fontsize=9)
    save_figure(fig, target)


def _wrapped(text: str, fig) -> str:
    """``text`` broken into lines that fit the figure's width at font size 9 (a title
    that says what its figures rest on is long)."""
    import textwrap

    width = int(14 * fig.get_size_inches()[0])
    return "\n".join(textwrap.fill(part, width) for part in text.split("\n"))


#: Per operability criterion (:data:`offshore_crane.studies.sweep.CRITERIA`): the verdict
#: columns of the colour and of the label, and the colour bar's text.
_SHOWN = {"actuators": ("worst_util", "governing", "worst utilisation over actuators"),
          "no slack": ("slack_util", None, "slack criterion: limit / (T_min / m g)"),
          "load": ("load_util", "load_governing", "worst hanging-load utilisation"),
          "all": ("overall_util", "overall_governing", "worst utilisation, actuators and "
                  "load")}


def operability_diagram(target, table, title: str = "", operability=None,
                        criterion: str = "actuators") -> None:
    """The operability diagram of one combination of the non-sea parameters.

    Args:
        target: The figure file (or an :class:`~offshore_crane.io.Target`).
        table: Verdicts (:func:`offshore_crane.studies.sweep.verdicts`) with columns ``hs``,
            ``tp``, ``heading`` and the criterion's utilisation (inf: failed) and
            governing columns.
        title: The figure's title.
        operability: ``{heading: percent}`` to print under each panel, or None.
        criterion: Which utilisation is drawn: ``"actuators"`` (``worst_util``, labels
            the governing actuator), ``"no slack"`` (``slack_util``, labels the tension
            ratio), ``"load"`` or ``"all"``.
    """
    from offshore_crane.outputs.report import save_figure

    plt = pyplot()
    from matplotlib.colors import TwoSlopeNorm

    headings = sorted(table["heading"].unique())
    n = len(headings)
    fig, axes = plt.subplots(1, n, figsize=(4.6 * n + 1.2, 4.4), squeeze=False,
                             constrained_layout=True)
    column, governing, meaning = _SHOWN[criterion]
    finite = table[column].replace([np.inf], np.nan)
    top = max(2.0, float(np.nanmax(finite)) if finite.notna().any() else 2.0)
    norm = TwoSlopeNorm(vmin=0.0, vcenter=1.0, vmax=top)
    mesh = None
    for ax, heading in zip(axes[0], headings):
        h = table[table["heading"] == heading]
        hs = np.sort(h["hs"].unique())
        tp = np.sort(h["tp"].unique())
        U = np.full((len(hs), len(tp)), np.nan)
        who = np.full((len(hs), len(tp)), "", dtype=object)
        failed = np.zeros((len(hs), len(tp)), bool)
        for _, r in h.iterrows():
            i, j = np.searchsorted(hs, r["hs"]), np.searchsorted(tp, r["tp"])
            U[i, j] = r[column]
            failed[i, j] = r.get("failed", 0) > 0
            who[i, j] = (r[governing] if governing else
                         f"T_min {r['tension_ratio_min']:.2f} m g")
        shown = np.where(np.isinf(U), top, U)
        if len(hs) > 1 and len(tp) > 1:
            mesh = ax.pcolormesh(tp, hs, shown, shading="nearest", cmap="RdYlGn_r",
                                 norm=norm)
            if np.nanmin(shown) < 1.0 < np.nanmax(shown):
                ax.contour(tp, hs, shown, levels=[1.0], colors="k", linewidths=2)
        else:
            T, H = np.meshgrid(tp, hs)
            mesh = ax.scatter(T.ravel(), H.ravel(), c=shown.ravel(), cmap="RdYlGn_r",
                              norm=norm, s=300, marker="s")
        for i in range(len(hs)):
            for j in range(len(tp)):
                if math.isnan(U[i, j]):
                    continue
                label = ("× failed" if failed[i, j] else "× slack" if np.isinf(U[i, j]) else
                         f"{who[i, j]}\n{100 * U[i, j]:.0f} %" if who[i, j] else "")
                ax.annotate(label, (tp[j], hs[i]), ha="center", va="center", fontsize=7)
        ax.set_xlabel("Tp [s] (full scale)")
        ax.set_ylabel("Hs [m] (full scale)")
        sub = f"heading {heading:g}°"
        if operability is not None and heading in operability:
            sub += f": operable {operability[heading]:.1f} % of the time"
        ax.set_title(sub, fontsize=10)
    if mesh is not None:
        bar = fig.colorbar(mesh, ax=axes[0].tolist(), shrink=0.9)
        bar.set_label(f"{meaning} (1 = 100 %)")
    text = ((f"{title}; " if title else "") + "black line: 100 % contour; labels: "
            + ("governing actuator" if criterion == "actuators" else
               "smallest tension" if criterion == "no slack" else "what governs"))
    fig.suptitle(_wrapped(text, fig), fontsize=9)
    save_figure(fig, target)
