"""Locate the robot's xacro, list its arguments, expand it and cache the URDF.

The expanded URDF is cached under a SHA-256 of (xacro text, arguments, xacro's version),
in ``$OFFSHORE_CRANE_CACHE`` or ``$XDG_CACHE_HOME/offshore-crane`` or
``~/.cache/offshore-crane``. A cache hit costs a file read; xacro is imported only on a
miss. An unwritable cache directory only costs speed.

The cache does not trust what it finds: each entry's first line holds the SHA-256 of the
URDF that follows; an entry whose content does not match (truncated, edited, damaged) is
named in one :class:`CacheWarning`, rebuilt and rewritten. Entries are written to a
unique temporary file and renamed (removed on any failure), so concurrent processes never
see a partial entry. xacro keeps global state while it expands, so expansions in one
process are serialised by a lock (threads loading robots at once all succeed).
"""

from __future__ import annotations

import hashlib
import math
import os
import re
import threading
import warnings
from functools import lru_cache
from pathlib import Path

from ..errors import ModelError, require

#: First line of a cache entry: the SHA-256 of the URDF text that follows it.
_STAMP = "<!-- offshore-crane cache sha256="
_LOCK = threading.Lock()


class CacheWarning(UserWarning):
    """A cache entry was damaged or edited: it was rebuilt."""


@lru_cache(maxsize=1)
def _xacro_version() -> str:
    """The installed xacro's version (part of the cache key), or "" without xacro."""
    from importlib import metadata

    try:
        return metadata.version("xacro")
    except metadata.PackageNotFoundError:
        return ""

XACRO_FILE = "offshore_crane.urdf.xacro"
_ARG_RE = re.compile(r'<xacro:arg\s+name="([^"]+)"\s+default="([^"]*)"\s*/>')


def xacro_path() -> Path:
    """Path of the robot's xacro: inside the installed package, else the source tree."""
    here = Path(__file__).resolve()
    for candidate in (here.parents[1] / "models" / XACRO_FILE,      # installed wheel
                      here.parents[3] / "models" / XACRO_FILE):     # source checkout
        if candidate.is_file():
            return candidate
    raise ModelError(f"cannot find {XACRO_FILE}: reinstall offshore-crane")


@lru_cache(maxsize=None)
def _xacro_text(path: Path) -> str:
    return path.read_text(encoding="utf-8")


@lru_cache(maxsize=None)
def _arguments(path: Path) -> tuple:
    return tuple(_ARG_RE.findall(_xacro_text(path)))


def xacro_arguments(path: Path | None = None) -> dict[str, str]:
    """The xacro's arguments and their default values (as text), in file order.

    The file is read and scanned once per process.
    """
    return dict(_arguments(path or xacro_path()))


def cache_dir() -> Path:
    """Directory of the expanded-URDF cache."""
    if os.environ.get("OFFSHORE_CRANE_CACHE"):
        return Path(os.environ["OFFSHORE_CRANE_CACHE"])
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "offshore-crane"


def normalise_overrides(overrides: dict, path: Path | None = None) -> dict[str, str]:
    """Check override names against the xacro's arguments and format values.

    Args:
        overrides: ``{argument: number}``; numbers given as text are accepted.

    Returns:
        ``{argument: text}`` with values written with full precision, sorted by name.

    Raises:
        ModelError: unknown argument (the message lists the known ones), non-numeric or
            non-finite value.
    """
    known = xacro_arguments(path)
    out = {}
    for name, value in overrides.items():
        if name not in known:
            raise ModelError(f"unknown robot parameter '{name}'; known parameters: "
                             f"{', '.join(known)}", element=name)
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise ModelError(f"robot parameter {name}={value!r} is not a number",
                             element=name) from None
        if not math.isfinite(number):
            raise ModelError(f"robot parameter {name}={value!r} is not finite", element=name)
        out[name] = repr(number)
    return dict(sorted(out.items()))


def expand(overrides: dict | None = None, path: Path | None = None) -> tuple[str, Path | None]:
    """Expand the xacro with ``overrides`` and return ``(urdf_text, cache_file)``.

    ``cache_file`` is None when the cache directory cannot be written.
    """
    path = path or xacro_path()
    args = normalise_overrides(overrides or {}, path)
    text = _xacro_text(path)
    key = hashlib.sha256((text + "\0" + repr(sorted(args.items())) + "\0"
                          + _xacro_version()).encode()).hexdigest()[:20]
    cached = cache_dir() / f"offshore_crane-{key}.urdf"
    urdf = _read_entry(cached)
    if urdf is not None:
        return urdf, cached
    xacro = require("xacro", "xacro", "Expanding the robot's xacro")
    with _LOCK:                           # xacro's expansion keeps global state
        try:
            urdf = xacro.process_file(str(path), mappings=args).toprettyxml(indent="  ")
        except Exception as exc:  # xacro raises bare Exceptions with useful text
            raise ModelError(f"expanding {path.name} failed: {exc}") from None
    return urdf, _write_entry(cached, urdf)


def _read_entry(cached: Path) -> str | None:
    """The URDF of a cache entry whose stamp matches its content, else None (a damaged
    or edited entry is reported once and will be rewritten)."""
    try:
        raw = cached.read_bytes()
    except OSError:
        return None
    first, _, body = raw.partition(b"\n")
    try:
        stamp = first.decode("ascii")
        urdf = body.decode("utf-8")
    except UnicodeDecodeError:
        stamp = urdf = ""
    expected = _STAMP + hashlib.sha256(body).hexdigest() + " -->"
    if stamp != expected:
        warnings.warn(CacheWarning(f"the cached URDF {cached} is damaged or was edited (its "
                                   "content does not match its checksum): rebuilt"),
                      stacklevel=4)
        return None
    return urdf


def _write_entry(cached: Path, urdf: str) -> Path | None:
    """Write a stamped entry atomically (a unique temporary file, renamed); None when the
    cache directory cannot be written."""
    import tempfile

    body = urdf.encode("utf-8")
    data = (_STAMP + hashlib.sha256(body).hexdigest() + " -->\n").encode("ascii") + body
    try:
        cached.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=".oc-", suffix=".tmp", dir=cached.parent)
    except OSError:
        return None
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.replace(tmp, cached)
    except OSError:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        return None
    return cached
