"""Model loading (issue 10, families 5 and 6): thread safety, a cache that verifies what
it reads, keys on the tools' versions, leaks no temporary file and survives an
unwritable directory."""

from __future__ import annotations

import os
import tempfile
import threading
import warnings

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane import progress
from offshore_crane import robot as model
from offshore_crane.robot import xacro_cache
from offshore_crane.robot.description import resolve
from offshore_crane.robot.xacro_cache import CacheWarning, expand

THREADS = 8
ROUNDS = 10


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """An empty cache directory, no memoised robot, no warning given yet."""
    folder = tmp_path / "cache"
    monkeypatch.setenv("OFFSHORE_CRANE_CACHE", str(folder))
    monkeypatch.setattr(model, "_ROBOTS", {})
    monkeypatch.setattr(progress, "_noticed", set())
    return folder


def _in_threads(function, n=THREADS):
    """Run ``function(k)`` in ``n`` threads started together; (results, errors)."""
    barrier = threading.Barrier(n)
    results, errors = [None] * n, []

    def work(k):
        try:
            barrier.wait()
            results[k] = function(k)
        except Exception as exc:           # noqa: BLE001 - collected and reported
            errors.append(exc)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(n)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return results, errors


def test_load_robot_from_threads_on_a_cold_cache(tmp_path, monkeypatch):
    reference = oc.load_robot().urdf
    for r in range(ROUNDS):
        monkeypatch.setenv("OFFSHORE_CRANE_CACHE", str(tmp_path / f"cache{r}"))
        monkeypatch.setattr(model, "_ROBOTS", {})
        robots, errors = _in_threads(lambda k: oc.load_robot())
        assert not errors, errors
        assert all(robot is robots[0] for robot in robots)   # one build, shared
        assert robots[0].urdf == reference


def test_expansions_from_threads(cache):
    """Eight different descriptions expanded at once (xacro's global state is guarded):
    each gives the URDF a lone expansion gives."""
    data = [resolve(overrides={"platform.mass": 40.0 + k}).xacro_data()
            for k in range(THREADS)]
    results, errors = _in_threads(lambda k: expand(data[k])[0])
    assert not errors, errors
    for k in range(THREADS):
        assert results[k] == xacro_cache.run_xacro(xacro_cache.description_yaml(data[k]))
        assert f'<mass value="{40.0 + k}"/>' in results[k]


def _damage(path, how):
    text = path.read_bytes()
    if how == "truncated":
        path.write_bytes(text[:len(text) // 2])
    elif how == "edited":
        path.write_bytes(text.replace(b'<mass value="40.0"/>', b'<mass value="41.0"/>'))
    elif how == "random bytes":
        path.write_bytes(np.random.default_rng(1).bytes(len(text)))
    elif how == "not UTF-8":
        path.write_bytes(text[:100] + b"\xff\xfe" + text[100:])
    elif how == "no trailer":
        path.write_bytes(text[:text.rindex(b"<!-- offshore-crane-cache")])
    elif how == "empty":
        path.write_bytes(b"")


@pytest.mark.parametrize("how", ["truncated", "edited", "random bytes", "not UTF-8",
                                 "no trailer", "empty"])
def test_damaged_entry_is_named_rebuilt_and_reported_once(cache, how):
    data = resolve().xacro_data()
    urdf, path = expand(data)
    assert path.read_text().startswith(urdf)
    _damage(path, how)
    with pytest.warns(CacheWarning, match=f"URDF cache entry {path} .*: rebuilt from the "
                      "xacro") as record:
        assert expand(data) == (urdf, path)
    assert len(record) == 1
    with warnings.catch_warnings():
        warnings.simplefilter("error")                   # the entry was rewritten
        assert expand(data) == (urdf, path)
    _damage(path, how)                                    # again: reported only once
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert expand(data) == (urdf, path)


def test_robot_from_a_damaged_cache_has_the_right_forces(cache):
    """An edited cached URDF (another mass) is not used: the forces are the true ones."""
    robot = oc.load_robot()
    _damage(robot.urdf_path, "edited")
    model._ROBOTS.clear()
    with pytest.warns(CacheWarning):
        again = oc.load_robot()
    assert again is not robot and again.urdf == robot.urdf
    assert again.hybrid.platform_mass == robot.hybrid.platform_mass == 45.0


def test_key_includes_the_tool_versions(cache, monkeypatch):
    data = resolve().xacro_data()
    _, path = expand(data)
    monkeypatch.setattr(xacro_cache, "_versions", lambda: "xacro=0.0;PyYAML=0.0")
    _, other = expand(data)
    assert other != path and other.is_file()


def test_key_includes_the_xacro_and_the_description(cache):
    data = resolve().xacro_data()
    key = xacro_cache.cache_key(data)
    assert xacro_cache.cache_key(resolve(overrides={"legs.lower.mass": 2.5}).xacro_data()) != key
    assert key == xacro_cache.cache_key(resolve().xacro_data())


def _only_entries(folder):
    names = sorted(os.listdir(folder))
    assert all(n.startswith("offshore_crane-") and n.endswith(".urdf") for n in names), names
    return names


def test_no_temporary_file_is_left(cache):
    for mass in (40.0, 41.0, 42.0):
        expand(resolve(overrides={"platform.mass": mass}).xacro_data())
    assert len(_only_entries(cache)) == 3


def test_failed_write_leaves_no_temporary(cache, monkeypatch):
    data = resolve(overrides={"platform.mass": 43.0}).xacro_data()

    def fail(*args):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(xacro_cache.os, "replace", fail)
    urdf, path = expand(data)
    assert path is None and '<mass value="43.0"/>' in urdf     # computed, not cached
    assert _only_entries(cache) == []


def _record_temporaries(monkeypatch) -> list:
    """The names of the temporary files the cache creates from now on."""
    created = []
    real = tempfile.mkstemp

    def recording(*args, **kwargs):
        fd, name = real(*args, **kwargs)
        created.append(name)
        return fd, name

    monkeypatch.setattr(xacro_cache.tempfile, "mkstemp", recording)
    return created


def test_failed_expansion_leaves_no_temporary(cache, monkeypatch):
    import xacro
    created = _record_temporaries(monkeypatch)

    def broken(*args, **kwargs):
        raise RuntimeError("xacro broke")

    monkeypatch.setattr(xacro, "process_file", broken)
    with pytest.raises(oc.ModelError, match="expanding offshore_crane.urdf.xacro failed: "
                       "xacro broke"):
        expand(resolve(overrides={"platform.mass": 44.0}).xacro_data())
    assert created and not any(os.path.exists(name) for name in created)


def test_unwritable_cache_only_costs_speed(tmp_path, monkeypatch):
    blocker = tmp_path / "a file"
    blocker.write_text("not a directory")
    monkeypatch.setenv("OFFSHORE_CRANE_CACHE", str(blocker / "cache"))   # cannot exist
    monkeypatch.setattr(model, "_ROBOTS", {})
    created = _record_temporaries(monkeypatch)
    with warnings.catch_warnings():
        warnings.simplefilter("error")                 # not a damaged entry: silent
        robot = oc.load_robot(overrides={"platform.mass": 46.0})
    assert robot.urdf_path is None and robot.hybrid.platform_mass == 51.0
    assert created and not any(os.path.exists(name) for name in created)


def test_edited_description_file_is_reloaded(tmp_path):
    """Robots are memoised on the file's content, not only its name."""
    path = tmp_path / "lab.toml"
    source = (model.description.default_description()).read_text()
    path.write_text(source)
    first = oc.load_robot(path)
    assert oc.load_robot(path) is first
    path.write_text(source.replace("mass = 40.0", "mass = 42.0"))
    assert oc.load_robot(path).hybrid.platform_mass == 47.0
