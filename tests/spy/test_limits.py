"""spy's rules for untrusted data, without a network: JSON without NaN/Infinity, the caps on
what a reader keeps, discovery samples dropped alone, partition names capped, the text
view of a huge config. The live tier is tests/hostile/test_live_spy.py."""
from __future__ import annotations

import json
import math

import pytest

from rapidgen.spy import watch
from rapidgen.spy.collect import CONFIG_LINES, config_lines
from rapidgen.spy.model import Snapshot, plain
from rapidgen.spy.render import as_json


def test_non_finite_floats_are_strings_and_json_is_strict():
    assert plain([math.inf, -math.inf, math.nan, 1.5]) == ["Infinity", "-Infinity", "NaN", 1.5]
    snap = Snapshot(0, 1.0)
    snap.assets = []
    snap.limits = ["x"]
    text = as_json(snap)

    def refuse(name):
        raise ValueError(name)
    assert json.loads(text, parse_constant=refuse)["limits"] == ["x"]


def _rec(writer: str, seq: int) -> watch.Seen:
    return watch.Seen(seq, float(seq), None, writer, None)


def test_a_reader_keeps_the_newest_records_per_writer_and_pools_writers_past_the_cap():
    st = watch.Stream("t", "p", "rapid::AgentState", None, 0.0, None)
    seq = 0
    for w in range(watch.MAX_WRITERS_PER_STREAM + 3):
        for _ in range(watch.KEEP_PER_WRITER + 10):
            st.keep(_rec(f"w{w}", seq))
            seq += 1
    assert st.count == seq
    assert len(st.by_writer) == watch.MAX_WRITERS_PER_STREAM + 1  # and one pool
    assert all(len(q) == watch.KEEP_PER_WRITER for q in st.by_writer.values())
    assert len(st.pooled) == 3 and len(st.seen) == (watch.MAX_WRITERS_PER_STREAM + 1) * watch.KEEP_PER_WRITER
    assert [s.seq for s in st.seen] == sorted(s.seq for s in st.seen)  # arrival order
    assert st.of_writer("w0")[-1].seq == watch.KEEP_PER_WRITER + 9  # the newest kept
    last = f"w{watch.MAX_WRITERS_PER_STREAM + 2}"
    assert st.of_writer(last) and all(s.writer == last for s in st.of_writer(last))


class _Sample:
    def __init__(self, size: int) -> None:
        self.wire_size = size


def test_big_latest_samples_share_one_budget():
    w = watch.Watcher.__new__(watch.Watcher)
    w.big_bytes, w.tap, w.cmd_ids = 0, None, {}
    w._seq = iter(range(10**6))
    big = watch.BIG_SAMPLE + 1
    n = watch.BIG_BUDGET // big
    streams = [watch.Stream(f"t{i}", "p", "rapid::CommandConfig", None, 0.0, None)
               for i in range(n + 2)]
    for st in streams:
        w._arrived(st, _Sample(big))
    kept = [st for st in streams if st.latest is not None and st.latest.sample is not None]
    assert len(kept) == n and w.big_bytes == n * big <= watch.BIG_BUDGET
    assert sum(st.not_kept for st in streams) == 2
    w._arrived(streams[0], _Sample(big))  # a reader's new latest replaces its old one in the budget
    assert streams[0].latest is not None and streams[0].latest.sample is not None and w.big_bytes == n * big
    small = streams[-1]
    w._arrived(small, _Sample(100))  # small samples are always kept
    assert small.latest is not None and small.latest.sample is not None


def test_discovery_drops_an_unreadable_builtin_sample_alone_and_caps_partitions():
    pytest.importorskip("cyclonedds")
    from cyclonedds.qos import Policy, Qos

    from rapidgen.live import discovery as d

    class Reader:
        def __init__(self, items):
            self.items = list(items)

        def take(self, N=1):
            assert N == 1
            if not self.items:
                return []
            item = self.items.pop(0)
            if isinstance(item, Exception):
                raise item
            return [item]

    disc = d.Discovery.__new__(d.Discovery)
    disc.dropped, disc.ignored = {}, {}
    got = disc._take("writer", Reader([1, UnicodeDecodeError("utf-8", b"\xff", 0, 1, "bad\x1b"), 2, 3]))
    assert got == [1, 2, 3] and disc.dropped["writer"].count == 1 and "\x1b" not in disc.dropped["writer"].first_error
    names = [f"P{i}" for i in range(4000)] + ["x" * 300]
    q = d.QosSummary.of(Qos(Policy.Partition(names)))
    assert q.partitions == tuple(names[:d.MAX_ENDPOINT_PARTITIONS]) and q.partitions_left_out == 4001 - 64


def test_a_huge_config_is_cut_in_the_text_view():
    cfg = {"availableSubsystemTypes": [{"name": f"T{i}", "commands": [
        {"name": f"c{j}", "parameters": [{"key": "k", "type": "RAPID_INT"}]} for j in range(100)]} for i in range(64)],
        "availableSubsystems": []}
    lines = config_lines(cfg)
    assert len(lines) == CONFIG_LINES + 1 and lines[-1].startswith(f"... {64 * 101 - CONFIG_LINES} more line(s)")
