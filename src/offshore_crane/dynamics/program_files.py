"""Files of generated programs, shared by :mod:`.lanes` (the block drivers) and
:mod:`.native` (the compiled objects): where they live, reading one and writing one
atomically."""

from __future__ import annotations

import contextlib
import os
import uuid
from pathlib import Path


def package_cache(name: str) -> Path:
    """The folder ``name`` of generated programs: beside this package's own Numba cache
    (so that ``NUMBA_CACHE_DIR`` and its copies hold their compiled code as they hold the
    other kernels'), or in the user's cache folder when the package's is not writable."""
    beside = Path(__file__).resolve().parent / "__pycache__" / name
    try:
        beside.mkdir(parents=True, exist_ok=True)
        if os.access(beside, os.W_OK):
            return beside
    except OSError:
        pass
    return Path.home() / ".cache" / "offshore_crane" / name


def read_file(path: Path) -> tuple[bytes | None, str | None]:
    """``(its bytes, None)``; ``(None, None)`` when there is no file; ``(None, why it
    cannot be read)``."""
    try:
        return path.read_bytes(), None
    except FileNotFoundError:
        return None, None
    except OSError as exc:
        return None, f"cannot be read ({exc.strerror or exc})"


def write_atomically(path: Path, data: bytes, before=lambda: None,
                     mtime: int | None = None) -> str | None:
    """Write ``data`` to ``path`` atomically (a temporary file of a name of its own,
    renamed over ``path``: processes racing write the same bytes; ``before()`` runs once
    the folder exists, ``mtime`` the file's modification time) and read it back: None
    when ``path`` then holds them, else what went wrong."""
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        before()
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        if mtime is not None:
            os.utime(tmp, (mtime, mtime))
        os.replace(tmp, path)
        if path.read_bytes() != data:
            return "does not read back as written"
    except OSError as exc:
        return f"cannot be written ({exc.strerror or exc})"
    finally:
        with contextlib.suppress(OSError):
            tmp.unlink()
    return None
