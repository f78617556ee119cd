"""Loader units: YAML marks, hostile YAML, spec locations, computed values."""
import pytest

from rapidgen.asset import load_asset
from rapidgen.asset.facts import fits
from rapidgen.asset.publish import union_value, value_keys
from rapidgen.yamlread import parse_yaml
from rapidgen.diagnostics import DiagnosticSink
from tests.asset.conftest import ROOT

RAPID = str(ROOT / "specs" / "rapid")


def doc_of(text: str):
    sink = DiagnosticSink()
    return parse_yaml(text, "t.yaml", sink), sink


def codes(sink):
    return [d.code for d in sink.diagnostics]


def test_every_value_and_key_keeps_its_position():
    doc, sink = doc_of("version: 1\nasset:\n  name: K10\n  tags: [a, 'b c']\n")
    assert not sink.diagnostics
    loc = doc.loc(("asset", "name"))
    assert (loc.line, loc.col, loc.end_col) == (3, 9, 12)
    assert (doc.loc(("asset", "tags", 1)).line, doc.loc(("asset", "tags", 1)).col) == (4, 13)
    assert (doc.key_loc(("asset", "tags")).line, doc.key_loc(("asset", "tags")).col) == (4, 3)
    assert doc.loc(("asset", "missing", 3)) == doc.loc(("asset",))  # nearest located ancestor


def test_keys_stay_text_and_scalars_are_typed():
    doc, _ = doc_of("on: yes\n1: 0x10\nd: 2024-01-02\nn: ~\n")
    assert doc.data == {"on": True, "1": 16, "d": "2024-01-02", "n": None}


@pytest.mark.parametrize("text,code", [
    ("a: &a [*a, *a]\nb: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a, *a]\n"
     + "".join(f"c{i}: &c{i} [{', '.join(['*' + ('b' if i == 0 else f'c{i - 1}')] * 10)}]\n" for i in range(6)),
     "RG1012"),  # alias bomb
    ("[" * 5000 + "]" * 5000, "RG1012"),  # deep nesting
    ("a: !!python/object:os.system x\n", "RG1012"),
    ("a: 1\n---\nb: 2\n", "RG1010"),
    ("a: \x07\n", "RG1010"),
    ("a: [1, 2\n", "RG1010"),
    ("? [a, b]\n: 1\n", "RG1012"),
    ("a: .nan\n", "RG1013"),
])
def test_hostile_yaml_is_a_diagnostic(text, code):
    doc, sink = doc_of(text)
    assert doc is None and code in codes(sink)
    assert all(d.loc.line >= 1 for d in sink.diagnostics)


def test_spec_locations(tmp_path):
    (tmp_path / "a.yaml").write_text(
        "version: 1\nasset: {name: A, kind: rover}\nsubsystem_types:\n"
        "  - name: T\n    commands:\n      - name: c\n        parameters:\n"
        "          - {name: p, type: RAPID_FLOAT, range: [0, 1], default: 0.5}\n"
        "subsystems: [{name: S, type: T}]\n")
    sink = DiagnosticSink()
    loaded = load_asset(str(tmp_path / "a.yaml"), sink, RAPID)
    assert not sink.diagnostics
    p = loaded.spec.subsystem_types[0].commands[0].parameters[0]
    assert (p.min, p.max, p.default) == (0, 1, 0.5)
    assert (p.at("max").line, p.at("max").col) == (8, 53)  # max points into `range: [0, 1]`
    assert p.at("nonexistent") == p.loc and p.has("range") and not p.has("unit")
    assert loaded.spec.subsystems[0].at("type").col == 30


def test_paths_are_relative_to_the_descriptor(tmp_path, monkeypatch):
    sub = tmp_path / "robots"
    (sub / "idl").mkdir(parents=True)
    (sub / "idl" / "X.idl").write_text('#include "Message.idl"\nmodule x { valuetype S : rapid::Message { public long v; }; };\n')
    (sub / "r.yaml").write_text("version: 1\nasset: {name: R, kind: rover}\nidl: {include: [idl], files: [idl/X.idl]}\n"
                                "telemetry:\n  - {kind: custom, sample: {type: x::S, topic: x_s}}\n")
    monkeypatch.chdir(tmp_path)
    sink = DiagnosticSink()
    loaded = load_asset("robots/r.yaml", sink, RAPID)
    assert not sink.diagnostics, sink.diagnostics
    assert loaded.spec.idl_files == ("robots/idl/X.idl",) and loaded.spec.include_dirs == ("robots/idl",)


def test_union_values_use_the_codec_value_form(seed):
    facts = seed("k10").facts
    assert union_value(facts, "RAPID_BOOL") == {"discriminator": "RAPID_BOOL", "value": False}
    assert union_value(facts, "RAPID_INT", 3) == {"discriminator": "RAPID_INT", "value": 3}
    assert union_value(facts, "RAPID_LONGLONG") == {"discriminator": "RAPID_LONGLONG", "value": 0}
    assert union_value(facts, "RAPID_DOUBLE", 2) == {"discriminator": "RAPID_DOUBLE", "value": 2.0}
    assert union_value(facts, "RAPID_STRING", "x") == {"discriminator": "RAPID_STRING", "value": "x"}
    assert union_value(facts, "RAPID_MAT33f") == {"discriminator": "RAPID_MAT33f", "value": [0.0] * 9}


def test_computed_configs_encode_with_the_reference_codec(seed):
    from rapidgen.cdr import Codec

    loaded = seed("robonaut2")
    codec = Codec(loaded.model)
    hdr = {"srcName": "R2", "assetName": "R2", "timeStamp": 0, "statusCode": 0, "serial": 1}
    for _topic, (type_name, value) in loaded.configs.items():
        full = dict(hdr=hdr, **value)
        decoded = codec.decode(type_name, codec.encode(type_name, full))
        assert decoded["hdr"] == hdr
        assert set(decoded) == set(full)


def test_value_keys_carry_defaults(seed):
    from rapidgen.asset.spec import AgentTelemetry
    loaded = seed("eva-suit")
    agent = next(t for t in loaded.spec.telemetry if isinstance(t, AgentTelemetry))
    keys = value_keys(loaded.facts, agent.values)
    assert keys[0] == {"key": "suitPressure", "padding": 0, "value": {"discriminator": "RAPID_FLOAT", "value": 4.3}}
    assert keys[3]["value"] == {"discriminator": "RAPID_INT", "value": 0}


def test_string_bounds_leave_room_for_the_nul():
    assert fits("x" * 31, 32) and not fits("x" * 32, 32)
    assert not fits("é" * 16, 32)  # 32 UTF-8 bytes
    assert fits("anything", None)


def test_checks_without_a_model_still_run(tmp_path):
    from rapidgen.asset.check import check_asset
    from rapidgen.asset.resolved import LoadedAsset
    sink = DiagnosticSink()
    (tmp_path / "a.yaml").write_text(
        "version: 1\nasset: {name: A, kind: rover}\nsubsystems: [{name: Admin}, {name: Admin}]\n"
        "telemetry:\n  - kind: agent\n    values: [{key: v, type: RAPID_FLOAT, min: 2, max: 1}]\n")
    loaded = load_asset(str(tmp_path / "a.yaml"), DiagnosticSink(), RAPID)
    check_asset(LoadedAsset(loaded.spec, None), sink)
    assert sorted(codes(sink)) == ["RG1101", "RG1203"]
