"""The packaged QoS library's precomputed form (rapidgen/qos/packaged.py) is fresh and is
the very library the YAML parses to: default_library() returns the same either way."""
from pathlib import Path

from rapidgen.qos import packaged, spec


def test_packaged_module_is_fresh():
    path = Path(spec.__file__).resolve().parent / spec.PACKAGED_MODULE
    assert path.read_text(encoding="utf-8") == spec.packaged_module_text(), \
        "stale: run `python -m rapidgen.qos --write`"


def test_precomputed_equals_parsed():
    text = spec._packaged_text()
    assert packaged.SOURCE == text
    parsed = spec._parse_packaged(text)
    assert packaged.library() == parsed
    assert repr(packaged.library()) == repr(parsed)
    spec.default_library.cache_clear()
    assert spec.default_library() == parsed


def test_stale_copy_is_ignored(monkeypatch):
    monkeypatch.setattr(packaged, "SOURCE", "something else")
    spec.default_library.cache_clear()
    try:
        assert spec.default_library() == spec._parse_packaged(spec._packaged_text())
    finally:
        spec.default_library.cache_clear()
