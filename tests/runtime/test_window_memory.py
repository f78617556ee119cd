"""What the command window keeps per command, without DDS (bench/README.md, "the Python
bridge's memory over 100,000 commands"; docs/runtime.md, "Bounded memory"): the manager and
the journal share one entry per completed command, the journal keeps the last `window`
outcomes once each and in order (a cmdId finished again moves to the end), its compaction
writes the same lines as before, and the window's Python objects cost a few hundred bytes a
command (about 600 before: a Cmd key, two OrderedDicts, a dataclass Entry)."""
from __future__ import annotations

import tracemalloc
from types import SimpleNamespace

from rapid_runtime import journal as J
from rapid_runtime.command import Cmd
from rapid_runtime.manager import CommandManager
from tests.runtime.test_command_window import SOURCE, Blocking, Outbox
from tests.runtime.tables_of import tables

DOMAIN = 190  # a file name only: no DDS here
BYTES_PER_COMMAND = 450  # manager + journal, per command in the window (measured 285; 600 before)


def _cmd(cid: str, serial: int = 0):
    return SimpleNamespace(cmd_id=cid, src_name=SOURCE, asset_name="K10Red", serial=serial)


def _open(tmp_path, window: int):
    logs: list[str] = []
    j, rec = J.Journal.open(tmp_path, "K10Red", DOMAIN, window, logs.append)
    assert j is not None, logs
    return j, rec


def test_the_last_window_outcomes_once_each_in_order(tmp_path):
    j, _ = _open(tmp_path, 3)
    for cid in "abcd":
        j.note(_cmd(cid), "x")
        j.note(_cmd(cid), "c", "ACK_COMPLETED_OK", f"done {cid}")
    j.note(_cmd("b"), "c", "ACK_COMPLETED_EXEC_FAILED", "again")  # finished again: now the newest
    assert list(j.done) == ["c", "d", "b"] and j.done["b"].message == "again"
    j.note(_cmd("e"), "c", "ACK_COMPLETED_OK", "")
    assert list(j.done) == ["d", "b", "e"]
    for n in range(100):  # one id finished over and over: the order's replaced entries do not pile up
        j.note(_cmd("b"), "c", "ACK_COMPLETED_OK", str(n))
        assert len(j._order) <= 2 * j.window + 1
    assert list(j.done) == ["d", "e", "b"] and j.done["b"].message == "99"
    j.sync()
    j.close(clean=False)
    j2, rec = _open(tmp_path, 3)
    try:
        assert rec.crashed and rec.unfinished == []
        assert [(e.cmd_id, e.completion, e.message) for e in rec.finished] == [
            ("d", "ACK_COMPLETED_OK", "done d"), ("e", "ACK_COMPLETED_OK", ""), ("b", "ACK_COMPLETED_OK", "99")]
    finally:
        j2.close(clean=True)


def test_compaction_writes_the_live_and_the_last_window_as_lines_of_the_same_format(tmp_path):
    window = 600  # more than REWRITE_CHUNK: written in several pieces
    j, _ = _open(tmp_path, window)
    for n in range(J.COMPACT_FACTOR * window):
        j.note(_cmd(f"m{n}", n), "x")
        j.note(_cmd(f"m{n}", n), "c", "ACK_COMPLETED_OK", "" if n % 2 else f"r{n}")
        if n % 64 == 63:
            j.sync()  # compacts when due
    j.note(_cmd("live"), "q")
    j.sync()
    j._rewrite([])
    lines = j.path.read_bytes().splitlines(keepends=True)
    recs = [J._parse(line) for line in lines]
    assert None not in recs and len(lines) == j.lines == window + 1
    n0 = J.COMPACT_FACTOR * window - window
    assert recs[0] == {"k": "c", "id": f"m{n0}", "src": SOURCE, "asset": "K10Red", "serial": n0,
                       "c": "ACK_COMPLETED_OK", "m": "" if n0 % 2 else f"r{n0}"}
    assert lines[0] == J._line(recs[0])  # byte for byte what note() writes
    assert recs[-1] == {"k": "q", "id": "live", "src": SOURCE, "asset": "K10Red", "serial": 0}
    j.close(clean=False)
    j2, rec = _open(tmp_path, window)
    try:
        assert [e.cmd_id for e in rec.finished] == [f"m{n}" for n in range(n0, n0 + window)]
        assert [e.cmd_id for e in rec.unfinished] == ["live"]
    finally:
        j2.close(clean=True)


def _manager(tmp_path, window: int):
    j, _ = _open(tmp_path, window)
    m = CommandManager(tables("k10"), Blocking(), Outbox(), window=window, journal=j)
    m.receive(Cmd("control", SOURCE, "AccessControl", "requestControl", (), "QUEUE_BYPASS", "", SOURCE, "K10Red"))
    return m, j


def _send(m, first: int, count: int) -> None:
    for base in range(first, first + count, 64):  # one journal sync per 64, as the intake batches
        with m.batch():
            for n in range(base, min(base + 64, first + count)):
                m.receive(Cmd(f"m{n}", SOURCE, "Admin", "noOp", (), "QUEUE_BYPASS", "", SOURCE, "K10Red"))


def test_the_manager_keeps_the_journals_entry_not_a_copy(tmp_path):
    m, j = _manager(tmp_path, 8)
    try:
        _send(m, 0, 20)
        assert len(m.acked) == len(j.done) == 8
        assert all(kept is j.done[kept.cmd_id] for kept in m.acked)
        assert m.out.retired == ["control"] + [f"m{n}" for n in range(12)]  # the oldest retired, as before
    finally:
        j.close(clean=True)


def test_the_window_costs_a_few_hundred_bytes_a_command(tmp_path):
    window = 1024  # the default's structures, a quarter of the size (and of the time)
    m, j = _manager(tmp_path, window)
    m.out.ack = lambda *a: None  # keep nothing outside the window
    m.out.retire = lambda cmd: None
    try:
        _send(m, 0, 64)
        tracemalloc.start()
        try:
            before = tracemalloc.get_traced_memory()[0]
            _send(m, 64, 2 * window)  # the window fills, then turns over once
            grown = tracemalloc.get_traced_memory()[0] - before
        finally:
            tracemalloc.stop()
        assert len(m.seen) == len(m.acked) == len(j.done) == window
        print(f"the window: {grown / window:.0f} bytes a command")
        assert grown / window < BYTES_PER_COMMAND, f"{grown / window:.0f} bytes a command"
    finally:
        j.close(clean=True)


def test_the_names_a_command_carries_are_one_object_and_their_table_is_bounded():
    from rapid_runtime import messages as M

    def sample(n: int, src: str):
        hdr = SimpleNamespace(srcName="".join(src), assetName="".join("K10Red"), serial=0)  # new str objects
        return SimpleNamespace(cmdId=f"m{n}", cmdSrc="".join(src), subsysName="".join("Admin"), cmdName="".join("noOp"),
                               arguments=[], cmdAction="QUEUE_BYPASS", targetCmdId="", hdr=hdr)
    a, b = M.command_in(sample(1, SOURCE)), M.command_in(sample(2, SOURCE))
    assert a.src_name == SOURCE and a.cmd_src == SOURCE and a.asset_name == "K10Red" and a.name == "noOp"
    assert a.src_name is b.src_name and a.asset_name is b.asset_name and a.subsystem is b.subsystem
    assert a.name is b.name and a.cmd_src is b.cmd_src and a.cmd_id is not b.cmd_id
    for n in range(3 * M.NAMES_KEPT):  # a commander naming itself anew each time: the table stays bounded
        M.command_in(sample(n, f"src{n}"))
        assert len(M._names) <= M.NAMES_KEPT
