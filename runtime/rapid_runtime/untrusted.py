"""Data from the wire is untrusted: any participant in the asset's partition can write any
RAPID topic, with any bytes. Two rules hold for everything the runtime reads:

- a sample that does not decode (invalid UTF-8, a sequence past its bound, truncated CDR)
  is dropped on its own, counted against the writer that sent it and logged once per
  writer; the samples around it are still delivered (cyclonedds' DataReader.take decodes a
  whole batch and raises on the first bad one, losing the rest, so this takes raw bytes);
- wire text reaches a log only through visible(): no ESC, BEL or C1 byte gets to a terminal.

rapidgen's live tools keep the same two rules in rapidgen/live/take.py and
rapidgen/textsafe.py (the runtime cannot import the compiler: a robot installs the
runtime alone); tests/security/test_live_helpers.py holds both to the same answers.
"""
from __future__ import annotations

import collections
from dataclasses import dataclass

from cyclonedds._clayer import ddspy_take
from cyclonedds.core import InstanceState, SampleState, ViewState

# Samples taken from DDS per call: a batch is held raw and decoded, so this bounds what one
# call holds (a CommandConfig may be 4.6 MB at its IDL bounds).
BATCH = 32
# Writers whose drops are counted one by one; past this, drops count as "others" (a flood of
# new writers must not grow the table).
MAX_WRITERS = 256


def visible(text: str, limit: int = 200) -> str:
    """One printable line of at most `limit` characters: what is not printable (newlines,
    controls, escape sequences, C1 codes, lone surrogates) shown as a backslash escape."""
    out = "".join(ch if ch.isprintable() else _escape(ch) for ch in str(text)[:limit])
    return out + ("..." if len(str(text)) > limit else "")


_SHORT = {"\\": "\\\\", "\n": "\\n", "\r": "\\r", "\t": "\\t"}


def _escape(ch: str) -> str:
    """The same escapes as rapidgen.textsafe.visible (a test holds them equal)."""
    code = ord(ch)
    if ch in _SHORT:
        return _SHORT[ch]
    if code < 0x80:
        return f"\\x{code:02x}"
    return f"\\u{code:04x}" if code <= 0xFFFF else f"\\U{code:08x}"


@dataclass
class Drop:
    writer: str  # who: the writer's GUID, participant first
    count: int = 0
    first_error: str = ""


class GuardedReader:
    """take() returns the samples of a reader that decode (each with .sample_info, like
    cyclonedds'); the others are counted in `drops` and reported through `log` once per writer."""

    def __init__(self, reader, log=None, batch: int = BATCH, wanted=None) -> None:
        """wanted(raw bytes) -> bool: a cheap look at the encoding before decoding; samples
        it refuses are counted in `skipped` and never decoded (a commander following a few
        cmdIds keeps up with an ack flood for others that way)."""
        self.reader, self.log, self.batch, self.wanted = reader, log, batch, wanted
        self.skipped = 0
        self.drops: collections.OrderedDict[int, Drop] = collections.OrderedDict()
        self.dropped = 0
        self.last_taken = 0  # samples the last take() got from DDS, decoded or not

    def take(self, n: int | None = None) -> list:
        data_type = self.reader.topic.data_type
        raw = ddspy_take(self.reader._ref, SampleState.Any | ViewState.Any | InstanceState.Any, n or self.batch)
        if isinstance(raw, int):  # a DDS error code: nothing taken
            self.last_taken = 0
            return []
        self.last_taken = len(raw)
        out = []
        for data, info in raw:
            if not info.valid_data:  # dispose/unregister notices carry no value
                continue
            if self.wanted is not None and not self.wanted(data):
                self.skipped += 1
                continue
            try:
                sample = data_type.deserialize(data)
            except Exception as exc:  # any decode failure: the bytes are someone else's problem
                self._dropped(info.publication_handle, exc)
                continue
            sample.sample_info = info
            out.append(sample)
        return out

    def _dropped(self, handle: int, exc: Exception) -> None:
        self.dropped += 1
        drop = self.drops.get(handle)
        if drop is None:
            if len(self.drops) >= MAX_WRITERS:
                handle = 0  # "others"
                drop = self.drops.setdefault(0, Drop("other writers"))
            else:
                drop = self.drops[handle] = Drop(writer_name(self.reader, handle))
        drop.count += 1
        if drop.count == 1:
            drop.first_error = visible(f"{type(exc).__name__}: {exc}", 160)
            if self.log is not None:
                self.log(f"dropped an undecodable {visible(self.reader.topic.name)} sample from {drop.writer}: "
                         f"{drop.first_error} (further ones from this writer are counted, not logged)")


def writer_name(reader, handle: int) -> str:
    """'writer <GUID> of participant <GUID prefix>' for a matched writer, from discovery."""
    try:
        ep = reader.get_matched_publication_data(handle)
    except Exception:  # the writer left already
        ep = None
    if ep is None:
        return f"writer handle {handle:#x}"
    return f"writer {ep.key} (participant {ep.participant_key.hex[:24]})"
