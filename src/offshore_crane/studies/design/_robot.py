"""A design of the front as a robot description file: the scene's description with its
robot fields (the scene's ``[robot]`` and ``[payload]``, ``--set``) and the design's
variables written in, its expressions kept, so that every number that depends on a
variable follows it (``--robot design.toml`` runs it with any command).
"""

from __future__ import annotations

import os


def design_description(scene, values: dict, header: str = "") -> str:
    """The TOML text of ``scene``'s robot with the design's ``values`` (``{dotted name:
    value}``) over its fields.

    The scene's own robot fields are written in too: a command that runs the file with
    the same scene applies them again, to the same values, so it runs the very robot the
    design evaluated (the same digest); with another scene it runs the designed arm with
    this scene's payload (the header says so).

    Raises:
        DescriptionError: the values make no valid robot (checked by resolving the text).
    """
    from offshore_crane.robot.description import (default_description, read_description,
                                                  read_toml, resolve_data)
    from offshore_crane.robot.description.loading import flat_values
    from offshore_crane.robot.description.writing import description_text

    path = os.fspath(scene.robot_description or default_description())
    overrides = {**scene.robot, **values}
    raw = dict(flat_values(read_toml(path, read_description(path)), path, overrides).raw)
    fields = ", ".join(sorted(scene.robot)) or "none"
    text = description_text(raw, header=(
        f"{header}\nwritten by offshore-crane design from {path}: the design's variables "
        f"({', '.join(values)}) and the scene's robot fields ({fields}) written in; "
        "expressions kept").strip())
    import tomllib

    resolve_data(tomllib.loads(text), "design description")       # a valid robot
    return text
