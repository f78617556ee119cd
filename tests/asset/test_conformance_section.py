"""The descriptor's conformance section (what `rapidgen conform` may send that moves the
asset): resolved into LoadedAsset.conformance with arguments in parameter order (a
parameter left out is sent its default); rapidgen init's commented example validates once uncommented. Its errors are
tests/asset/negative/conformance-motion.yaml."""
from __future__ import annotations

import re
from pathlib import Path

from rapidgen.asset.scaffold import starter
from rapidgen.asset.load import load_asset
from rapidgen.diagnostics import DiagnosticSink

ROOT = Path(__file__).resolve().parents[2]


def _load(path: Path):
    sink = DiagnosticSink()
    loaded = load_asset(str(path), sink)
    assert loaded is not None and not sink.has_errors, [str(d) for d in sink.diagnostics]
    return loaded


def test_the_seed_rovers_allow_one_long_drive():
    for asset in ("k10", "athlete", "chariot"):
        got = _load(ROOT / "specs/assets" / f"{asset}.yaml").conformance
        want = [("RAPID_STRING", "site"), ("RAPID_VEC3d", [500.0, 0.0, 0.0])]
        assert got == {"motion": {"Mobility/simpleMove": want}}, asset


def test_no_section_is_none():
    assert _load(ROOT / "specs/assets/xarm2.yaml").conformance is None


def test_whole_numbers_are_sent_as_the_vector_of_doubles(tmp_path):
    text = f"""\
version: 1
asset: {{name: Probe, kind: rover}}
idl: {{rapid: {ROOT / 'specs/rapid'}}}
subsystems: [{{name: Admin}}, {{name: Mobility}}]
conformance:
  motion:
    - command: Mobility/move
      args: {{xytTolerance: [-1, -1, -1], xyt: [1, 0, 0], frame: site}}
"""
    path = tmp_path / "probe.yaml"
    path.write_text(text)
    assert _load(path).conformance == {"motion": {"Mobility/move": [  # in parameter order, whatever the YAML's
        ("RAPID_STRING", "site"), ("RAPID_VEC3d", [1.0, 0.0, 0.0]), ("RAPID_VEC3d", [-1.0, -1.0, -1.0])]}}


def test_the_starter_example_validates_uncommented(tmp_path):
    text = starter("Probe", "probe.yaml")
    block = re.search(r"^# conformance:\n(#.*\n)+", text, flags=re.M)
    assert block is not None
    path = tmp_path / "probe.yaml"
    path.write_text(text.replace(block.group(0), re.sub(r"^# ?", "", block.group(0), flags=re.M)))
    assert _load(path).conformance == {"motion": {"Mobility/simpleMove": [("RAPID_STRING", "site"),
                                                                          ("RAPID_VEC3d", [0.5, 0.0, 0.0])]}}
