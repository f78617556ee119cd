"""One cargo build per session of a generated Rust crate and the test programs.

Built into a target folder in the pytest session's temp folder (the cache lives inside
the run, shared by every test): K10's crate (the RAPID set plus K10's extension IDL, so
every golden vector's type), in release mode, offline (the generated crate with its
default features and the test programs need no crate from a registry).

What does need registry crates (the RustDDS peer; the `serde` and `dds` features under
clippy and serde_json) builds with tests/rust/peer/Cargo.lock: the peer's own, copied
beside the other manifests as their starting lock, so every build uses its versions.
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
VECTORS = ROOT / "tests" / "vectors" / "rapid.json"
K10 = ROOT / "generated" / "k10" / "rust"
CRATE = "rapid_k10red"
RUSTDDS_MSRV = (1, 88)  # rustdds 0.15.0's rust-version
PEER_LOCK = HERE / "peer" / "Cargo.lock"  # the versions of every registry crate the tests use


def cargo() -> str:
    found = shutil.which("cargo") or str(Path(os.environ.get("CARGO_HOME", Path.home() / ".cargo")) / "bin" / "cargo")
    if not Path(found).exists():
        pytest.fail("cargo is needed (scripts/setup.sh installs Debian's when none is found)")
    return found


def run(cmd: list[str], cwd: Path, target: Path, timeout: float = 900) -> subprocess.CompletedProcess:
    env = dict(os.environ, CARGO_TARGET_DIR=str(target), CARGO_TERM_COLOR="never")
    # stdin closed: cargo probes `rustc -` with the inherited stdin, which under a full
    # test run may hold another test's output
    res = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout, env=env,
                         stdin=subprocess.DEVNULL)
    assert res.returncode == 0, f"{' '.join(cmd)}\n{res.stdout[-3000:]}\n{res.stderr[-6000:]}"
    return res


def vector_lines() -> list[str]:
    """'id type le_hex be_hex' per golden vector: the programs' stdin."""
    data = json.loads(VECTORS.read_text(encoding="utf-8"))
    return [f"{v['id']} {v['type']} {v['xcdr1_le']} {v['xcdr1_be']}" for v in data["vectors"]]


HARNESS = """\
[package]
name = "rapidgen_rust_tests"
version = "0.0.0"
edition = "2021"
publish = false

[dependencies]
gen = {{ package = "{crate}", path = "{path}" }}

"""
BIN = """
[[bin]]
name = "{name}"
path = "{path}"
"""


def build_programs(folder: Path, crate_dir: Path, crate: str, target: Path, extra: dict[str, Path] | None = None) -> Path:
    """The test programs of tests/rust/src (and `extra` ones) built against the crate in
    crate_dir (imported as `gen`); returns the folder holding the executables."""
    bins = {"vectors": HERE / "src" / "vectors.rs", "fuzz": HERE / "src" / "fuzz.rs", **(extra or {})}
    text = HARNESS.format(crate=crate, path=crate_dir.as_posix())
    text += "".join(BIN.format(name=n, path=p.as_posix()) for n, p in bins.items())
    (folder / "Cargo.toml").write_text(text, encoding="utf-8")
    # the dev profile (debug assertions and overflow checks on): K10's crate and the four
    # programs build in 2.5 CPU-s against --release's 15, and run in 2.8 (0.7)
    run([cargo(), "build", "--offline", "--bins"], folder, target)
    return target / "debug"


@pytest.fixture(scope="session")
def rust_build(tmp_path_factory, rust_target) -> Path:
    """The test programs built against K10's crate; returns their folder."""
    start = time.monotonic()
    out = build_programs(tmp_path_factory.mktemp("rust-harness"), K10, CRATE, rust_target,
                         {"configs": HERE / "src" / "configs.rs", "reuse": HERE / "src" / "reuse.rs"})
    print(f"\nrust: cargo build of {CRATE} and the test programs took {time.monotonic() - start:.1f} s")
    return out


def skip_unless_registry_toolchain() -> None:
    """Skips on a toolchain older than the crates of PEER_LOCK need (RustDDS 0.15: 1.88)."""
    version = subprocess.run([cargo(), "--version"], capture_output=True, text=True,
                             stdin=subprocess.DEVNULL).stdout.split()
    if tuple(int(x) for x in version[1].split(".")[:2]) < RUSTDDS_MSRV:
        pytest.skip(f"RustDDS 0.15 needs Rust >= 1.88, this is {version[1]} (Debian 12's cargo is 1.63: use rustup)")


SERDE_HARNESS = """\
[package]
name = "rapidgen_rust_serde_tests"
version = "0.0.0"
edition = "2021"
publish = false

[dependencies]
gen = {{ package = "{crate}", path = "{path}", features = ["serde"] }}
serde_json = "=1.0.154"
"""


def build_serde_programs(folder: Path, crate_dir: Path, crate: str, target: Path, programs: dict[str, Path]) -> Path:
    """Programs built against the crate in crate_dir with its `serde` feature (as `gen`)
    and serde_json, at PEER_LOCK's versions; returns the folder holding the executables."""
    skip_unless_registry_toolchain()
    text = SERDE_HARNESS.format(crate=crate, path=crate_dir.as_posix())
    text += "".join(BIN.format(name=n, path=p.as_posix()) for n, p in programs.items())
    (folder / "Cargo.toml").write_text(text, encoding="utf-8")
    shutil.copyfile(PEER_LOCK, folder / "Cargo.lock")
    # the dev profile, as the RustDDS peer: serde's crates built once for both (the same
    # target folder), and no optimizer over serde_json for programs that run a few hundred vectors
    run([cargo(), "build", "--bins"], folder, target)
    return target / "debug"


def build_rust_peer(target: Path) -> Path:
    """The RustDDS peer (tests/rust/peer, Cargo.lock pinned) built in target (the session's
    `rust_peer` fixture, tests/conftest.py); skips on a toolchain RustDDS cannot use."""
    skip_unless_registry_toolchain()
    start = time.monotonic()
    run([cargo(), "build", "--locked"], HERE / "peer", target, timeout=1200)
    print(f"\nrust: cargo build of the RustDDS peer took {time.monotonic() - start:.1f} s")
    return target / "debug" / "peer"
