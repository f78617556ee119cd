"""`rapidgen monitor --replay FILE`: an MCAP recording of `rapidgen record` (channel topic =
DDS topic, metadata dds_type and partition, cdr messages with the bytes as received) read
with rapidgen.record's reader, decoded with the bindings, and played into a Hub whose clock
is the replay's position. The page's slider seeks: a new hub is filled with everything up
to that time (of each picture channel only the last picture is decoded), and the page
starts over from it. Play and pause move the position at the recording's own pace.

The messages are kept in memory (their bytes, at most MAX_BYTES); a message that does not
decode as its channel's type is dropped and counted, like a guarded take."""
from __future__ import annotations

import bisect
import threading
import time
from dataclasses import dataclass

from rapidgen.monitor.hints import Hints
from rapidgen.monitor.state import Hub, short

MAX_BYTES = 1 << 30  # message bytes kept from one recording
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
        try:
            rec, items = open_recording(path)
            self.channels: list[Channel] = []
            ids: dict[tuple[str, str, str], int] = {}
            self.times: list[int] = []  # log times [ns], in order
            self.msgs: list[tuple[int, bytes]] = []  # (channel index, bytes)
            kept = 0
            self.truncated = False
            for _schema, ch, m in items:
                if ch.message_encoding != "cdr":
                    continue
                key = (ch.topic, ch.metadata.get("partition", ""), ch.metadata.get("dds_type", ""))
                if key not in ids:
                    ids[key] = len(self.channels)
                    self.channels.append(Channel(*key, self._type_class(key[2])))
                if kept + len(m.data) > MAX_BYTES:
                    self.truncated = True
                    break
                kept += len(m.data)
                self.times.append(m.log_time)
                self.msgs.append((ids[key], bytes(m.data)))
        except RecordingError as exc:
            raise ReplayError(str(exc)) from None
        if not self.times:
            raise ReplayError(f"{path} holds no cdr message to play")
        order = sorted(range(len(self.times)), key=self.times.__getitem__)  # a cut file is in file order
        self.times = [self.times[i] for i in order]
        self.msgs = [self.msgs[i] for i in order]
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

    def _type_class(self, type_name: str):
        from rapidgen.live.bindings import find_type_class
        return find_type_class(self.bindings, type_name)

    # ---- feeding ---------------------------------------------------------------------------
    def _feed(self, hub: Hub, i: int) -> None:
        ch = self.channels[self.msgs[i][0]]
        if ch.cls is None:
            return
        try:
            sample = ch.cls.deserialize(self.msgs[i][1])  # type: ignore[attr-defined]
        except Exception:  # a message that does not decode: dropped alone
            self.dropped += 1
            return
        hub.sample(ch.partition, ch.topic, ch.type_name, sample, self.times[i] / 1e9)

    def _hub_at(self, t: float) -> Hub:
        """A new hub holding everything logged up to t."""
        hub = Hub(self.hints, clock=lambda: self.position)
        end = bisect.bisect_right(self.times, _ns(t))
        last_picture: dict[int, int] = {}
        for i in range(end):
            c = self.msgs[i][0]
            if short(self.channels[c].type_name) == "ImageSensorSample":
                last_picture[c] = i
        pictures = set(last_picture.values())
        for i in range(end):
            c = self.msgs[i][0]
            if short(self.channels[c].type_name) != "ImageSensorSample" or i in pictures:
                self._feed(hub, i)
        self._notes(hub)
        return hub

    def _notes(self, hub: Hub) -> None:
        notes = []
        if self.cut:
            notes.append(f"the recording is cut ({self.cut}): played up to its last whole message")
        if self.truncated:
            notes.append(f"only the first {MAX_BYTES >> 20} MiB of messages are played")
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
