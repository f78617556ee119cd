"""The C++ asset runtime's builds, once per pytest session (tests/cpp_runtime/build.py holds
them, shared with tests/conformance/test_cpp_asset.py), all with -Wall -Wextra -Werror:
the runtime first (found with find_package by the tests, as a robot would), K10's
generated package (its tables and glue are what the logic suite runs on), the GoogleTest
suite; the seeds' bridges only when a test asks for them."""
from __future__ import annotations

from pathlib import Path

import pytest

from tests.cpp_runtime import build as B


@pytest.fixture(scope="session")
def runtime_build(tmp_path_factory) -> Path:
    """The runtime package and the test folder's build; returns the tests' build folder."""
    def make() -> Path:
        runtime = B.runtime_dir(tmp_path_factory)
        out = B.base(tmp_path_factory) / "tests"
        B.configure(B.HERE, out, f"-Drapid_runtime_cpp_DIR={runtime}", *B.UNITY, *B.table_dirs(tmp_path_factory))
        B.build(out, "logic", "faults")
        return out
    return B.once(tmp_path_factory, "runtime-tests", make)  # type: ignore[no-any-return]


@pytest.fixture(scope="session")
def logic_under_tsan(runtime_build: Path, tmp_path_factory) -> Path:
    """The logic suite again, runtime and test built with ThreadSanitizer (handlers run on
    threads of their own, acks go out under the manager's lock)."""
    return B.once(tmp_path_factory, "tsan", lambda: _tsan(runtime_build, tmp_path_factory))  # type: ignore[no-any-return]


def _tsan(runtime_build: Path, tmp_path_factory) -> Path:
    base = runtime_build.parent / "tsan"
    flags = [f"-DCMAKE_CXX_FLAGS={B.FLAGS} -fsanitize=thread -O1", B.SAN_DEBUG, "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread"]
    B.run(["cmake", "-S", str(B.ROOT / "runtime" / "cpp"), "-B", str(base / "runtime"), "-DCMAKE_BUILD_TYPE=Debug",
           *B.UNITY, *flags])
    B.build(base / "runtime")
    B.run(["cmake", "-S", str(B.HERE), "-B", str(base / "tests"), "-DCMAKE_BUILD_TYPE=Debug", *B.UNITY, *flags,
           f"-Drapid_runtime_cpp_DIR={base / 'runtime'}", *B.table_dirs(tmp_path_factory)])
    B.build(base / "tests", "logic", "faults")  # (the fault-injecting handlers' suite beside it)
    return base / "tests" / "logic"


@pytest.fixture(scope="session")
def faults_under_sanitizers(tmp_path_factory) -> Path:
    """The fault-injecting handlers' suite (test_handler_faults.cpp) again, on the run's runtime
    configured with -DRAPID_RUNTIME_SANITIZE=ON (ASan and UBSan, which reach the test through
    rapid_runtime_cpp::core's flags; B.asan_runtime_dir, shared with K10's test bridge).
    Built once per run, shared like the others."""
    return B.once(tmp_path_factory, "asan-faults", lambda: _sanitized(tmp_path_factory))  # type: ignore[no-any-return]


def _sanitized(tmp_path_factory) -> Path:
    runtime = B.asan_runtime_dir(tmp_path_factory)
    out = B.asan_dir(tmp_path_factory) / "tests"
    B.run(["cmake", "-S", str(B.HERE), "-B", str(out), "-DCMAKE_BUILD_TYPE=Debug", f"-DCMAKE_CXX_FLAGS={B.ASAN_FLAGS}",
           B.SAN_DEBUG, f"-Drapid_runtime_cpp_DIR={runtime}", *B.table_dirs(tmp_path_factory)])
    B.build(out, "faults")
    return out / "faults"


@pytest.fixture(scope="session")
def seed_bridges(tmp_path_factory) -> dict[str, Path]:
    """Every seed's generated bridge (seed -> program)."""
    return B.seed_bridges(tmp_path_factory)
