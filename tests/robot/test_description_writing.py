"""Writing a description (robot/description/writing.py): the text read back resolves to
the same robot (the digest: every resolved number and drawing), with overrides and
expressions kept; what a file cannot hold is refused by name."""

import tomllib

import pytest

from offshore_crane.errors import DescriptionError
from offshore_crane.robot.description import (default_description, description_dir, read_toml,
                                              resolve, resolve_data)
from offshore_crane.robot.description.loading import flat_values
from offshore_crane.robot.description.writing import description_text


def _written(path, overrides=None, comments=None):
    raw = flat_values(read_toml(path), str(path), overrides).raw
    text = description_text(raw, comments, "a header\nof two lines")
    return text, resolve_data(tomllib.loads(text), str(path))


@pytest.mark.parametrize("name", ["lab.toml", "harib_srinivasan_2003.toml"])
def test_a_written_shipped_description_builds_the_same_robot(name):
    path = description_dir() / name
    text, spec = _written(path, comments={"platform.mass": "the plate",
                                          "legs.lower": "the cylinders\non the base"})
    assert spec.digest() == resolve(path).digest()
    assert text.startswith("# a header\n# of two lines\n")
    assert "# the plate" in text and "# the cylinders\n# on the base\n[legs.lower]" in text


def test_overrides_and_expressions_are_written():
    """An override (a per-leg table, a vector) is in the text; an expression stays one,
    so the dimension it reads still drives it."""
    over = {"legs.3.lower.mass": 2.5, "platform.com": [0.01, 0.0, 0.0],
            "platform.shape.length": 0.05}
    text, spec = _written(default_description(), over)
    assert spec.digest() == resolve(default_description(), over).digest()
    assert "[legs.3.lower]\nmass = 2.5" in text
    assert 'height = "-platform.shape.length / 2"' in text


def test_a_vector_given_in_part_is_refused():
    raw = dict(flat_values(read_toml(default_description()), "lab.toml").raw)
    raw["legs.2.upper.com.z"] = -0.1
    with pytest.raises(DescriptionError, match=r"legs\.2\.upper\.com is given in part "
                       r"\(legs\.2\.upper\.com\.x missing\)"):
        description_text(raw)
    raw.pop("legs.2.upper.com.z")
    raw["platform.colour"] = 1.0
    with pytest.raises(DescriptionError, match="platform.colour is not a field"):
        description_text(raw)
