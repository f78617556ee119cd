"""The Rust bridges, built once per session for every test of the folder (build.py)."""
from __future__ import annotations

from pathlib import Path

import pytest

from tests.rust_runtime.build import build_bridges


@pytest.fixture(scope="session")
def bridges(rust_target, tmp_path_factory) -> dict[str, Path]:
    """seed (and build.HOSTILE) -> its bridge's binary (its `<crate>_cmd` beside it); "ws":
    the workspace (the hostile descriptor and its generated QoS files are there)."""
    return build_bridges(rust_target, tmp_path_factory)
