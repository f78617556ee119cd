"""The committed bindings of the full RAPID set (generated/rapid/python), imported from the
tree without installing: every type present under its DDS name, every message filled with
non-default data and round-tripped through cyclonedds, final XCDR1 with the base members
first, keys as the protocol says, constants as in the IDL. No DDS traffic here.
"""
from __future__ import annotations

import dataclasses
import importlib
import sys

import pytest

from rapidgen.model import ir
from tests.python_backend.fill import GENERATED_RAPID, Filler, differences, message_types, plain, rapid_model


@pytest.fixture(scope="module")
def rapid():
    sys.path.insert(0, GENERATED_RAPID)
    sys.dont_write_bytecode, saved = True, sys.dont_write_bytecode  # no __pycache__ in generated/
    try:
        module = importlib.import_module("rapid_types.rapid")
        yield module
    finally:
        sys.path.remove(GENERATED_RAPID)
        sys.dont_write_bytecode = saved


@pytest.fixture(scope="module")
def model() -> ir.Model:
    return rapid_model()


def test_every_declaration_is_generated_under_its_dds_name(rapid, model):
    import cyclonedds.idl as idl

    counts = {"struct": 0, "union": 0, "enum": 0, "typedef": 0, "const": 0}
    for d in model.declarations:
        obj = getattr(rapid, d.name)
        counts[d.kind] += 1
        if d.kind in ("struct", "union", "enum"):
            assert obj.__idl_typename__ == d.scoped_name.replace("::", ".")
        if d.kind in ("struct", "union"):
            assert obj.__idl__.idl_transformed_typename == d.scoped_name  # what DDS registers
            assert issubclass(obj, idl.IdlStruct if d.kind == "struct" else idl.IdlUnion)
        if d.kind == "typedef":  # typing.Annotated[T, types.typedef(name, T)]
            assert obj.__metadata__[0].name == d.scoped_name.replace("::", ".")
    assert counts == {"struct": 33, "union": 1, "enum": 8, "typedef": 74, "const": 72}


def test_messages_are_flattened_with_the_protocol_keys(rapid, model):
    expected_keys = {"Ack": ["hdr", "cmdId"], "FileAnnounce": ["hdr", "fileUuid"]}
    messages = message_types(model)
    assert len(messages) == 15
    for s in messages:
        cls = getattr(rapid, s.name)
        names = [f.name for f in dataclasses.fields(cls)]
        assert names == [m.name for m in model.all_members(s)] and names[0] == "hdr"
        assert cls.__bases__[0].__name__ == "IdlStruct"  # no Python inheritance from Message
        keyed = [n for n, a in cls.__idl_field_annotations__.items() if a.get("key")]
        assert keyed == expected_keys.get(s.name, ["hdr"]), s.name
        assert cls.__idl_annotations__.get("extensibility") == "final"


@pytest.mark.parametrize("index", range(15))
def test_message_round_trip_with_filled_values(rapid, model, index):
    from cyclonedds.idl._support import Endianness

    s = message_types(model)[index]
    filler = Filler(model)
    value = filler.message(s)
    cls = type(value)
    data = value.serialize()
    assert data[:2] == b"\x00\x01", "final types go out as XCDR1 little-endian"
    assert not differences(plain(value), plain(cls.deserialize(data)))
    big = value.serialize(endianness=Endianness.Big)
    assert big[:2] == b"\x00\x00"
    assert not differences(plain(value), plain(cls.deserialize(big)))
    # base members first: the message starts with exactly the bytes of its header
    header = value.hdr.serialize()[4:]
    assert data[4:4 + len(header)] == header


def test_instance_keys(rapid):
    def hdr(src="gds", asset="K10Red", ts=1):
        return rapid.Header(srcName=src, assetName=asset, timeStamp=ts, statusCode=0, serial=7)

    a = rapid.Command(hdr=hdr(), cmdId="1", cmdName="noOp")
    b = rapid.Command(hdr=hdr(ts=99), cmdId="2", cmdName="echo")
    c = rapid.Command(hdr=hdr(asset="Chariot"), cmdId="1", cmdName="noOp")
    assert a.serialize_key() == b.serialize_key() != c.serialize_key()
    ack1 = rapid.Ack(hdr=hdr(), cmdId="1", message="x")
    ack2 = rapid.Ack(hdr=hdr(ts=5), cmdId="1", message="y")
    ack3 = rapid.Ack(hdr=hdr(), cmdId="2")
    assert ack1.serialize_key() == ack2.serialize_key() != ack3.serialize_key()


def test_every_parameter_union_branch(rapid):
    values = {"b": (True, "RAPID_BOOL"), "d": (-2.5, "RAPID_DOUBLE"), "f": (0.5, "RAPID_FLOAT"),
              "i": (-7, "RAPID_INT"), "ll": (2**40, "RAPID_LONGLONG"), "s": ("text \u00e9", "RAPID_STRING"),
              "vec3d": ([1.0, 2.0, 3.0], "RAPID_VEC3d"), "mat33f": ([float(i) for i in range(9)], "RAPID_MAT33f")}
    for name, (v, label) in values.items():
        u = rapid.ParameterUnion(**{name: v})
        assert u.discriminator is rapid.DataType[label]
        back = rapid.ParameterUnion.deserialize(u.serialize())
        assert back == u and back.value == v


def test_defaults_and_constants(rapid):
    cmd = rapid.Command()
    assert cmd.hdr == rapid.Header() and cmd.arguments == [] and cmd.cmdAction == rapid.QueueAction.QUEUE_BYPASS
    assert rapid.Transform3D().rot == [0.0] * 9
    assert rapid.KeyTypeValueTriple().value == rapid.ParameterUnion(b=False)
    assert rapid.COMMAND_TOPIC == "rapid_command" and rapid.JOINT_OVER_CURRENT == 0x0300
    assert rapid.MIME_IMAGE_JPEG == "image/jpeg" and rapid.QUEUE_STATE_MAX_RECORDS == 64
    dtypes = [getattr(rapid, n) for n in dir(rapid) if "_DTYPE_" in n]
    assert dtypes and all(isinstance(d, rapid.DataType) for d in dtypes)


def test_bounds_are_enforced(rapid):
    with pytest.raises(Exception):
        rapid.Header(srcName="x" * 40).serialize()  # String32
    with pytest.raises(Exception):
        rapid.AgentState(values=[rapid.ParameterUnion(i=1)] * 65).serialize()  # ValueSequence64


def _reference_form(value):
    """A generated value in the reference codec's value form (enums by enumerator name)."""
    import enum

    from cyclonedds.idl import IdlUnion

    if isinstance(value, IdlUnion):
        d, v = value.get()
        return {"discriminator": _reference_form(d), "value": _reference_form(v)}
    if dataclasses.is_dataclass(value):
        return {f.name: _reference_form(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, enum.Enum):
        return value.name
    if isinstance(value, (list, tuple)):
        return [_reference_form(v) for v in value]
    return value


@pytest.mark.parametrize("index", range(15))
def test_bytes_equal_the_reference_encoder(rapid, model, index):
    """cyclonedds with the generated class and rapidgen's model-only encoder agree byte for
    byte: final XCDR1, base members first, both byte orders."""
    from cyclonedds.idl._support import Endianness

    from rapidgen.cdr import Codec

    s = message_types(model)[index]
    value = Filler(model).message(s)
    codec = Codec(model)
    form = _reference_form(value)
    assert value.serialize() == codec.encode(s.scoped_name, form)
    assert value.serialize(endianness=Endianness.Big) == codec.encode(s.scoped_name, form, little=False)
