"""Encode / decode ns/op of the generated Rust codec beside the generated C++ codec and fastddsgen.

    .venv/bin/python bench/rust_codec.py [--runs N] [--quick] [--no-cpp] [--keep DIR]

Builds bench/rust_codec (a Cargo program using generated/rapid/rust, crate rapid_types,
default features, `cargo build --release --offline`) and bench/cpp_codec.py's program (the
generated C++ of generated/rapid/cpp and fastddsgen's code, Release -O2), both in a
temporary folder (--keep DIR: in DIR, kept). The two programs time the same values (Command
with 3 arguments, JointSample with 64 joints, a 1 MB ImageSensorSample) the same way: each
figure is the best of 5 timed loops of the same iteration counts. The script runs them
alternately --runs times (default 5) and prints the median of the runs and their spread.
It also checks that the Rust bytes equal the reference encoder's (rapidgen.cdr) and that
they decode back to an equal value (the C++ program checks its own round trip and its
bytes against fastddsgen's). Prints figures only; exits 1 when a build or a check fails.
--quick (a smoke run: iterations / 1000, one run) gives no meaningful figures.
"""
from __future__ import annotations

import argparse
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import cpp_codec  # noqa: E402  (also puts the repository on sys.path)
from cpp_codec import ROOT, BuildFailed  # noqa: E402
from rapidgen.cdr import Codec  # noqa: E402

PROJECT = HERE / "rust_codec"
CRATE_PATH = '"../../generated/rapid/rust"'  # as bench/rust_codec/Cargo.toml spells it
# (name both programs print, file stem of --dump, IDL type)
CASES = (("Command (3 arguments)", "Command", "rapid::Command"),
         ("JointSample (64)", "JointSample", "rapid::JointSample"),
         ("ImageSensorSample 1MB", "ImageSensorSample", "rapid::ImageSensorSample"))
Rows = dict[str, dict[str, float]]


def cargo() -> str:
    """cargo on PATH, else rustup's in CARGO_HOME (as tests/rust/conftest.py finds it)."""
    found = shutil.which("cargo") or str(Path(os.environ.get("CARGO_HOME", Path.home() / ".cargo")) / "bin" / "cargo")
    if not Path(found).exists():
        raise BuildFailed("cargo is not installed (scripts/setup.sh, or rustup)")
    return found


def _version(cmd: list[str]) -> str:
    try:
        res = subprocess.run(cmd, capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=30)
    except OSError:
        return f"{cmd[0]}: not found"
    return (res.stdout or res.stderr).splitlines()[0].strip() if res.returncode == 0 else f"{cmd[0]}: failed"


def machine_line() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text(encoding="utf-8").splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    rustc = str(Path(cargo()).with_name("rustc")) if Path(cargo()).with_name("rustc").exists() else "rustc"
    return (f"machine: {cpu}, {os.cpu_count()} cores, {platform.system()} {platform.release()}, "
            f"load {os.getloadavg()[0]:.2f}; {_version([rustc, '--version'])} (release: opt-level 3); "
            f"{_version(['g++', '--version'])} (-O2)")


def build_rust(work: Path) -> Path:
    """bench/rust_codec copied into work/rust_codec (the crate's path made absolute, so no
    Cargo.lock lands in the repository), built there into work/target; the program's path."""
    project = work / "rust_codec"
    shutil.copytree(PROJECT, project, dirs_exist_ok=True, ignore=shutil.ignore_patterns("target", "Cargo.lock"))
    manifest = project / "Cargo.toml"
    text = manifest.read_text(encoding="utf-8")
    if CRATE_PATH not in text:
        raise BuildFailed(f"{PROJECT / 'Cargo.toml'} no longer names the crate as {CRATE_PATH}")
    manifest.write_text(text.replace(CRATE_PATH, f'"{(ROOT / "generated/rapid/rust").as_posix()}"'), encoding="utf-8")
    target = work / "target"
    env = dict(os.environ, CARGO_TARGET_DIR=str(target), CARGO_TERM_COLOR="never")
    res = subprocess.run([cargo(), "build", "--release", "--offline"], cwd=project, env=env,
                         capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=1800)
    if res.returncode != 0:
        raise BuildFailed(f"cargo build of bench/rust_codec failed:\n{res.stderr[-6000:]}")
    return target / "release" / "rust_codec_bench"


def measure_rust(program: Path, scale: int = 1, dump: Path | None = None) -> tuple[Rows, list[str]]:
    """One run of the Rust program: {case: {bytes, encode, decode}} and the problems seen."""
    cmd = [str(program), "--scale", str(scale)] + (["--dump", str(dump)] if dump else [])
    res = subprocess.run(cmd, capture_output=True, text=True, stdin=subprocess.DEVNULL)
    rows: Rows = {}
    notes = [line for line in res.stderr.splitlines() if line.strip()]
    for line in res.stdout.splitlines():
        name, size, enc, dec, status = line.split("\t")
        rows[name] = {"bytes": float(size), "encode": float(enc), "decode": float(dec)}
        if status != "ok":
            notes.append(f"{name}: Rust round trip {status}")
    if res.returncode != 0:
        notes.append(f"rust_codec_bench exited {res.returncode}")
    return rows, notes


def reference_values(codec: Codec) -> dict[str, object]:
    """The values bench/cpp_codec/bench.cpp and bench/rust_codec/src/main.rs build, in the
    reference encoder's value form, by file stem."""
    def of(type_name: str, **members: object) -> dict:
        value = codec.types.default_value(codec.types.type_of(type_name))
        assert isinstance(value, dict)
        return {**value, **members}

    hdr = of("rapid::Header", srcName="commander-01", assetName="K10Red", timeStamp=1700000000000000)
    ramp = [0.25 * i for i in range(64)]
    return {
        "Command": of("rapid::Command", hdr=hdr, cmdName="driveTo", cmdId="17-commander-01-1700000000",
                      cmdSrc="commander-01", subsysName="Locomotion", cmdAction="QUEUE_APPEND",
                      arguments=[{"discriminator": "RAPID_STRING", "value": "waypoint-7"},
                                 {"discriminator": "RAPID_DOUBLE", "value": 0.5},
                                 {"discriminator": "RAPID_VEC3d", "value": [1.0, 2.0, 3.0]}]),
        "JointSample": of("rapid::JointSample", hdr=hdr, anglePos=ramp, angleVel=ramp, angleAcc=ramp,
                          current=ramp, torque=ramp, temperature=ramp, status=[1] * 64),
        "ImageSensorSample": of("rapid::ImageSensorSample", hdr=hdr, mimeType="image/x-raw-gray8",
                                meta=of("rapid::ImageMetadata", sensorName="panCamLeft", width=1024, height=1024),
                                data=bytes((i * 31) & 0xFF for i in range(1 << 20))),
    }


def check_bytes(dump: Path) -> list[str]:
    """Differences between the Rust program's bytes and the reference encoder's."""
    codec = Codec(cpp_codec.rapid_model())
    problems = []
    for (name, stem, type_name), (_, value) in zip(CASES, reference_values(codec).items()):
        got = dump / f"{stem}.bin"
        want = codec.encode(type_name, value)
        if not got.exists():
            problems.append(f"{name}: the Rust program wrote no bytes")
        elif got.read_bytes() != want:
            have = got.read_bytes()
            at = next((i for i, (a, b) in enumerate(zip(have, want)) if a != b), min(len(have), len(want)))
            problems.append(f"{name}: Rust bytes differ from the reference encoder's at offset {at} "
                            f"({len(have)} bytes, reference {len(want)})")
    return problems


def _cell(values: list[float]) -> str:
    return f"{statistics.median(values):.1f}" if values else "-"


def _spread(values: list[float]) -> str:
    """max/min - 1 over the runs, in percent."""
    return f"{100 * (max(values) / min(values) - 1):.0f}%" if len(values) > 1 and min(values) > 0 else "-"


def table(rust: list[Rows], cpp: list[Rows]) -> str:
    """Medians over the runs, then the spread of each figure."""
    cols = [("enc Rust", rust, "encode"), ("enc C++", cpp, "ser_ours"), ("enc fdg", cpp, "ser_fdg"),
            ("dec Rust", rust, "decode"), ("dec C++", cpp, "de_ours"), ("dec fdg", cpp, "de_fdg"),
            ("memcpy", cpp, "memcpy")]

    def series(runs: list[Rows], case: str, key: str) -> list[float]:
        return [r[case][key] for r in runs if case in r]

    head = f"{'type':<22} {'bytes':>8}" + "".join(f" {c[0]:>10}" for c in cols) + f" {'Rust/C++ enc':>13} {'dec':>6}"
    lines = [head]
    spread = [f"{'spread (max/min-1)':<31}" + "".join(f" {c[0]:>10}" for c in cols)]
    for name, _, _ in CASES:
        size = series(rust, name, "bytes") or series(cpp, name, "bytes")
        row = f"{name:<22} {int(size[0]) if size else 0:>8}"
        row += "".join(f" {_cell(series(runs, name, key)):>10}" for _, runs, key in cols)
        ratios = []
        for ours, theirs in (("encode", "ser_ours"), ("decode", "de_ours")):
            r, c = series(rust, name, ours), series(cpp, name, theirs)
            ratios.append(f"{statistics.median(r) / statistics.median(c):.2f}x" if r and c else "-")
        lines.append(row + f" {ratios[0]:>13} {ratios[1]:>6}")
        spread.append(f"{name:<31}" + "".join(f" {_spread(series(runs, name, key)):>10}" for _, runs, key in cols))
    return "\n".join(lines + [""] + spread)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5, help="runs of each program (default 5)")
    ap.add_argument("--quick", action="store_true", help="smoke run: iterations / 1000, one run, no meaningful figures")
    ap.add_argument("--no-cpp", action="store_true", help="the Rust program only")
    ap.add_argument("--keep", help="build in this folder and keep it")
    args = ap.parse_args()
    if args.runs < 1:
        ap.error("--runs must be at least 1")
    runs, scale = (1, 1000) if args.quick else (args.runs, 1)
    with tempfile.TemporaryDirectory(prefix="rust_codec_") as tmp:
        work = Path(args.keep) if args.keep else Path(tmp)
        work.mkdir(parents=True, exist_ok=True)
        try:
            print(machine_line())
            rust_program = build_rust(work)
            cpp_program = None if args.no_cpp else cpp_codec.build(work / "cpp")
        except BuildFailed as err:
            print(err)
            return 1
        dump = work / "bytes"
        dump.mkdir(exist_ok=True)
        rust: list[Rows] = []
        cpp: list[Rows] = []
        notes: list[str] = []
        for i in range(runs):  # alternated, so a busy moment on the machine hits both
            if cpp_program is not None:
                rows, more = cpp_codec.measure(cpp_program)
                cpp.append(rows)
                notes += more
            rows, more = measure_rust(rust_program, scale, dump if i == 0 else None)
            rust.append(rows)
            notes += more
        notes += check_bytes(dump)
        print(f"ns/op, median of {runs} run(s), each figure the best of 5 timed loops; Rust/C++: Rust's "
              f"time over rapidgen's C++ (above 1: C++ is faster); fdg: fastddsgen's C++"
              + ("; --quick: iterations / 1000, not a measurement" if args.quick else ""))
        print(table(rust, cpp))
        print(f"load after the runs: {os.getloadavg()[0]:.2f}")
        for note in dict.fromkeys(notes):
            print("problem:", note)
        if not notes:
            print(f"checks: Rust bytes = reference encoder's and decode back equal, for all {len(CASES)} cases"
                  + ("" if cpp_program is None else "; C++ round trips and bytes = fastddsgen's"))
        return 1 if notes else 0


if __name__ == "__main__":
    sys.exit(main())
