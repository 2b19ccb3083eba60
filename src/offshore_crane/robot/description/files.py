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


def read_toml(path) -> dict:
    """Parse a description file.

    Raises:
        DescriptionError: unreadable file, not UTF-8, not TOML (naming the file).
    """
    import tomllib

    where = os.fspath(path)
    try:
        data = Path(where).read_bytes()
    except OSError as exc:
        raise DescriptionError(f"{where}: cannot read the robot description: "
                               f"{exc.strerror or exc}", path=where) from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise DescriptionError(f"{where}: line {line}: not UTF-8 text (byte "
                               f"0x{data[exc.start]:02x}); save the file as UTF-8",
                               path=where) from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise DescriptionError(f"{where}: not valid TOML: {exc}", path=where) from None


def label(path: str) -> str:
    """How messages name a description file: as given, the default one by its name."""
    try:
        if Path(path).resolve() == default_description().resolve():
            return f"{Path(path).name} (the default description)"
    except DescriptionError:
        pass
    return path
