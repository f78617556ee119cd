"""`rapidgen spy echo TOPIC`: print one topic's samples as they arrive, decoded, as text
or JSON lines (one per sample, with partition and the writer's source time)."""
from __future__ import annotations

import json
import sys
import time

from rapidgen.backends.escape import visible
from rapidgen.spy.model import plain


def echo(w, topic: str, as_json: bool, seconds: float | None, count: int | None, out=None) -> int:
    """Print until seconds pass, count samples were printed, or Ctrl-C. Returns how many."""
    out = out or sys.stdout
    printed = 0
    cursor: dict[tuple[str, str, bool, bool], int] = {}  # stream key -> how many of its samples were printed
    end = None if seconds is None else time.monotonic() + seconds
    while end is None or time.monotonic() < end:
        w.step()
        for key, st in w.streams.items():
            if st.topic != topic:
                continue
            new = st.seen[cursor.get(key, 0):]
            cursor[key] = len(st.seen)
            for s in new:
                data = plain(s.sample)
                if as_json:
                    line = json.dumps({"topic": topic, "partition": st.partition, "type": st.type_name,
                                       "source_time": s.stamp, "sample": data}, ensure_ascii=True, default=str)
                else:
                    line = visible(f"[{st.partition}] {topic} {json.dumps(data, ensure_ascii=False, default=str)}")
                print(line, file=out, flush=True)
                printed += 1
                if count is not None and printed >= count:
                    return printed
            # our reader keeps what it took; echo needs only what is new
            if len(st.seen) > 1000:
                cursor[key] -= len(st.seen) - 100
                del st.seen[:-100]
        time.sleep(0.02)
    return printed
