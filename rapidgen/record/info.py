"""`rapidgen record --info FILE`: what a recording holds. A complete file is summarised from
its statistics; a cut one (a killed recorder) is read up to its last whole chunk. Every
name from the file is escaped before it reaches the terminal."""
from __future__ import annotations

import os
import sys
from collections import Counter

from rapidgen.textsafe import visible


def print_info(path: str) -> int:
    from rapidgen.record.command import _mcap_missing
    from rapidgen.record.mcapfile import RecordingError, open_recording
    if _mcap_missing("record"):
        return 1
    try:
        rec, messages = open_recording(path)
        counts: Counter[int] = Counter()
        sizes: Counter[int] = Counter()
        first = last = None
        if rec.complete and rec.statistics is not None:
            stats = rec.statistics
            counts.update(stats.channel_message_counts)
            if stats.message_count:
                first, last = stats.message_start_time, stats.message_end_time
            messages.close()  # a generator: closing it closes the file
        else:
            for _schema, channel, msg in messages:
                counts[channel.id] += 1
                sizes[channel.id] += len(msg.data)
                t = msg.log_time
                first = t if first is None else min(first, t)
                last = t if last is None else max(last, t)
    except RecordingError as exc:
        print(f"rapidgen record: {exc}", file=sys.stderr)
        return 1
    out = sys.stdout
    state = "complete (summary and index)" if rec.complete and not rec.cut_reason else \
        f"cut: read up to its last whole chunk ({visible(rec.cut_reason or 'no summary')})"
    out.write(f"file: {visible(path)} ({os.path.getsize(path)} bytes), {state}\n")
    out.write(f"written by: {visible(rec.library)}\n")
    for name, values in sorted(rec.metadata.items()):
        shown = ", ".join(f"{visible(k)}={visible(v)[:80]}" for k, v in sorted(values.items()))
        out.write(f"metadata {visible(name)}: {shown}\n")
    for name, media_type, length in rec.attachments:
        out.write(f"attachment {visible(name)} ({visible(media_type)}, {length} bytes)\n")
    seconds = (last - first) / 1e9 if first is not None and last is not None else 0.0
    out.write(f"messages: {sum(counts.values())} over {seconds:.1f} s, {len(rec.channels)} channel(s), "
              f"{len(rec.schemas)} schema(s)\n")
    for cid, ch in sorted(rec.channels.items(), key=lambda kv: (kv[1].topic, kv[0])):
        meta = ch.metadata
        rate = f"{counts[cid] / seconds:.2f}/s" if seconds > 0 else "-"
        size = f", {sizes[cid]} bytes" if sizes else ""
        out.write(f"  [{visible(meta.get('partition', ''))}] {visible(ch.topic)} ({visible(meta.get('dds_type', ''))}, "
                  f"{visible(meta.get('role', ''))}): {counts[cid]} messages, {rate}{size}\n")
    return 0
