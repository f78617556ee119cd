"""RAPIDGEN_WITHOUT (rapidgen.speed_devices): each speed device can be switched off alone,
the switch reaches the device, and the output is the same without it (bench/codegen.py
--devices times what each one saves)."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from rapidgen import fork_ahead, speed_devices
from rapidgen.backends import templating
from rapidgen.idl import grammar

REPO = Path(__file__).resolve().parents[2]


def _tree(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def _generate(out: Path, without: str) -> dict[str, bytes]:
    """The generated tree; each run has a home of its own (OUT-home: the code cache's folder)."""
    env = {"PATH": "/usr/bin:/bin", "RAPIDGEN_WITHOUT": without, "HOME": str(out.with_name(out.name + "-home"))}
    res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", "specs/assets/k10.yaml", "-o", str(out),
                          "--lang", "python,cpp,rust,qos"], cwd=REPO, env=env, capture_output=True, text=True,
                         timeout=120)
    assert res.returncode == 0, res.stderr
    return _tree(out)


def test_the_output_is_the_same_without_each_device(tmp_path):
    every = _generate(tmp_path / "every", "")
    assert len(every) > 50
    for device in speed_devices.DEVICES:
        assert _generate(tmp_path / device, device) == every, device
        # the code cache is written by every run but the one without it
        cache = list((tmp_path / f"{device}-home" / ".cache" / "rapidgen").glob("dataclass-code.*"))
        assert bool(cache) == (device != "codecache"), (device, cache)


def test_the_switch_reaches_each_device(monkeypatch):
    monkeypatch.setenv("RAPIDGEN_JOBS", "")
    source = (REPO / "templates" / "rust" / "Cargo.toml.j2").read_text(encoding="utf-8")
    monkeypatch.setenv("RAPIDGEN_WITHOUT", "")
    assert templating.precompiled_code("rust", "Cargo.toml.j2", source) is not None
    packaged_tables = grammar.tables()
    monkeypatch.setenv("RAPIDGEN_WITHOUT", "precompiled-templates, lalr-tables,two-processes")
    assert templating.precompiled_code("rust", "Cargo.toml.j2", source) is None
    built = grammar.tables()
    assert built is not packaged_tables and built == packaged_tables  # built by lark, the same tables
    assert fork_ahead.jobs() == 1


def test_an_unknown_device_is_a_programming_error():
    with pytest.raises(AssertionError):
        speed_devices.without("turbo")
