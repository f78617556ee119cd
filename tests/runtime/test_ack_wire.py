"""rapid_runtime/ack_wire.py: the bridge's hand-made Ack bytes equal what cyclonedds-python's
DataWriter.write sends for the same Ack (serialize, padded to 4), in XCDR1 and XCDR2, for
names, ids and messages of every length mod 8 and non-ASCII text; what it cannot encode
exactly (a string past its bound, an embedded NUL, a lone surrogate, an int out of range)
gives None, so the bridge writes the sample the generic way."""
from __future__ import annotations

import importlib
import random
import sys
from types import SimpleNamespace

import pytest

from rapid_runtime.ack_wire import AckWire
from tests.runtime.live import python_dir

STATUS = ["ACK_QUEUED", "ACK_EXECUTING", "ACK_REQUEUED", "ACK_COMPLETED"]
DONE = ["ACK_COMPLETED_NOT", "ACK_COMPLETED_OK", "ACK_COMPLETED_BAD_SYNTAX", "ACK_COMPLETED_EXEC_FAILED",
        "ACK_COMPLETED_CANCELED"]


@pytest.fixture(scope="module")
def rapid():
    sys.path.insert(0, str(python_dir("k10")))
    try:
        return importlib.import_module("rapid_k10red.rapid")
    finally:
        sys.path.remove(str(python_dir("k10")))


def generic(rapid, v2: bool, src, asset, serial, stamp, cmd_id, status, done, message, code=0) -> bytes:
    ack = rapid.Ack(hdr=rapid.Header(srcName=src, assetName=asset, timeStamp=stamp, statusCode=code, serial=serial),
                    cmdId=cmd_id, status=rapid.AckStatus[status], completedStatus=rapid.AckCompletedStatus[done],
                    message=message)
    data = ack.serialize(use_version_2=v2)
    return data.ljust((len(data) + 3) & ~3, b"\0")  # as DataWriter.write pads


@pytest.mark.parametrize("v2", [False, True])
def test_the_bytes_are_the_generic_serializers(rapid, v2):
    wire = AckWire(rapid, SimpleNamespace(_use_version_2=v2))
    assert wire.ok
    rnd = random.Random(40)
    alphabet = "abcXYZ-_09 éü✓"
    for n in range(600):
        src = "".join(rnd.choice(alphabet) for _ in range(n % 9 + rnd.randrange(3)))
        asset = "".join(rnd.choice(alphabet) for _ in range(rnd.randrange(10)))
        cmd_id = "".join(rnd.choice(alphabet) for _ in range(rnd.randrange(40)))
        message = "".join(rnd.choice(alphabet) for _ in range(rnd.randrange(60)))
        serial, stamp, code = rnd.randrange(-2**31, 2**31), rnd.randrange(0, 2**62), rnd.randrange(-5, 5)
        status, done = rnd.choice(STATUS), rnd.choice(DONE)
        got = wire.encode(src, asset, serial, stamp, cmd_id, status, done, message, code)
        assert got == generic(rapid, v2, src, asset, serial, stamp, cmd_id, status, done, message, code), n


def test_what_it_cannot_encode_exactly_goes_the_generic_way(rapid):
    wire = AckWire(rapid, SimpleNamespace(_use_version_2=False))
    ok = dict(src="RapidWorkbench", asset="K10Red", serial=1, stamp_us=5, cmd_id="c1", status="ACK_COMPLETED",
              completed="ACK_COMPLETED_OK", message="")
    assert wire.encode(**ok) is not None
    for bad in (dict(cmd_id="x" * 65), dict(src="s" * 33), dict(message="é" * 70), dict(message="a\0b"),
                dict(message="\ud800"), dict(serial=2**31), dict(stamp_us=2**63), dict(status="ACK_NONE")):
        assert wire.encode(**{**ok, **bad}) is None, bad


def test_another_shape_of_ack_is_not_encoded_by_hand(rapid):
    other = SimpleNamespace(Ack=rapid.Header, Header=rapid.Header, AckStatus=rapid.AckStatus,
                            AckCompletedStatus=rapid.AckCompletedStatus)
    wire = AckWire(other, SimpleNamespace(_use_version_2=False))
    assert not wire.ok and wire.encode("a", "b", 1, 2, "c", "ACK_COMPLETED", "ACK_COMPLETED_OK", "") is None
