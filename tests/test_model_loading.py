"""Model loading under stress (issue 10, families 5 and 6): threads on a cold cache, and
a cache that verifies what it reads."""

import threading
import warnings

import pytest

import offshore_crane as oc
from offshore_crane.model import _ROBOTS, xacro_cache
from offshore_crane.model.xacro_cache import CacheWarning, expand


@pytest.fixture
def cold_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("OFFSHORE_CRANE_CACHE", str(tmp_path))
    saved = dict(_ROBOTS)
    _ROBOTS.clear()
    yield tmp_path
    _ROBOTS.clear()
    _ROBOTS.update(saved)


def test_threads_on_a_cold_cache(cold_cache):
    """8 threads x 10 rounds of load_robot() (several parameter sets) all succeed with
    identical models (xacro alone fails this: its expansion keeps global state)."""
    results, errors = [], []

    def work(k):
        try:
            for r in range(10):
                _ROBOTS.clear() if r == 5 and k == 0 else None
                robot = oc.load_robot(column_mass=5.0 + (r % 3))
                results.append((r % 3, robot.urdf))
        except Exception as exc:            # noqa: BLE001 - any failure is reported
            errors.append(exc)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == []
    for variant in range(3):
        assert len({u for v, u in results if v == variant}) == 1
    assert not list(cold_cache.glob(".oc-*"))      # no temporary file left


@pytest.mark.parametrize("damage", [
    lambda text: text[: len(text) // 2],                                 # truncated
    lambda text: text.replace('name="offshore_crane"', 'name="edited"'),  # edited
    lambda text: "\\x00\\xff random bytes",                               # garbage
])
def test_damaged_entry_is_named_rebuilt_and_reported_once(cold_cache, damage):
    text, path = expand({"column_mass": 6})
    raw = path.read_text(encoding="utf-8", errors="replace")
    path.write_bytes(damage(raw).encode("utf-8", errors="replace"))
    with pytest.warns(CacheWarning, match=f"{path.name} is damaged or was edited"):
        again, path2 = expand({"column_mass": 6})
    assert again == text and path2 == path
    with warnings.catch_warnings():
        warnings.simplefilter("error")           # repaired: no second warning
        assert expand({"column_mass": 6}) == (text, path)


def test_unwritable_cache_only_costs_speed(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    monkeypatch.setenv("OFFSHORE_CRANE_CACHE", str(blocker / "cache"))
    text, path = expand({"column_mass": 6})
    assert path is None and "<robot" in text


def test_cache_key_includes_xacro_version(cold_cache, monkeypatch):
    _, path = expand({"column_mass": 6})
    monkeypatch.setattr(xacro_cache, "_xacro_version", lambda: "999.0")
    _, other = expand({"column_mass": 6})
    assert other != path
