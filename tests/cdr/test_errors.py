"""Refusals: values the encoder cannot write and bytes the decoder does not accept, each
a CdrError with a message, an offset and where in the value it happened."""
from __future__ import annotations

import pytest

from rapidgen.cdr import CdrError


def h(text: str) -> bytes:
    return bytes.fromhex(text.replace(" ", ""))


@pytest.mark.parametrize("type_name, value, message", [
    ("kt::Str", {"s": "123456789"}, "string of 9 bytes exceeds its bound 8"),
    ("kt::Str", {"s": "ééééé"}, "string of 10 bytes exceeds its bound 8"),
    ("kt::Str", {"s": "a\0b"}, "NUL"),
    ("kt::Str", {"s": 5}, "expected a string"),
    ("kt::Str", {}, "member 's' is missing"),
    ("kt::Str", {"s": "", "t": 1}, "'t' is not a member"),
    ("kt::OctLL", {"a": 256, "b": 0}, "256 is out of range for octet"),
    ("kt::OctLL", {"a": 1, "b": 2 ** 63}, "out of range for int64"),
    ("kt::OctLL", {"a": True, "b": 0}, "expected an integer"),
    ("kt::SeqShort", {"v": [1, "x"]}, "expected an integer"),
    ("kt::SeqShort", {"v": b"\x01\x02"}, "bytes are only accepted for sequences of octet"),
    ("kt::Arr", {"a": [[1, 2, 3]]}, "needs 2 elements"),
    ("kt::Arr", {"a": [[1, 2, 3], [4, 5]]}, "needs 3 elements"),
    ("kt::U", {"discriminator": 1}, "value missing"),
    ("kt::U", {"value": 1}, "expected"),
    ("kt::NoDefault", {"discriminator": 0, "value": 5}, "selects no member"),
    ("kt::Colors", {"c": ["PURPLE"]}, "'PURPLE' is not an enumerator"),
    ("kt::Flags", 1 << 5, "sets bits that kt::Flags does not define"),
    ("kt::Bits", {"a": 8}, "does not fit in the 3-bit field"),
    ("kt::LD", {"a": 0, "x": "1"}, "expected a number"),
    ("kt::Opt", {"a": 1.0}, "expected an integer"),
    ("kt::Everything", None, "expected an object"),
])
def test_encoder_refuses(kt, type_name, value, message):
    with pytest.raises(CdrError) as info:
        kt.encode(type_name, value)
    assert message in str(info.value)


def test_encoder_error_names_the_place(rapid_codec):
    value = rapid_codec.types.default_value(rapid_codec.types.type_of("rapid::Command"))
    value["arguments"] = [{"discriminator": "RAPID_INT", "value": 1}, {"discriminator": "RAPID_FLOAT", "value": 1e39}]
    with pytest.raises(CdrError) as info:
        rapid_codec.encode("rapid::Command", value)
    assert info.value.path == "arguments[1].f"
    assert "out of range for float32" in info.value.message
    value["arguments"] = [{"discriminator": "RAPID_BOOL", "value": True}] * 17
    with pytest.raises(CdrError, match="17 elements exceeds its bound 16"):
        rapid_codec.encode("rapid::Command", value)


@pytest.mark.parametrize("type_name, data, message", [
    ("kt::Str", "", "cannot hold the 4-byte encapsulation header"),
    ("kt::Str", "0001", "cannot hold"),
    ("kt::Str", "0005 0000 00000000", "unknown encapsulation identifier 0x0005"),
    ("kt::Str", "0009 0000 01000000 00", "D_CDR2_LE does not suit a @final type"),
    ("kt::App", "0007 0000 0500 0000 01000000 00", "CDR2_LE does not suit a @appendable type"),
    ("kt::Str", "0001 0000 030000", "truncated"),
    ("kt::Str", "0001 0000 00000000", "string length 0"),
    ("kt::Str", "0001 0000 03000000 616263", "not NUL-terminated"),
    ("kt::Str", "0001 0000 03000000 610000", "NUL byte before its end"),
    ("kt::Str", "0001 0000 03000000 ff6100", "not valid UTF-8"),
    ("kt::Str", "0001 0000 0a000000 414141414141414141 00", "9 bytes exceeds its bound 8"),
    ("kt::Str", "0001 0000 ffffffff 00", "exceeds its bound"),
    ("kt::Everything", "0001 0000 01 61", "truncated"),
    ("kt::SeqShort", "0001 0000 ffffff7f 0100", "needs at least"),
    ("kt::SeqStruct", "0007 0000 08000000 ffffffff 00000000", "needs at least"),
    ("kt::SeqStruct", "0007 0000 ff000000 00000000", "DHEADER length 255 exceeds"),
    ("kt::SeqStruct", "0007 0000 08000000 00000000 00000000", "4 bytes left inside a DHEADER"),
    ("kt::Colors", "0001 0000 01000000 07000000", "7 is not a value of enum kt::Color"),
    ("kt::ByBool", "0001 0000 02", "boolean byte is 2"),
    ("kt::Opt", "0007 0000 01 02", "optional flag is 2"),
    ("kt::Flags", "0007 0000 2000", "sets bits that kt::Flags does not define"),
    ("kt::Str", "0001 0000 01000000 00 00000000", "4 bytes left after the end of the value"),
    ("kt::Mut", "000b 0000 08000000 090000a0 01000000", "unknown must-understand member id 9"),
    ("kt::Mut", "000b 0000 08000000 01000010 01000000", "key member 'id' of kt::Mut is missing"),
    ("kt::Mut", "000b 0000 10000000 000000a0 07000000 000000a0 07000000", "member id 0 appears twice"),
    ("kt::Mut", "000b 0000 08000000 00000040 ffffff00", "member length 16777215 exceeds"),
    ("kt::Mut", "0003 0000 017f0800 00000040 04000000 07000000", "truncated"),
    ("kt::Mut", "0003 0000 017f0400 00000040", "PID_EXTENDED with length 4"),
    ("kt::Mut", "0003 0000 017f0800 00000040 40000000 07000000 027f0000", "parameter length 64 exceeds"),
    ("kt::Tree", "0001 0000" + " 01000000 00 000000 01000000" * 150 + " 01000000 00 000000 00000000",
     "nests deeper than 100"),
])
def test_decoder_refuses(kt, type_name, data, message):
    with pytest.raises(CdrError) as info:
        kt.decode(type_name, h(data))
    assert message in str(info.value)
    assert info.value.offset is not None


def test_decoder_error_offset_and_path(rapid_codec):
    value = rapid_codec.types.default_value(rapid_codec.types.type_of("rapid::Ack"))
    data = bytearray(rapid_codec.encode("rapid::Ack", value))
    other = rapid_codec.encode("rapid::Ack", {**value, "status": "ACK_EXECUTING"})
    at = next(i for i in range(len(data)) if data[i] != other[i])  # where status is
    data[at] = 9  # AckStatus has no value 9
    with pytest.raises(CdrError) as info:
        rapid_codec.decode("rapid::Ack", bytes(data))
    assert info.value.path == "status"
    assert str(info.value) == f"9 is not a value of enum rapid::AckStatus at offset {at} (in status)"


def test_huge_counts_are_refused_before_allocating(kt, rapid_codec):
    # a 4-billion-element octet sequence announced in 12 bytes: refused at once, nothing allocated
    value = rapid_codec.types.default_value(rapid_codec.types.type_of("rapid::ImageSensorSample"))
    data = bytearray(rapid_codec.encode("rapid::ImageSensorSample", value))
    data[-4:] = b"\xff\xff\xff\x7f"
    with pytest.raises(CdrError, match="exceeds its bound 1048576"):
        rapid_codec.decode("rapid::ImageSensorSample", bytes(data))
    with pytest.raises(CdrError, match="needs at least"):
        kt.decode("kt::Tree", h("0001 0000 01000000 00 000000 ffffffff"))


def test_decode_without_header_needs_the_encoding(kt):
    with pytest.raises(CdrError, match="give version"):
        kt.decode("kt::Str", h("01000000 00"), header=False)
    assert kt.decode("kt::Str", h("00000001 00"), header=False, version=2, little=False) == {"s": ""}


def test_unknown_type(kt):
    with pytest.raises(CdrError, match="unknown type 'kt::Nope'"):
        kt.encode("kt::Nope", {})
