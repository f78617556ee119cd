"""The committed golden vectors (tests/vectors/rapid.json): coverage of the RAPID set, and
the reference codec decodes and re-encodes every one byte for byte, in both byte orders."""
from __future__ import annotations

import pytest

from rapidgen.model import ir
from rapidgen.vectors import ENCODINGS, FORMAT

# every RAPID message (rapid-protocol.md section 4) and the seed extension messages
MESSAGES = ["Command", "Ack", "CommandConfig", "AgentConfig", "AgentState", "PositionConfig", "PositionSample",
            "JointConfig", "JointSample", "ImageSensorSample", "ImageSensorState", "TextMessage",
            "AccessControlState", "FileAnnounce", "QueueState"]


def test_format_and_size(committed):
    assert committed["format"] == FORMAT
    assert committed["count"] == len(committed["vectors"]) >= 200
    ids = [v["id"] for v in committed["vectors"]]
    assert len(set(ids)) == len(ids)
    types = [v["type"] for v in committed["vectors"]]
    assert types == sorted(types)


def test_every_struct_union_and_message_is_covered(committed, rapid_model):
    have = {v["type"] for v in committed["vectors"]}
    wanted = {d.scoped_name for d in rapid_model.declarations if isinstance(d, (ir.Struct, ir.Union))}
    assert wanted == have
    for name in MESSAGES:
        assert f"rapid::{name}" in have
    for d in rapid_model.declarations:  # every message type (a struct derived from Message)
        if isinstance(d, ir.Struct) and d.base == "rapid::Message":
            variants = {v["variant"] for v in committed["vectors"] if v["type"] == d.scoped_name}
            assert {"min", "max", "low", "mixed"} <= variants


def test_every_parameter_union_branch_appears(committed):
    branches = {"RAPID_BOOL", "RAPID_DOUBLE", "RAPID_FLOAT", "RAPID_INT", "RAPID_LONGLONG", "RAPID_STRING",
                "RAPID_VEC3d", "RAPID_MAT33f"}
    for message in ("rapid::Command", "rapid::AgentState", "rapid::PositionSample"):
        seen = set()
        for v in committed["vectors"]:
            if v["type"] == message:
                for key in ("arguments", "values"):
                    seen |= {a["discriminator"] for a in v["value"].get(key, [])}
        assert seen == branches, message
    union = {v["variant"] for v in committed["vectors"] if v["type"] == "rapid::ParameterUnion"}
    assert {f"branch-{b}" for b in branches} <= union


def test_extremes_and_text(committed):
    text = " ".join(str(v["value"]) for v in committed["vectors"])
    for needle in ("9223372036854775807", "-9223372036854775808", "2147483647",
                   "-2147483648", "1.7976931348623157e+308", "5e-324", "-0.0", "3.4028234663852886e+38",
                   "ü", "火星", "🚀"):
        assert needle in text
    # strings at their bound, in bytes (String2K in TextMessage/max)
    msg = next(v for v in committed["vectors"] if v["id"] == "rapid::TextMessage/max")
    assert len(msg["value"]["message"].encode("utf-8")) == 2048
    assert len(msg["value"]["category"].encode("utf-8")) == 64
    # small-bounded sequences at their bound
    cmd = next(v for v in committed["vectors"] if v["id"] == "rapid::Command/max")
    assert len(cmd["value"]["arguments"]) == 16
    assert next(v for v in committed["vectors"] if v["id"] == "rapid::Command/min")["value"]["arguments"] == []


@pytest.mark.parametrize("key", list(ENCODINGS))
def test_decode_and_reencode_every_vector(committed, rapid_codec, key):
    version, little, _ = ENCODINGS[key]
    for v in committed["vectors"]:
        data = bytes.fromhex(v[key])
        assert rapid_codec.decode(v["type"], data) == v["value"], v["id"]
        assert rapid_codec.encode(v["type"], v["value"], version=version, little=little) == data, v["id"]


def test_every_vector_round_trips_in_xcdr2_big_endian(committed, rapid_codec):
    for v in committed["vectors"]:
        data = rapid_codec.encode(v["type"], v["value"], version=2, little=False)
        assert data[:2] == b"\x00\x06"
        assert rapid_codec.decode(v["type"], data) == v["value"], v["id"]
        # same content as little-endian, byte-swapped field by field: same length
        assert len(data) == len(bytes.fromhex(v["xcdr2_le"]))


def test_headers_match_the_encoding(committed):
    for v in committed["vectors"]:  # RAPID types are all @final
        assert v["xcdr1_le"][:8] == "00010000"
        assert v["xcdr1_be"][:8] == "00000000"
        assert v["xcdr2_le"][:8] == "00070000"
