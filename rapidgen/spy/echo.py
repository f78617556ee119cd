"""`rapidgen spy echo TOPIC`: print one topic's samples as they arrive, decoded, as text
or JSON lines (one per sample, with partition and the writer's source time). Samples that
do not decode are dropped by the Watcher's guarded readers; echo says so in a line of its
own (JSON: an object with "dropped" instead of "sample"), per writer, at most once a
second while the count grows. Samples are printed after each step; when more than
BACKLOG_BYTES of them wait, the oldest are skipped and a line says how many."""
from __future__ import annotations

import collections
import json
import sys
import time

from rapidgen.textsafe import visible
from rapidgen.spy.model import plain

BACKLOG_BYTES = 16 << 20  # wire bytes of samples waiting to be printed
BACKLOG_SAMPLES = 4096


def echo(w, topic: str, as_json: bool, seconds: float | None, count: int | None, out=None) -> int:
    """Print until seconds pass, count samples were printed, or Ctrl-C. Returns how many."""
    out = out or sys.stdout
    backlog: collections.deque = collections.deque()  # (stream, record, sample)
    state = {"bytes": 0, "skipped": 0}

    def tap(st, rec) -> None:
        if st.topic != topic:
            return
        backlog.append((st, rec, rec.sample))
        state["bytes"] += rec.size
        while len(backlog) > 1 and (state["bytes"] > BACKLOG_BYTES or len(backlog) > BACKLOG_SAMPLES):
            state["bytes"] -= backlog.popleft()[1].size
            state["skipped"] += 1

    w.tap = tap
    w.topics = {topic}
    printed = 0
    told: dict[tuple, tuple[int, float]] = {}  # (stream key, writer handle) -> (count told, when)
    end = None if seconds is None else time.monotonic() + seconds
    try:
        while end is None or time.monotonic() < end:
            w.step()
            _tell_drops(w, topic, as_json, out, told, final=False)
            if state["skipped"]:
                _line(out, as_json, {"topic": topic, "skipped": state["skipped"]},
                      f"{topic}: {state['skipped']} sample(s) not printed (echo fell behind)")
                state["skipped"] = 0
            while backlog:
                st, rec, sample = backlog.popleft()
                state["bytes"] -= rec.size
                data = plain(sample)
                if as_json:
                    line = json.dumps({"topic": topic, "partition": st.partition, "type": st.type_name,
                                       "source_time": rec.stamp, "sample": data}, ensure_ascii=True,
                                       allow_nan=False, default=str)
                else:
                    line = visible(f"[{st.partition}] {topic} "
                                   f"{json.dumps(data, ensure_ascii=False, allow_nan=False, default=str)}")
                print(line, file=out, flush=True)
                printed += 1
                if count is not None and printed >= count:
                    return printed
            time.sleep(0.02)
        return printed
    finally:
        _tell_drops(w, topic, as_json, out, told, final=True)
        w.tap = None


def _tell_drops(w, topic: str, as_json: bool, out, told: dict, final: bool) -> None:
    now = time.monotonic()
    for key, st in w.streams.items():
        if st.topic != topic:
            continue
        for handle, d in st.guard.drops.items():
            n, when = told.get((key, handle), (0, -1.0))
            if d.count == n or (not final and now - when < 1.0):
                continue
            told[(key, handle)] = (d.count, now)
            guid = st.writer_of(handle) if handle else None
            writer = f"writer {guid}" if guid else d.writer
            _line(out, as_json, {"topic": topic, "partition": st.partition, "dropped": d.count,
                                 "writer": guid or d.writer, "error": d.first_error},
                  f"[{st.partition}] {topic}: {d.count} sample(s) from {writer} did not decode and were dropped "
                  f"({d.first_error})")


def _line(out, as_json: bool, obj: dict, text: str) -> None:
    print(json.dumps(obj, ensure_ascii=True, allow_nan=False, default=str) if as_json else visible(text),
          file=out, flush=True)
