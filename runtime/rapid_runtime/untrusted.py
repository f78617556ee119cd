"""Data from the wire is untrusted: any participant in the asset's partition can write any
RAPID topic, with any bytes. Two rules hold for everything the runtime reads:

- a sample that does not decode (invalid UTF-8, a sequence past its bound, truncated CDR)
  is dropped on its own, counted against the writer that sent it and logged once per
  writer; the samples around it are still delivered (cyclonedds' DataReader.take decodes a
  whole batch and raises on the first bad one, losing the rest, so this takes raw bytes);
- wire text reaches a log only through visible(): no ESC, BEL or C1 byte gets to a terminal.

rapidgen's live tools take through this same GuardedReader (the tools may import the
runtime; the runtime imports nothing of the compiler: a robot installs it alone);
visible() is held to rapidgen.textsafe's by tests/hostile/test_live_helpers.py.
"""
from __future__ import annotations

import collections
import copy
from dataclasses import dataclass

from cyclonedds._clayer import ddspy_take
from cyclonedds.core import InstanceState, SampleState, ViewState

# Samples taken from DDS per call: a batch is held raw and decoded, so this bounds what one
# call holds (a CommandConfig may be 4.6 MB at its IDL bounds).
BATCH = 32
# Writers whose drops are counted one by one; past this, drops count as "others" (a flood of
# new writers must not grow the table).
MAX_WRITERS = 256
MAX_REMEMBERED = 1024  # (writer, instance) pairs whose last bytes are kept for dedupe
MAX_REMEMBERED_BYTES = 64 << 20  # and at most this many bytes of them


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
    cyclonedds', and .wire_size, its encoded bytes); the others are counted in `drops` and,
    with a `log`, reported once per writer. The bridge reads commands through it, and
    rapidgen's live tools (spy, conform, cmd) every topic they read."""

    def __init__(self, reader, log=None, batch: int = BATCH, wanted=None, dedupe: bool = False,
                 remember_bytes: int = MAX_REMEMBERED_BYTES) -> None:
        """wanted(raw bytes) -> bool: a cheap look at the encoding before decoding; samples
        it refuses are counted in `skipped` and never decoded (a commander following a few
        cmdIds keeps up with an ack flood for others that way).
        dedupe: a writer republishing the same bytes for the same instance (a durable config
        at 10 Hz) is decoded once and the earlier value handed out again (counted in
        `reused`); the bytes remembered for that are bounded (MAX_REMEMBERED pairs,
        remember_bytes)."""
        self.reader, self.log, self.batch, self.wanted = reader, log, batch, wanted
        self.dedupe, self.remember_bytes = dedupe, remember_bytes
        self.skipped = 0
        self.drops: collections.OrderedDict[int, Drop] = collections.OrderedDict()
        self.dropped = 0
        self.reused = 0
        self.last_taken = 0  # samples the last take() got from DDS, decoded or not
        self._last: collections.OrderedDict[tuple[int, int], tuple[bytes, object]] = collections.OrderedDict()
        self._last_bytes = 0

    def take(self, n: int | None = None) -> list:
        return self._take(n or self.batch)[1]

    def take_all(self, limit: int = 100_000) -> list:
        """Take until the reader is empty (at most about `limit` samples, in batches)."""
        out: list = []
        while len(out) < limit:
            n, got = self._take(self.batch)
            out.extend(got)
            if n < self.batch:
                break
        return out

    def _take(self, n: int) -> tuple[int, list]:
        """(how many were taken, the ones that decode)."""
        data_type = self.reader.topic.data_type
        raw = ddspy_take(self.reader._ref, SampleState.Any | ViewState.Any | InstanceState.Any, n)
        if isinstance(raw, int):  # a DDS error code: nothing taken
            self.last_taken = 0
            return 0, []
        self.last_taken = len(raw)
        out = []
        for data, info in raw:
            if not info.valid_data:  # dispose/unregister notices carry no value
                continue
            if self.wanted is not None and not self.wanted(data):
                self.skipped += 1
                continue
            sample = self._decode(data_type, data, info)
            if sample is not None:
                sample.sample_info = info
                sample.wire_size = len(data)
                out.append(sample)
        return len(raw), out

    def _decode(self, data_type, data: bytes, info):
        """The sample, or None when it does not decode (counted against its writer)."""
        key = (info.publication_handle, info.instance_handle)
        if self.dedupe:
            last = self._last.get(key)
            if last is not None and last[0] == data:
                self._last.move_to_end(key)
                self.reused += 1
                return copy.copy(last[1])
        try:
            sample = data_type.deserialize(data)
        except Exception as exc:  # any decode failure: the bytes are someone else's problem
            self._dropped(info.publication_handle, exc)
            return None
        if self.dedupe:
            old = self._last.pop(key, None)
            self._last_bytes += len(data) - (len(old[0]) if old else 0)
            self._last[key] = (bytes(data), sample)
            while len(self._last) > 1 and (len(self._last) > MAX_REMEMBERED or self._last_bytes > self.remember_bytes):
                self._last_bytes -= len(self._last.popitem(last=False)[1][0])
            return copy.copy(sample)
        return sample

    def _dropped(self, handle: int, exc: Exception) -> None:
        self.dropped += 1
        drop = self.drops.get(handle)
        if drop is None:
            if len(self.drops) >= MAX_WRITERS:
                drop = self.drops.setdefault(0, Drop("other writers"))  # "others"
            else:
                drop = self.drops[handle] = Drop(writer_name(self.reader, handle))
        drop.count += 1
        if drop.count == 1:
            drop.first_error = visible(f"{type(exc).__name__}: {exc}", 160)
            if self.log is not None:
                self.log(f"dropped an undecodable {visible(self.reader.topic.name)} sample from {drop.writer}: "
                         f"{drop.first_error} (further ones from this writer are counted, not logged)")

    def summary(self) -> list[str]:
        """One line per writer whose samples were dropped (for a tool's output)."""
        topic = visible(self.reader.topic.name)
        return [f"{d.count} undecodable {topic} sample(s) from {d.writer} dropped ({d.first_error})"
                for d in self.drops.values()]


def writer_name(reader, handle: int) -> str:
    """'writer <GUID> of participant <GUID prefix>' for a matched writer, from discovery."""
    try:
        ep = reader.get_matched_publication_data(handle)
    except Exception:  # the writer left already
        ep = None
    if ep is None:
        return f"writer handle {handle:#x}"
    return f"writer {ep.key} (participant {ep.participant_key.hex[:24]})"
