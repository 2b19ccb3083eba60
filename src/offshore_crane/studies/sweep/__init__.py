"""Sweeps: one scene run over a grid of sea states and robot parameters, one row per case,
in parallel (joblib's loky processes, or a Dask cluster), stored as a resumable Parquet
dataset; verdicts per case over seeds, and the operability over a wave scatter diagram.

A **grid** (TOML, :func:`load_grid`) names lists of values; the cases are their product::

    hs = [1.0, 2.0, 3.0]             # [sea] keys, full scale: Hs [m], Tp [s],
    tp = [6.0, 8.0, 10.0]            # heading [deg], Froude scale, seed
    heading = [90.0, 180.0]
    seed = [0, 1, 2, 3, 4]
    "payload.mass" = [0.0, 2.0]      # any robot field by its dotted name (or alias)

The sea keys need a scene whose trajectory is the sea (``source = "sea"``); every value
is checked before anything runs by the scene's own checks (:class:`GridError` names the
grid file, the key and the index). Each case (:func:`run_case`) runs the scene with the
case's values: the inverse dynamics (:func:`record`), or the forward simulation when the
scene has a ``[control]`` section, and its envelope (:func:`offshore_crane.studies.sizing.envelope`).
A case that fails (workspace, singularity, a diverged simulation, a slack cable) yields
a row with its error, and the sweep goes on.

Determinism: every case runs the compiled kernels (or NumPy when Numba is absent, chosen
once in the parent) on one thread, from its own values only, so a row is bit-identical
whether the sweep runs serially, on joblib workers or on a Dask cluster. The parent warms
the compiled kernels up (:func:`offshore_crane.dynamics.warm_up`) before starting workers,
so that they load them from the on-disk cache instead of compiling them in parallel.

**Results** (:class:`ResultsStore`): a directory holding ``_manifest.json`` (the scene's
content hash and the grids run), a lock held for the whole run, and the rows in Parquet
files: batches written while the run goes (every 2000 rows or 2 s), compacted into one
``rows-<run>.parquet`` at its end (:mod:`offshore_crane.studies.sweep.rowfiles`); together
one Parquet dataset (``pyarrow.dataset.dataset(dir)`` reads it; names starting with ``_``
or ``.`` are not data; :func:`read_results` gives each case once). Rerunning with the same
directory skips the cases already there, so a killed sweep loses only the cases in flight
and at most 2 s of finished rows; a directory that holds another scene's results, or
anything but results, is refused before anything runs.

joblib, Dask (``distributed``), pandas, pyarrow and tqdm are optional (``pip install
offshore-crane[sweep]``), imported when used."""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr

from offshore_crane.studies.sweep.grid import (MAX_CASES, SEA_KEYS, CaseIds, Grid, case_id,
                                               case_scene, check_grid, load_grid,
                                               scene_values)
from offshore_crane.studies.sweep.cases import CASE_COLUMNS, CaseRun, record, run_case, row_schema
from offshore_crane.studies.sweep.store import (MANIFEST, MANIFEST_FORMAT, scene_hash,
                                                ResultsStore, read_results)
from offshore_crane.studies.sweep.backends import LOCAL_WORKERS, connect
from offshore_crane.studies.sweep.scheduler import CONNECT_TIMEOUT, MAX_HANDSHAKE
from offshore_crane.studies.sweep.running import run
from offshore_crane.studies.sweep.assessment import (VERDICT_COLUMNS, CRITERIA, group_keys, verdicts,
                                                      verdict_quantities,
                                                      Scatter, load_scatter, limiting_hs,
                                                      operability)


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
