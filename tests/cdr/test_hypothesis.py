"""Property tests of the reference codec: random values round-trip in every encoding;
random and mutated bytes give a value or a CdrError, nothing else, without hanging or
allocating far beyond the input."""
from __future__ import annotations

import tracemalloc

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rapidgen.model import ir
from rapidgen.cdr import CdrError, Codec
from tests.cdr.conftest import KITCHEN, ROOT, _load, seed_assets
from tests.cdr.strategies import Strategies

ENCODINGS = [(1, True), (1, False), (2, True), (2, False)]
SETTINGS = settings(max_examples=25, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture,
                                           HealthCheck.data_too_large])
_CODECS: dict[str, Codec] = {}


def codec(which: str) -> Codec:
    if which not in _CODECS:
        import os
        _CODECS[which] = Codec(_load([os.path.relpath(KITCHEN, ROOT)] if which == "kitchen" else seed_assets()))
    return _CODECS[which]


def _names(which: str) -> list[str]:
    c = codec(which)
    return sorted(d.scoped_name for d in c.model.declarations if isinstance(d, (ir.Struct, ir.Union)))


TYPES = [("kitchen", n) for n in _names("kitchen")] + [("rapid", n) for n in _names("rapid")]


@pytest.mark.parametrize("which, name", TYPES)
@SETTINGS
@given(data=st.data())
def test_random_values_round_trip(which, name, data):
    c = codec(which)
    value = data.draw(Strategies(c.types).of(name), label="value")
    for version, little in ENCODINGS:
        encoded = c.encode(name, value, version=version, little=little)
        decoded = c.decode(name, encoded)
        assert decoded == value
        assert c.encode(name, decoded, version=version, little=little) == encoded  # -0.0 and all


@pytest.mark.parametrize("name", ["kt::Everything", "kt::MutAll", "kt::LD"])
@SETTINGS
@given(data=st.data())
def test_nan_and_infinities_survive_as_bytes(name, data):
    c = codec("kitchen")
    value = data.draw(Strategies(c.types, nan=True).of(name))
    for version, little in ENCODINGS:
        encoded = c.encode(name, value, version=version, little=little)
        assert c.encode(name, c.decode(name, encoded), version=version, little=little) == encoded


def _decode_any(c: Codec, name: str, data: bytes) -> None:
    try:
        value = c.decode(name, data)
    except CdrError as err:
        assert err.offset is None or 0 <= err.offset <= len(data)
        return
    # whatever decodes is a valid value: it encodes again
    for version, little in ENCODINGS:
        c.encode(name, value, version=version, little=little)


HEADERS = [bytes((0, k, 0, 0)) for k in (0, 1, 2, 3, 6, 7, 8, 9, 10, 11)]


@pytest.mark.parametrize("which, name", TYPES)
@SETTINGS
@given(header=st.sampled_from(HEADERS), body=st.binary(max_size=200))
def test_random_bytes_only_raise_cdr_error(which, name, header, body):
    _decode_any(codec(which), name, header + body)


def _mutate(data: bytes, ops: list[tuple[int, int, int]]) -> bytes:
    buf = bytearray(data)
    for kind, where, value in ops:
        if not buf:
            break
        i = where % len(buf)
        if kind == 0:
            buf[i] ^= 1 << (value % 8)
        elif kind == 1:
            buf[i] = value & 0xFF
        elif kind == 2:
            del buf[i:]
        elif kind == 3:
            buf[i:i] = bytes([value & 0xFF]) * (1 + value % 5)
        elif kind == 4:  # a huge length or count
            buf[i:i + 4] = (0xFFFFFFF0 + value % 16).to_bytes(4, "little")
        else:
            del buf[i:i + 1 + value % 4]
    return bytes(buf)


MUTATIONS = st.lists(st.tuples(st.integers(0, 5), st.integers(0, 1 << 16), st.integers(0, 255)),
                     min_size=1, max_size=4)


@pytest.mark.parametrize("which, name", TYPES)
@SETTINGS
@given(data=st.data(), ops=MUTATIONS, encoding=st.sampled_from(ENCODINGS))
def test_mutated_encodings_only_raise_cdr_error(which, name, data, ops, encoding):
    c = codec(which)
    value = data.draw(Strategies(c.types).of(name), label="value")
    encoded = c.encode(name, value, version=encoding[0], little=encoding[1])
    _decode_any(c, name, _mutate(encoded, ops))


@pytest.mark.parametrize("which, name", [("rapid", "rapid::QueueState"), ("rapid", "rapid::ImageSensorSample"),
                                         ("kitchen", "kt::Tree"), ("kitchen", "kt::Everything")])
@settings(max_examples=40, deadline=None, derandomize=True)
@given(ops=MUTATIONS, encoding=st.sampled_from(ENCODINGS))
def test_decoding_allocates_in_proportion_to_the_input(which, name, ops, encoding):
    c = codec(which)
    value = c.types.default_value(c.types.type_of(name))
    data = _mutate(c.encode(name, value, version=encoding[0], little=encoding[1]), ops)
    tracemalloc.start()
    try:
        _decode_any(c, name, data)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 256 * 1024 + 200 * len(data)
