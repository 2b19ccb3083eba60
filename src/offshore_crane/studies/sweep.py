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
content hash and the grids run) and one Parquet file per finished case
(``case-<id>.parquet``, written atomically as the case finishes), which together form one
Parquet dataset (``pyarrow.dataset.dataset(dir)`` reads it; names starting with ``_`` or
``.`` are not data). Rerunning with the same directory skips the cases already there, so a
killed sweep loses only the cases in flight; a directory that holds another scene's
results, or anything but results, is refused before anything runs.

joblib, Dask (``distributed``), pandas, pyarrow and tqdm are optional (``pip install
offshore-crane[sweep]``), imported when used.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import os
import sys
import time
from dataclasses import dataclass, fields, replace
from pathlib import Path

import numpy as np

from offshore_crane.errors import GridError, OffshoreCraneError, ResultsDirectoryError, SchedulerError

#: Grid keys that set the scene's ``[sea]`` (full scale): Hs [m], Tp [s], heading [deg],
#: Froude scale [-], random-phase seed.
SEA_KEYS = ("hs", "tp", "heading", "scale", "seed")
#: Columns of a row besides the grid's keys and the envelope (:func:`row_schema`).
CASE_COLUMNS = (("case_id", "string"), ("status", "string"), ("error_type", "string"),
                ("error", "string"), ("warnings", "int64"))
#: Columns of :func:`verdicts` besides the parameters and the utilisations.
VERDICT_COLUMNS = ("seeds", "failed", "record_s", "exposure_s", "basis", "error_type",
                   "error")
MANIFEST = "_manifest.json"
MANIFEST_FORMAT = "offshore-crane sweep results"
#: Seconds to wait for a Dask scheduler before calling it unreachable.
CONNECT_TIMEOUT = 3.0
#: Default Dask ``LocalCluster`` size (``--scheduler local``) when ``workers`` is not given.
LOCAL_WORKERS = 2


def _install_hint(module: str, purpose: str):
    from offshore_crane.errors import require

    package = {"distributed": "distributed", "pyarrow": "pyarrow"}.get(module, module)
    return require(module, f"{package} (or: pip install offshore-crane[sweep])", purpose)


# =========================================================================== the grid
@dataclass(frozen=True)
class Grid:
    """A checked grid: ``keys`` in product order, ``values`` their lists.

    Attributes:
        keys: Grid keys; robot fields by their dotted names, then the sea keys.
        values: ``{key: tuple of values}``: floats (``seed``: ints).
        where: The grid file (or ``"grid"``), for messages.
    """

    keys: tuple
    values: dict
    where: str = "grid"

    def cases(self) -> list[dict]:
        """The product of the lists, in order: the last key varies fastest (the seeds
        of one case are consecutive; robot fields vary slowest, so that a worker keeps
        its robot for many cases)."""
        return [dict(zip(self.keys, combo))
                for combo in itertools.product(*(self.values[k] for k in self.keys))]

    def as_dict(self) -> dict:
        return {k: list(self.values[k]) for k in self.keys}


def _flatten(table: dict, where: str, prefix: str = "") -> dict:
    out = {}
    for key, value in table.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            out.update(_flatten(value, where, f"{name}."))
        else:
            out[name] = value
    return out


def load_grid(path) -> dict:
    """Read a grid file (TOML): ``{key: list}`` with TOML's dotted keys joined
    (``payload.mass = [...]`` and ``"payload.mass" = [...]`` alike); checked by
    :func:`check_grid` against a scene.

    Raises:
        GridError: unreadable file, invalid TOML.
    """
    from offshore_crane.errors import InputError
    from offshore_crane.io import read_toml

    where = os.fspath(path)
    try:
        data = read_toml(where, "grid file")
    except InputError as exc:
        raise GridError(str(exc), path=where) from None
    return _flatten(data, where)


def _plain(v) -> str:
    return json.dumps(v) if not isinstance(v, float) else f"{v:g}"


def check_grid(scene, grid: dict, where: str = "grid") -> Grid:
    """Check a grid against a scene, value by value, before anything runs.

    Args:
        scene: The :class:`~offshore_crane.scenes.Scene` swept.
        grid: ``{key: list of values}`` (:func:`load_grid`, or a dict).
        where: The grid's name in messages (its file).

    Returns:
        :class:`Grid`.

    Raises:
        GridError: not a table of lists, an unknown key (neither a sea key nor a robot
            field), an empty list, a repeated value, a value that is not a number (an
            integer ≥ 0 for ``seed``), a sea key on a scene that is not a sea, a key given
            twice (an alias and its dotted name), or a value the scene's own checks refuse
            (``hs <= 0``, a negative mass, ...), naming the key and the index.
    """
    from offshore_crane.errors import DescriptionError, SceneError
    from offshore_crane.robot.overrides import normalise

    if not isinstance(grid, dict) or not grid:
        raise GridError(f"{where}: the grid is empty: give lists of values, e.g. "
                        "hs = [1.0, 2.0]", path=where)
    robot_keys, sea, values = [], [], {}
    for key, raw in grid.items():
        if not isinstance(raw, (list, tuple)):
            raise GridError(f"{where}: {key} = {_plain(raw)}: must be a list of values, "
                            f"e.g. {key} = [{_plain(raw)}]", path=where, key=key)
        if not raw:
            raise GridError(f"{where}: {key} = []: the list is empty: give at least one "
                            "value (a grid's cases are the product of its lists)",
                            path=where, key=key)
        if key in SEA_KEYS:
            name = key
            if scene.trajectory != "sea":
                raise GridError(f"{where}: {key}: a sea key, but the scene "
                                f"{scene.where()} is not a sea (its [trajectory] source is "
                                f"{scene.trajectory!r}): use a scene with source = \"sea\"",
                                path=where, key=key)
            sea.append(key)
        else:
            try:
                name = next(iter(normalise({key: 0.0}, where)))
            except DescriptionError as exc:
                raise GridError(f"{where}: unknown grid key {key!r}: neither a sea key "
                                f"({', '.join(SEA_KEYS)}) nor a robot field ({exc})",
                                path=where, key=key) from None
            if name in values:
                raise GridError(f"{where}: {key} and {name} name the same robot field: "
                                "give it once", path=where, key=key)
            robot_keys.append(name)
        checked = []
        for i, v in enumerate(raw):
            bad = isinstance(v, bool) or not isinstance(v, (int, float))
            if key == "seed":
                if bad or not isinstance(v, int) or v < 0:
                    raise GridError(f"{where}: seed[{i}] = {_plain(v)}: must be an integer "
                                    "≥ 0", path=where, key=key, index=i)
                checked.append(int(v))
                continue
            if bad or not math.isfinite(v):
                raise GridError(f"{where}: {key}[{i}] = {_plain(v)}: must be a finite "
                                "number", path=where, key=key, index=i)
            checked.append(float(v))
        if len(set(checked)) != len(checked):
            raise GridError(f"{where}: {key} = {_plain(list(raw))}: names a value twice",
                            path=where, key=key)
        for i, v in enumerate(checked):         # the scene's own checks, value by value
            try:
                case_scene(scene, {name: v}, origin=f"{where}: {key}[{i}] = {_plain(v)}")
            except (SceneError, DescriptionError) as exc:
                raise GridError(str(exc), path=where, key=key, index=i) from None
        values[name] = tuple(checked)
    keys = tuple(sorted(robot_keys)) + tuple(k for k in SEA_KEYS if k in sea)
    return Grid(keys, values, where)


def case_scene(scene, params: dict, origin: str | None = None):
    """``scene`` with a case's values: sea keys into ``[sea]``, robot fields (dotted
    names) over the scene's own (a grid value replaces the scene's, on purpose)."""
    sea = {k: v for k, v in params.items() if k in SEA_KEYS}
    robot = {k: v for k, v in params.items() if k not in SEA_KEYS}
    changes = {}
    if sea:
        changes["sea"] = {**scene.sea, **sea}
    if robot:
        changes.update(robot={**scene.robot, **robot}, arm=None, payload=None)
    if not changes:
        return scene
    return replace(scene, origin=origin or f"{scene.where()} case {params}", **changes)


def case_id(params: dict) -> str:
    """A case's identity: 16 hex digits of the SHA-256 of its values (sorted keys,
    floats by ``repr``), stable across runs, processes and grid orders."""
    text = json.dumps({k: params[k] for k in sorted(params)}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


# =========================================================================== one case
@dataclass
class CaseRun:
    """One scene run and its envelope.

    Attributes:
        scene, robot, trajectory: What ran.
        kind: ``"inverse dynamics"`` or ``"simulation"``.
        t, q, qd, X: ``(N,)`` [s], ``(N, 9)`` the motion [m, rad, /s] and the actuator
            forces [N·m, N] the envelope is of (the simulation's applied forces).
        result: The :class:`~offshore_crane.dynamics.Result` (condition numbers), of
            the inverse dynamics of the simulated motion for a simulation.
        simulation: The :class:`~offshore_crane.simulation.rigid.SimulationResult`, or None.
        envelope: :class:`~offshore_crane.studies.sizing.Envelope`.
        seconds: Run time of the trajectory and the dynamics (the case's own
            computation) [s].
    """

    scene: object
    robot: object
    trajectory: object
    kind: str
    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    X: np.ndarray
    result: object
    simulation: object
    envelope: object
    seconds: float


def record(scene, robot=None, trajectory=None, *, backend: str = "auto", threads: int = 1,
           limits: bool = True, thresholds=None, method: str | None = None) -> CaseRun:
    """Run one scene and take its envelope: the inverse dynamics of its trajectory
    (method ``scene.methods[0]``), or, when the scene has a ``[control]`` section, the
    forward simulation under its controller over the trajectory's span (the envelope is
    of the applied forces; the condition numbers of the inverse dynamics of the
    simulated motion).

    With a payload on a cable (``payload.cable_length > 0``) the inverse dynamics is the
    swing's (:func:`offshore_crane.dynamics.cable.swing`, the scene's ``[cable]`` options) and the
    envelope gains the largest sway and the tension range; a slack cable fails the case.

    Raises:
        The errors of the loaders, of :func:`offshore_crane.dynamics.solve`, of
        :mod:`offshore_crane.dynamics.cable` (:class:`~offshore_crane.errors.SlackCableError`) and
        of :func:`offshore_crane.simulation.rigid.simulate`.
    """
    from offshore_crane import scenes
    from offshore_crane.dynamics import solve
    from offshore_crane.robot.kinematics.workspace import Thresholds
    from offshore_crane.studies.sizing import conditions, envelope

    thresholds = thresholds or Thresholds()
    robot = robot or scenes.load_robot(scene)
    t0 = time.perf_counter()
    traj = trajectory or scenes.load_trajectory(scene, robot)
    options = dict(limits=limits, thresholds=thresholds, backend=backend, threads=threads)
    simulation = None
    if scene.control:
        simulation = _simulate(scene, robot, traj, limits)
        t, q, qd, X = simulation.t, simulation.q, simulation.qd, simulation.X
        result = solve(robot, q, qd, simulation.qdd, "kane", scene.gravity,
                       outputs=scene.wanted(), t=t, **options)
        kind = "simulation"
    else:
        if robot.hybrid.cable is not None:            # the swing (offshore_crane.dynamics.cable)
            result = scenes._swing(scene, robot, traj, method or scene.methods[0],
                                   limits=limits, thresholds=thresholds)
        else:
            result = solve(robot, traj.q, traj.qd, traj.qdd, method or scene.methods[0],
                           scene.gravity, leg_model=scene.leg_model, outputs=scene.wanted(),
                           t=traj.t, **options)
        t, q, qd, X = traj.t, traj.q, traj.qd, result.X
        kind = "inverse dynamics"
    seconds = time.perf_counter() - t0
    wanted = scene.wanted()
    arm = any(n in wanted for n in ("T1", "T2", "Fs"))
    legs = any(n.startswith("Fl") for n in wanted)
    Xw = np.where([n in wanted for n in ("T1", "T2", "Fs", "Fl1", "Fl2", "Fl3", "Fl4",
                                         "Fl5", "Fl6")], X, np.nan)
    env = envelope(robot, t, q, qd, Xw, conditions(result), arm=arm, legs=legs,
                   cable=getattr(result, "cable", None))
    return CaseRun(scene, robot, traj, kind, t, q, qd, Xw, result, simulation, env, seconds)


def _simulate(scene, robot, traj, limits: bool):
    """The scene's controlled run over its trajectory's span (as ``offshore-crane
    simulate --scene`` without flags)."""
    from offshore_crane import scenes
    from offshore_crane.simulation.rigid import simulate

    c = scene.control
    q0, qd0, _ = (x[0] for x in traj.reference(traj.t[:1]))
    q0 = q0.copy()
    if c.get("initial_error") is not None:
        q0 += np.asarray(c["initial_error"], dtype=float)
    return simulate(robot, float(traj.t[-1] - traj.t[0]), traj.reference, q0=q0, qd0=qd0,
                    controller=scenes.controller(scene, robot), gravity=scene.gravity,
                    step=c.get("step", 1e-3), integrator=c.get("integrator", "rk4"),
                    limits=limits, t0=float(traj.t[0]))


def _failed_row() -> dict:
    """The envelope columns of a failed case: NaN, 0 and empty strings."""
    from offshore_crane.studies.sizing import row_columns

    row = {}
    for name, kind in row_columns():
        row[name] = math.nan if kind == "float64" else (0 if kind == "int64" else "")
    return row


def run_case(scene, params: dict, backend: str = "auto", timing: dict | None = None) -> dict:
    """One case: the row of :func:`row_schema` (``case_id``, the case's values, its
    status, error and envelope). A library error (workspace, singularity, simulation
    stopped, missing capability) is recorded in the row (``status = "failed"``,
    ``error_type``, ``error``) instead of raised; the row's other numbers are then NaN.
    ``timing`` (a dict), when given, receives ``compute``: the case's own computation
    (trajectory and dynamics, :attr:`CaseRun.seconds`) [s] — never part of the row, which
    holds only what is reproducible."""
    import warnings

    row = {"case_id": case_id(params), **params}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            done = record(case_scene(scene, params), backend=backend, threads=1)
        except OffshoreCraneError as exc:
            row.update(status="failed", error_type=type(exc).__name__, error=str(exc),
                       **_failed_row())
            done = None
    if done is not None:
        row.update(status="ok", error_type="", error="", **done.envelope.row())
    if timing is not None:
        timing["compute"] = done.seconds if done is not None else 0.0
    from offshore_crane.robot.kinematics.workspace import OffshoreCraneWarning

    row["warnings"] = sum(issubclass(w.category, OffshoreCraneWarning) for w in caught)
    return row


def _task(payload):
    """What a worker runs: ``(scene, params, backend)`` → ``(case_id, row, seconds,
    compute seconds)``: the run time of :func:`run_case` whole and of the case's own
    computation [s]."""
    scene, params, backend = payload
    timing: dict = {}
    t0 = time.perf_counter()
    row = run_case(scene, params, backend, timing)
    return row["case_id"], row, time.perf_counter() - t0, timing["compute"]


def row_schema(grid: Grid):
    """The ``pyarrow.Schema`` of a sweep's rows: ``case_id``, the grid's keys (float64,
    ``seed`` int64), ``status``, ``error_type``, ``error``, ``warnings``, then the
    envelope (:func:`offshore_crane.studies.sizing.row_columns`)."""
    pa = _install_hint("pyarrow", "A sweep's results (Parquet)")
    from offshore_crane.studies.sizing import row_columns

    types = {"float64": pa.float64(), "int64": pa.int64(), "string": pa.string()}
    cols = [("case_id", "string")] + [(k, "int64" if k == "seed" else "float64")
                                      for k in grid.keys]
    cols += list(CASE_COLUMNS[1:]) + row_columns()
    return pa.schema([(n, types[t]) for n, t in cols])


# =========================================================================== the store
def scene_hash(scene) -> str:
    """SHA-256 of what a scene computes: its fields (but where it was read from) and the
    content of every file it reads (robot description, trajectory CSV, vessel RAOs)."""
    from offshore_crane.robot.description import default_description

    h = hashlib.sha256()
    data = {f.name: getattr(scene, f.name) for f in fields(scene)
            if f.name not in ("path", "origin", "robot_description", "name",
                              "description")}
    h.update(json.dumps(data, sort_keys=True, default=repr).encode())
    files = [scene.robot_description or default_description()]
    if scene.trajectory not in ("table1", "sea"):
        files.append(scene.trajectory)
    if "vessel" in scene.sea and os.path.isfile(str(scene.sea["vessel"])):
        files.append(scene.sea["vessel"])
    for f in files:
        h.update(b"\0" + Path(f).read_bytes())
    return h.hexdigest()


class ResultsStore:
    """A sweep's results directory (see the module docstring).

    Create with :meth:`open` (checks only, writes nothing), then :meth:`create` before
    the first row; :meth:`write` stores a row atomically; :meth:`done` lists the finished
    case ids; :meth:`read` returns the rows as a ``pyarrow.Table``.
    """

    def __init__(self, path, scene_name: str, digest: str, manifest: dict | None):
        self.path = os.fspath(path)
        self.scene_name = scene_name
        self.digest = digest
        self.manifest = manifest

    @classmethod
    def open(cls, path, scene) -> "ResultsStore":
        """Check ``path`` for the sweep of ``scene`` (nothing is written).

        Raises:
            ResultsDirectoryError: ``path`` is a file; a directory that holds files but
                no manifest; a manifest of another scene; a damaged manifest; a missing
                parent directory.
        """
        given = os.fspath(path)
        digest = scene_hash(scene)

        def refuse(reason):
            raise ResultsDirectoryError(f"--out {given}: {reason}", path=given, reason=reason)

        if os.path.exists(given) and not os.path.isdir(given):
            refuse("exists and is not a directory: give a results directory (new, empty, "
                   "or of an earlier run of the same scene)")
        if not os.path.isdir(given):
            parent = os.path.dirname(os.path.abspath(given))
            if not os.path.isdir(parent):
                refuse(f"directory {os.path.dirname(given) or '.'} does not exist: create "
                       "it first")
            return cls(given, scene.name, digest, None)
        manifest_path = os.path.join(given, MANIFEST)
        if not os.path.exists(manifest_path):
            if os.listdir(given):
                refuse("exists and holds files but no sweep manifest (_manifest.json): "
                       "it is not a results directory; choose a new or empty directory")
            return cls(given, scene.name, digest, None)
        try:
            manifest = json.loads(Path(manifest_path).read_text(encoding="utf-8"))
            ok = isinstance(manifest, dict) and manifest.get("format") == MANIFEST_FORMAT
            other = manifest["scene"]["hash"] if ok else None
        except (OSError, ValueError, KeyError, TypeError):
            ok = False
        if not ok:
            refuse(f"its {MANIFEST} is damaged or not a sweep manifest: choose another "
                   "directory")
        if other != digest:
            refuse(f"holds the results of another scene ({manifest['scene'].get('name')!r}"
                   f", hash {other[:12]}), not of {scene.name!r} (hash {digest[:12]}): "
                   "results of different scenes are never mixed; choose another directory")
        return cls(given, scene.name, digest, manifest)

    def create(self, grid: Grid) -> None:
        """Make the directory and write (or extend) the manifest with ``grid``."""
        from offshore_crane.io import write_text

        try:
            os.makedirs(self.path, exist_ok=True)
        except OSError as exc:
            raise ResultsDirectoryError(f"--out {self.path}: cannot create the directory: "
                                        f"{exc.strerror}", path=self.path,
                                        reason=str(exc.strerror)) from None
        manifest = self.manifest or {"format": MANIFEST_FORMAT, "version": 1,
                                     "scene": {"name": self.scene_name,
                                               "hash": self.digest},
                                     "grids": []}
        for name in os.listdir(self.path):          # a killed run's half-written row
            if name.startswith(".oc-") and name.endswith(".tmp"):
                try:
                    os.unlink(os.path.join(self.path, name))
                except OSError:
                    pass
        if grid.as_dict() not in manifest["grids"]:
            manifest["grids"].append(grid.as_dict())
            write_text(os.path.join(self.path, MANIFEST), json.dumps(manifest, indent=1))
        self.manifest = manifest

    def part(self, cid: str) -> str:
        return os.path.join(self.path, f"case-{cid}.parquet")

    def done(self) -> set:
        """Case ids with a row in the directory."""
        if not os.path.isdir(self.path):
            return set()
        return {n[5:-8] for n in os.listdir(self.path)
                if n.startswith("case-") and n.endswith(".parquet")}

    def write(self, row: dict, schema) -> None:
        """Store one row atomically (temporary file + rename in the directory)."""
        from offshore_crane.io import write_bytes

        write_bytes(self.part(row["case_id"]), _parquet_bytes([row], schema))

    def read(self, schema, ids=None):
        """The rows (``pyarrow.Table``) of ``ids`` (default all), unordered."""
        pa = _install_hint("pyarrow", "A sweep's results (Parquet)")
        import pyarrow.parquet as pq

        names = sorted(self.done() if ids is None else set(ids) & self.done())
        tables = [pq.ParquetFile(self.part(c)).read().cast(schema) for c in names]
        return pa.concat_tables(tables) if tables else schema.empty_table()


def _parquet_bytes(rows: list, schema) -> bytes:
    pa = _install_hint("pyarrow", "A sweep's results (Parquet)")
    import pyarrow.parquet as pq

    table = pa.Table.from_pylist(rows, schema=schema)
    sink = pa.BufferOutputStream()
    # one row: no compression, dictionaries or statistics (they cost ~1 ms a part and
    # save nothing); a reader merging the parts may rewrite them compacted
    pq.write_table(table, sink, compression="none", use_dictionary=False,
                   write_statistics=False)
    return sink.getvalue().to_pybytes()


# =========================================================================== backends
def _check_scheduler(scheduler) -> str | None:
    from offshore_crane.errors import InputError

    if scheduler is None or scheduler == "local":
        return scheduler
    if not isinstance(scheduler, str) or "://" not in scheduler:
        raise InputError(f"--scheduler {scheduler!r}: give 'local' (a Dask LocalCluster on "
                         "this machine) or a scheduler address tcp://HOST:PORT",
                         name="scheduler")
    return scheduler


def connect(scheduler: str, workers: int | None = None, timeout: float = CONNECT_TIMEOUT):
    """A ``dask.distributed.Client``: on a new ``LocalCluster`` (``"local"``: processes,
    ``workers`` of one thread each, no dashboard) or connected to ``tcp://HOST:PORT``.

    Returns:
        ``(client, cluster or None)``.

    Raises:
        SchedulerError: the scheduler cannot be reached within ``timeout`` [s] (or the
            local cluster does not start).
    """
    distributed = _install_hint("distributed", "--scheduler (Dask)")
    import logging

    try:
        if scheduler == "local":
            cluster = distributed.LocalCluster(n_workers=workers or LOCAL_WORKERS,
                                               threads_per_worker=1, processes=True,
                                               dashboard_address=None)
            return distributed.Client(cluster), cluster
        logging.getLogger("distributed").setLevel(logging.CRITICAL)
        return distributed.Client(scheduler, timeout=f"{timeout}s"), None
    except (OSError, TimeoutError) as exc:
        reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise SchedulerError(f"--scheduler {scheduler}: cannot reach the Dask scheduler "
                             f"within {timeout:g} s ({reason}): start it (dask scheduler) or "
                             "check the address; nothing was run or written",
                             address=scheduler, reason=reason) from None


def _serial(payloads):
    for p in payloads:
        yield _task(p)


def _joblib(payloads, workers: int):
    joblib = _install_hint("joblib", "--workers (parallel cases)")
    parallel = joblib.Parallel(n_jobs=workers, backend="loky",
                               return_as="generator_unordered", batch_size=1)
    yield from parallel(joblib.delayed(_task)(p) for p in payloads)


def _dask(payloads, client):
    distributed = _install_hint("distributed", "--scheduler (Dask)")
    if not payloads:
        return
    futures = client.map(_task, payloads, pure=False)
    try:
        for _, result in distributed.as_completed(futures, with_results=True):
            yield result
    finally:
        client.cancel(futures)


def _warm_up(scene) -> None:
    """Compile or load, once in this process, the kernels this sweep's cases use: the
    inverse dynamics of the scene's first method (and Kane's, which a simulated case
    uses for its condition numbers), the hanging load's kernels, the simulation loop for a
    scene with ``[control]``
    (:func:`offshore_crane.dynamics.warm_up` would also load Pinocchio for the RNEA
    path, which a Kane sweep never uses)."""
    from offshore_crane import scenes
    from offshore_crane.dynamics import numba_available, solve

    if not numba_available():
        return
    from offshore_crane.dynamics.cable import warm_up as warm_up_cable

    robot = scenes.load_robot(scene).without_hanging_payload()
    q = np.zeros((1, 9))
    q[0, 2] = float(robot.home_height or 0.5)
    for method in dict.fromkeys((scene.methods[0], "kane")):
        solve(robot, q, 0 * q, 0 * q, method=method, backend="numba", limits=False)
    warm_up_cable()            # any case may hang its payload (a grid's cable_length)
    if scene.control:
        from offshore_crane.simulation.rigid import warm_up as warm_up_simulation

        warm_up_simulation()


def _warm_workers(client, scene) -> None:
    """Load (or compile) the kernels on a remote cluster's workers one at a time, so
    that workers sharing a cache never compile it at once (the first compiles, the others
    load)."""
    for address in sorted(client.scheduler_info()["workers"]):
        client.run(_warm_up, scene, workers=[address])


def run(scene, grid, workers: int | None = 1, scheduler: str | None = None, out=None, *,
        progress: bool = False, stats: dict | None = None, backend: str = "auto",
        where: str = "grid"):
    """Run a sweep: every case of ``grid`` on ``scene``, one row per case.

    Args:
        scene: A :class:`~offshore_crane.scenes.Scene` (or a scene file path).
        grid: ``{key: list}`` (:func:`load_grid`), a grid file path, or a :class:`Grid`.
        workers: Parallel processes: 1 (serially, in this process), N > 1 (joblib loky
            workers), or with ``scheduler = "local"`` the cluster's size (default 2).
        scheduler: None (joblib or serial), ``"local"`` (a Dask ``LocalCluster``) or a
            Dask scheduler address ``tcp://HOST:PORT``.
        out: A results directory (resumable: finished cases are skipped), or None to
            keep the rows in memory only.
        progress: Show a progress bar (tqdm) on standard error.
        stats: A dict filled with ``cases``, ``skipped``, ``ran``, ``failed``,
            ``seconds`` (wall time from the dispatch to the last row written),
            ``case_seconds`` (each case's run time in its worker, :func:`run_case` whole)
            and ``compute_seconds`` (each case's own computation: trajectory and
            dynamics) — for benchmarks.
        backend: Kernels of every case (``"auto"``: compiled when Numba is installed),
            resolved once here so that every worker runs the same code.
        where: The grid's name in messages when it is a dict.

    Returns:
        ``pandas.DataFrame``: one row per case of the grid in grid order (column ``case``,
        its index), with the columns of :func:`row_schema`.

    Raises:
        GridError, SceneError: bad grid or scene (before anything runs or is written).
        ResultsDirectoryError: ``out`` is not a results directory of this scene.
        SchedulerError: the scheduler cannot be reached (nothing written).
    """
    from offshore_crane import scenes
    from offshore_crane.dynamics import resolve_backend
    from offshore_crane.errors import InputError

    if isinstance(scene, (str, os.PathLike)):
        scene = scenes.load_scene(scene)
    if isinstance(grid, (str, os.PathLike)):
        where = os.fspath(grid)
        grid = load_grid(grid)
    if not isinstance(grid, Grid):
        grid = check_grid(scene, grid, where)
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise InputError(f"workers = {workers!r}: must be an integer ≥ 1", name="workers")
    scheduler = _check_scheduler(scheduler)
    backend = resolve_backend(backend)
    _install_hint("pandas", "A sweep's results table")
    schema = row_schema(grid)
    cases = grid.cases()
    ids = [case_id(c) for c in cases]
    store = ResultsStore.open(out, scene) if out is not None else None
    finished = store.done() if store is not None else set()
    pending = [(scene, c, backend) for c, cid in zip(cases, ids) if cid not in finished]
    pending = list({case_id(p[1]): p for p in pending}.values())     # each case once
    client = cluster = None
    if scheduler is not None and pending:
        client, cluster = connect(scheduler, workers)
    rows: dict = {}
    info = {"cases": len(set(ids)), "skipped": len(set(ids) & finished), "ran": 0,
            "failed": 0, "case_seconds": [], "compute_seconds": []}
    try:
        if store is not None:
            store.create(grid)
        if pending:
            _warm_up(scene)
            if client is not None and cluster is None:
                _warm_workers(client, scene)
        t0 = time.perf_counter()
        if client is not None:
            results = _dask(pending, client)
        elif (workers or 1) > 1 and len(pending) > 1:
            results = _joblib(pending, min(workers, len(pending)))
        else:
            results = _serial(pending)
        bar = None
        if progress:
            tqdm = _install_hint("tqdm", "the progress bar")
            bar = tqdm.tqdm(total=len(pending), unit="case", file=sys.stderr,
                            desc="sweep", leave=False)
        try:
            for cid, row, seconds, compute in results:
                if store is not None:
                    store.write(row, schema)
                rows[cid] = row
                info["ran"] += 1
                info["failed"] += row["status"] != "ok"
                info["case_seconds"].append(seconds)
                info["compute_seconds"].append(compute)
                if bar is not None:
                    bar.update()
        finally:
            if bar is not None:
                bar.close()
        info["seconds"] = time.perf_counter() - t0
    finally:
        if client is not None:
            client.close()
        if cluster is not None:
            cluster.close()
    if stats is not None:
        stats.update(info)
    fresh = [rows[c] for c in dict.fromkeys(ids) if c in rows]   # rows of this run, held
    table = _table(fresh, schema)
    if store is not None and len(fresh) < len(set(ids)):         # and those run before
        pa = _install_hint("pyarrow", "A sweep's results (Parquet)")
        table = pa.concat_tables([table, store.read(schema, set(ids) - set(rows))])
    df = table.to_pandas()
    order = {cid: i for i, cid in enumerate(ids)}
    df.insert(0, "case", df["case_id"].map(order).astype("int64"))
    return df.sort_values("case", kind="stable").reset_index(drop=True)


def _table(rows, schema):
    pa = _install_hint("pyarrow", "A sweep's results (Parquet)")
    return pa.Table.from_pylist(rows, schema=schema)


def read_results(out):
    """Every row of a results directory as a ``pandas.DataFrame`` (for a notebook)."""
    _install_hint("pandas", "A sweep's results table")     # to_pandas needs it
    ds = _install_hint("pyarrow.dataset", "A sweep's results (Parquet)")
    return ds.dataset(os.fspath(out), format="parquet").to_table().to_pandas()


# =========================================================================== verdicts
def group_keys(df) -> list:
    """The parameter columns of a results table but ``seed`` (a case's seeds form one
    group)."""
    from offshore_crane.studies.sizing import row_columns

    skip = {"case", "case_id", "seed", *(n for n, _ in CASE_COLUMNS),
            *(n for n, _ in row_columns()), *VERDICT_COLUMNS}
    return [c for c in df.columns if c not in skip]


def verdicts(df, scene, exposure: float | None = None):
    """One verdict per case over its seeds (:func:`offshore_crane.studies.sizing.verdict`'s
    rule, applied to the rows' utilisation columns: a capacity is constant over a case's
    seeds and the Gumbel fit is location-scale equivariant, so the most probable maximum
    of a utilisation is that of the peak divided by the capacity).

    Args:
        df: Rows of :func:`run`.
        scene: The scene swept (its ``[sea] scale`` when the grid does not vary it).
        exposure: Full-scale exposure [s] (default 3 h).

    Returns:
        ``pandas.DataFrame``: the group's parameters, ``seeds``, ``failed`` (seeds whose
        case failed), ``basis`` (``gumbel``, ``observed`` or ``failed``), ``record_s``,
        ``exposure_s``, ``{actuator}_util`` and ``worst_util`` (inf when a seed failed:
        not operable), ``governing``, ``governing_capacity``, ``error_type`` and
        ``error`` (of the first failed seed, else empty).
    """
    from offshore_crane.conventions import ACTUATORS
    from offshore_crane.studies.sizing import CAPACITIES, EXPOSURE, MIN_SEEDS, most_probable_maximum

    pd = _install_hint("pandas", "A sweep's results table")
    exposure = EXPOSURE if exposure is None else exposure
    keys = group_keys(df)
    sea = scene.trajectory == "sea"
    out = []
    groups = df.groupby(keys, sort=False, dropna=False) if keys else [((), df)]
    for values, g in groups:
        values = values if isinstance(values, tuple) else (values,)
        row = dict(zip(keys, values))
        ok = g[g["status"] == "ok"]
        scale = float(row.get("scale", scene.sea.get("scale", math.nan))) if sea else None
        n = len(g)
        gumbel = sea and len(ok) == n and n >= MIN_SEEDS
        record_s = (float(ok["duration_s"].iloc[0]) * math.sqrt(scale)
                    if sea and len(ok) else math.nan)
        row.update(seeds=n, failed=n - len(ok), record_s=record_s,
                   exposure_s=exposure if gumbel else math.nan,
                   basis="failed" if len(ok) < n else ("gumbel" if gumbel else "observed"))
        bad = g[g["status"] != "ok"]
        row.update(error_type=bad["error_type"].iloc[0] if len(bad) else "",
                   error=bad["error"].iloc[0] if len(bad) else "")
        util = np.full((9, len(CAPACITIES)), np.nan)
        for k, a in enumerate(ACTUATORS):
            for c, cap in enumerate(CAPACITIES):
                col = ok[f"{a}_util_{cap}"].to_numpy(dtype=float)
                if len(ok) < n or not len(col) or np.isnan(col).any():
                    continue
                util[k, c] = (most_probable_maximum(col, record_s, exposure) if gumbel
                              else col.max())
        for k, a in enumerate(ACTUATORS):
            u = util[k]
            row[f"{a}_util"] = math.nan if np.isnan(u).all() else float(np.nanmax(u))
        if len(ok) < n:
            row.update(worst_util=math.inf, governing="", governing_capacity="")
        elif np.isnan(util).all():
            row.update(worst_util=math.nan, governing="", governing_capacity="")
        else:
            k, c = np.unravel_index(np.nanargmax(util), util.shape)
            row.update(worst_util=float(util[k, c]), governing=ACTUATORS[k],
                       governing_capacity=CAPACITIES[c])
        out.append(row)
    return pd.DataFrame(out)


# =========================================================================== operability
@dataclass(frozen=True)
class Scatter:
    """A wave scatter diagram: occurrence of (Hs, Tp) cells, full scale.

    Attributes:
        hs: ``(m,)`` Hs of the rows (cell centres) [m], increasing.
        tp: ``(n,)`` Tp of the columns [s], increasing.
        p: ``(m, n)`` probabilities (normalised to sum 1).
        path: The file read, or None.
    """

    hs: np.ndarray
    tp: np.ndarray
    p: np.ndarray
    path: str | None = None


def load_scatter(path) -> Scatter:
    """Read a wave scatter diagram (CSV): lines starting with ``#`` are comments; the
    first other line is the header, its first cell a label (``hs_m/tp_s``) and the others
    the Tp of each column [s]; each further line an Hs [m] then the occurrences of its
    cells (probabilities, per mille or counts: normalised to sum 1).

    Raises:
        InputError: naming the file, the line and the cell (not a number, negative,
            not increasing, rows of different lengths, all zero).
    """
    from offshore_crane.errors import InputError
    from offshore_crane.io import read_text

    where = os.fspath(path)
    text = read_text(where, "scatter diagram")
    lines = [(i + 1, l) for i, l in enumerate(text.splitlines())
             if l.strip() and not l.lstrip().startswith("#")]
    if len(lines) < 2:
        raise InputError(f"{where}: a scatter diagram needs a header line (label, Tp "
                         "values [s]) and at least one row (Hs [m], occurrences)",
                         name=where)

    def numbers(lineno, cells, what):
        out = []
        for j, c in enumerate(cells):
            try:
                x = float(c)
            except ValueError:
                x = math.nan
            if not math.isfinite(x) or x < 0:
                raise InputError(f"{where}, line {lineno}, cell {j + 2}: {c.strip()!r} is "
                                 f"not a finite number ≥ 0 ({what})", name=where)
            out.append(x)
        return out

    head_line, head = lines[0]
    tp = numbers(head_line, head.split(",")[1:], "Tp [s]")
    hs, p = [], []
    for lineno, line in lines[1:]:
        cells = line.split(",")
        if len(cells) != len(tp) + 1:
            raise InputError(f"{where}, line {lineno}: {len(cells)} cells, but the header "
                             f"has {len(tp) + 1} (Hs then one per Tp)", name=where)
        h = numbers(lineno, cells[:1], "Hs [m]")[0]
        hs.append(h)
        p.append(numbers(lineno, cells[1:], "occurrence"))
    hs, tp, p = np.array(hs), np.array(tp), np.array(p)
    for name, a, line in (("Hs", hs, "rows"), ("Tp", tp, "header")):
        if len(a) > 1 and not (np.diff(a) > 0).all():
            raise InputError(f"{where}: the {name} values of the {line} must increase",
                             name=where)
    if (hs <= 0).any() or (tp <= 0).any():
        raise InputError(f"{where}: Hs and Tp must be > 0", name=where)
    if p.sum() <= 0:
        raise InputError(f"{where}: every occurrence is 0", name=where)
    return Scatter(hs, tp, p / p.sum(), where)


def limiting_hs(hs, util) -> float:
    """The largest Hs [m] up to which the utilisation stays ≤ 1, from utilisations at
    increasing ``hs``: linear interpolation between the last Hs within capacity and the
    first beyond; 0 when the smallest already exceeds; the largest swept Hs when none
    exceeds (beyond it nothing is known). A failed case counts as beyond (inf)."""
    hs, util = np.asarray(hs, float), np.asarray(util, float)
    order = np.argsort(hs)
    hs, util = hs[order], np.where(np.isnan(util[order]), 0.0, util[order])
    over = np.flatnonzero(util > 1.0)
    if not len(over):
        return float(hs[-1])
    j = int(over[0])
    if j == 0:
        return 0.0
    u0, u1 = util[j - 1], util[j]
    if not math.isfinite(u1):
        return float(hs[j - 1])
    return float(hs[j - 1] + (1.0 - u0) / (u1 - u0) * (hs[j] - hs[j - 1]))


def operability(table, scatter: Scatter, scene):
    """Operability over a scatter diagram, per heading and overall.

    For each heading (and combination of other swept parameters), the limiting Hs of each
    swept Tp (:func:`limiting_hs` on the worst utilisation of :func:`verdicts`) is
    interpolated linearly in Tp; a scatter cell is operable when its Hs ≤ that limit. Cells
    whose Tp lies outside the swept Tp range are not covered and count as not operable
    (their share is reported). Overall: the mean over the headings (equally likely).

    Returns:
        ``pandas.DataFrame``: the other parameters, ``heading``, ``operability_pct``,
        ``uncovered_pct``; and a row with ``heading = NaN`` (overall) per combination.
    """
    pd = _install_hint("pandas", "A sweep's results table")
    v = table.copy()
    for key in ("hs", "tp", "heading"):
        if key not in v.columns:
            v[key] = float(scene.sea.get(key, math.nan))
    others = [k for k in group_keys(v) if k not in ("hs", "tp", "heading")]
    out = []
    combos = v.groupby(others, sort=False, dropna=False) if others else [((), v)]
    for values, g in combos:
        values = values if isinstance(values, tuple) else (values,)
        base = dict(zip(others, values))
        per_heading = []
        for heading, h in g.groupby("heading", sort=True):
            tps = np.sort(h["tp"].unique())
            limits = np.array([limiting_hs(h.loc[h["tp"] == tp, "hs"],
                                           h.loc[h["tp"] == tp, "worst_util"]) for tp in tps])
            covered = (scatter.tp >= tps[0] - 1e-9) & (scatter.tp <= tps[-1] + 1e-9)
            lim = np.interp(scatter.tp, tps, limits)
            ok = (scatter.hs[:, None] <= lim[None, :] + 1e-12) & covered[None, :]
            pct = 100.0 * float((scatter.p * ok).sum())
            uncovered = 100.0 * float(scatter.p[:, ~covered].sum())
            per_heading.append(pct)
            out.append({**base, "heading": float(heading), "operability_pct": pct,
                        "uncovered_pct": uncovered})
        out.append({**base, "heading": math.nan,
                    "operability_pct": float(np.mean(per_heading)),
                    "uncovered_pct": float(np.mean([r["uncovered_pct"] for r in out[-len(
                        per_heading):]]))})
    return pd.DataFrame(out)
