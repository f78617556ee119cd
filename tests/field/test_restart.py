"""A bridge that restarts never leaves a command without an outcome (issue 23; docs/runtime.md,
"Restarts: the journal").

Live: the Restarter asset's bridge (tests/field/restart_asset.py) takes a stream of commands
from a ground process (tests/field/restart_ground.py) on loopback and is killed with SIGKILL
at random moments (KILLS; 20 with RAPIDGEN_FIELD_FULL=1), then started again on the same
journal; before the second restart the journal gets a torn record and a garbage line.
Every command sent gets a final ack, at its sender and at a late-joining ground tool (the
same one); no command runs twice (the handler appends each cmdId it runs to a file); a
command answered "restarted before it ran" never ran, one that completed OK ran once; the
damaged journal is reported in one log line and set aside; no traceback.

Without DDS: damaged journals (torn tail, a bad line in the middle, binary junk, an empty
file, a folder that cannot be written) are survived; compaction keeps the file bounded.
"""
from __future__ import annotations

import json
import os
import random
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from rapid_runtime.command import Cmd
from rapid_runtime.journal import COMPACT_FACTOR, Journal, file_name
from tests.field.restart_asset import ROOT, check_kill_run, generate

DOMAIN = 195
FULL = os.environ.get("RAPIDGEN_FIELD_FULL") == "1"
KILLS = 20 if FULL else 5
COMMANDS = 200 if FULL else 60


def test_kill_9_at_random_moments_leaves_no_command_without_an_outcome(tmp_path):
    pydir = generate(tmp_path / "gen")
    seed = random.SystemRandom().randrange(1_000_000)
    # its own process group: if it has to be killed, its bridges go with it (a bridge left
    # running would answer the next run's commands on this domain)
    proc = subprocess.Popen([sys.executable, "-m", "tests.field.restart_ground", str(pydir), str(tmp_path), str(DOMAIN),
                             str(COMMANDS), str(KILLS), str(seed)], cwd=ROOT, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        out, err = proc.communicate(timeout=600)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.communicate()
    assert proc.returncode == 0, f"seed {seed}: {out[-2000:]} {err[-4000:]}"
    got = json.loads(out.splitlines()[-1])
    why = f"seed {seed}: {json.dumps({k: v for k, v in got.items() if k != 'plan'})[-6000:]}"
    assert got["starts"] == KILLS + 1 and got["stop_code"] == 0 and got["tracebacks"] == 0, why

    check_kill_run(got, KILLS, why)


# ---- the journal alone --------------------------------------------------------------------------

def _cmd(i: int) -> Cmd:
    return Cmd(f"c{i}", "Ground", "Belt", "work", src_name="Ground", asset_name="Restarter", serial=7)


def _journal(folder: Path, window: int = 64) -> tuple[Journal, object, list[str]]:
    logs: list[str] = []
    j, rec = Journal.open(folder, "Restarter", 1, window, logs.append)
    assert j is not None, logs
    return j, rec, logs


def _crash(j: Journal) -> None:
    os.close(j.fd)  # no stop record: what a kill leaves


def test_a_crash_is_recovered_and_a_clean_stop_starts_afresh(tmp_path):
    j, rec, _ = _journal(tmp_path)
    assert not rec.crashed
    j.start(100)
    j.note(_cmd(1), "q")
    j.note(_cmd(2), "q")
    j.note(_cmd(2), "x")
    j.note(_cmd(3), "x")
    j.note(_cmd(3), "c", "ACK_COMPLETED_OK", "done")
    j.serial(105)
    j.sync()
    _crash(j)
    j, rec, logs = _journal(tmp_path)
    assert rec.crashed and rec.last_serial == 105 and logs == []
    assert [(e.cmd_id, e.state) for e in rec.unfinished] == [("c1", "q"), ("c2", "x")]
    assert [(e.cmd_id, e.completion, e.message) for e in rec.finished] == [("c3", "ACK_COMPLETED_OK", "done")]
    assert rec.unfinished[0].src_name == "Ground" and rec.unfinished[0].serial == 7
    j.close(clean=True)
    j, rec, _ = _journal(tmp_path)
    assert not rec.crashed and rec.unfinished == [] and rec.finished == [] and rec.last_serial == 105


@pytest.mark.parametrize("damage", ["torn tail", "bad middle line", "binary junk", "empty"])
def test_a_damaged_journal_is_reported_once_and_set_aside(tmp_path, damage):
    j, _, _ = _journal(tmp_path)
    for i in range(5):
        j.note(_cmd(i), "q")
    j.sync()
    _crash(j)
    path = tmp_path / file_name("Restarter", 1)
    data = path.read_bytes()
    lines = data.splitlines(keepends=True)
    if damage == "torn tail":
        data = data[:-7]  # the last record cut short (never synced: its ack never went out)
    elif damage == "bad middle line":
        data = b"".join([*lines[:2], lines[2].replace(b"c2", b"c9"), *lines[3:]])  # CRC no longer matches
    elif damage == "binary junk":
        data = bytes(random.Random(1).randrange(256) for _ in range(3000))
    else:
        data = b""
    path.write_bytes(data)
    j, rec, logs = _journal(tmp_path)
    aside = sorted(p.name for p in tmp_path.glob("*.damaged-*"))
    if damage == "empty":
        assert logs == [] and aside == [] and not rec.crashed
        return
    assert len(logs) == 1 and "damaged line" in logs[0] and len(aside) == 1 and aside[0] in logs[0], logs
    want = {"torn tail": ["c0", "c1", "c2", "c3"], "bad middle line": ["c0", "c1", "c3", "c4"], "binary junk": []}
    assert [e.cmd_id for e in rec.unfinished] == want[damage]
    j.note(_cmd(9), "q")  # the new journal works
    j.sync()
    _crash(j)
    _j, rec, logs = _journal(tmp_path)
    assert logs == [] and rec.unfinished[-1].cmd_id == "c9"


def test_an_oversized_journal_is_set_aside_unread(tmp_path, monkeypatch):
    import rapid_runtime.journal as journal
    monkeypatch.setattr(journal, "MAX_READ", 4096)
    (tmp_path / file_name("Restarter", 1)).write_bytes(b"x" * 5000)
    j, rec, logs = _journal(tmp_path)
    assert len(logs) == 1 and "damaged" in logs[0] and rec.unfinished == [] and rec.crashed
    assert len(list(tmp_path.glob("*.damaged-*"))) == 1
    j.close(clean=True)


def test_the_journal_stays_bounded(tmp_path):
    window = 16
    j, _, _ = _journal(tmp_path, window)
    for i in range(400):
        j.note(_cmd(i), "q")
        j.note(_cmd(i), "x")
        j.note(_cmd(i), "c", "ACK_COMPLETED_OK", "")
        if i % 8 == 7:  # a batch of 8 commands, one sync (compaction happens in sync)
            j.sync()
            assert j.lines <= COMPACT_FACTOR * window + 16 + 3 * 8
    _crash(j)
    size = (tmp_path / file_name("Restarter", 1)).stat().st_size
    assert size < (COMPACT_FACTOR * window + 20) * 120
    _j, rec, _ = _journal(tmp_path, window)
    assert [e.cmd_id for e in rec.finished] == [f"c{i}" for i in range(400 - window, 400)]


def test_a_folder_that_cannot_be_used_means_no_journal_not_a_crash(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    logs: list[str] = []
    j, rec = Journal.open(blocker / "journal", "Restarter", 1, 16, logs.append)
    assert j is None and not rec.crashed and len(logs) == 1 and "running without one" in logs[0]
    j1, _, _ = _journal(tmp_path)
    j2, rec, = Journal.open(tmp_path, "Restarter", 1, 16, logs.append)  # the same file: another bridge holds it
    assert j2 is None and "in use" in logs[-1]
    j1.close(clean=True)


def test_rapidgen_cmd_waiting_across_a_kill_learns_the_outcome(tmp_path):
    """rapidgen cmd (the generated package, importable) sends a long queued command and waits;
    the bridge is killed (SIGKILL) while the command runs and started again: cmd gets the
    restart's answer from the new bridge's ack history and exits 1 with it."""
    import time

    from tests.field.restart_asset import PACKAGE, env_for
    pydir = generate(tmp_path / "gen")
    env = env_for(pydir)
    executions = tmp_path / "executions"
    argv = [sys.executable, "-m", "tests.field.restart_bridge", str(pydir), str(executions), "--domain",
            str(DOMAIN + 1), "--journal", str(tmp_path / "journal")]

    def start() -> subprocess.Popen:
        proc = subprocess.Popen(argv, cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        line = proc.stdout.readline() if proc.stdout else ""
        assert line.startswith("bridge ready"), line
        return proc

    bridge = start()
    cmd = subprocess.Popen([sys.executable, "-m", "rapidgen", "cmd", PACKAGE, "Belt",
                            "work", "ms=8000", "--action", "APPEND", "--id", "long-1", "--domain", str(DOMAIN + 1),
                            "--timeout", "60"], cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           text=True)
    try:
        end = time.monotonic() + 60
        while not (executions.exists() and "long-1" in executions.read_text()):
            assert time.monotonic() < end and cmd.poll() is None, cmd.communicate()
            time.sleep(0.05)
        bridge.kill()
        bridge.wait()
        bridge = start()
        out, err = cmd.communicate(timeout=90)
    finally:
        for p in (cmd, bridge):
            if p.poll() is None:
                p.kill()
                p.wait()
    assert cmd.returncode == 1, out + err
    assert "asset restarted while it ran" in out + err and "EXEC_FAILED" in out + err, out + err
    assert "sending it again" not in err, err  # the journal answered it: nothing to send again
    assert executions.read_text().split() == ["long-1"]


RESEND_DOMAIN, CPP_RESEND_DOMAIN = 84, 85  # one each: a killed bridge's participant outlives it a lease


def _lost_in_a_killed_bridge(tmp_path: Path, domain: int, ground: list[str], words: list[str], pydir: Path,
                             env: dict, ground_env: dict) -> list[str]:
    """A command the bridge took from its DDS reader but never journaled (RESTART_STALL holds
    it there, as a process being killed leaves it) is gone with the process; the restarted
    bridge knows nothing of it. The ground program (`ground` + `words`, cmdId lost-1),
    waiting, sees the asset come back without an answer, sends the command again with the
    same cmdId and says so; the new bridge answers it OK. Returns the bridge's EXECFILE lines."""
    import time

    executions = tmp_path / "executions"
    argv = [sys.executable, "-m", "tests.field.restart_bridge", str(pydir), str(executions), "--domain",
            str(domain), "--journal", str(tmp_path / "journal")]

    def start(extra: dict) -> subprocess.Popen:
        proc = subprocess.Popen(argv, cwd=ROOT, env=dict(env, **extra), stdout=subprocess.PIPE,
                                stderr=subprocess.DEVNULL, text=True)
        line = proc.stdout.readline() if proc.stdout else ""
        assert line.startswith("bridge ready"), line
        return proc

    bridge = start({"RESTART_STALL": "lost-"})
    cmd = subprocess.Popen([*ground, *words, "--id", "lost-1", "--domain", str(domain), "--timeout", "60"], cwd=ROOT,
                           env=ground_env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        end = time.monotonic() + 60
        while not (executions.exists() and "stalled lost-1" in executions.read_text()):
            assert time.monotonic() < end and cmd.poll() is None, cmd.communicate()
            time.sleep(0.05)
        bridge.kill()
        bridge.wait()
        bridge = start({})
        out, err = cmd.communicate(timeout=120)
    finally:
        for p in (cmd, bridge):
            if p.poll() is None:
                p.kill()
                p.wait()
    assert cmd.returncode == 0 and "COMPLETED OK" in out, out + err
    resends = [ln for ln in err.splitlines() if "sending it again with the same cmdId" in ln]
    # one for the comeback; on a slow machine maybe one before it for the stalled bridge's silence
    assert sum("came back" in ln for ln in resends) == 1 and len(resends) <= 2, err
    return executions.read_text().splitlines()


def test_rapidgen_cmd_sends_again_a_command_lost_in_a_killed_bridge(tmp_path):
    from tests.field.restart_asset import PACKAGE, env_for
    pydir = generate(tmp_path / "gen")
    env = env_for(pydir)
    ran = _lost_in_a_killed_bridge(tmp_path, RESEND_DOMAIN, [sys.executable, "-m", "rapidgen", "cmd", PACKAGE],
                                   ["Belt", "work", "ms=100", "--action", "APPEND"], pydir, env, env)
    assert ran == ["stalled lost-1", "lost-1"]  # run once, by the new bridge


def test_cpp_cmd_sends_again_a_command_lost_in_a_killed_bridge(tmp_path, tmp_path_factory):
    """The same with the C++ ground program: K10's rapid_k10red_cmd and K10's Python bridge
    (the stall served on its package: RESTART_PACKAGE), requestControl lost in the old one."""
    from tests.cpp_runtime import build as B
    from tests.runtime.live import SEEDS, env_for, python_dir
    program = B.k10_cmd(tmp_path_factory)
    pydir = python_dir("k10")
    env = dict(env_for(pydir, SEEDS["k10"]), RESTART_PACKAGE=SEEDS["k10"],
               PYTHONPATH=os.pathsep.join([str(pydir), str(ROOT / "runtime"), str(ROOT)]))
    ran = _lost_in_a_killed_bridge(tmp_path, CPP_RESEND_DOMAIN, [str(program), "--source", "RapidWorkbench"],
                                   ["AccessControl", "requestControl"], pydir, env, B.dds_env())  # rapid_local
    assert ran == ["stalled lost-1"]  # the old bridge took it and died; the new one answered it


# ---- the C++ runtime's journal: the same file format ------------------------------------------------

def _probe(tmp_path: Path) -> Path:
    import shutil
    if shutil.which("g++") is None:
        pytest.skip("g++ not installed")
    exe = tmp_path / "probe"
    res = subprocess.run(["g++", "-std=c++17", "-O0", "-Wall", "-Wextra", "-Werror",
                          f"-I{ROOT / 'runtime' / 'cpp' / 'include'}", str(ROOT / "tests" / "field" /
                                                                           "restart_journal_probe.cpp"),
                          str(ROOT / "runtime" / "cpp" / "src" / "journal.cpp"), "-o", str(exe)],
                         capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr[-3000:]
    return exe


def test_the_cpp_journal_reads_and_writes_the_python_format(tmp_path):
    from rapid_runtime.journal import _parse
    probe = _probe(tmp_path)
    folder = tmp_path / "journal"
    # Python writes, C++ reads
    j, _, _ = _journal(folder)
    j.start(300)
    j.note(_cmd(1), "q")
    j.note(_cmd(2), "x")
    j.note(Cmd("c3", "Ground", "Belt", "work", src_name="Ground", asset_name="Restarter", serial=7), "c",
           "ACK_COMPLETED_EXEC_FAILED", 'said "\u00e9\u2603\U0001f680"')
    j.sync()
    _crash(j)
    res = subprocess.run([str(probe), "read", str(folder)], capture_output=True, text=True, timeout=60)
    assert res.returncode == 0, res.stdout + res.stderr
    lines = res.stdout.splitlines()
    head = json.loads(lines[0][9:])  # the probe's own summary record (kind "r")
    recs = [head, *(_parse((ln + "\n").encode()) for ln in lines[1:])]  # the journal's records: CRC and shape
    assert None not in recs, res.stdout
    assert head["crashed"] == 1 and head["serial"] == 300
    assert [(r["k"], r["id"]) for r in recs[1:]] == [("q", "c1"), ("x", "c2"), ("c", "c3")]
    assert recs[3]["m"] == 'said "\u00e9\u2603\U0001f680"' and recs[3]["c"] == "ACK_COMPLETED_EXEC_FAILED"
    # C++ writes (after the read above, which left no stop record), Python reads
    res = subprocess.run([str(probe), "write", str(folder)], capture_output=True, text=True, timeout=60)
    assert res.returncode == 0, res.stdout + res.stderr
    _j, rec, logs = _journal(folder)
    assert logs == [] and rec.crashed and rec.last_serial == 300
    assert [(e.cmd_id, e.state) for e in rec.unfinished] == [("c1", "q"), ("c2", "x"), ("cpp-1", "q"), ("cpp-2", "x")]
    assert [(e.cmd_id, e.message) for e in rec.finished] == [("c3", 'said "\u00e9\u2603\U0001f680"'),
                                                             ("cpp-3", 'done "\u00e9\u2603"')]
    _crash(_j)
    # a torn tail: C++ reports it once and sets the file aside
    with open(folder / file_name("Restarter", 1), "ab") as fh:
        fh.write(b'0badc0de {"k":"q","id":"torn')
    res = subprocess.run([str(probe), "read", str(folder)], capture_output=True, text=True, timeout=60)
    logs = [ln for ln in res.stdout.splitlines() if ln.startswith("log ")]
    assert res.returncode == 0 and len(logs) == 1 and "damaged line" in logs[0], res.stdout
    assert len(list(folder.glob("*.damaged-*"))) == 1


def test_cmd_sends_again_only_for_a_new_asset_participant_and_at_most_three_times():
    """rapidgen/cmd/recover.py without DDS: a new participant that only reads commands (a spy)
    is not the asset; one with a command reader and an ack writer is, and the command is due
    again once it stayed silent `settle` seconds; a later newcomer restarts that wait; never
    more than MAX_RESENDS."""
    from types import SimpleNamespace

    from rapidgen.cmd.recover import MAX_RESENDS, AssetWatch

    readers, writers = {1: "old"}, {1: "old"}  # instance handle -> participant key

    def side(table: dict):
        return (lambda: list(table)), (lambda h: SimpleNamespace(participant_key=table[h]))

    r_list, r_data = side(readers)
    w_list, w_data = side(writers)
    commander = SimpleNamespace(writer=SimpleNamespace(get_matched_subscriptions=r_list,
                                                       get_matched_subscription_data=r_data),
                                ack_reader=SimpleNamespace(get_matched_publications=w_list,
                                                           get_matched_publication_data=w_data))
    watch = AssetWatch(commander, rtt=1.0, now=0.0)
    assert watch.known == {"old"} and watch.settle == 5.0  # 3 s + 2 round trips
    readers[2] = "spy"
    assert not watch.due(0.0, True) and not watch.due(100.0, True)  # reads commands, writes no acks
    readers[3], writers[3] = "new", "new"
    assert not watch.due(10.0, True) and not watch.due(14.9, True)
    readers[4], writers[4] = "newer", "newer"  # came back again: its history must arrive too
    assert not watch.due(15.0, True) and not watch.due(19.9, True) and watch.due(20.0, True)
    assert watch.resends == 1 and "came back" in watch.why
    assert not watch.due(40.0, True)  # nothing new since: once per comeback
    for n in range(5, 5 + MAX_RESENDS + 1):
        readers[n], writers[n] = f"p{n}", f"p{n}"
        watch.due(100.0 * n, True)
        watch.due(100.0 * n + 6, True)
    assert watch.resends == MAX_RESENDS


def test_cmd_sends_again_a_command_the_asset_never_answered():
    """No ack at all 5 s + 2 round trips after the send: the command never reached the
    asset (a writer matched before the asset's reader knew it); sent again, the wait starts
    over from that send, at most MAX_RESENDS times; an answered command is never resent
    for silence, nor one whose asset is not there."""
    from types import SimpleNamespace

    from rapidgen.cmd.recover import MAX_RESENDS, AssetWatch

    key = {1: "asset"}
    side = SimpleNamespace(get_matched_subscriptions=lambda: list(key), get_matched_publications=lambda: list(key),
                           get_matched_subscription_data=lambda h: SimpleNamespace(participant_key=key[h]),
                           get_matched_publication_data=lambda h: SimpleNamespace(participant_key=key[h]))
    watch = AssetWatch(SimpleNamespace(writer=side, ack_reader=side), rtt=2.6, now=100.0)
    assert watch.unanswered == 10.2  # 5 s + 2 round trips
    assert not watch.due(110.1, False) and not watch.due(500.0, True)  # answered: only a comeback counts
    key.clear()
    assert not watch.due(110.3, False)  # the asset is not there: a resend would reach nobody
    key[1] = "asset"
    assert watch.due(110.2, False) and watch.resends == 1 and "has not answered within 10.2 s" in watch.why
    assert not watch.due(120.3, False) and watch.due(120.4, False)  # counted from the resend
    assert watch.due(131.0, False) and watch.resends == MAX_RESENDS and not watch.due(1000.0, False)
