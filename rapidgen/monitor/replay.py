"""`rapidgen monitor --replay FILE`: an MCAP recording of `rapidgen record` (channel topic =
DDS topic, metadata dds_type and partition, cdr messages with the bytes as received) read
with rapidgen.record's reader, decoded with the bindings, and played into a Hub whose clock
is the replay's position. The page's slider seeks: a new hub is filled with everything up
to that time (of each picture channel only the last picture is decoded), and the page
starts over from it. Play and pause move the position at the recording's own pace.

The messages are kept in memory, compactly (their bytes in segments of a few MiB, and per
message its time, channel and place in arrays: 24 bytes), up to MAX_BYTES counting
PER_MESSAGE bytes for each message besides its own; past it the recording is refused
(ReplayError), as it is past the reader's caps (rapidgen.record.mcapfile: a chunk's
inflation). A message that does not decode as its channel's type is dropped and counted,
like a guarded take."""
from __future__ import annotations

import bisect
import threading
import time
from array import array
from dataclasses import dataclass

from rapidgen.monitor.hints import Hints
from rapidgen.monitor.state import Hub, short

MAX_BYTES = 1 << 30  # what one recording may take: its messages' bytes, plus PER_MESSAGE each
# A message costs 24 bytes in the arrays (about 37 measured with their growth), and sorting
# a file that is not in time order (a cut one) about 50 more for a moment: 3 million empty
# messages out of order peak at 68 bytes each (they took 781 MiB in order before).
PER_MESSAGE = 128
SEGMENT = 4 << 20  # message bytes are appended to segments of this size (a larger message: its own)
STEP = 0.05  # seconds between two advances while playing


def _ns(t: float) -> int:
    """A position [s] as a log time [ns], 1 us late: float seconds near 1.8e9 keep ~0.2 us,
    so the position of a message's own time must not fall just before it."""
    return round(t * 1e9) + 1000


class ReplayError(Exception):
    """The recording cannot be played (said without a traceback)."""


@dataclass(frozen=True)
class Channel:
    topic: str
    partition: str
    type_name: str
    cls: object | None


class ReplaySource:
    mode = "replay"

    def __init__(self, path: str, bindings: list, hints: Hints) -> None:
        from rapidgen.record.mcapfile import RecordingError, open_recording
        self.path, self.bindings, self.hints = path, bindings, hints
        self.channels: list[Channel] = []
        self.times = array("q")  # log times [ns], in order
        self._chan = array("I")  # per message: its channel's index
        self._seg = array("I")  # per message: its segment, its offset there, its length
        self._off = array("I")
        self._len = array("I")
        self._segs: list[bytearray] = []
        try:
            rec, items = open_recording(path)
            ids: dict[tuple[str, str, str], int] = {}
            kept = 0
            for _schema, ch, m in items:
                if ch.message_encoding != "cdr":
                    continue
                key = (ch.topic, ch.metadata.get("partition", ""), ch.metadata.get("dds_type", ""))
                if key not in ids:
                    ids[key] = len(self.channels)
                    self.channels.append(Channel(*key, self._type_class(key[2])))
                kept += len(m.data) + PER_MESSAGE
                if kept > MAX_BYTES:
                    items.close()
                    raise ReplayError(f"{path}: its messages take more than {MAX_BYTES >> 20} MiB (their bytes "
                                      f"plus {PER_MESSAGE} for each), the most a replay holds: refused (replay a "
                                      "shorter recording: `rapidgen record --split-size` writes files of a chosen "
                                      "size)")
                c = ids[key]
                self._add(c, m.log_time, m.data if self.channels[c].cls is not None else b"")
        except RecordingError as exc:
            raise ReplayError(str(exc)) from None
        if not self.times:
            raise ReplayError(f"{path} holds no cdr message to play")
        if any(self.times[i] > self.times[i + 1] for i in range(len(self.times) - 1)):
            self._sort()  # a cut file is in file order
        self._pictures = [short(c.type_name) == "ImageSensorSample" for c in self.channels]
        self.cut = "" if rec.complete else (rec.cut_reason or "no summary: read up to its last whole record")
        self.start, self.end = self.times[0] / 1e9, self.times[-1] / 1e9
        self.dropped = 0
        self.lock = threading.RLock()
        self.playing = True
        self.position = self.start
        self.hub = self._hub_at(self.start)
        self._index = bisect.bisect_right(self.times, _ns(self.start))
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._play, name="monitor-replay", daemon=True)
        self._thread.start()

    def _add(self, channel: int, log_time: int, data: bytes) -> None:
        n = len(data)
        if n > SEGMENT // 4:  # a large message: a segment of its own
            self._segs.append(bytearray(data))
        elif not self._segs or len(self._segs[-1]) + n > SEGMENT:
            self._segs.append(bytearray())
        seg = self._segs[-1]
        self._seg.append(len(self._segs) - 1)
        self._off.append(len(seg) if n <= SEGMENT // 4 else 0)
        self._len.append(n)
        if n <= SEGMENT // 4:
            seg += data
        self.times.append(log_time)
        self._chan.append(channel)

    def _sort(self) -> None:
        """The messages in time order (stable). One list of (time << bits | index) integers,
        sorted in place: about 48 bytes a message for a moment, where sorted(range(n),
        key=...) took about 100 (a list of indexes and one of keys)."""
        times, bits = self.times, len(self.times).bit_length()
        first = min(times)
        keys = [((t - first) << bits) | i for i, t in enumerate(times)]
        keys.sort()
        mask = (1 << bits) - 1
        order = array("I", (k & mask for k in keys))
        del keys
        for name in ("times", "_chan", "_seg", "_off", "_len"):
            old = getattr(self, name)
            setattr(self, name, array(old.typecode, (old[i] for i in order)))
            del old

    def _data(self, i: int) -> bytes:
        off = self._off[i]
        return bytes(self._segs[self._seg[i]][off:off + self._len[i]])

    def _type_class(self, type_name: str):
        from rapidgen.live.bindings import find_type_class
        return find_type_class(self.bindings, type_name)

    # ---- feeding ---------------------------------------------------------------------------
    def _feed(self, hub: Hub, i: int) -> None:
        ch = self.channels[self._chan[i]]
        if ch.cls is None:
            return
        try:
            sample = ch.cls.deserialize(self._data(i))  # type: ignore[attr-defined]
        except Exception:  # a message that does not decode: dropped alone
            self.dropped += 1
            return
        hub.sample(ch.partition, ch.topic, ch.type_name, sample, self.times[i] / 1e9)

    def _hub_at(self, t: float) -> Hub:
        """A new hub holding everything logged up to t."""
        hub = Hub(self.hints, clock=lambda: self.position)
        end = bisect.bisect_right(self.times, _ns(t))
        last_picture: dict[int, int] = {}
        chan, is_picture = self._chan, self._pictures
        if any(is_picture):
            for i in range(end):
                if is_picture[chan[i]]:
                    last_picture[chan[i]] = i
        pictures = set(last_picture.values())
        for i in range(end):
            if not is_picture[chan[i]] or i in pictures:
                self._feed(hub, i)
        self._notes(hub)
        return hub

    def _notes(self, hub: Hub) -> None:
        notes = []
        if self.cut:
            notes.append(f"the recording is cut ({self.cut}): played up to its last whole message")
        unknown = sorted({c.type_name for c in self.channels if c.cls is None})
        if unknown:
            notes.append(f"no bindings for {', '.join(unknown[:5])} (give the asset's descriptor with --asset)")
        if self.dropped:
            notes.append(f"{self.dropped} message(s) that do not decode as their channel's type were dropped")
        hub.notes = notes

    def _play(self) -> None:
        last = time.monotonic()
        while not self._stop.wait(STEP):
            now = time.monotonic()
            with self.lock:
                if self.playing:
                    self.position = min(self.end, self.position + (now - last))
                    upto = bisect.bisect_right(self.times, _ns(self.position))
                    while self._index < upto:
                        self._feed(self.hub, self._index)
                        self._index += 1
                    if self.position >= self.end:
                        self.playing = False
                    self._notes(self.hub)
            last = now

    # ---- the page ----------------------------------------------------------------------------
    def info(self) -> dict:
        return {"file": self.path, "start": self.start, "end": self.end, "t": self.position, "playing": self.playing}

    def handle(self, msg: dict) -> dict | None:
        kind = msg.get("type")
        with self.lock:
            if kind == "seek" and isinstance(msg.get("t"), (int, float)):
                t = min(self.end, max(self.start, float(msg["t"])))
                self.position = t
                self.hub = self._hub_at(t)
                self._index = bisect.bisect_right(self.times, _ns(t))
            elif kind == "play":
                if self.position >= self.end:
                    self.position, self.hub, self._index = self.start, self._hub_at(self.start), 0
                    self._index = bisect.bisect_right(self.times, _ns(self.start))
                self.playing = True
            elif kind == "pause":
                self.playing = False
            elif kind == "command":
                return {"type": "refused", "partition": msg.get("partition"), "ref": msg.get("ref"),
                        "reason": "a replay sends no command"}
        return None

    def close(self) -> None:
        self._stop.set()
        self._thread.join(timeout=5)
