"""Taking samples from the network in the live tools (spy, conform, cmd): the wire is
untrusted, any participant in a partition may write any RAPID topic with any bytes.

    guard = GuardedReader(reader)            # dedupe=True for durable, repeated samples
    for sample in guard.take():              # only the samples that decode, .sample_info set
        ...
    guard.drops                              # {writer: Drop(count, first_error)}: say so in the output

- A sample that does not decode is dropped alone, counted against its writer (the rest of
  the batch is kept: cyclonedds' DataReader.take raises on the first bad sample and the
  others taken with it are lost).
- Batches are small (raw bytes of a CommandConfig at its IDL bounds are 4.6 MB).
- dedupe: a writer republishing the same bytes for the same instance (a durable config at
  10 Hz) is decoded once; the earlier value is handed out again. The bytes remembered for
  that are bounded per reader (remember_bytes).
- Each sample handed out carries `wire_size` (its encoded bytes), for callers that budget.
- The tables are bounded: MAX_WRITERS writers are counted one by one, then as "others".

The runtime keeps the same rules for the robot side in rapid_runtime/untrusted.py (a robot
installs the runtime without the compiler); tests/security/test_live_helpers.py holds the
two to the same behaviour.
"""
from __future__ import annotations

import collections
import copy
from dataclasses import dataclass

from rapidgen.textsafe import visible

BATCH = 32
MAX_WRITERS = 256
MAX_REMEMBERED = 1024  # (writer, instance) pairs whose last bytes are kept for dedupe
MAX_REMEMBERED_BYTES = 64 << 20  # and at most this many bytes of them


@dataclass
class Drop:
    writer: str
    count: int = 0
    first_error: str = ""


class GuardedReader:
    def __init__(self, reader, dedupe: bool = False, batch: int = BATCH,
                 remember_bytes: int = MAX_REMEMBERED_BYTES) -> None:
        self.reader, self.dedupe, self.batch, self.remember_bytes = reader, dedupe, batch, remember_bytes
        self.drops: collections.OrderedDict[int, Drop] = collections.OrderedDict()
        self.dropped = 0
        self.reused = 0  # samples not decoded again (same writer, instance and bytes)
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
        from cyclonedds._clayer import ddspy_take
        from cyclonedds.core import InstanceState, SampleState, ViewState

        data_type = self.reader.topic.data_type
        raw = ddspy_take(self.reader._ref, SampleState.Any | ViewState.Any | InstanceState.Any, n)
        if isinstance(raw, int):  # a DDS error code: nothing taken
            return 0, []
        out = []
        for data, info in raw:
            if not info.valid_data:
                continue
            sample = self._decode(data_type, data, info)
            if sample is not None:
                sample.sample_info = info
                sample.wire_size = len(data)
                out.append(sample)
        return len(raw), out

    def _decode(self, data_type, data: bytes, info):
        key = (info.publication_handle, info.instance_handle)
        if self.dedupe:
            last = self._last.get(key)
            if last is not None and last[0] == data:
                self._last.move_to_end(key)
                self.reused += 1
                return copy.copy(last[1])
        try:
            sample = data_type.deserialize(data)
        except Exception as exc:  # any decode failure: drop this sample, keep the others
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
                drop = self.drops.setdefault(0, Drop("other writers"))
            else:
                drop = self.drops[handle] = Drop(writer_name(self.reader, handle))
        drop.count += 1
        if drop.count == 1:
            drop.first_error = visible(f"{type(exc).__name__}: {exc}"[:160])

    def summary(self) -> list[str]:
        """One line per writer whose samples were dropped (for a tool's output)."""
        topic = visible(self.reader.topic.name)
        return [f"{d.count} undecodable {topic} sample(s) from {d.writer} dropped ({d.first_error})"
                for d in self.drops.values()]


def writer_name(reader, handle: int) -> str:
    """'writer <GUID> (participant <GUID prefix>)' for a matched writer, from discovery."""
    try:
        ep = reader.get_matched_publication_data(handle)
    except Exception:  # the writer left already
        ep = None
    if ep is None:
        return f"writer handle {handle:#x}"
    return f"writer {ep.key} (participant {ep.participant_key.hex[:24]})"
