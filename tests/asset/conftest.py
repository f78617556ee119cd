from pathlib import Path

import pytest

from rapidgen.asset import load_asset
from rapidgen.diagnostics import DiagnosticSink

ROOT = Path(__file__).resolve().parents[2]
ASSETS = ROOT / "specs" / "assets"
SEEDS = ("k10", "chariot", "athlete", "eva-suit", "robonaut2", "xarm2")


@pytest.fixture(scope="session")
def seed():
    """seed("robonaut2") -> LoadedAsset of specs/assets/robonaut2.yaml (asserts it is clean)."""
    cache = {}

    def load(name: str):
        if name not in cache:
            sink = DiagnosticSink()
            loaded = load_asset(str(ASSETS / f"{name}.yaml"), sink)
            assert loaded is not None and not sink.diagnostics, sink.diagnostics
            cache[name] = loaded
        return cache[name]
    return load
