"""Every simulation that ran before the simulation core was unified (issue 37) gives the
same result after it: ``tests/data/golden_sim_025ad9a.npz`` holds the runs of
:mod:`golden_cases` from main 025ad9a (every plant, every law and option of that day, and
three runs that stop), compared here bit for bit, or within :data:`MOVED` where a
deliberate unification changed round-off (each named with its reason)."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))
import golden_cases  # noqa: E402

GOLDEN = Path(__file__).parents[1] / "data" / "golden_sim_025ad9a.npz"

#: ``{"case/field": relative bound}`` for arrays a deliberate unification moved by
#: round-off (relative to the array's largest magnitude); the issue's bound is 1e-12.
MOVED: dict[str, float] = {}


@pytest.fixture(scope="module")
def now() -> dict:
    return golden_cases.arrays(golden_cases.runs())


def _names() -> list[str]:
    with np.load(GOLDEN) as g:
        return list(g.files)


@pytest.mark.parametrize("name", _names())
def test_simulation_unchanged(now, name):
    with np.load(GOLDEN) as g:
        before = g[name]
    assert name in now, f"{name} is no longer computed"
    if before.dtype.kind == "U":                       # a stop's message
        assert str(now[name]) == str(before)
        return
    assert now[name].shape == before.shape
    if name in MOVED:
        with np.errstate(invalid="ignore"):
            moved = float(np.nanmax(np.abs(now[name] - before)) /
                          max(np.nanmax(np.abs(before)), np.finfo(float).tiny))
        assert moved <= MOVED[name], f"{name} moved by {moved:.3g} relative"
    else:
        np.testing.assert_array_equal(now[name], before)


def test_no_new_array_escapes_the_golden_file(now):
    """A case or field added later must be written into the golden file too."""
    assert set(now) == set(_names())
