"""bench/rust_codec.py in its smoke mode (--quick --no-cpp): it builds, its program's bytes
equal the reference encoder's and decode back equal, and the checks it relies on catch a
wrong byte or a failed C++ check. Never about time."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests.rust.conftest import ROOT, cargo

sys.path.insert(0, str(ROOT / "bench"))
import cpp_codec  # noqa: E402
import rust_codec  # noqa: E402

CASES = [name for name, _, _ in rust_codec.CASES]


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory) -> tuple[subprocess.CompletedProcess, Path]:
    cargo()  # fails the test, saying why, without cargo
    work = tmp_path_factory.mktemp("rust-codec-bench")
    in_repo = [ROOT / "bench" / "rust_codec" / name for name in ("Cargo.lock", "target")]
    before = [p.exists() for p in in_repo]
    res = subprocess.run([sys.executable, str(ROOT / "bench" / "rust_codec.py"), "--quick", "--no-cpp", "--keep", str(work)],
                         capture_output=True, text=True, timeout=1800, stdin=subprocess.DEVNULL, cwd=ROOT)
    # it builds in its own folder: nothing new in the repository's copy of the project
    assert [p.exists() for p in in_repo] == before
    return res, work


def test_quick_run_builds_and_checks_the_bytes(quick_run) -> None:
    res, work = quick_run
    assert res.returncode == 0, res.stdout + res.stderr
    out = res.stdout
    assert out.startswith("machine: ") and "rustc " in out.splitlines()[0]
    assert "checks: Rust bytes = reference encoder's and decode back equal, for all 3 cases" in out
    lines = out.splitlines()
    first = lines.index(next(line for line in lines if line.startswith("type ")))
    medians = lines[first + 1:lines.index("", first)]  # the spread table follows a blank line
    rows = {line[:22].strip(): line[22:].split() for line in medians}
    assert list(rows) == CASES
    sizes = {name: int(cols[0]) for name, cols in rows.items()}
    assert sizes == {"Command (3 arguments)": 213, "JointSample (64)": 1876, "ImageSensorSample 1MB": 1048760}
    for cols in rows.values():
        float(cols[1])  # enc Rust: a figure (its value is not the test's business)
        assert cols[2] == "-"  # no C++ column with --no-cpp
    assert (work / "rust_codec" / "Cargo.lock").exists()


def test_a_changed_byte_is_reported(quick_run, tmp_path) -> None:
    _, work = quick_run
    for f in (work / "bytes").iterdir():
        (tmp_path / f.name).write_bytes(f.read_bytes())
    assert rust_codec.check_bytes(tmp_path) == []
    data = bytearray((tmp_path / "JointSample.bin").read_bytes())
    data[40] ^= 1
    (tmp_path / "JointSample.bin").write_bytes(bytes(data))
    (tmp_path / "Command.bin").unlink()
    problems = rust_codec.check_bytes(tmp_path)
    assert problems == ["Command (3 arguments): the Rust program wrote no bytes",
                        "JointSample (64): Rust bytes differ from the reference encoder's at offset 40 "
                        "(1876 bytes, reference 1876)"]


def test_program_refuses_a_bad_scale(quick_run) -> None:
    _, work = quick_run
    res = subprocess.run([str(work / "target" / "release" / "rust_codec_bench"), "--scale", "0"],
                         capture_output=True, text=True, stdin=subprocess.DEVNULL)
    assert res.returncode == 2 and "usage" in res.stderr and res.stdout == ""


def test_cpp_output_parsed_with_its_failed_checks() -> None:
    text = ("type                       bytes     ser ours      ser fdg      de ours       de fdg     memcpy    ser x     de x\n"
            "JointSample: fastddsgen bytes differ from ours\n"
            "JointSample (64)            1876         31.8        107.2         48.5        125.4       12.8    3.37x    2.58x\n")
    rows, notes = cpp_codec.parse(text)
    assert rows == {"JointSample (64)": {"bytes": 1876.0, "ser_ours": 31.8, "ser_fdg": 107.2, "de_ours": 48.5,
                                         "de_fdg": 125.4, "memcpy": 12.8, "ser_x": 3.37, "de_x": 2.58}}
    assert notes == ["JointSample: fastddsgen bytes differ from ours"]
