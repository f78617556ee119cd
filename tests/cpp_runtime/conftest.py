"""One CMake build per pytest session of the C++ asset runtime (runtime/cpp) and its test
programs, in the session's temp folder, with -Wall -Wextra -Werror: the runtime first
(found with find_package by the tests, as a robot would), then the GoogleTest suite; the
K10 bridge only when a test asks for it (it needs K10's generated C++ types, generated
here into the temp folder with `rapidgen generate --lang cpp`)."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
FLAGS = "-Wall -Wextra -Werror"
JOBS = str(max(1, min(4, os.cpu_count() or 1)))


def run(cmd: list[str], timeout: float = 900) -> subprocess.CompletedProcess:
    res = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, cwd=ROOT)
    assert res.returncode == 0, f"{' '.join(cmd)}\n{res.stdout[-3000:]}\n{res.stderr[-6000:]}"
    return res


def configure(src: Path, build: Path, *defs: str) -> None:
    run(["cmake", "-S", str(src), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release", f"-DCMAKE_CXX_FLAGS={FLAGS}", *defs])


def build(build_dir: Path, *targets: str) -> None:
    extra = [a for t in targets for a in ("--target", t)]
    run(["cmake", "--build", str(build_dir), "-j", JOBS, *extra])


@pytest.fixture(scope="session")
def runtime_build(tmp_path_factory) -> Path:
    """The runtime package and the test folder's build; returns the tests' build folder."""
    if shutil.which("cmake") is None or shutil.which("g++") is None or \
            not Path("/usr/include/fastdds/dds/topic/TopicDataType.hpp").exists() or \
            not Path("/usr/include/gtest/gtest.h").exists():
        pytest.fail("cmake, g++, googletest and libfastrtps-dev/libfastcdr-dev are needed")
    base = tmp_path_factory.mktemp("cpp-runtime")
    configure(ROOT / "runtime" / "cpp", base / "runtime")
    build(base / "runtime")
    configure(HERE, base / "tests", f"-Drapid_runtime_cpp_DIR={base / 'runtime'}")
    build(base / "tests", "logic")
    return base / "tests"


@pytest.fixture(scope="session")
def logic_under_tsan(runtime_build: Path) -> Path:
    """The logic suite again, runtime and test built with ThreadSanitizer (handlers run on
    threads of their own, acks go out under the manager's lock)."""
    base = runtime_build.parent / "tsan"
    flags = [f"-DCMAKE_CXX_FLAGS={FLAGS} -fsanitize=thread -g -O1", "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread"]
    run(["cmake", "-S", str(ROOT / "runtime" / "cpp"), "-B", str(base / "runtime"), "-DCMAKE_BUILD_TYPE=Debug",
         *flags])
    build(base / "runtime")
    run(["cmake", "-S", str(HERE), "-B", str(base / "tests"), "-DCMAKE_BUILD_TYPE=Debug", *flags,
         f"-Drapid_runtime_cpp_DIR={base / 'runtime'}"])
    build(base / "tests", "logic")
    return base / "tests" / "logic"


@pytest.fixture(scope="session")
def k10_bridge(runtime_build: Path) -> Path:
    """K10's bridge on the runtime: K10's C++ types generated and built, then the program."""
    base = runtime_build.parent
    run([sys.executable, "-m", "rapidgen", "generate", "specs/assets/k10.yaml", "--lang", "cpp", "-o",
         str(base / "k10gen")])
    configure(base / "k10gen" / "cpp", base / "k10types")
    build(base / "k10types")
    configure(HERE, runtime_build, f"-Drapid_runtime_cpp_DIR={base / 'runtime'}",
              f"-Drapid_k10red_DIR={base / 'k10types'}")
    build(runtime_build, "k10_bridge")
    return runtime_build / "k10_bridge"
