"""Expand the robot's xacro with a resolved description, and cache the URDF.

The xacro (``models/offshore_crane.urdf.xacro``) takes one argument, ``description``: the
path of a YAML file holding the resolved description
(:meth:`offshore_crane.robot.description.Description.xacro_data`), which it reads with
``xacro.load_yaml``. :func:`expand` writes that YAML to a temporary file (unique name,
removed whatever happens), runs xacro and caches the URDF.

Thread safety: xacro keeps its state in module globals (substitution arguments, file
and macro stacks, included files), so two expansions in one process must not overlap:
:data:`_EXPAND_LOCK` serialises them (processes are independent).

Cache: ``$OFFSHORE_CRANE_CACHE``, else ``$XDG_CACHE_HOME/offshore-crane``, else
``~/.cache/offshore-crane``; one file per key, the SHA-256 of everything that decides
the URDF: the xacro's text, the versions of xacro and PyYAML, and the resolved
description. Each entry ends with a trailer ``<!-- offshore-crane-cache sha256=... -->`` holding the hash of
the URDF before it; an entry whose content does not match (truncated, edited, random
bytes, not UTF-8) is named in one :class:`CacheWarning` per file and process, rebuilt
and rewritten. Entries are written atomically (a temporary file beside it, then a
rename); the temporary file is removed on any failure. An unwritable cache directory
only costs speed (every load expands).
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
import threading
import warnings
from functools import lru_cache
from pathlib import Path

from offshore_crane.errors import ModelError, require
from offshore_crane.progress import first_time

XACRO_FILE = "offshore_crane.urdf.xacro"
#: Serialises xacro expansions within the process (xacro's state is global).
_EXPAND_LOCK = threading.Lock()
_TRAILER = "<!-- offshore-crane-cache sha256="


class CacheWarning(UserWarning):
    """A damaged URDF cache entry was found and rebuilt (reported once per file)."""


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
def _versions() -> str:
    """The installed tools that turn the YAML into a URDF (part of the cache key): each
    module's file, size and modification time, which change with any other version or
    build. (``importlib.metadata.version`` would say the same and cost ~10 ms of imports
    at every start-up; ``find_spec`` imports nothing.)"""
    from importlib.util import find_spec

    out = []
    for module in ("xacro", "yaml"):
        spec = find_spec(module)
        origin = getattr(spec, "origin", None)
        try:
            st = os.stat(origin)
            out.append(f"{module}={origin}:{st.st_size}:{st.st_mtime_ns}")
        except (TypeError, OSError):
            out.append(f"{module}=absent")
    return ";".join(out)


def cache_dir() -> Path:
    """Directory of the expanded-URDF cache."""
    if os.environ.get("OFFSHORE_CRANE_CACHE"):
        return Path(os.environ["OFFSHORE_CRANE_CACHE"])
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "offshore-crane"


def description_yaml(data: dict) -> str:
    """The YAML text the xacro reads (floats written with ``repr``: they round-trip)."""
    yaml = require("yaml", "PyYAML", "Expanding the robot's xacro")
    return yaml.safe_dump(data, sort_keys=False, allow_unicode=True)


def cache_key(data: dict, path: Path | None = None) -> str:
    """SHA-256 (hex) of the xacro (its text and its resolved path, which xacro writes
    into the URDF's header), the tools' versions and the resolved description (as JSON:
    floats written with ``repr``, so equal keys mean equal numbers)."""
    path = path or xacro_path()
    h = hashlib.sha256()
    for part in (_xacro_text(path), str(Path(path).resolve()), _versions(),
                 json.dumps(data, allow_nan=True)):
        h.update(part.encode("utf-8"))
        h.update(b"\0")
    return h.hexdigest()


def _digest(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _warn_once(path: Path, problem: str) -> None:
    if not first_time(("URDF cache entry", path)):
        return
    warnings.warn(CacheWarning(f"URDF cache entry {path} {problem}: rebuilt from the xacro"),
                  stacklevel=4)


def read_entry(path: Path) -> str | None:
    """The URDF held by cache entry ``path``, or None (missing, or damaged: warned)."""
    try:
        data = path.read_bytes()
    except (FileNotFoundError, NotADirectoryError, PermissionError):
        return None                      # no entry, or no usable cache: just slower
    except OSError as exc:
        _warn_once(path, f"cannot be read ({exc.strerror or exc})")
        return None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        _warn_once(path, "is not UTF-8 text (damaged)")
        return None
    body, sep, trailer = text.rpartition(_TRAILER)
    digest = trailer.split(" ", 1)[0] if sep else ""
    if not sep or not trailer.endswith("-->\n") or _digest(body) != digest:
        what = ("has no checksum trailer (truncated or not written by this version)"
                if not sep else "does not match its checksum (truncated or edited)")
        _warn_once(path, what)
        return None
    return body


def write_entry(path: Path, urdf: str) -> bool:
    """Write ``urdf`` with its checksum trailer atomically; False if it cannot be written."""
    tmp = None
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=".tmp", suffix=".urdf", dir=path.parent)
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(urdf + f"{_TRAILER}{_digest(urdf)} -->\n")
        os.replace(tmp, path)
        tmp = None
        return True
    except OSError:
        return False
    finally:
        _remove(tmp)


def run_xacro(yaml_text: str, path: Path | None = None) -> str:
    """Expand the xacro with the description ``yaml_text`` (no cache)."""
    path = path or xacro_path()
    xacro = require("xacro", "xacro", "Expanding the robot's xacro")
    tmp = None
    try:
        fd, tmp = _temporary()
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(yaml_text)
        with _EXPAND_LOCK:
            doc = xacro.process_file(str(path), mappings={"description": tmp})
            return doc.toprettyxml(indent="  ")
    except Exception as exc:  # xacro raises bare Exceptions with useful text
        if isinstance(exc, OSError) and tmp is None:
            raise ModelError(f"cannot write a temporary file for xacro: {exc}") from None
        raise ModelError(f"expanding {path.name} failed: {exc}") from None
    finally:
        _remove(tmp)


def _remove(tmp: str | None) -> None:
    """Delete a temporary file if there is one (a failure to delete is not an error)."""
    if tmp is not None:
        try:
            os.unlink(tmp)
        except OSError:
            pass


def _temporary():
    """A new temporary YAML file: in the cache directory if writable, else the system's."""
    for folder in (cache_dir(), None):
        try:
            if folder is not None:
                folder.mkdir(parents=True, exist_ok=True)
            return tempfile.mkstemp(prefix=".desc", suffix=".yaml", dir=folder)
        except OSError:
            if folder is None:
                raise
    raise AssertionError("unreachable")


def expand(data: dict, path: Path | None = None) -> tuple[str, Path | None]:
    """URDF of the resolved description ``data`` and its cache file.

    Args:
        data: :meth:`Description.xacro_data`.

    Returns:
        ``(urdf_text, cache_file)``; ``cache_file`` is None when the cache cannot be
        written.
    """
    path = path or xacro_path()
    cached = cache_dir() / f"offshore_crane-{cache_key(data, path)[:32]}.urdf"
    urdf = read_entry(cached)
    if urdf is not None:
        return urdf, cached
    urdf = run_xacro(description_yaml(data), path)
    return urdf, (cached if write_entry(cached, urdf) else None)
