"""Where the shipped descriptions are, reading a description file, and how a file is named in
messages.
"""

from __future__ import annotations

import os
from pathlib import Path

from offshore_crane.errors import DescriptionError
from offshore_crane.robot.description.schema import DEFAULT_DESCRIPTION, DESCRIPTION_DIR


# ===================================================================== reading files
def description_dir() -> Path:
    """Folder of the shipped descriptions (inside the package, else the source tree)."""
    here = Path(__file__).resolve()
    for candidate in (here.parents[2] / "models" / DESCRIPTION_DIR,
                      here.parents[4] / "models" / DESCRIPTION_DIR):
        if candidate.is_dir():
            return candidate
    raise DescriptionError(f"cannot find the folder {DESCRIPTION_DIR}/ of the shipped robot "
                           "descriptions: reinstall offshore-crane")


def default_description() -> Path:
    """The shipped default description (the placeholder lab design)."""
    return description_dir() / DEFAULT_DESCRIPTION


def read_description(path) -> bytes:
    """The bytes of a description file. A pipe (``<(cat lab.toml)``, a FIFO) can be read
    only once: its content is kept for the process, so that a scene's check and the robot
    it loads read the same description.

    Raises:
        DescriptionError: unreadable file, a directory, a pipe without a writer.
    """
    import stat

    from offshore_crane.errors import InputError
    from offshore_crane.io import read_bytes

    where = os.fspath(path)
    if where in _PIPES:
        return _PIPES[where]
    try:
        data = read_bytes(where, "robot description")
    except InputError as exc:
        raise DescriptionError(str(exc), path=where) from None
    try:
        if stat.S_ISFIFO(os.stat(where).st_mode):
            _PIPES[where] = data
    except OSError:                        # a process substitution gone after its read
        _PIPES[where] = data
    return data


#: The content of the pipes read as descriptions, by path (read once per process).
_PIPES: dict = {}


def read_toml(path, data: bytes | None = None) -> dict:
    """Parse a description file (:func:`offshore_crane.io.read_toml`), or its content
    ``data`` already read.

    Raises:
        DescriptionError: unreadable file, not UTF-8, not TOML (naming the file, and the
            line and column of a bad byte).
    """
    from offshore_crane.errors import InputError
    from offshore_crane.io import read_toml as read

    try:
        return read(path, "robot description", data)
    except InputError as exc:
        raise DescriptionError(str(exc), path=os.fspath(path)) from None


def label(path: str) -> str:
    """How messages name a description file: as given, the default one by its name."""
    try:
        if Path(path).resolve() == default_description().resolve():
            return f"{Path(path).name} (default)"
    except DescriptionError:
        pass
    return path
