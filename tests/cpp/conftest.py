"""One CMake build per session of the generated C++ packages and the test programs.

Built in a pytest session temp folder (the cache lives inside the run): the RAPID set's
package (a library, to check it compiles) and K10's (the RAPID set plus K10's extension
IDL, what the test programs use, found with find_package), all with -Wall -Wextra -Werror.
K10's is the run's `rapidgen generate` output (tests/cpp_runtime/build.py cpp_tests: the
same bytes as generated/k10, test_committed_generated_tree_is_current), which K10's test
bridge is built from too: it links this build's sanitized codec (libtypes_san.a).
"""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
VECTORS = ROOT / "tests" / "vectors" / "rapid.json"
K10 = ROOT / "generated" / "k10"
PKG = "rapid_k10red"
FLAGS = "-Wall -Wextra -Werror"
RELEASE = "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG"  # as tests/cpp_runtime/build.py (why there)
JOBS = str(max(1, min(4, os.cpu_count() or 1)))


def _run(cmd: list[str], timeout: float = 600) -> subprocess.CompletedProcess:
    res = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    assert res.returncode == 0, f"{' '.join(cmd)}\n{res.stdout[-3000:]}\n{res.stderr[-6000:]}"
    return res


def _cmake(src: Path, build: Path, *defs: str) -> None:
    _run(["cmake", "-S", str(src), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
          f"-DCMAKE_CXX_FLAGS={FLAGS}", RELEASE, *defs])
    _run(["cmake", "--build", str(build), "-j", JOBS])


def vector_lines() -> list[str]:
    """'id type le_hex be_hex' per golden vector: the programs' stdin."""
    data = json.loads(VECTORS.read_text(encoding="utf-8"))
    return [f"{v['id']} {v['type']} {v['xcdr1_le']} {v['xcdr1_be']}" for v in data["vectors"]]


def topics() -> list[dict]:
    """K10's topics (topic, type, profile) from its generated QoS topic map."""
    return json.loads((K10 / "qos" / "topics.json").read_text(encoding="utf-8"))["topics"]


def build_cpp_tests(base: Path, k10: Path = K10 / "cpp") -> Path:
    """The generated packages and the test programs built under base, on K10's C++ package
    `k10` (the session's `cpp_build` fixture, tests/conftest.py); returns the programs' folder."""
    if shutil.which("cmake") is None or shutil.which("g++") is None or \
            not Path("/usr/include/fastdds/dds/topic/TopicDataType.hpp").exists():
        pytest.fail("cmake, g++ and libfastrtps-dev/libfastcdr-dev are needed (scripts/setup.sh installs them)")
    _cmake(ROOT / "generated" / "rapid" / "cpp", base / "rapid_types")
    _cmake(k10, base / PKG)
    dispatch = base / "dispatch"
    dispatch.mkdir()
    types = sorted({line.split()[1] for line in vector_lines()})
    (dispatch / "dispatch.inc").write_text("".join(f'RAPIDGEN_TYPE(::{t}, "{t}")\n' for t in types))
    # every RAPID message type (the vectors' types with a header): K10's topics and the rest
    vectors = json.loads(VECTORS.read_text(encoding="utf-8"))["vectors"]
    topic_types = sorted({t["type"] for t in topics()} |
                         {v["type"] for v in vectors if isinstance(v["value"], dict) and "hdr" in v["value"]})
    (dispatch / "topics.inc").write_text("".join(f'RAPIDGEN_TYPE(::{t}, "{t}")\n' for t in topic_types))
    asset_hpp = (k10 / "include" / PKG / "asset.hpp").read_text(encoding="utf-8")
    (dispatch / "configs.inc").write_text("".join(
        f"RAPIDGEN_CONFIG({fn}, {topic})\n"
        for topic, fn in re.findall(r"// The config published on (\"[^\"]*\")\.\ninline \S+ (\w+)\(\)", asset_hpp)))
    _cmake(HERE, base / "tests", f"-DPKG={PKG}", f"-D{PKG}_DIR={base / PKG}",
           f"-DPKG_SOURCE={k10}", f"-DDISPATCH_DIR={dispatch}")
    return base / "tests"
