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
        B.configure(B.HERE, out, f"-Drapid_runtime_cpp_DIR={runtime}", *B.table_dirs(tmp_path_factory))
        B.build(out, "logic", "faults")
        return out
    return B.once(tmp_path_factory, "runtime-tests", make)  # type: ignore[no-any-return]


@pytest.fixture(scope="session")
def logic_under_tsan(runtime_build: Path, tmp_path_factory) -> Path:
    """The logic suite again, runtime and test built with ThreadSanitizer (handlers run on
    threads of their own, acks go out under the manager's lock)."""
    return B.once(tmp_path_factory, "tsan", lambda: _tsan(runtime_build, tmp_path_factory))  # type: ignore[no-any-return]


# The sanitized runtimes' core as one translation unit, with line tables only (-g1: reports keep
# file:line): the core's CPU under TSan 17.7 -> 13.4 s, under ASan/UBSan 35.8 -> 30.1 s
# (docs/testing.md, "Where CI time goes"). The tests stay file by file: their fixtures are in
# anonymous namespaces.
UNITY = ["-DCMAKE_UNITY_BUILD=ON", "-DCMAKE_UNITY_BUILD_BATCH_SIZE=0"]


def _tsan(runtime_build: Path, tmp_path_factory) -> Path:
    base = runtime_build.parent / "tsan"
    flags = [f"-DCMAKE_CXX_FLAGS={B.FLAGS} -fsanitize=thread -g1 -O1", "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread"]
    B.run(["cmake", "-S", str(B.ROOT / "runtime" / "cpp"), "-B", str(base / "runtime"), "-DCMAKE_BUILD_TYPE=Debug",
           *UNITY, *flags])
    B.build(base / "runtime")
    B.run(["cmake", "-S", str(B.HERE), "-B", str(base / "tests"), "-DCMAKE_BUILD_TYPE=Debug", *flags,
           f"-Drapid_runtime_cpp_DIR={base / 'runtime'}", *B.table_dirs(tmp_path_factory)])
    B.build(base / "tests", "logic", "faults")  # (the fault-injecting handlers' suite beside it)
    return base / "tests" / "logic"


@pytest.fixture(scope="session")
def faults_under_sanitizers(runtime_build: Path, tmp_path_factory) -> Path:
    """The fault-injecting handlers' suite (test_handler_faults.cpp) again, on a runtime
    configured with -DRAPID_RUNTIME_SANITIZE=ON (ASan and UBSan, which reach the test through
    rapid_runtime_cpp::core's flags). Built once per run, shared like the others."""
    made = B.once(tmp_path_factory, "asan-faults", lambda: _sanitized(runtime_build, tmp_path_factory))
    return made  # type: ignore[no-any-return]


def _sanitized(runtime_build: Path, tmp_path_factory) -> Path:
    base = runtime_build.parent / "asan"
    # (GCC 12's -Wmaybe-uninitialized misfires on <regex> and <functional> under the sanitizers)
    flags = [f"-DCMAKE_CXX_FLAGS={B.FLAGS} -Wno-maybe-uninitialized -g1 -O1"]
    B.run(["cmake", "-S", str(B.ROOT / "runtime" / "cpp"), "-B", str(base / "runtime"), "-DCMAKE_BUILD_TYPE=Debug",
           "-DRAPID_RUNTIME_SANITIZE=ON", *UNITY, *flags])
    B.build(base / "runtime")
    B.run(["cmake", "-S", str(B.HERE), "-B", str(base / "tests"), "-DCMAKE_BUILD_TYPE=Debug", *flags,
           f"-Drapid_runtime_cpp_DIR={base / 'runtime'}", *B.table_dirs(tmp_path_factory)])
    B.build(base / "tests", "faults")
    return base / "tests" / "faults"


@pytest.fixture(scope="session")
def seed_bridges(tmp_path_factory) -> dict[str, Path]:
    """Every seed's generated bridge (seed -> program)."""
    return B.seed_bridges(tmp_path_factory)
