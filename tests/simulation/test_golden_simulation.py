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
#:
#: The elastic plant's right-hand side became one compiled kernel
#: (:mod:`offshore_crane.dynamics.cable.elastic_plant`) instead of NumPy calls: |ρ| by a
#: plain dot instead of BLAS's norm, libm's sin and cos instead of NumPy's, one rounding
#: of the pull that the Cholesky solve of M carries into q̈. Measured: q̈ 9.2e-14 (hoist),
#: 1.6e-14 (rate), 2.7e-17 (none); q̇ ≤ 1.3e-15; X ≤ 7.1e-16; power ≤ 2.9e-15; the payload
#: ≤ 8.3e-16; q ≤ 1.8e-17.
#:
#: Then the explicit form's legs were reduced to their sphere centre (issue 37's speed:
#: :func:`offshore_crane.dynamics.formulas.leg_share`, a leg's B and M formed in the 3
#: components of v_S and carried to the platform's speeds, instead of each link's
#: partials in the nine speeds): the same sums in another order, so M, h and every run
#: built on them moved by round-off. Measured against the file: at most 5.3e-13 (the X
#: of ``rigid_pd_rate_stops``, a run that ends on a workspace stop, its message and step
#: unchanged), 3.4e-13 (q̈ of ``rigid_dop853``), ≤ 1.6e-13 elsewhere; no stop moved.
_ELASTIC_UNIFIED = (
    ("elastic_ct_hoist", ("q", "qd", "qdd", "X_cmd", "X", "power", "payload",
                          "payload_velocity")),
    ("elastic_ct_rate", ("q", "qd", "qdd", "X_cmd", "X", "power", "payload_velocity")),
    ("elastic_none", ("q", "qd", "qdd", "payload", "payload_velocity")))
_LEGS_AT_S = (
    ("elastic_ct_hoist", ("tension",)),
    ("rigid_ct", ("q", "qd", "qdd", "X_cmd", "X", "power")),
    ("rigid_ct_out_rate", ("q", "qd", "qdd", "X_cmd", "X", "power")),
    ("rigid_ct_rate_noise_model", ("q", "qd", "qdd", "X_cmd", "X", "energy", "power")),
    ("rigid_dop853", ("q", "qd", "qdd", "X_cmd", "X")),
    ("rigid_none", ("q", "qd", "qdd", "energy")),
    ("rigid_pd_gravity", ("q", "qd", "qdd", "X_cmd", "X", "power")),
    ("rigid_pd_rate_stops", ("q", "qd", "qdd", "X_cmd", "X", "energy", "power")),
    ("rigid_python", ("qd", "qdd", "X_cmd", "X", "power")),
    ("rigid_saturated", ("q", "qd", "qdd", "X_cmd", "X", "energy", "power")),
    *((case, ("q", "qd", "qdd", "X_cmd", "X", "energy", "power", "sway", "sway_rate",
              "tension")) for case in ("swing_anti_sway", "swing_ct", "swing_rate_model")))
#: Then the rigid robot's built-in laws moved from their own compiled loop onto the RK4
#: driver (issue 37: one driver for every plant): the same q, q̇, q̈, X and energy bit
#: for bit (the computed torque shares the plant's pass as the loop did), the power
#: computed from the record (``record.actuator_power``) instead of inside the loop
#: (measured 4e-15 [W] on Table 1), already within the bounds above.
#: Then the elastic plant's pull's share of X (which its rates subtract) came from the
#: law's program at the law's commanded accelerations instead of at rest (two Kane passes
#: where it was three; X is affine in the pull): ``elastic_ct_hoist`` moved by round-off,
#: measured against the previous code: q̈ 1.1e-13, q̇ 1.3e-15, X 8.4e-16, power 1.2e-15,
#: the payload 3.8e-17, its velocity 3.3e-16, q 1.8e-17; already within the bounds above.
MOVED: dict[str, float] = {f"{case}/{field}": 1e-12
                           for case, fields in (*_ELASTIC_UNIFIED, *_LEGS_AT_S)
                           for field in fields}


#: ``{"case/stopped": (kept before, kept now, why)}``: a stop's message whose count of the
#: samples kept changed, nothing else in it.
_ON_THE_DRIVER = ("the rigid robot's built-in laws run on the driver, whose record ends "
                  "before the sample that left the workspace, as every plant's does (the "
                  "compiled loop kept that sample)")
RECOUNTED = {"rigid_pd_rate_stops/stopped": (196, 195, _ON_THE_DRIVER),
             "rigid_saturated/stopped": (144, 143, _ON_THE_DRIVER)}

#: ``{"case/field": why}``: arrays that were not computed (all NaN) and now are.
ADDED = {f"{case}/energy": "the elastic plant records its mechanical energy (issue 37)"
         for case in ("elastic_ct_hoist", "elastic_ct_rate", "elastic_none")}
ADDED["rigid_python/energy"] = ("the driver's rigid plant records its mechanical energy, "
                                "as the compiled loop does (issue 37)")


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
        expected = str(before)
        if name in RECOUNTED:
            was, kept, _ = RECOUNTED[name]
            assert f"the {was} samples" in expected
            expected = expected.replace(f"the {was} samples", f"the {kept} samples")
        assert str(now[name]) == expected
        return
    assert now[name].shape == before.shape
    if name in ADDED:
        assert np.isnan(before).all() and np.isfinite(now[name]).all(), ADDED[name]
        return
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


def test_one_compiled_explicit_pass_serves_every_plant(now):
    """The runs above that reach the compiled explicit pass (``compiled.explicit_sample``,
    ~20 s to compile with its formulas inlined: the rigid robot's loop and the forward
    dynamics) went through one specialisation of it: a caller handing it another array
    layout or type would compile it again."""
    from offshore_crane.dynamics import compiled

    assert len(compiled.explicit_sample.signatures) == 1, compiled.explicit_sample.signatures
