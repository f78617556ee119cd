"""An Ack's wire bytes made directly: the bridge writes two or more acks per command, and
cyclonedds-python's generic serializer took ~13 us of the ~20 us each write cost (about a
tenth of a command's path through the bridge; bench/README.md).

    wire = AckWire(rapid, writer)         # None from encode(): write the sample as before
    data = wire.encode(src, asset, serial, stamp_us, cmd_id, status, completed, message)

The bytes are what `writer.write(rapid.Ack(...))` sends: the writer's own encapsulation
header (taken from one sample it serialized), then rapid::Ack (@final: Header{srcName,
assetName, timeStamp, statusCode, serial}, cmdId, status, completedStatus, message) in
little-endian CDR, int64 aligned to 8 in XCDR1 and 4 in XCDR2, padded to 4 as DataWriter.write
pads. The type is checked member by member when made; any other shape, a string past its
bound, a value out of range or text that does not encode gives None, and the caller goes the
generic way (with its errors). tests/runtime/test_ack_wire.py holds the bytes equal.
"""
from __future__ import annotations

import struct

from rapid_runtime import messages as M

_HEADER = [("srcName", "string"), ("assetName", "string"), ("timeStamp", "int"), ("statusCode", "int"),
           ("serial", "int")]
_ACK = [("hdr", "struct"), ("cmdId", "string"), ("status", "enum"), ("completedStatus", "enum"), ("message", "string")]
_I32 = struct.Struct("<i")
_I64 = struct.Struct("<q")


def _layout(cls, want) -> list | None:
    members = M.members(cls)
    shapes = [(name, M.shape(t)) for name, t in members.items()]
    if [(n, s.kind) for n, s in shapes] != want:
        return None
    return shapes


class AckWire:
    def __init__(self, rapid, writer) -> None:
        self.ok = False
        try:
            ack, hdr = _layout(rapid.Ack, _ACK), _layout(rapid.Header, _HEADER)
            annotations = getattr(rapid.Ack, "__idl_annotations__", {}) or {}
            if ack is None or hdr is None or annotations.get("extensibility") != "final":
                return
            if [s.bound for _, s in hdr[2:]] != [64, 32, 32]:
                return
            self.bounds = (hdr[0][1].bound, hdr[1][1].bound, ack[1][1].bound, ack[4][1].bound)
            self.status = {e.name: e.value for e in rapid.AckStatus}
            self.completed = {e.name: e.value for e in rapid.AckCompletedStatus}
            self.v2 = bool(getattr(writer, "_use_version_2", False))
            probe = rapid.Ack(hdr=rapid.Header(srcName="", assetName="", timeStamp=0, statusCode=0, serial=0),
                              cmdId="", status=rapid.AckStatus(0), completedStatus=rapid.AckCompletedStatus(0),
                              message="")
            self.encapsulation = probe.serialize(use_version_2=self.v2)[:4]
            self.ok = True
        except Exception:  # another generator's classes, another cyclonedds: the generic way
            self.ok = False

    def encode(self, src: str, asset: str, serial: int, stamp_us: int, cmd_id: str, status: str, completed: str,
               message: str, status_code: int = 0) -> bytes | None:
        if not self.ok:
            return None
        try:
            texts = [s.encode("utf-8") for s in (src, asset, cmd_id, message)]
            for text, raw, bound in zip((src, asset, cmd_id, message), texts, self.bounds):
                if bound is not None and (len(raw) > bound or len(text) > bound) or b"\0" in raw:
                    return None
            out = bytearray(self.encapsulation)
            _string(out, texts[0])
            _string(out, texts[1])
            _align(out, 4 if self.v2 else 8)
            out += _I64.pack(stamp_us)
            out += _I32.pack(status_code)
            out += _I32.pack(serial)
            _string(out, texts[2])
            _align(out, 4)
            out += _I32.pack(self.status[status])
            out += _I32.pack(self.completed[completed])
            _string(out, texts[3])
            out += b"\0" * (-len(out) % 4)
            return bytes(out)
        except (KeyError, struct.error, UnicodeError, TypeError):
            return None


def _align(out: bytearray, n: int) -> None:
    out += b"\0" * (-(len(out) - 4) % n)  # offsets count from the end of the encapsulation header


def _string(out: bytearray, raw: bytes) -> None:
    _align(out, 4)
    out += _I32.pack(len(raw) + 1)
    out += raw
    out += b"\0"
