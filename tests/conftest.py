import os
from pathlib import Path

import pytest

from tests.cpp_runtime import build as B
from tests.rust.conftest import build_rust_peer

# Every diagnostic reported while the tests run (in this process and in the children the
# tests start) is checked against rapidgen/codes.py: code registered, severity allowed.
os.environ["RAPIDGEN_CHECK_CODES"] = "1"

# Every bridge the tests start keeps its restart journal (docs/runtime.md) in this run's own
# folder: a journal left by an earlier run (a killed bridge) would otherwise answer its old
# commands again in this one. Tests that need their own folder pass --journal. Under xdist
# each worker makes its own (the one it inherits is marked as the tests'): two workers'
# bridges of one asset must not share a journal.
if os.environ.get("RAPID_STATE_DIR", "") in ("", os.environ.get("RAPIDGEN_TESTS_STATE_DIR")):
    import tempfile
    os.environ["RAPID_STATE_DIR"] = os.environ["RAPIDGEN_TESTS_STATE_DIR"] = \
        tempfile.mkdtemp(prefix="rapidgen-tests-state-")


def _xdist_scope(nodeid: str) -> str:
    """The unit of work a worker takes: a test file (its module fixtures, e.g. a whole
    broken-kinds campaign, run once), tests/rust as one (its tests share the cargo target
    folder, where programs' names repeat)."""
    path = nodeid.split("::", 1)[0]
    return "tests/rust" if path.startswith("tests/rust/") else path


def _measured_seconds() -> dict[str, float]:
    """Each unit of work's wall seconds in a measured run (tests/durations.json)."""
    import json
    with open(Path(__file__).parent / "durations.json", encoding="utf-8") as fh:
        return json.load(fh)["seconds"]  # type: ignore[no-any-return]


class _XdistScheduling:
    def pytest_xdist_make_scheduler(self, config, log):
        """scripts/test's workers take whole files (_xdist_scope), the longest first by a
        measured run (tests/durations.json): one started last would leave the other workers
        idle at the end of the run. xdist's loadgroup cannot group on pytest 9 (it renames
        node ids pytest no longer reads)."""
        from xdist.scheduler import LoadScopeScheduling
        seconds = _measured_seconds()

        class ByFile(LoadScopeScheduling):
            def _split_scope(self, nodeid: str) -> str:
                return _xdist_scope(nodeid)

            def _assign_work_unit(self, node) -> None:
                if not getattr(self, "_longest_first", False):  # (the queue is whole by the first call)
                    self._longest_first = True
                    for scope in sorted(self.workqueue, key=lambda s: -seconds.get(s, 0.0)):
                        self.workqueue.move_to_end(scope)
                super()._assign_work_unit(node)
        config.option.loadscopereorder = False  # (by test count: the slow tiers have few tests)
        return ByFile(config, log)


def pytest_configure(config):
    if config.pluginmanager.hasplugin("xdist"):  # (its hook is unknown to pytest without it)
        config.pluginmanager.register(_XdistScheduling(), "rapidgen-xdist-scheduling")


def pytest_addoption(parser):
    parser.addoption("--update-golden", action="store_true", default=False,
                     help="rewrite golden expectations from the current output")


@pytest.fixture
def update_golden(request) -> bool:
    return bool(request.config.getoption("--update-golden"))


# The builds several tiers share (tests/cpp, tests/rust: the Rust <-> C++ interop test needs
# both), once per run (B.once: across xdist workers too), inside the run's temp folder.
@pytest.fixture(scope="session")
def cpp_build(tmp_path_factory) -> Path:
    """The generated C++ packages and tests/cpp's programs (peer, vectors, fuzz, configs)."""
    return B.cpp_tests(tmp_path_factory)


@pytest.fixture(scope="session")
def rust_target(tmp_path_factory) -> Path:
    """The session's cargo target folder (shared: every Rust program builds once). The
    programs' names repeat across tests: the tests using it share one xdist worker
    (pytest_collection_modifyitems)."""
    return tmp_path_factory.mktemp("cargo-target")


@pytest.fixture(scope="session")
def rust_peer(rust_target) -> Path:
    """The RustDDS interop peer (tests/rust/peer)."""
    return build_rust_peer(rust_target)


def pytest_collection_modifyitems(config, items):
    """Each test marked with what it needs (tests/tiers.py), for `-m` and the fast tier."""
    from tests.tiers import needs

    for item in items:
        for mark in sorted(needs(item.nodeid) or ()):
            item.add_marker(getattr(pytest.mark, mark))
