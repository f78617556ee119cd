import os
from pathlib import Path

import pytest

from tests.cpp.conftest import build_cpp_tests
from tests.rust.conftest import build_rust_peer

# Every diagnostic reported while the tests run (in this process and in the children the
# tests start) is checked against rapidgen/codes.py: code registered, severity allowed.
os.environ["RAPIDGEN_CHECK_CODES"] = "1"

# Every bridge the tests start keeps its restart journal (docs/runtime.md) in this run's own
# folder: a journal left by an earlier run (a killed bridge) would otherwise answer its old
# commands again in this one. Tests that need their own folder pass --journal.
if "RAPID_STATE_DIR" not in os.environ:
    import tempfile
    os.environ["RAPID_STATE_DIR"] = tempfile.mkdtemp(prefix="rapidgen-tests-state-")


def pytest_addoption(parser):
    parser.addoption("--update-golden", action="store_true", default=False,
                     help="rewrite golden expectations from the current output")


@pytest.fixture
def update_golden(request) -> bool:
    return bool(request.config.getoption("--update-golden"))


# The builds several tiers share (tests/cpp, tests/rust: the Rust <-> C++ interop test needs
# both), once per session, inside the session's temp folder.
@pytest.fixture(scope="session")
def cpp_build(tmp_path_factory) -> Path:
    """The generated C++ packages and tests/cpp's programs (peer, vectors, fuzz, configs)."""
    return build_cpp_tests(tmp_path_factory.mktemp("cpp"))


@pytest.fixture(scope="session")
def rust_target(tmp_path_factory) -> Path:
    """The session's cargo target folder (shared: every Rust program builds once)."""
    return tmp_path_factory.mktemp("cargo-target")


@pytest.fixture(scope="session")
def rust_peer(rust_target) -> Path:
    """The RustDDS interop peer (tests/rust/peer)."""
    return build_rust_peer(rust_target)
