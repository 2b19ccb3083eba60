"""Design of the arm for the platform you have: a multi-objective search over robot
description fields, each candidate judged by the sweep engine over the sea states it must
work in (``offshore-crane design``; docs/design.md).

A **space** (TOML, :func:`load_space`, checked by :func:`check_space`)::

    [variables]                      # description fields by dotted name: [low, high]
    "arm.link1.shape.size.x" = [0.3, 0.7]          # or { choices = [a, b, ...] }
    "arm.link2.shape.size.x" = [0.2, 0.6]
    [objectives]                     # verdict columns or expressions of fields
    maximise = ["arm.link1.shape.size.x + arm.link2.shape.size.x + arm.slider.max"]
    minimise = ["T1_util_push"]
    [constraints]                    # worst_util <= 1 unless given
    worst_util = { "<=" = 0.8 }
    [sea]                            # optional: sea states (and seeds) of every candidate
    hs = [2.5]
    heading = [90.0]

A **candidate** is a set of variable values; its cases (one per sea state and seed: the
scene's ``[extremes] seeds`` from its seed, as ``size`` runs, when ``[sea]`` lists none)
are sweep cases (:func:`offshore_crane.studies.sweep.run`): they run on local workers or a
Dask cluster and land in the sweep's results store, where a rerun finds them. Its
verdict per sea state is the sweep's (:func:`offshore_crane.studies.sweep.verdicts`: the
Gumbel most probable maximum from 5 seeds of exposure-long records, else the observed),
a column's value its worst over the sea states. **The search** (:func:`run`) is pymoo's
NSGA-II, seeded, for at most ``budget`` evaluations; the **front**
(:attr:`Design.front`) the non-dominated feasible candidates of all evaluated.
:func:`write_front` writes ``pareto.csv``; :func:`design_description` writes a design as a
robot description file.

pymoo is optional (``pip install offshore-crane[design]``), imported when a search runs.
"""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr

from offshore_crane.studies.design._space import (DEFAULT_CONSTRAINT, OPERATORS, Constraint,
                                                  Objective, Quantity, Space, Variable,
                                                  check_space, load_space)
from offshore_crane.studies.design._evaluate import Candidate, Evaluator
from offshore_crane.studies.design._search import (FAILED, MIN_POPULATION, PER_VARIABLE,
                                                   Design, front, run)
from offshore_crane.studies.design._front import (PARETO, front_columns, front_rows,
                                                  front_text, picked, read_front,
                                                  write_front)
from offshore_crane.studies.design._robot import design_description

__all__ = ["DEFAULT_CONSTRAINT", "FAILED", "MIN_POPULATION", "OPERATORS", "PARETO",
           "PER_VARIABLE", "Candidate", "Constraint", "Design", "Evaluator", "Objective",
           "Quantity", "Space", "Variable", "check_space", "design_description", "front",
           "front_columns", "front_rows", "front_text", "load_space", "picked",
           "read_front", "run", "write_front"]

#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
