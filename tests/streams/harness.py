"""Builds for the setpoint-stream tests and bench: generated packages whose user-owned
bridge/handlers.cpp gets a few lines of test code (what a robot team writes in theirs),
built with -Wall -Wextra -Werror in a folder kept between runs (incremental: a run after
the first rebuilds only what changed).

    packages = build(["robonaut2", "xarm2"])   # name -> the <package>_bridge program

Folder: $RAPIDGEN_STREAMS_BUILD, else <tmp>/rapidgen-streams-<uid>-<checkout digest> (one per
checkout: CMake refuses a build folder made from another source tree). Extra descriptors
(the bench's) are given as paths.
"""
from __future__ import annotations

import hashlib
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
FLAGS = "-Wall -Wextra -Werror"
MARK = "// ---- test code (tests/streams/harness.py) ----"


def workdir() -> Path:
    tree = hashlib.sha1(str(ROOT).encode()).hexdigest()[:8]
    d = os.environ.get("RAPIDGEN_STREAMS_BUILD") or os.path.join(tempfile.gettempdir(),
                                                                 f"rapidgen-streams-{os.getuid()}-{tree}")
    Path(d).mkdir(parents=True, exist_ok=True)
    return Path(d)


def run(cmd: list, cwd: Path = ROOT, timeout: float = 1800) -> str:
    res = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=timeout, cwd=cwd)
    if res.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))}\n{res.stdout[-3000:]}\n{res.stderr[-6000:]}")
    return res.stdout


def toolchain_missing() -> str | None:
    if shutil.which("cmake") is None or shutil.which("g++") is None:
        return "cmake and g++ are needed (scripts/setup.sh)"
    if not Path("/usr/include/fastdds/dds/topic/TopicDataType.hpp").exists():
        return "libfastrtps-dev and libfastcdr-dev are needed (scripts/setup.sh)"
    return None


def runtime(work: Path) -> Path:
    out = work / "runtime"
    run(["cmake", "-S", ROOT / "runtime" / "cpp", "-B", out, "-DCMAKE_BUILD_TYPE=Release", f"-DCMAKE_CXX_FLAGS={FLAGS}"])
    run(["cmake", "--build", out, "-j", "2"])
    return out


def _write_if_changed(path: Path, text: str) -> None:
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def with_test_code(stub: str, includes: str, before: str, in_make: str) -> str:
    """The generated handlers.cpp with `includes` after its own, `before` ahead of
    make_handlers() and `in_make` where it returns the set (the stubs stay as generated:
    commands answer "not implemented")."""
    inc = '#include "handlers.hpp"\n'
    assert inc in stub
    stub = stub.replace(inc, inc + includes, 1)
    head, sep, tail = stub.partition("HandlerSet make_handlers() {")
    assert sep, "make_handlers() not found in the generated handlers.cpp"
    body, ret, rest = tail.partition("    return set;\n}")
    assert ret, "make_handlers() does not end as generated"
    return f"{head}{MARK}\n{before}\n{sep}{body}{in_make}{ret}{rest}"


def generate(work: Path, descriptor: Path, code: tuple[str, str, str]) -> Path:
    """The descriptor's C++ package under work/gen/<stem>, its handlers.cpp with the test code."""
    out = work / "gen" / descriptor.stem
    handlers = out / "cpp" / "bridge" / "handlers.cpp"
    old = (handlers.read_text(encoding="utf-8"), handlers.stat()) if handlers.exists() else None
    if old is not None:
        handlers.unlink()  # fresh stubs, then the test's lines
    run([sys.executable, "-m", "rapidgen", "generate", descriptor, "--lang", "cpp", "-o", out])
    text = with_test_code(handlers.read_text(encoding="utf-8"), *code)
    handlers.write_text(text, encoding="utf-8")
    if old is not None and old[0] == text:  # unchanged: keep its time, so make skips it
        os.utime(handlers, ns=(old[1].st_atime_ns, old[1].st_mtime_ns))
    return out / "cpp"


def package_of(cpp: Path) -> str:
    return next(p.parent.name for p in (cpp / "include").glob("*/asset.hpp"))


def build(descriptors: dict[Path, tuple[str, str, str]], alloc_count: Path | None = None,
          quick: bool = False, runtime_dir: Path | None = None) -> dict[str, Path]:
    """Each descriptor's bridge with its test code; stem -> program. quick: unity builds
    without optimization (tests); else optimized (the bench). runtime_dir: a built runtime
    to use (the test session's, tests/cpp_runtime/build.py); else one built here."""
    work = workdir()
    rt = runtime_dir or runtime(work)
    dirs = {d.stem: generate(work, d, code) for d, code in descriptors.items()}
    out = work / ("bridges-quick" if quick else "bridges-alloc" if alloc_count else "bridges")
    defs = [f"-Drapid_runtime_cpp_DIR={rt}", "-DPACKAGE_DIRS=" + ";".join(str(d) for d in dirs.values()),
            f"-DALLOC_COUNT={alloc_count or ''}", f"-DQUICK={'ON' if quick else 'OFF'}"]
    run(["cmake", "-S", HERE, "-B", out, "-DCMAKE_BUILD_TYPE=Release", f"-DCMAKE_CXX_FLAGS={FLAGS}", *defs])
    run(["cmake", "--build", out, "-j", "2", *[a for d in dirs.values() for a in ("--target", f"{package_of(d)}_bridge")]])
    return {s: out / d.parent.name / f"{package_of(d)}_bridge" for s, d in dirs.items()}


def dds_env() -> dict[str, str]:
    """No Fast DDS profile variables: the bridges' built-in profiles (rapid_local: loopback) rule."""
    return {k: v for k, v in os.environ.items() if not k.startswith(("FASTDDS_", "FASTRTPS_"))}


def lines_matching(lines: list[str], pattern: str) -> list[re.Match]:
    return [m for m in (re.search(pattern, line) for line in lines) if m]
