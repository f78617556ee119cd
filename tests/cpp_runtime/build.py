"""Builds shared by the C++ runtime's tests (tests/cpp_runtime) and the conformance tier's
C++ bridges (tests/conformance/test_cpp_asset.py): each is made once per pytest session,
in the session's temp folder, with -Wall -Wextra -Werror.

    runtime_dir(f)      runtime/cpp built (rapid_runtime_cpp_DIR for find_package)
    generated(f, seed)  `rapidgen generate <descriptor> --lang cpp` (the package)
    seed_bridges(f)     every seed's <package>_bridge and the hostile descriptor's, one
                        CMake build of them all (K10's file by file, the others as unity
                        builds: seeds/CMakeLists.txt); k10_bridge(f) K10's alone in it
    asan_runtime_dir(f) runtime/cpp under ASan/UBSan, a test build: the fault suite's runtime
                        (conftest.py) and the core of K10's test bridge (client_programs)
    cpp_tests(f)        tests/cpp's programs on K10's generated package (the `cpp_build`
                        fixture), and its codec under ASan/UBSan, K10's test bridge's too

`f` is pytest's tmp_path_factory. The seeds are tests.runtime.live.SEEDS (all six unless
RAPIDGEN_CPP_SEEDS names some, comma-separated) and HOSTILE, K10 with names C++ reserves
and text that ends comments and strings (hostile_descriptor()).

Under pytest-xdist (scripts/test runs the suite on workers) each build is still made once
per run, in the run's folder the workers share: the first worker to ask makes it under a
file lock, the others take its result (once())."""
from __future__ import annotations

import fcntl
import os
import pickle
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from tests.runtime.live import SEEDS

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
FLAGS = "-Wall -Wextra -Werror"
# Release in the tests is -O1, not CMake's -O3: about a quarter less compiler CPU (the runtime:
# 20.9 -> 15.6 s of user CPU), still optimized (the warnings that need optimization fire).
# The bench's builds keep -O3 (bench/, tests/streams/harness.py's optimized bridges).
RELEASE = "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG"
JOBS = str(max(1, min(4, os.cpu_count() or 1)))
_CACHE: dict[tuple[str, str], object] = {}  # (session temp folder, what) -> result


def run(cmd: list[str], timeout: float = 1200) -> subprocess.CompletedProcess:
    res = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, cwd=ROOT)
    assert res.returncode == 0, f"{' '.join(cmd)}\n{res.stdout[-3000:]}\n{res.stderr[-6000:]}"
    return res


def configure(src: Path, build: Path, *defs: str, build_type: str = "Release") -> None:
    run(["cmake", "-S", str(src), "-B", str(build), f"-DCMAKE_BUILD_TYPE={build_type}", f"-DCMAKE_CXX_FLAGS={FLAGS}",
         RELEASE, *defs])


def build(build_dir: Path, *targets: str) -> None:
    """The targets built, under a lock on the build folder: workers build different targets of
    one CMake build (the seeds') and two makes in one tree race."""
    extra = [a for t in targets for a in ("--target", t)]
    with open(build_dir.parent / f".{build_dir.name}.build-lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        run(["cmake", "--build", str(build_dir), "-j", JOBS, *extra])


def needs_toolchain() -> None:
    if shutil.which("cmake") is None or shutil.which("g++") is None or \
            not Path("/usr/include/fastdds/dds/topic/TopicDataType.hpp").exists() or \
            not Path("/usr/include/gtest/gtest.h").exists():
        pytest.fail("cmake, g++, googletest and libfastrtps-dev/libfastcdr-dev are needed (scripts/setup.sh)")


def run_root(factory) -> Path:
    """The session's temp folder; under xdist the run's, which every worker's is inside."""
    own = factory.getbasetemp()
    return own.parent if os.environ.get("PYTEST_XDIST_WORKER") else own


def once(factory, what: str, make):
    """make()'s result, made once per run: per process (_CACHE) and, under xdist, across
    workers (a lock file and the pickled result in the run's folder)."""
    key = (str(factory.getbasetemp()), what)
    if key not in _CACHE:
        if not os.environ.get("PYTEST_XDIST_WORKER"):
            _CACHE[key] = make()
        else:
            shared = run_root(factory) / "shared-builds"
            shared.mkdir(exist_ok=True)
            with open(shared / f"{what}.lock", "w") as lock:
                fcntl.flock(lock, fcntl.LOCK_EX)  # (released on close; a failed make leaves no result)
                done = shared / f"{what}.pickle"
                if not done.exists():
                    done.write_bytes(pickle.dumps(make()))
                _CACHE[key] = pickle.loads(done.read_bytes())
    return _CACHE[key]


_once = once  # (the name the functions below use)


def run_folder(factory, name: str) -> Path:
    """A new folder in the session's temp folder, under xdist in the run's (call it in once())."""
    if not os.environ.get("PYTEST_XDIST_WORKER"):
        return factory.mktemp(name)  # type: ignore[no-any-return]
    out = run_root(factory) / name
    out.mkdir()
    return out


def base(factory) -> Path:
    return _once(factory, "base", lambda: run_folder(factory, "cpp-runtime"))  # type: ignore[no-any-return]


def runtime_dir(factory) -> Path:
    def make() -> Path:
        needs_toolchain()
        out = base(factory) / "runtime"
        configure(ROOT / "runtime" / "cpp", out, *UNITY)
        build(out)
        return out
    return _once(factory, "runtime", make)  # type: ignore[no-any-return]


# The sanitized builds (Debug: no NDEBUG, -O1) keep line tables only, reports still say file:line.
# CMake puts CMAKE_CXX_FLAGS_DEBUG (-g) after CMAKE_CXX_FLAGS, so a -g1 there lost to it: -g1
# is the Debug flags themselves (compile CPU: the ASan/UBSan runtime 43.0 -> 33.8 s, the TSan
# runtime and suites 69.0 -> 50.6 s; docs/testing.md).
SAN_DEBUG = "-DCMAKE_CXX_FLAGS_DEBUG=-g1"
# Each target as one translation unit: the runtime's core under TSan 17.7 -> 13.4 CPU-s, under
# ASan/UBSan 35.8 -> 30.1, at -O1 17.3 -> 12.0; the logic and fault suites 33.5 -> 27.4
# (docs/testing.md, "Where CI time goes").
UNITY = ["-DCMAKE_UNITY_BUILD=ON", "-DCMAKE_UNITY_BUILD_BATCH_SIZE=0"]
# ASan/UBSan builds: GCC 12's -Wmaybe-uninitialized misfires on <regex> and <functional> under
# the sanitizers. RAPID_RUNTIME_TEST_BREAKS: one sanitized runtime serves the fault suite and
# K10's test bridge, which takes --break KIND; the breaks are off unless a bridge is told one
# (the fault suite's handlers run on the same decisions as a plain build's).
ASAN_FLAGS = f"{FLAGS} -Wno-maybe-uninitialized -O1 -DRAPID_RUNTIME_TEST_BREAKS"


def asan_dir(factory) -> Path:
    """The folder of the run's ASan/UBSan builds: runtime/ (asan_runtime_dir), tests/ (the fault suite)."""
    return base(factory) / "asan"


def asan_runtime_dir(factory) -> Path:
    """runtime/cpp configured with -DRAPID_RUNTIME_SANITIZE=ON (ASan and UBSan on the core and,
    through its PUBLIC flags, on what links it), a test build (ASAN_FLAGS), its core one unit."""
    def make() -> Path:
        needs_toolchain()
        out = asan_dir(factory) / "runtime"
        run(["cmake", "-S", str(ROOT / "runtime" / "cpp"), "-B", str(out), "-DCMAKE_BUILD_TYPE=Debug",
             "-DRAPID_RUNTIME_SANITIZE=ON", *UNITY, f"-DCMAKE_CXX_FLAGS={ASAN_FLAGS}", SAN_DEBUG])
        build(out)
        return out
    return _once(factory, "asan-runtime", make)  # type: ignore[no-any-return]


def cpp_tests(factory) -> Path:
    """tests/cpp's build (tests/cpp/conftest.py build_cpp_tests) on K10's package as generated
    here; its folder's libtypes_san.a (K10_TYPES_SAN) is K10's codec under ASan/UBSan."""
    from tests.cpp.conftest import build_cpp_tests  # (here, not above: tests/conftest.py imports both)
    return _once(factory, "cpp-tests",  # type: ignore[no-any-return]
                 lambda: build_cpp_tests(base(factory) / "cpp", generated(factory, "k10")))


def k10_types_san(factory) -> Path:
    return base(factory) / "cpp" / "tests" / "libtypes_san.a"  # (cpp_tests makes it)


def descriptor(factory, seed: str) -> Path:
    """The seed's descriptor (HOSTILE's written to the session's folder)."""
    if seed == STREAM_RIG:
        return ROOT / "tests" / "streams" / "rig.yaml"
    if seed != HOSTILE:
        return ROOT / "specs" / "assets" / f"{seed}.yaml"

    def make() -> Path:
        path = base(factory) / "hostile.yaml"
        path.write_text(yaml.safe_dump(hostile_descriptor(), allow_unicode=True), encoding="utf-8")
        return path
    return _once(factory, "hostile.yaml", make)  # type: ignore[no-any-return]


def generated(factory, seed: str) -> Path:
    """The seed's generated C++ package (its cpp/ folder)."""
    def make() -> Path:
        out = base(factory) / "gen" / seed
        run([sys.executable, "-m", "rapidgen", "generate", str(descriptor(factory, seed)), "--lang", "cpp", "-o",
             str(out)])
        return out / "cpp"
    return _once(factory, f"gen-{seed}", make)  # type: ignore[no-any-return]


def table_dirs(factory) -> list[str]:
    """The -D options naming the generated bridge folders tests/cpp_runtime/CMakeLists.txt
    compiles tables from: K10's (the logic suite, the spec cases) and Chariot's (the spec
    cases of an asset without a queue)."""
    return [f"-DK10_BRIDGE_DIR={generated(factory, 'k10') / 'bridge'}",
            f"-DCHARIOT_BRIDGE_DIR={generated(factory, 'chariot') / 'bridge'}"]


def package_of(cpp: Path) -> str:
    return next(p.parent.name for p in (cpp / "include").glob("*/asset.hpp"))


def chosen_seeds() -> list[str]:
    names = [s.strip() for s in os.environ.get("RAPIDGEN_CPP_SEEDS", "").split(",") if s.strip()]
    return [s for s in [*SEEDS, HOSTILE] if not names or s in names]


def seeds_build(factory) -> Path:
    """The seeds' CMake build (HERE/seeds: every chosen seed's package, the types library and
    <package>_bridge as the generated CMakeLists says, found runtime, all in one project),
    configured; the functions below build its targets."""
    def make() -> Path:
        runtime = runtime_dir(factory)
        dirs = [generated(factory, s) for s in chosen_seeds()]
        out = base(factory) / "bridges"
        rig = generated(factory, STREAM_RIG)  # built by stream_bridges() only
        configure(HERE / "seeds", out, f"-Drapid_runtime_cpp_DIR={runtime}",
                  "-DSEED_DIRS=" + ";".join(str(d) for d in [*dirs, rig]),
                  f"-DPLAIN_DIR={generated(factory, 'k10') if 'k10' in chosen_seeds() else ''}",
                  f"-DSAN_RUNTIME_DIR={asan_dir(factory) / 'runtime'}",  # (both made by client_programs only)
                  f"-DK10_TYPES_SAN={k10_types_san(factory)}")
        return out
    return _once(factory, "seeds-configured", make)  # type: ignore[no-any-return]


def seed_bridges(factory) -> dict[str, Path]:
    """Every chosen seed's bridge, in the seeds' build."""
    def make() -> dict[str, Path]:
        out = seeds_build(factory)
        dirs = {s: generated(factory, s) for s in chosen_seeds()}
        build(out, *(f"{package_of(d)}_bridge" for d in dirs.values()))
        return {s: out / d.parent.name / f"{package_of(d)}_bridge" for s, d in dirs.items()}
    return _once(factory, "bridges", make)  # type: ignore[no-any-return]


def seed_types(factory, seed: str) -> Path:
    """A chosen seed's types library (built with the bridges; -O1, file by file, as users
    build it: seeds/CMakeLists.txt), for tests/cpp/test_every_package.py."""
    out, pkg = seeds_build(factory), package_of(generated(factory, seed))
    build(out, pkg)  # (nothing to do once the bridges are built)
    return out / seed / f"lib{pkg}.a"


def k10_bridge(factory) -> dict[str, Path]:
    """K10's bridge ("bridge") and types library ("types") alone, in the seeds' build (the
    seeds' other bridges are not waited for): tests/secure's programs use them. Skips when
    K10 is not among RAPIDGEN_CPP_SEEDS."""
    if "k10" not in chosen_seeds():
        pytest.skip("RAPIDGEN_CPP_SEEDS leaves out k10")

    def make() -> dict[str, Path]:
        out, pkg = seeds_build(factory), package_of(generated(factory, "k10"))
        build(out, f"{pkg}_bridge")  # (its types library with it)
        return {"bridge": out / "k10" / f"{pkg}_bridge", "types": out / "k10" / f"lib{pkg}.a"}
    return _once(factory, "k10-bridge", make)  # type: ignore[no-any-return]


STREAM_RIG = "streamrig"  # tests/streams/rig.yaml: one input stream per loss action
STREAM_SEEDS = ("robonaut2", "xarm2")  # X-Arm-2 writes the hand pose Robonaut 2 reads


def stream_bridges(factory) -> dict[str, Path]:
    """For tests/streams: the seeds' bridges with streams and the streams' test asset's
    (STREAM_RIG), in the seeds' build (no second runtime build: one more bridge). Skips
    when RAPIDGEN_CPP_SEEDS leaves out a seed the streams need."""
    def make() -> dict[str, Path]:
        bridges = seed_bridges(factory)
        missing = [s for s in STREAM_SEEDS if s not in bridges]
        if missing:
            return {"missing": Path(",".join(missing))}
        rig = generated(factory, STREAM_RIG)
        out = base(factory) / "bridges"
        build(out, f"{package_of(rig)}_bridge")
        return {**{s: bridges[s] for s in STREAM_SEEDS}, STREAM_RIG: out / rig.parent.name / f"{package_of(rig)}_bridge"}
    made = _once(factory, "stream-bridges", make)
    if "missing" in made:
        pytest.skip(f"the setpoint-stream tests need {made['missing']} among RAPIDGEN_CPP_SEEDS")
    return made  # type: ignore[no-any-return]


def dds_env() -> dict[str, str]:
    """The environment without Fast DDS profile variables: the bridge's built-in profiles
    (rapid_local: loopback only) are what it uses."""
    return {k: v for k, v in os.environ.items() if not k.startswith(("FASTDDS_", "FASTRTPS_"))}


# ---- a descriptor C++ must not take as it is ---------------------------------------------------------

HOSTILE = "hostile"
HOSTILE_RULES = '''
subsystem_types:
  - name: "class"
    description: 'ends */ a comment ??/ and a "quote" \\ back'
    commands:
      - name: "delete"
        description: "x */ y"
        parameters:
          - {name: "ctx", type: RAPID_STRING, allowed: ["a\\"b", "??=", "\\\\"], default: "??="}
          - {name: "this", type: RAPID_FLOAT, unit: "m*/s", range: [-3.0e+38, 3.0e+38], default: 0}
          - {name: "my-arg", type: RAPID_INT, range: [-2147483648, 2147483647]}
          - {name: "my arg", type: RAPID_LONGLONG, default: -9223372036854775808}
          - {name: "9lives", type: RAPID_VEC3d, default: [1, 2.5, -3]}
          - {name: "\u00dcber", type: RAPID_MAT33f}
          - {name: "assert", type: RAPID_BOOL, default: true}
      - name: "class Handler"
      - name: "ClassHandler"
      - name: "do-it"
        parameters:
          - {name: "std", type: RAPID_STRING}
          - {name: "rapid_runtime", type: RAPID_DOUBLE, range: [0, 1]}
  - name: "Class Handler"
    commands:
      - {name: "on_start"}
      - {name: "HandlerSet"}
subsystems:
  - {name: "x y", type: "class"}
  - {name: "Twin One", type: "Class Handler"}
  - {name: "Twin Two", type: "Class Handler"}
'''


def hostile_descriptor() -> dict:
    """K10's descriptor plus subsystem types, commands and parameters named like C++
    keywords, macros and the generated code's own names, and text that ends comments and
    strings (its telemetry and extension types stay)."""
    k10 = ROOT / "specs" / "assets" / "k10.yaml"
    data = yaml.safe_load(k10.read_text(encoding="utf-8"))
    data["idl"] = {k: str((k10.parent / v).resolve()) if isinstance(v, str) else [str((k10.parent / x).resolve())
                   for x in v] for k, v in data["idl"].items()}
    hostile = yaml.safe_load(HOSTILE_RULES)
    data["subsystem_types"] += hostile["subsystem_types"]
    data["subsystems"] += hostile["subsystems"]
    data["asset"]["name"] = "Hostile_1"
    data["asset"]["description"] = 'a "robot" */ with ??/ trigraphs \\'
    data["dds"] = {"domain": 7, "partition": 'Hostile "1" part'}  # (no ? or *: DDS partition wildcards)
    return data


def k10_cmd(factory) -> Path:
    """K10's `rapid_k10red_cmd` alone, in the seeds' build (client_programs() also builds an
    ASan bridge); skips when K10 is not among RAPIDGEN_CPP_SEEDS."""
    if "k10" not in chosen_seeds():
        pytest.skip("RAPIDGEN_CPP_SEEDS leaves out k10")

    def make() -> Path:
        out = seed_bridges(factory)["k10"].parent.parent
        build(out, "rapid_k10red_cmd")
        return out / "rapid_k10red_cmd"
    return _once(factory, "field-cmd", make)  # type: ignore[no-any-return]


def client_programs(factory) -> dict[str, Path]:
    """On K10's package, in the seeds' build (seeds/CMakeLists.txt): `cmd`, the ground-side
    client program with K10's tables (rapid_runtime_cpp_add_cmd), and `bridge_test`, K10's
    generated bridge with the runtime (asan_runtime_dir's core) and the codec (cpp_tests') under
    ASan/UBSan and --break KIND (RAPID_RUNTIME_TEST_BREAKS). Fails when K10 is not among
    RAPIDGEN_CPP_SEEDS."""
    def make() -> dict[str, Path]:
        bridges = seed_bridges(factory)
        if "k10" not in bridges:
            pytest.fail("the C++ client tests need K10 among RAPIDGEN_CPP_SEEDS")
        asan_runtime_dir(factory)
        cpp_tests(factory)
        out = bridges["k10"].parent.parent
        build(out, "rapid_k10red_cmd", "rapid_k10red_bridge_test")
        return {"cmd": out / "rapid_k10red_cmd", "bridge_test": out / "rapid_k10red_bridge_test"}
    return _once(factory, "clients", make)  # type: ignore[no-any-return]
