"""Every item of rapid-protocol.md section 1 (the original RTI dialect), on inputs written
for these tests (tests/golden/ir/rapid_dialect/input), checked fact by fact."""
import json
from pathlib import Path

import pytest

from tests.helpers import rapidgen

CASE = Path(__file__).parents[1] / "golden" / "ir" / "rapid_dialect"


@pytest.fixture(scope="module")
def model():
    import os
    cwd = os.getcwd()
    os.chdir(CASE)
    try:
        res = rapidgen("ir", *(CASE / "args").read_text().split())
    finally:
        os.chdir(cwd)
    assert res.code == 0, res.err
    assert res.err == "", "the RAPID dialect must parse without warnings"
    return {d["name"]: d for d in json.loads(res.out)["declarations"]}


def members(d):
    return [(m["name"], m["type"]) for m in d["members"]]


def test_valuetype_with_base_is_a_struct_with_base_first_layout(model):
    ack = model["rapid::Ack"]
    assert ack["kind"] == "struct" and ack["origin"] == "valuetype" and ack["base"] == "rapid::Message"
    assert members(model["rapid::Message"]) == [("hdr", "rapid::Header")]
    assert members(ack) == [("cmdId", "rapid::String64"), ("status", "rapid::AckStatus"),
                            ("message", "rapid::String128")]


def test_trailing_key_comments_and_inherited_keys(model):
    assert model["rapid::Header"]["keys"] == ["srcName", "assetName"]
    assert model["rapid::Message"]["keys"] == ["hdr.srcName", "hdr.assetName"]
    assert model["rapid::Ack"]["keys"] == ["hdr.srcName", "hdr.assetName", "cmdId"]
    assert model["rapid::ext::arc::Marker"]["keys"] == ["hdr.srcName", "hdr.assetName", "shape"]


def test_baseless_valuetype_with_private_member(model):
    rec = model["rapid::CommandRecord"]
    assert rec["base"] is None and rec["origin"] == "valuetype"
    assert members(rec) == [("cmdId", "rapid::String64"), ("result", "long")]


def test_typedefs_of_strings_arrays_and_sequences(model):
    assert model["rapid::String32"]["type"] == "string<32>"
    assert model["rapid::Vec3d"]["type"] == "double[3]"
    assert model["rapid::Mat33f"]["type"] == "float[9]"
    assert model["rapid::FloatSequence64"]["type"] == "sequence<float, 64>"
    assert model["rapid::String32Sequence16"]["type"] == "sequence<rapid::String32, 16>"
    assert model["rapid::KeyTypeSequence16"]["type"] == "sequence<rapid::KeyTypePair, 16>"
    assert model["rapid::ParameterSequence16"]["type"] == "sequence<rapid::ParameterUnion, 16>"


def test_member_forms(model):
    assert members(model["rapid::Queue"]) == [
        ("records", "sequence<rapid::CommandRecord, 8>"),  # anonymous sequence member
        ("xyz", "short[3]"),  # array declarator
        ("weights", "sequence<float, 16>"),  # bound from a named constant
        ("values", "rapid::FloatSequence64"), ("keys", "rapid::KeyTypeSequence16"),
        ("names", "rapid::String32Sequence16"), ("args", "rapid::ParameterSequence16")]


def test_enums_plain_and_rti_explicit_values(model):
    assert [e["value"] for e in model["rapid::DataType"]["enumerators"]] == list(range(8))
    assert [(e["name"], e["value"]) for e in model["rapid::ext::arc::ShapeType"]["enumerators"]] == [
        ("ARROW", 0), ("CUBE", 1), ("SPHERE", 2), ("TEXT", 10)]


def test_union_on_enum_without_default(model):
    u = model["rapid::ParameterUnion"]
    assert u["discriminator"] == "rapid::DataType"
    assert [(c["labels"][0]["name"], c["name"], c["type"], c["default"]) for c in u["cases"]] == [
        ("RAPID_BOOL", "b", "boolean", False), ("RAPID_DOUBLE", "d", "double", False),
        ("RAPID_FLOAT", "f", "float", False), ("RAPID_INT", "i", "long", False),
        ("RAPID_LONGLONG", "ll", "long long", False), ("RAPID_STRING", "s", "rapid::String128", False),
        ("RAPID_VEC3d", "vec3d", "rapid::Vec3d", False), ("RAPID_MAT33f", "mat33f", "rapid::Mat33f", False)]


def test_constants_of_typedef_string_enum_and_hex(model):
    assert model["rapid::ACK_TOPIC"]["type"] == "rapid::String64"
    assert model["rapid::ACK_TOPIC"]["value"] == "rapid_ack"
    assert model["rapid::FIRST_STATUS"]["value"]["name"] == "ACK_QUEUED"
    assert model["rapid::JOINT_OVER_CURRENT"]["value"] == 0x0300


def test_nested_modules_and_scoped_names(model):
    assert members(model["rapid::ext::arc::Marker"]) == [
        ("shape", "rapid::ext::arc::ShapeType"), ("pose", "rapid::Transform3D"), ("scale", "rapid::Vec3d")]


def test_modern_dialect_annotations_and_keylist(model):
    assert model["rapid::ext::Battery"]["keys"] == ["name"]
    assert model["rapid::ext::Battery"]["extensibility"] == "final"
    assert model["rapid::ext::Gps"]["extensibility"] == "appendable"
    assert model["rapid::ext::Tuning"]["extensibility"] == "mutable"
    battery = {m["name"]: m for m in model["rapid::ext::Battery"]["members"]}
    assert battery["chargePercent"]["id"] == 2 and battery["temperature"]["optional"]
    assert model["rapid::ext::Legacy"]["keys"] == ["id"]


def test_files_included_twice_by_different_paths_are_read_once(monkeypatch):
    # Ack.idl includes BaseTypes.idl as "common/BaseTypes.idl" and, through Message.idl, via -I.
    from rapidgen.diagnostics import DiagnosticSink
    from rapidgen.idl.preprocess import preprocess

    monkeypatch.chdir(CASE)
    args = (CASE / "args").read_text().split()
    sink = DiagnosticSink()
    pre = preprocess([a for a in args if a.endswith(".idl")], ["input/common"], sink)
    assert not sink.diagnostics
    assert [f for f in pre.files if f.endswith("BaseTypes.idl")] == ["input/common/BaseTypes.idl"]
    assert pre.text.count("struct Header") == 1
