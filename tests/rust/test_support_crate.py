"""runtime/rust/rapid_support, the fixed modules every generated Rust crate carries (docs/
architecture.md, "Fixed code"), checked as a crate of its own: clippy with -D warnings on
its default features (the codec; a few seconds, no dependency). Its `serde` and `dds`
modules are linted with every feature in each generated crate's clippy run
(test_backend.py), byte for byte the same text (tests/unit/test_support_files.py)."""
from __future__ import annotations

from tests.rust.conftest import cargo, run
from tests.runtime.live import ROOT

CRATE = ROOT / "runtime" / "rust" / "rapid_support"


def test_the_support_crate_is_clippy_clean(rust_target):
    res = run([cargo(), "clippy", "--locked", "--all-targets", "--", "-D", "warnings"], CRATE, rust_target / "support")
    assert "warning" not in res.stderr.replace("-D warnings", "")
