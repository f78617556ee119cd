"""The Rust bridges, built once per run for every test of the folder (build.py)."""
from __future__ import annotations

import os
from pathlib import Path

import pytest

from tests.cpp_runtime import build as B
from tests.rust_runtime.build import build_bridges, libclang

# One LIBCLANG_PATH for every cargo run in the bridges' target folder (the tests' own builds,
# rapid_dds's unit tests, the test-breaks bridge): bindgen's build script reruns whenever it
# changes, set or unset, and bindgen, cyclors, rapid_dds and every bridge above them compile
# again (about 7 CPU-s each time).
_CLANG = libclang()
if _CLANG and not os.environ.get("LIBCLANG_PATH"):
    os.environ["LIBCLANG_PATH"] = _CLANG


@pytest.fixture(scope="session")
def bridges(tmp_path_factory) -> dict[str, Path]:
    """seed (and build.HOSTILE) -> its bridge's binary (its `<crate>_cmd` beside it); "ws":
    the workspace (the hostile descriptor and its generated QoS files are there); "target":
    the cargo target folder they were built in. Once per run: under pytest-xdist the
    workers running test_dds_bridge.py and test_interop_client.py share one build (B.once),
    in a target folder of its own (cyclors is built there and nowhere else)."""
    return B.once(tmp_path_factory, "rust-bridges",  # type: ignore[no-any-return]
                  lambda: build_bridges(B.run_folder(tmp_path_factory, "rust-bridges-target"),
                                        B.run_folder(tmp_path_factory, "rust-bridges")))
