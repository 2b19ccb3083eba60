"""Every file the project writes goes through here; every text file it reads too.

Rules (``docs/outputs.md``):

- **Checked before computing.** :func:`plan_outputs` validates every output path before
  any work: an empty name, a directory, a missing parent directory, a place that cannot
  be written, a file that is also an input, two outputs on one file, an unknown file type
  (figures), a block device, a socket, a FIFO that no process reads within
  :data:`PIPE_TIMEOUT` are one-line :class:`~offshore_crane.errors.OutputError`\\ s (a
  FIFO that is read is opened then, held until written: the write never waits).
- **Nothing is destroyed.** A regular file (new or existing) is written to a temporary
  file beside it (a short name, ``.oc-XXXXXXXX.tmp``, so that a long target name never
  gives a longer temporary one) and renamed over it only once complete; an existing
  file keeps its permission bits, a new one gets ``0o666 & ~umask``. A symbolic link is
  written *through*: the file it points to is replaced atomically, the link stays. A FIFO,
  a character device (``/dev/null``, ``/dev/stdout``) or ``-`` (standard output) is
  written directly (opened without blocking), never replaced or removed.
- **No leftovers.** The temporary file is removed on any exception, and on SIGTERM and
  SIGINT, which :func:`signals_as_exceptions` turns into exceptions (the command line then
  exits with status 143 or 130 and one line, no traceback). A failed write (full disk,
  I/O error) is an :class:`OutputError` naming the file and the system's reason.

Readers: :func:`read_text` decodes UTF-8 and names the file, line and column of a bad
byte.
"""

from __future__ import annotations

import contextlib
import errno
import os
import signal
import stat
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from offshore_crane.errors import InputError, OutputError
from offshore_crane.special_files import (Held, device_writer, is_fifo, pipe_writer,
                                          read_pipe)

#: Rows per block of :func:`write_csv` (a large output is streamed, so an interrupted
#: write is realistic and memory stays bounded).
CSV_BLOCK = 65536
#: Figure formats matplotlib's Agg-based backends write.
FIGURE_FORMATS = ("png", "pdf", "svg", "svgz", "eps", "ps", "jpg", "jpeg", "tif", "tiff",
                  "webp")


class Terminated(BaseException):
    """Raised in the main thread on SIGTERM (see :func:`signals_as_exceptions`)."""


@dataclass(frozen=True)
class Target:
    """Where one output goes.

    Attributes:
        name: The option or role (``"--out"``), for messages.
        given: The path as given.
        kind: ``"file"`` (a regular file, new or existing: written atomically),
            ``"special"`` (FIFO or character device: written directly) or ``"stdout"``.
        path: For ``"file"``, the final file (a symlink resolved), else the path given.
        held: A FIFO's write end held from :func:`plan_outputs` to the first write.
    """

    name: str
    given: str
    kind: str
    path: str
    held: list = field(default_factory=list, compare=False, repr=False)

    def __str__(self) -> str:
        return self.given


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _fail(name: str, given: str, reason: str):
    raise OutputError(f"{name}: cannot write {given!s}: {reason}", path=given, reason=reason)


def _same(a: str, b: str) -> bool:
    try:
        return os.path.samefile(a, b)
    except OSError:
        return os.path.realpath(a) == os.path.realpath(b)


def plan_outputs(outputs: dict, inputs=(), formats: dict | None = None) -> dict:
    """Check every output path before any computation.

    Args:
        outputs: ``{name: path or None}`` (None: no such output), e.g.
            ``{"--out": "x.csv", "--plot": None}``.
        inputs: Paths the run reads (an output may not be one of them).
        formats: ``{name: allowed suffixes}`` for outputs whose type the suffix chooses.

    Returns:
        ``{name: Target}`` for the outputs given.

    Raises:
        OutputError: naming the option and the path, and what to do.
    """
    planned: dict = {}
    for name, given in outputs.items():
        if given is None:
            continue
        given = os.fspath(given)
        if given == "":
            _fail(name, "''", "the file name is empty: give a file name, or leave the option "
                  "out")
        if given == "-":
            planned[name] = Target(name, given, "stdout", given)
            continue
        try:
            st = os.stat(given)                   # follows symlinks
        except FileNotFoundError:
            st = None
        except OSError as exc:
            if exc.errno == errno.ENAMETOOLONG:
                _fail(name, given, "the file name is longer than 255 bytes (the file "
                      "system's limit): shorten it")
            _fail(name, given, f"cannot be examined ({exc.strerror}): choose another path")
        if st is not None and stat.S_ISDIR(st.st_mode):
            _fail(name, given, "is a directory: give a file name inside it")
        if st is not None and stat.S_ISBLK(st.st_mode):
            _fail(name, given, "is a block device: write to a regular file")
        if st is not None and stat.S_ISSOCK(st.st_mode):
            _fail(name, given, "is a socket, not a file: write to a regular file")
        if st is not None and (stat.S_ISFIFO(st.st_mode) or stat.S_ISCHR(st.st_mode)):
            planned[name] = Target(name, given, "special", given)
            continue
        final = os.path.realpath(given)           # through symlinks, to the file written
        directory = os.path.dirname(final) or "."
        if not os.path.isdir(directory):
            if os.path.islink(given):
                _fail(name, given, f"is a symbolic link to {os.readlink(given)}, whose "
                      f"directory {directory} does not exist: create it or remove the link")
            _fail(name, given, f"directory {os.path.dirname(given) or '.'} does not exist: "
                  "create it first")
        try:
            limit = os.pathconf(directory, "PC_NAME_MAX")
        except (OSError, ValueError):
            limit = 255
        if len(os.path.basename(final).encode()) > limit:
            _fail(name, given, f"the file name is longer than {limit} bytes: shorten it")
        _probe(name, given, directory)
        if formats and name in formats:
            suffix = Path(given).suffix.lstrip(".").lower()
            if suffix not in formats[name]:
                kinds = ", ".join("." + f for f in formats[name])
                _fail(name, given, f"the file type '.{suffix}' is not one of {kinds}"
                      if suffix else f"the name has no file type: end it in {kinds}")
        planned[name] = Target(name, given, "file", final)
    for path in inputs:
        if path is None:
            continue
        for t in planned.values():
            if t.kind == "file" and os.path.exists(os.fspath(path)) and _same(t.path, path):
                _fail(t.name, t.given, f"is also an input ({os.fspath(path)}): writing it "
                      "would destroy the input; choose another file")
    files = [t for t in planned.values() if t.kind != "stdout"]
    for i, a in enumerate(files):
        for b in files[i + 1:]:
            if (a.kind == b.kind == "file" and a.path == b.path) or (
                    a.kind == b.kind == "special" and _same(a.path, b.path)):
                _fail(b.name, b.given, f"is the same file as {a.name} {a.given}: give each "
                      "output its own file")
    if sum(t.kind == "stdout" for t in planned.values()) > 1:
        _fail(list(planned)[-1], "-", "only one output can go to standard output")
    for t in planned.values():                    # last: the checks above cost no wait
        if t.kind == "special" and is_fifo(t.path):
            t.held.append(Held(_special_fd(t)))
    return planned


def _special_fd(target: Target) -> int:
    """A blocking descriptor for writing a FIFO or a device, opened without blocking
    (:mod:`.special_files`), or the FIFO's write end held since the planning. Raises
    OutputError for a FIFO no process reads within :data:`PIPE_TIMEOUT`."""
    held = target.held.pop().take() if target.held else None
    if held is not None or not is_fifo(target.path):
        return device_writer(target.path) if held is None else held
    try:
        fd = pipe_writer(target.path, PIPE_TIMEOUT)
    except OSError as exc:
        _fail(target.name, target.given, f"cannot be opened ({exc.strerror})")
    if fd is None:
        _fail(target.name, target.given, f"is a FIFO (named pipe) that no process read "
              f"within {PIPE_TIMEOUT:g} s: start its reader first, or write to a regular file")
    return fd


def refuse_inside(outputs: dict, directory, owner: str) -> None:
    """Refuse outputs that would land in ``directory`` (a directory another output owns,
    e.g. a sweep's results, whose files it alone writes), compared by real path.

    Args:
        outputs: ``{name: path or None}`` (a file, or a directory of outputs).
        directory: The owned directory (it need not exist yet).
        owner: Its option, for messages (``"--out"``).

    Raises:
        OutputError: naming the option, the path and the directory.
    """
    if directory is None:
        return
    home = os.path.realpath(os.fspath(directory))
    for name, given in outputs.items():
        if given is None or os.fspath(given) == "-":
            continue
        where = os.path.realpath(os.fspath(given))
        if os.path.commonpath([home, where]) == home:
            _fail(name, os.fspath(given), f"is inside {owner} {os.fspath(directory)}, "
                  "whose files are the run's alone: write it elsewhere")


def _probe(name: str, given: str, directory: str) -> None:
    """Create and remove an empty file in ``directory``: the only reliable test that it
    can be written (permission bits do not stop root; a read-only mount does)."""
    probe = os.path.join(directory, f".oc-probe-{os.getpid()}.tmp")
    try:
        fd = os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    except FileExistsError:
        return                                    # a crashed earlier run's probe: writable
    except OSError as exc:
        _fail(name, given, f"cannot write in {directory} ({exc.strerror}): choose a "
              "writable place")
    os.close(fd)
    os.unlink(probe)


def _temporary(directory: str):
    """A new temporary file beside the target: ``(fd, path)``."""
    import tempfile

    return tempfile.mkstemp(prefix=".oc-", suffix=".tmp", dir=directory)


@contextlib.contextmanager
def open_output(target, mode: str = "w"):
    """Open an output for writing (see the module docstring for what happens where).

    Args:
        target: A :class:`Target` of :func:`plan_outputs`, or a path (checked here).
        mode: ``"w"`` (text, UTF-8) or ``"wb"``.

    Yields:
        A file object. The file appears complete or not at all (regular files).

    Raises:
        OutputError: the write failed (the temporary file removed).
    """
    if not isinstance(target, Target):
        target = plan_outputs({"output": target})["output"]
    binary = "b" in mode
    if target.kind == "stdout":
        stream = sys.stdout.buffer if binary else sys.stdout
        try:
            yield stream
            stream.flush()
        except OSError as exc:
            if isinstance(exc, BrokenPipeError):
                raise
            raise OutputError(f"cannot write to standard output: {exc.strerror}",
                              path="-", reason=str(exc.strerror)) from None
        return
    if target.kind == "special":
        try:
            fd = _special_fd(target)
            with os.fdopen(fd, mode, **({} if binary else {"encoding": "utf-8"})) as fh:
                yield fh
        except OSError as exc:
            if isinstance(exc, OutputError):
                raise
            raise OutputError(f"cannot write {target.given}: {exc.strerror}",
                              path=target.given, reason=str(exc.strerror)) from None
        return
    directory = os.path.dirname(target.path) or "."
    try:
        fd, tmp = _temporary(directory)
    except OSError as exc:
        raise OutputError(f"cannot write in {directory}: {exc.strerror}", path=target.given,
                          reason=str(exc.strerror)) from None
    try:
        try:
            mode_bits = stat.S_IMODE(os.stat(target.path).st_mode)
        except FileNotFoundError:
            mode_bits = 0o666 & ~_umask()
        os.fchmod(fd, mode_bits)
        with os.fdopen(fd, mode, **({} if binary else {"encoding": "utf-8"})) as fh:
            yield fh
            fh.flush()
        os.replace(tmp, target.path)
    except OSError as exc:
        _remove(tmp)
        raise OutputError(f"cannot write {target.given}: {exc.strerror or exc}",
                          path=target.given, reason=str(exc.strerror or exc)) from None
    except BaseException:
        _remove(tmp)
        raise


def _remove(path: str) -> None:
    with contextlib.suppress(OSError):
        os.unlink(path)


def write_text(target, text: str) -> None:
    """Write ``text`` to an output (:func:`open_output`)."""
    with open_output(target, "w") as fh:
        fh.write(text)


def write_bytes(target, data: bytes) -> None:
    """Write ``data`` to an output (:func:`open_output`)."""
    with open_output(target, "wb") as fh:
        fh.write(data)


def write_csv(target, header: str, data: np.ndarray, fmt: str = "%.17g",
              block: int = CSV_BLOCK) -> None:
    """Write a header line and the rows of ``data`` ``(N, k)``, ``fmt`` per value (17
    significant digits by default: float64 round-trips), streamed by blocks of rows."""
    data = np.asarray(data)
    with open_output(target, "w") as fh:
        fh.write(header + "\n")
        for start in range(0, len(data), block):
            np.savetxt(fh, data[start:start + block], delimiter=",", fmt=fmt)


#: How long reading a named pipe (a FIFO, ``<(command)``) waits for its writer to
#: connect and finish [s]: a pipe nobody writes to is an error, not a hang.
PIPE_TIMEOUT = 5.0


def read_bytes(path, what: str = "file", timeout: float | None = None) -> bytes:
    """The content of ``path``, read once (a pipe cannot be read twice: read it here and
    pass the bytes on).

    Raises:
        InputError: the file cannot be read, is a directory, or is a pipe that gives no
            end of data within ``timeout`` seconds (default :data:`PIPE_TIMEOUT`).
    """
    where = os.fspath(path)
    timeout = PIPE_TIMEOUT if timeout is None else timeout
    try:
        mode = os.stat(where).st_mode
        if stat.S_ISDIR(mode):
            raise IsADirectoryError
        if not stat.S_ISFIFO(mode):
            return Path(where).read_bytes()
    except IsADirectoryError:
        raise InputError(f"{where}: is a directory, not a {what}", name=where) from None
    except OSError as exc:
        raise InputError(f"{where}: cannot read the {what}: {exc.strerror}", name=where) from None
    try:
        data = read_pipe(where, timeout)
    except OSError as exc:
        raise InputError(f"{where}: cannot read the {what}: {exc.strerror}", name=where) from None
    if data is None:
        raise InputError(f"{where}: a pipe that gave no complete {what} within {timeout:g} s "
                         "(is its writer running?): give a regular file", name=where)
    return data


def read_text(path, what: str = "file", data: bytes | None = None) -> str:
    """The UTF-8 text of ``path`` (or of its content ``data`` already read).

    Raises:
        InputError: the file cannot be read, or holds a byte that is not UTF-8 (naming the
            line and column).
    """
    where = os.fspath(path)
    raw = read_bytes(where, what) if data is None else data
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw.count(b"\n", 0, exc.start) + 1
        column = exc.start - (raw.rfind(b"\n", 0, exc.start) + 1) + 1
        raise InputError(f"{where}, line {line}, column {column}: byte 0x{raw[exc.start]:02x} "
                         f"is not UTF-8: save the {what} as UTF-8 text", name=where) from None


def read_toml(path, what: str = "file", data: bytes | None = None) -> dict:
    """The TOML document of ``path`` (or of its content ``data`` already read):
    :func:`read_text`, then parsed.

    Raises:
        InputError: the file cannot be read, is not UTF-8, or is not valid TOML (naming
            the file).
    """
    import tomllib

    where = os.fspath(path)
    try:
        return tomllib.loads(read_text(where, what, data))
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{where}: not valid TOML: {exc}", name=where) from None


def toml_value(value) -> str:
    """``value`` as it would be written in TOML, for messages that quote a file's value:
    ``true``/``false``, strings in double quotes (JSON escapes are valid TOML basic
    strings), floats at full precision, whole ones without ``.0`` (``0.1``, ``2``, ``inf``), lists and inline
    tables recursively; anything else by ``str``."""
    import json

    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, float):
        text = repr(float(value))           # shortest round-trip form; 2.0 shown as 2
        return text[:-2] if text.endswith(".0") else text
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {toml_value(v)}" for k, v in value.items()) + " }"
    return str(value)


@contextlib.contextmanager
def signals_as_exceptions():
    """In the main thread: SIGTERM raises :class:`Terminated`, SIGINT KeyboardInterrupt
    (Python's default), so that ``finally`` blocks (temporary files) run. Restores the
    previous handlers on exit. Elsewhere a no-op."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def on_term(signum, frame):
        raise Terminated()

    previous = signal.signal(signal.SIGTERM, on_term)
    previous_int = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)
        signal.signal(signal.SIGINT, previous_int)


@contextlib.contextmanager
def output_path(target, suffix: str = ""):
    """A file path for a writer that needs a path, not a file object (ffmpeg), with the
    guarantees of :func:`open_output`.

    For a regular file, yields a temporary path beside it (ending in ``suffix``, so that a
    tool choosing its format by the name sees the right one), renamed over the target
    once the block completes, removed on any failure or signal. For standard output, a
    FIFO or a character device, yields a temporary path in the system's temporary
    directory and copies the finished file to the target.

    Raises:
        OutputError: the temporary file cannot be made or the rename / copy failed.
    """
    import shutil
    import tempfile

    if not isinstance(target, Target):
        target = plan_outputs({"output": target})["output"]
    directory = (os.path.dirname(target.path) or ".") if target.kind == "file" else None
    try:
        fd, tmp = tempfile.mkstemp(prefix=".oc-", suffix=".tmp" + suffix, dir=directory)
    except OSError as exc:
        raise OutputError(f"cannot write in {directory or tempfile.gettempdir()}: "
                          f"{exc.strerror}", path=target.given,
                          reason=str(exc.strerror)) from None
    os.close(fd)
    try:
        yield tmp
        if target.kind == "file":
            try:
                mode_bits = stat.S_IMODE(os.stat(target.path).st_mode)
            except FileNotFoundError:
                mode_bits = 0o666 & ~_umask()
            os.chmod(tmp, mode_bits)
            os.replace(tmp, target.path)
        else:
            with open(tmp, "rb") as src, open_output(target, "wb") as dst:
                shutil.copyfileobj(src, dst)
    except OSError as exc:
        if isinstance(exc, (BrokenPipeError, OutputError)):
            raise
        raise OutputError(f"cannot write {target.given}: {exc.strerror or exc}",
                          path=target.given, reason=str(exc.strerror or exc)) from None
    finally:
        _remove(tmp)
