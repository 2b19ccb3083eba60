"""The Parquet files a results directory keeps its rows in: batches written while a run goes
(``part-<run>-<n>.parquet``), compacted into one file per run (``rows-<run>.parquet``) at
its end; read back with every case once.

A row file is written whole to a temporary name and renamed (:func:`offshore_crane.io.
write_bytes`), so a file under its final name is complete; one damaged by anything else
(a disk error, an edit) is named in a one-line :class:`~offshore_crane.errors.
ResultsDirectoryError`. The same case may sit in two files for a moment (a run killed
between writing its compacted file and removing its batches): the readers keep its first
row (the rows are bit-identical, a case being a pure function of its values), and the next
run's recovery removes the batches.
"""

from __future__ import annotations

import os
import re
import time

from offshore_crane.errors import ResultsDirectoryError
from offshore_crane.studies.sweep.grid import install_hint

#: A batch is written when it holds this many rows ...
BATCH_ROWS = 2000
#: ... or when its first row waited this long [s]: a SIGKILL loses at most this much work
#: (``OFFSHORE_CRANE_BATCH_SECONDS`` sets it: shorter loses less, and writes more files).
BATCH_SECONDS = 2.0
#: Row files: a batch of a run, a run's compacted rows, a version-1 directory's single row.
ROW_FILE = re.compile(r"^(?:part-(?P<run>[0-9A-Za-z-]+?)-(?P<n>\d+)|rows-(?P<whole>"
                      r"[0-9A-Za-z-]+)|case-[0-9a-f]+)\.parquet$")


def batch_seconds() -> float:
    """:data:`BATCH_SECONDS`, or ``OFFSHORE_CRANE_BATCH_SECONDS`` when set [s].

    Raises:
        InputError: the variable is not a positive number.
    """
    import math

    from offshore_crane.errors import InputError

    text = os.environ.get("OFFSHORE_CRANE_BATCH_SECONDS")
    if text is None:
        return BATCH_SECONDS
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value > 0):
        raise InputError(f"OFFSHORE_CRANE_BATCH_SECONDS = {text!r}: give a positive number "
                         "of seconds (how much work a killed sweep may lose)",
                         name="OFFSHORE_CRANE_BATCH_SECONDS")
    return value


def new_run_token() -> str:
    """A run's name in its files: start time, process and 4 random hex digits (sortable
    by time, unique across processes and hosts in practice)."""
    import secrets

    return f"{time.strftime('%Y%m%dT%H%M%S')}-{os.getpid()}-{secrets.token_hex(2)}"


def row_files(path: str) -> list[str]:
    """Names of the row files in ``path``, in name order (runs by start time)."""
    if not os.path.isdir(path):
        return []
    return sorted(n for n in os.listdir(path) if ROW_FILE.match(n))


def parquet_bytes(rows_or_table, schema=None) -> bytes:
    """A Parquet file of ``rows`` (dicts, with ``schema``) or of a ``pyarrow.Table``:
    zstd-compressed with dictionaries (the envelope's many repeated or NaN values shrink
    a row from 1.3 kB to a few hundred bytes); no statistics (never queried by range)."""
    pa = install_hint("pyarrow", "A sweep's results (Parquet)")
    import pyarrow.parquet as pq

    table = (rows_or_table if isinstance(rows_or_table, pa.Table)
             else pa.Table.from_pylist(rows_or_table, schema=schema))
    sink = pa.BufferOutputStream()
    pq.write_table(table, sink, compression="zstd", use_dictionary=True,
                   write_statistics=False)
    return sink.getvalue().to_pybytes()


def _damaged(path: str, name: str, exc: Exception):
    reason = (str(exc).splitlines() or [type(exc).__name__])[0]
    return ResultsDirectoryError(f"--out {path}: {name} is damaged ({reason}): move it out "
                                 "of the directory and rerun the sweep to compute its cases "
                                 "again", path=path, reason=f"{name} damaged")


def read_file(path: str, name: str, columns=None):
    """One row file as a ``pyarrow.Table`` (``columns``: only those).

    Raises:
        ResultsDirectoryError: the file is not a readable Parquet file.
    """
    install_hint("pyarrow", "A sweep's results (Parquet)")
    import pyarrow.parquet as pq

    try:
        return pq.read_table(os.path.join(path, name), columns=columns)
    except Exception as exc:            # pyarrow raises ArrowInvalid, OSError, ...
        raise _damaged(path, name, exc) from None


def case_ids(path: str) -> set:
    """The case ids with a row in ``path`` (the ``case_id`` column of every row file)."""
    out: set = set()
    for name in row_files(path):
        out.update(read_file(path, name, ["case_id"]).column("case_id").to_pylist())
    return out


def read_rows(path: str, names=None, ids=None):
    """The rows of ``path`` (or of its files ``names``), each case once, as one
    ``pyarrow.Table`` whose columns are the union of the files' (a column absent from a
    file is null there: rows of grids over other robot fields); ``ids``: only those cases.
    """
    pa = install_hint("pyarrow", "A sweep's results (Parquet)")
    import pyarrow.compute as pc

    tables = [read_file(path, n) for n in (row_files(path) if names is None else names)]
    tables = [t for t in tables if t.num_rows]
    if not tables:
        return None
    table = each_case_once(pa.concat_tables(tables, promote_options="default"))
    if ids is not None:
        table = table.filter(pc.is_in(table.column("case_id"),
                                      value_set=pa.array(sorted(ids), pa.string())))
    return table


def each_case_once(table):
    """``table`` with only the first row of each ``case_id`` (a case in two files, or
    two rows renamed to one id), in their order."""
    pa = install_hint("pyarrow", "A sweep's results (Parquet)")
    import numpy as np

    _, first = np.unique(np.asarray(table.column("case_id").to_pylist(), dtype=object),
                         return_index=True)
    if len(first) < table.num_rows:
        table = table.take(pa.array(np.sort(first)))
    return table


def compact(path: str, run: str, names: list) -> None:
    """Merge the row files ``names`` into ``rows-<run>.parquet`` (written whole, then
    renamed), then remove them. Killed in between, both hold the rows: the readers keep
    each case once and :func:`recover` removes the batches."""
    from offshore_crane.io import write_bytes

    if not names:
        return
    table = read_rows(path, names)
    target = f"rows-{run}.parquet"
    if table is not None:
        write_bytes(os.path.join(path, target), parquet_bytes(table))
    for n in names:
        if n != target:
            os.unlink(os.path.join(path, n))


def recover(path: str) -> None:
    """What killed runs left, made whole (call under the directory's lock, before a run):
    their half-written temporary files removed, their batches compacted into one file per
    run, batches already compacted removed."""
    if not os.path.isdir(path):
        return
    for name in os.listdir(path):
        if name.startswith(".oc-") and name.endswith(".tmp"):
            try:
                os.unlink(os.path.join(path, name))
            except OSError:
                pass
    runs: dict = {}
    for name in row_files(path):
        m = ROW_FILE.match(name)
        if m.group("run"):
            runs.setdefault(m.group("run"), []).append(name)
    for run, names in runs.items():
        whole = f"rows-{run}.parquet"
        if os.path.exists(os.path.join(path, whole)):     # compacted, batches not removed
            for n in names:
                os.unlink(os.path.join(path, n))
        else:
            compact(path, run, names)


class BatchWriter:
    """Rows of one run into a results directory: :meth:`add` a row; a batch is written
    when it holds :data:`BATCH_ROWS` rows or when its first row has waited
    :func:`batch_seconds` s (a timer thread writes it then, even when no other row
    comes: a killed run loses at most that long of finished rows); :meth:`flush` writes
    what is held (on any stop); :meth:`finish` flushes and compacts the run's batches
    into one file."""

    def __init__(self, path: str, schema):
        import threading

        self.path, self.schema = path, schema
        self.run = new_run_token()
        self.rows: list = []
        self.parts: list = []
        self.seconds = batch_seconds()
        self._lock = threading.Lock()
        self._timer = None
        self._failure: BaseException | None = None   # of a write by the timer thread

    def add(self, row: dict) -> None:
        import threading

        self._raise_failure()
        with self._lock:
            self.rows.append(row)
            if len(self.rows) >= BATCH_ROWS:
                self._write()
            elif self._timer is None:
                self._timer = threading.Timer(self.seconds, self._on_timer)
                self._timer.daemon = True
                self._timer.start()

    def _on_timer(self) -> None:
        try:
            with self._lock:
                self._timer = None
                self._write()
        except BaseException as exc:            # raised again by the next add or flush
            self._failure = exc

    def _raise_failure(self) -> None:
        if self._failure is not None:
            exc, self._failure = self._failure, None
            raise exc

    def _write(self) -> None:
        """Write the held rows as the run's next batch (under the lock)."""
        from offshore_crane.io import write_bytes

        if self._timer is not None:
            self._timer.cancel()
            self._timer = None
        if not self.rows:
            return
        name = f"part-{self.run}-{len(self.parts):06d}.parquet"
        write_bytes(os.path.join(self.path, name), parquet_bytes(self.rows, self.schema))
        self.parts.append(name)
        self.rows = []

    def flush(self) -> None:
        with self._lock:
            self._write()
        self._raise_failure()

    def finish(self) -> None:
        self.flush()
        compact(self.path, self.run, self.parts)
        self.parts = []
