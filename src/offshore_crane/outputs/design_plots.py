"""Pictures of a design search (matplotlib, imported when drawing): the front among the
candidates evaluated.

- two objectives: a scatter of every evaluated candidate (feasible grey, infeasible
  marked ``×``), the front over it in colour, each front design numbered as in
  ``pareto.csv``;
- more: the same in pairwise panels (each objective against each other);
- one: the objective over the candidates in the order evaluated.

Written through :mod:`offshore_crane.io` (atomic; the format from the suffix).
"""

from __future__ import annotations

import itertools
import textwrap

import numpy as np

from offshore_crane.outputs.report import pyplot


def front_figure(target, design, title: str = "") -> None:
    """Draw ``design``'s front (:class:`offshore_crane.studies.design.Design`) to
    ``target``."""
    from offshore_crane.outputs.report import save_figure

    plt = pyplot()
    space = design.space
    names = [textwrap.fill(f"{o.sense[:3]}. {o.quantity.text}", 48)
             for o in space.objectives]
    ok = [c for c in design.candidates if c.status == "ok"]
    values = np.array([c.objectives for c in ok], dtype=float).reshape(len(ok), -1)
    feasible = np.array([c.feasible for c in ok], dtype=bool)
    front = np.array([c.objectives for c in design.front], dtype=float)
    m = len(names)
    if m == 1:
        fig, ax = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
        ax.plot([c.index + 1 for c in ok], values[:, 0], ".", color="0.6")
        ax.plot([c.index + 1 for c in design.front], front[:, 0], "o", color="C0")
        ax.set_xlabel("candidate (order evaluated)")
        ax.set_ylabel(names[0])
        axes = [ax]
    else:
        pairs = list(itertools.combinations(range(m), 2))
        cols = min(3, len(pairs))
        rows = -(-len(pairs) // cols)
        fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 4.4 * rows),
                                 constrained_layout=True, squeeze=False)
        axes = list(axes.ravel())
        for ax, (i, j) in zip(axes, pairs):
            ax.scatter(values[feasible, i], values[feasible, j], s=14, color="0.65",
                       label="feasible candidates")
            ax.scatter(values[~feasible, i], values[~feasible, j], s=18, marker="x",
                       color="C3", alpha=0.6, label="infeasible candidates")
            order = np.argsort(front[:, i], kind="stable")
            ax.plot(front[order, i], front[order, j], "o-", color="C0", ms=5, lw=1,
                    label="front (pareto.csv)")
            for n, (x, y) in enumerate(front[:, [i, j]], start=1):
                ax.annotate(str(n), (x, y), textcoords="offset points", xytext=(4, 4),
                            fontsize=7, color="C0")
            ax.set_xlabel(names[i])
            ax.set_ylabel(names[j])
            ax.grid(True, alpha=0.3)
        axes[0].legend(fontsize=8)
        for ax in axes[len(pairs):]:
            ax.set_visible(False)
    if title:
        fig.suptitle(title, fontsize=9)
    save_figure(fig, target)
