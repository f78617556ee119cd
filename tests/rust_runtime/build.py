"""The Rust bridges of tests/rust_runtime, built once per run (conftest.py's `bridges`, under
pytest-xdist once for all workers: tests/cpp_runtime/build.py once()):
the six seeds and the C++ tests' hostile descriptor generated into one temporary Cargo
workspace (runtime/ and the RAPID set's crate linked into it, so the bridges' paths to
runtime/rust resolve as in generated/), built by one `cargo build` (offline when it can) in
a target folder of their own from rapid_dds's Cargo.lock: cyclors and the runtime build once
for all, each crate's `<crate>_bridge` and `<crate>_cmd` with them."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml

from tests.cpp_runtime.build import hostile_descriptor
from tests.rust.conftest import cargo

ROOT = Path(__file__).resolve().parents[2]
RUNTIME = ROOT / "runtime" / "rust"
SEEDS = ("k10", "chariot", "athlete", "eva-suit", "robonaut2", "xarm2")
# and K10 with subsystem types, commands and parameters named like keywords, the generated
# code's own names and the crates it uses, names starting with a digit, text that ends
# comments and strings (the C++ bridge's hostile descriptor)
HOSTILE = "hostile"
# and tests/streams/rig.yaml: one input stream per loss action (test_streams.py)
RIG = "streamrig"
OLD_HANDLERS = Path("generated/robonaut2/rust/bridge/src/handlers.rs")
# the workspace: the bridges are members; what they reach by path is not (runtime/ has
# crates of its own, and a types crate as a member would resolve its optional RustDDS)
WORKSPACE = """[workspace]
resolver = "2"
members = ["generated/*/rust/bridge"]
exclude = ["runtime", "generated/rapid"]
"""


def libclang() -> str | None:
    for lib in sorted(Path("/usr/lib").glob("llvm-*/lib/libclang.so*"), reverse=True):
        return str(lib.parent)
    return None


def _package(folder: Path) -> str:
    for line in (folder / "Cargo.toml").read_text(encoding="utf-8").splitlines():
        if line.startswith("name = "):
            return json.loads(line.split("=", 1)[1].strip())
    raise AssertionError(f"no package name in {folder / 'Cargo.toml'}")


def descriptor(ws: Path, seed: str) -> Path:
    if seed == RIG:
        return ROOT / "tests" / "streams" / "rig.yaml"
    return ws / "hostile.yaml" if seed == HOSTILE else ROOT / "specs" / "assets" / f"{seed}.yaml"


def build_bridges(rust_target: Path, ws: Path) -> dict[str, Path]:
    """seed (and HOSTILE) -> its bridge's binary, all built by one cargo run in `rust_target`
    from the workspace made in `ws` (an empty folder; "ws" in the result: the hostile
    descriptor and its generated QoS files are there), "target": the target folder."""
    clang = os.environ.get("LIBCLANG_PATH") or libclang()
    if clang is None or shutil.which("cmake") is None:
        pytest.fail("cyclors builds Cyclone DDS with cmake and bindgen: Debian's cmake and libclang-14-dev "
                    "(scripts/apt-packages.txt) are needed")
    (ws / "generated").mkdir()
    (ws / "runtime").symlink_to(ROOT / "runtime")
    (ws / "generated" / "rapid").symlink_to(ROOT / "generated" / "rapid")
    (ws / "hostile.yaml").write_text(yaml.safe_dump(hostile_descriptor(), allow_unicode=True), encoding="utf-8")
    start = time.monotonic()
    for seed in (*SEEDS, HOSTILE, RIG):
        res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(descriptor(ws, seed)),
                              "--lang", "rust" if seed != HOSTILE else "rust,qos", "-o", str(ws / "generated" / seed)],
                             cwd=ROOT, capture_output=True, text=True, timeout=300)
        assert res.returncode == 0, res.stdout + res.stderr
    # Robonaut 2's committed handlers.rs predates the glue of its input stream (trait Streams,
    # HandlerSet::with_streams): built in place of the fresh stubs, it shows such a file compiles
    shutil.copy(ROOT / OLD_HANDLERS, ws / OLD_HANDLERS)
    print(f"\nrapidgen generate --lang rust, {len(SEEDS) + 2} descriptors: {time.monotonic() - start:.1f} s")
    (ws / "Cargo.toml").write_text(WORKSPACE, encoding="utf-8")
    shutil.copy(RUNTIME / "rapid_dds" / "Cargo.lock", ws / "Cargo.lock")
    env = dict(os.environ, CARGO_TARGET_DIR=str(rust_target), CARGO_TERM_COLOR="never", LIBCLANG_PATH=clang)
    start = time.monotonic()
    # offline first (nothing to fetch when the crates and their index entries are cached);
    # else online: a fresh machine downloads them
    for mode in (["--offline"], []):
        res = subprocess.run([cargo(), "build", *mode], cwd=ws, env=env, capture_output=True, text=True,
                             timeout=1800, stdin=subprocess.DEVNULL)
        if res.returncode == 0:
            break
    print(f"cargo build of the {len(SEEDS) + 2} bridges (debug, one workspace): {time.monotonic() - start:.1f} s")
    assert res.returncode == 0, res.stderr[-4000:]
    warnings = [line for line in res.stderr.splitlines() if line.startswith("warning")]
    assert not warnings, res.stderr[-4000:]  # the generated code compiles clean
    out = {seed: rust_target / "debug" / _package(ws / "generated" / seed / "rust" / "bridge")
           for seed in (*SEEDS, HOSTILE, RIG)}
    return {**out, "ws": ws, "target": rust_target}
