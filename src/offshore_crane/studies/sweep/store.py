"""The results store: a directory with a manifest naming the scene and its grids, locked for
one run at a time, its rows in Parquet row files (:mod:`.rowfiles`: batches while a run
goes, one file per run after it), resumed after a stop.
"""

from __future__ import annotations

import hashlib
import json
import os
from dataclasses import fields
from pathlib import Path

from offshore_crane.errors import ResultsDirectoryError
from offshore_crane.special_files import what_is
from offshore_crane.studies.sweep.grid import Grid, install_hint
from offshore_crane.studies.sweep.rowfiles import BatchWriter, case_ids, read_rows, recover


MANIFEST = "_manifest.json"
MANIFEST_FORMAT = "offshore-crane sweep results"
#: 2: case ids of the resolved case (:class:`~offshore_crane.studies.sweep.grid.CaseIds`);
#: 1: of the grid's values as given (migrated when a run takes the directory).
MANIFEST_VERSION = 2


# =========================================================================== the store
def scene_hash(scene) -> str:
    """SHA-256 of what a scene computes: its fields (but where it was read from) and the
    content of every file it reads (robot description, trajectory CSV, vessel RAOs)."""
    h = hashlib.sha256()
    data = {f.name: getattr(scene, f.name) for f in fields(scene)
            if f.name not in ("path", "origin", "robot_description", "name",
                              "description")}
    h.update(json.dumps(data, sort_keys=True, default=repr).encode())
    for f in scene.data_files():
        h.update(b"\0" + Path(f).read_bytes())
    return h.hexdigest()


#: The lock file that makes a results directory one run's at a time (``filelock``: an OS
#: lock, released when its process ends, however it ends) and who holds it.
LOCK, LOCK_INFO = "_lock", "_lock.json"


class ResultsStore:
    """A sweep's results directory (see the module docstring).

    Create with :meth:`open` (checks only, writes nothing), :meth:`lock` it for the run,
    :meth:`create` the manifest before the first case runs; :meth:`writer` stores the
    rows in batches; :meth:`done` lists the finished case ids; :meth:`read` returns the
    rows as a ``pyarrow.Table``, each case once.
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
            refuse(f"exists and is not a directory ({what_is(given)}): give a results "
                   "directory (new, empty, or of an earlier run of the same scene)")
        if not os.path.isdir(given):
            parent = os.path.dirname(os.path.abspath(given))
            if not os.path.isdir(parent):
                refuse(f"directory {os.path.dirname(given) or '.'} does not exist: create "
                       "it first")
            return cls(given, scene.name, digest, None)
        manifest_path = os.path.join(given, MANIFEST)
        if not os.path.exists(manifest_path):
            # the lock, its holder's name, and the whole-file writes' temporaries
            # (.oc-*.tmp) of a run that has just taken the directory are not results
            if [n for n in os.listdir(given) if n not in (LOCK, LOCK_INFO)
                    and not n.startswith(".oc-")]:
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

    def lock(self, scene) -> None:
        """Take the directory for this run (creating it), until :meth:`release`: a second
        run on it is refused at once, naming the process that holds it; a lock left by a
        killed run is free (the OS released it). Then check the directory again: a run
        of another scene may have claimed it since :meth:`open`.

        Raises:
            ResultsDirectoryError: the directory is in use, cannot be created or written
                (read-only: one line naming it and what to do), its lock file cannot be
                opened, or it now holds another scene's results.
        """
        import datetime

        from offshore_crane.errors import OutputError
        from offshore_crane.io import write_text

        filelock = install_hint("filelock", "A sweep's results directory lock")
        self._created = not os.path.isdir(self.path)
        self._had_manifest = os.path.isfile(os.path.join(self.path, MANIFEST))
        self._make_directory()
        self._lock = filelock.FileLock(os.path.join(self.path, LOCK), timeout=0)
        try:
            self._lock.acquire()
        except filelock.Timeout:                # a TimeoutError, so an OSError: first
            who = _holder(self.path)
            reason = f"in use by {who}"
            raise ResultsDirectoryError(f"--out {self.path}: {reason}: wait for that sweep "
                                        "to end or choose another directory",
                                        path=self.path, reason=reason) from None
        except OSError as exc:
            self._unmake_directory()
            raise self._refused(exc) from None
        since = datetime.datetime.now().strftime("%Y-%m-%d %H:%M:%S")
        try:
            write_text(os.path.join(self.path, LOCK_INFO),        # whole, or not at all
                       json.dumps({"pid": os.getpid(), "since": since}))
        except OutputError as exc:             # the lock file could be opened, not made
            self.release()
            raise self._refused(exc, writable=False) from None
        try:
            current = ResultsStore.open(self.path, scene)
        except ResultsDirectoryError:
            self.release()
            raise
        self.manifest = current.manifest
        try:
            recover(self.path)              # what killed runs left, made whole
            if self.manifest is not None and self.manifest.get("version", 1) < 2:
                self._migrate(scene)
        except BaseException:
            self.release()
            raise

    def _refused(self, exc: OSError, writable: bool | None = None) -> ResultsDirectoryError:
        """The one-line error of a directory whose lock (or its holder's note) cannot be
        written: not ``writable`` (permissions, a read-only mount: by default judged from
        ``exc``) or a ``_lock`` that cannot be opened (a directory of that name)."""
        import errno

        reason = getattr(exc, "reason", None) or exc.strerror or type(exc).__name__
        if writable is None:
            writable = not (isinstance(exc, PermissionError) or exc.errno == errno.EROFS)
        if not writable:
            what = ("is not writable, and a run writes its lock and rows there: make it "
                    "writable or give another --out (sweep.read_results reads it as it is)")
        else:
            what = (f"its lock file {LOCK} cannot be opened: remove {LOCK} if it is not a "
                    "sweep's lock, or give another --out")
        return ResultsDirectoryError(f"--out {self.path}: {what} ({reason})",
                                     path=self.path, reason=reason)

    def _migrate(self, scene) -> None:
        """Version-1 rows under the ids of their resolved cases (the grid keys' values of
        each row), each case once, in one new file; the old files removed; then the
        manifest says version 2. Killed on the way, the next run does it again (the
        new file's ids map to themselves)."""
        from offshore_crane.io import write_bytes, write_text
        from offshore_crane.studies.sweep.grid import CaseIds
        from offshore_crane.studies.sweep.rowfiles import (each_case_once, new_run_token,
                                                           parquet_bytes, row_files)

        pa = install_hint("pyarrow", "A sweep's results (Parquet)")

        names = row_files(self.path)
        table = read_rows(self.path, names)
        if table is not None:
            keys = [k for k in dict.fromkeys(k for g in self.manifest["grids"] for k in g)
                    if k in table.column_names]
            identify = CaseIds(scene)
            ids = [identify({k: v for k, v in row.items() if v is not None})
                   for row in table.select(keys).to_pylist()]
            table = each_case_once(table.set_column(
                table.schema.get_field_index("case_id"), "case_id", pa.array(ids, pa.string())))
            target = f"rows-{new_run_token()}.parquet"
            write_bytes(os.path.join(self.path, target), parquet_bytes(table))
            for n in names:
                os.unlink(os.path.join(self.path, n))
        self.manifest["version"] = MANIFEST_VERSION
        write_text(os.path.join(self.path, MANIFEST), json.dumps(self.manifest, indent=1))

    def _make_directory(self) -> None:
        try:
            os.makedirs(self.path, exist_ok=True)
        except OSError as exc:
            raise ResultsDirectoryError(f"--out {self.path}: cannot create the directory: "
                                        f"{exc.strerror}", path=self.path,
                                        reason=str(exc.strerror)) from None

    def _unmake_directory(self) -> None:
        """Remove the directory :meth:`lock` made, if it is still empty."""
        if self._created:
            try:
                os.rmdir(self.path)
            except OSError:
                pass

    def discard_if_new(self) -> None:
        """Remove the directory this run made (call under :meth:`lock`, before any row):
        its manifest and lock files, and the directory when it was new."""
        if self._had_manifest:
            return
        for name in (MANIFEST, LOCK_INFO):
            try:
                os.unlink(os.path.join(self.path, name))
            except OSError:
                pass
        self.release()
        try:
            os.unlink(os.path.join(self.path, LOCK))
            if self._created:
                os.rmdir(self.path)
        except OSError:
            pass

    def release(self) -> None:
        """Give the directory back (see :meth:`lock`)."""
        lock = getattr(self, "_lock", None)
        if lock is not None and lock.is_locked:
            try:
                os.unlink(os.path.join(self.path, LOCK_INFO))
            except OSError:
                pass
            lock.release()

    def create(self, grid: Grid, values: dict | None = None) -> None:
        """Make the directory and write (or extend) the manifest with ``grid`` and the
        scene's own ``values`` of its keys (:func:`~offshore_crane.studies.sweep.grid.
        scene_values`: what a row of a grid that did not vary a key had)."""
        from offshore_crane.io import write_text

        self._make_directory()
        manifest = self.manifest or {"format": MANIFEST_FORMAT,
                                     "version": MANIFEST_VERSION,
                                     "scene": {"name": self.scene_name,
                                               "hash": self.digest},
                                     "grids": []}
        known = manifest["scene"].setdefault("values", {})
        new_values = {k: v for k, v in (values or {}).items() if k not in known}
        if grid.as_dict() not in manifest["grids"] or new_values:
            known.update(new_values)
            if grid.as_dict() not in manifest["grids"]:
                manifest["grids"].append(grid.as_dict())
            target = os.path.join(self.path, MANIFEST)
            write_text(target, json.dumps(manifest, indent=1))
            with open(target, "rb") as fh:          # on disk before any case runs
                os.fsync(fh.fileno())
        self.manifest = manifest

    def done(self) -> set:
        """Case ids with a row in the directory.

        Raises:
            ResultsDirectoryError: a damaged row file (named).
        """
        return case_ids(self.path)

    def writer(self, schema) -> BatchWriter:
        """A :class:`~offshore_crane.studies.sweep.rowfiles.BatchWriter` for this run's
        rows (call under :meth:`lock`, after :meth:`create`)."""
        return BatchWriter(self.path, schema)

    def read(self, ids=None):
        """The rows (``pyarrow.Table``, each case once, unordered) of ``ids`` (default
        all), or None when there are none."""
        return read_rows(self.path, ids=ids)


#: How long a refused run waits for the holder's name (written just after it took the
#: lock) [s].
HOLDER_WAIT = 1.0


def _holder(path: str) -> str:
    """Who holds the directory's lock ("process 1234 since ..."), waiting up to
    :data:`HOLDER_WAIT` s for a run that has just taken it to say so."""
    import time

    deadline = time.monotonic() + HOLDER_WAIT
    while True:
        try:
            holder = json.loads(Path(path, LOCK_INFO).read_text(encoding="utf-8"))
            return f"process {holder['pid']} since {holder['since']}"
        except (OSError, ValueError, KeyError, TypeError):
            if time.monotonic() > deadline:
                return "another process"
            time.sleep(0.02)


def results_table(rows, schema):
    pa = install_hint("pyarrow", "A sweep's results (Parquet)")
    return pa.Table.from_pylist(rows, schema=schema)


def conform(table, schema):
    """``table``'s columns as ``schema`` orders and types them (a column it lacks: null)."""
    pa = install_hint("pyarrow", "A sweep's results (Parquet)")

    columns = [table.column(f.name).cast(f.type) if f.name in table.column_names
               else pa.nulls(table.num_rows, f.type) for f in schema]
    return pa.Table.from_arrays(columns, schema=schema)


def with_values(table, grid: Grid, values: dict):
    """``table`` with its grid-key columns set from ``values`` (``{case id: {key:
    value}}``): rows stored by another grid hold their case under that grid's keys (a
    key it did not vary is null there), this grid names it by its own."""
    pa = install_hint("pyarrow", "A sweep's results (Parquet)")

    ids = table.column("case_id").to_pylist()
    for key in grid.keys:
        i = table.schema.get_field_index(key)
        column = pa.array([values[c][key] for c in ids], table.schema.field(i).type)
        table = table.set_column(i, key, column)
    return table


def read_results(out):
    """Every row of a results directory as a ``pandas.DataFrame``, each case once (for a
    notebook): the columns are the union of its grids'; where a row's grid did not vary a
    key, its cell holds the scene's own value (from the manifest; null when the scene's
    description does not list the field).

    Raises:
        ResultsDirectoryError: ``out`` is not a results directory (no manifest), or a row
            file is damaged (named).
    """
    install_hint("pandas", "A sweep's results table")     # to_pandas needs it
    given = os.fspath(out)
    if not os.path.isfile(os.path.join(given, MANIFEST)):
        reason = f"no {MANIFEST}: not a sweep's results directory"
        raise ResultsDirectoryError(f"{given}: {reason}", path=given, reason=reason)
    table = read_rows(given)
    if table is None:
        import pandas as pd

        return pd.DataFrame({"case_id": pd.Series(dtype="string")})
    try:
        values = json.loads(Path(given, MANIFEST).read_text(encoding="utf-8"))["scene"].get(
            "values", {})
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        raise ResultsDirectoryError(f"{given}: its {MANIFEST} is damaged or not a sweep "
                                    "manifest", path=given, reason="damaged manifest") from None
    import pyarrow.compute as pc

    for key, value in values.items():
        i = table.schema.get_field_index(key)
        if i >= 0 and table.column(i).null_count:
            column = table.column(i)
            table = table.set_column(i, key, pc.fill_null(column, _scalar(value,
                                                                          column.type)))
    return table.to_pandas()


def _scalar(value, type_):
    pa = install_hint("pyarrow", "A sweep's results (Parquet)")
    return pa.scalar(value).cast(type_)
