"""The protocol specification (runtime/spec/cases/*.yaml) replayed by the Python runtime,
without DDS: each case drives a CommandManager on the seed's generated tables through a
collecting outbox and scripted handlers (runtime/spec/README.md). The C++ runtime replays
the same cases (tests/cpp_runtime/test_spec_cases.cpp)."""
from __future__ import annotations

import copy
import errno
import fnmatch
import math
import os
import threading
import time
import zlib
from pathlib import Path

import pytest

from rapid_runtime.command import Cmd
from rapid_runtime.handlers import CommandFailed
from rapid_runtime.intake import Intake
from rapid_runtime.journal import Journal, Recovered, default_dir, start_serials
from rapid_runtime.manager import COMMAND_WINDOW, CommandManager
from rapidgen.protocol_cases import load_cases, seed_tables

WAIT = float(os.environ.get("RAPID_SPEC_WAIT", "10"))  # bench/mutation.py shortens it
NOT_IMPLEMENTED = "not implemented"
CASES = load_cases()


class Outbox:
    """What the manager writes, as a ground tool would see it (plus the log and retirements)."""

    def __init__(self) -> None:
        self.cond = threading.Condition()
        self.acks: dict[str, list[tuple[str, str, str]]] = {}
        self.first: list[str] = []  # cmdIds in the order of their first ack
        self.stopped = 0  # the asset's shutdown callback's calls (Admin/shutdown)
        self.queue: tuple[int, list[str], list[str]] | None = None
        self.statuses: dict[str, str] = {}  # the last QueueState's pending and active records
        self.completed: list[str] = []  # the last QueueState's completed records' cmdIds
        self.access: tuple[str, list[str]] | None = None
        self.retired: list[str] = []
        self.logs: list[str] = []

    def _changed(self) -> None:
        self.cond.notify_all()

    def ack(self, cmd, status, completed, message):
        with self.cond:
            if cmd.cmd_id not in self.acks:
                self.first.append(cmd.cmd_id)
            self.acks.setdefault(cmd.cmd_id, []).append(
                (status.removeprefix("ACK_"), completed.removeprefix("ACK_COMPLETED_"), message))
            self._changed()

    def queue_state(self, code, pending, active, completed):
        with self.cond:
            self.queue = (code, [c.cmd_id for c, *_ in pending], [c.cmd_id for c, *_ in active])
            self.statuses = {c.cmd_id: status for c, _result, status in [*pending, *active]}
            self.completed = [c.cmd_id for c, *_ in completed]
            self._changed()

    def access_state(self, controller, requestors):
        with self.cond:
            self.access = (controller, list(requestors))
            self._changed()

    def retire(self, cmd):
        with self.cond:
            self.retired.append(cmd.cmd_id)
            self._changed()

    def log(self, text):
        with self.cond:
            self.logs.append(text)
            self._changed()

    def stop(self):
        with self.cond:
            self.stopped += 1
            self._changed()


class Scripted:
    """Every handler method: behaves as the case's `handler:` for the cmdId says."""

    def __init__(self, cond: threading.Condition) -> None:
        self.cond = cond  # the outbox's: a call wakes the expectations too
        self.behaviour: dict[str, dict] = {}
        self.released: dict[str, threading.Event] = {}
        self.calls: list[tuple[str, list]] = []
        self.lock = threading.Lock()

    def release_of(self, cmd_id: str) -> threading.Event:
        with self.lock:
            return self.released.setdefault(cmd_id, threading.Event())

    def __getattr__(self, method: str):
        if method.startswith("__"):
            raise AttributeError(method)
        return self._run

    def _run(self, ctx, **kwargs):
        cid = ctx.cmd.cmd_id
        with self.cond:
            self.calls.append((cid, list(kwargs.values())))
            self.cond.notify_all()
        h = self.behaviour.get(cid, {"kind": "ok", "text": "", "texts": []})
        kind, released = h["kind"], self.release_of(cid)
        if kind == "ok":  # (no text: a handler that returns nothing, None in Python)
            return h["text"] or None
        if kind == "fail":
            raise CommandFailed(h["text"])
        if kind == "error":
            raise RuntimeError(h["text"])
        if kind == "odd_error":  # (not an Exception: what a C++ handler's `throw 42` is there)
            raise OddError()
        if kind == "not_implemented":
            raise CommandFailed(NOT_IMPLEMENTED)
        if kind == "progress":
            for text in h["texts"]:
                ctx.progress(text)
            return ""
        if kind == "block":
            while not released.is_set():
                if not ctx.sleep(0.005):
                    return None  # told to stop: returns (CANCELED, or REQUEUED when preempted)
            return "released"
        if kind == "stubborn":
            released.wait(60)
            if h["text"]:  # (its progress once released: after its answer, it must go nowhere)
                ctx.progress(h["text"])
            return "released"
        raise AssertionError(f"unknown handler behaviour {kind}")


def _same(seen, want) -> bool:
    if isinstance(want, float) or isinstance(seen, float):
        try:
            return math.isclose(float(seen), float(want), rel_tol=1e-6, abs_tol=1e-9)
        except (TypeError, ValueError):
            return False
    if isinstance(want, list):
        return isinstance(seen, (list, tuple)) and len(seen) == len(want) and all(map(_same, seen, want))
    return seen == want


def _ack_matches(seen: tuple[str, str, str], want: dict) -> bool:
    status, completion, message = seen
    if status != want["status"] or (want["completion"] is not None and completion != want["completion"]):
        return False
    if want["message"] is None:
        return True
    return message.startswith(want["message"]) if want["prefix"] else message == want["message"]


class OddError(BaseException):
    """A handler's failure that is not an Exception (the `odd_error` behaviour)."""


class Dead:
    """The outbox of a crashed manager: what its handler threads still do is not seen."""

    def __getattr__(self, name: str):
        return lambda *args: None


class Replay:
    def __init__(self, case: dict, state_dir: Path) -> None:
        self.case = case
        self.out = Outbox()
        self.handlers = Scripted(self.out.cond)
        self.tables = seed_tables(case["asset"])
        if case["asset_name"] is not None:  # (the seed's tables under another asset name)
            self.tables = copy.copy(self.tables)
            self.tables.name = case["asset_name"]
        # a case that restarts the asset, or starts on a journal, runs with the restart journal
        # as the bridge does, in a state folder not made yet (the runtime makes it) unless
        # the case's journal is written there first
        self.journal_dir = None
        if case["journal"] is not None or case["state"] is not None or any(s["op"] == "restart" for s in case["steps"]):
            self.journal_dir = state_dir / (case["state"]["dir"] if case["state"] else "state/rapid_runtime")
        if case["journal"] is not None:
            self.journal_dir.mkdir(parents=True)
            (self.journal_dir / case["journal"]["file"]).write_bytes(case["journal"]["text"].encode())
            if case["journal"]["new"] is not None:  # (what a crash in the middle of a compaction left)
                (self.journal_dir / (case["journal"]["file"] + ".new")).write_bytes(case["journal"]["new"].encode())
        self.serial, self.started = 0, 0.0  # the configs' serial at the latest start, and when
        self.m = self.manager()
        # a case with a door offers commands there as the bridge's reader does; shut until `open`
        self.intake = None if case["door"] is None else Intake(self.m, self.out.log, inline=True, **case["door"])
        self.writers: dict[str, int] = {}  # a case's writer names as writer ids (0 is the shared FIFO's)

    def manager(self) -> CommandManager:
        journal, recovered = None, None
        if self.journal_dir is not None:
            window = self.case["options"].get("window", COMMAND_WINDOW)
            # (a case with `state:` starts the asset without a folder: the runtime's default one)
            folder = default_dir() if self.case["state"] is not None else self.journal_dir
            journal, recovered = Journal.open(folder, self.tables.name, 0, window, self.out.log)
            assert journal is not None, self.out.logs
        # the configs' serial as the bridge chooses it (start_serials): the one asked for, else
        # past the journal's last, else the clock's
        self.started = time.time()
        self.serial = start_serials(self.case["serial"], recovered or Recovered(), journal).start
        m = CommandManager(self.tables, self.handlers, self.out, journal=journal, on_shutdown=self.out.stop,
                           **self.case["options"])
        if recovered is not None and recovered.crashed:
            m.restore(recovered)
        return m

    def crash(self) -> None:
        """The process dies: the journal as the disk has it, nothing more written by the old manager."""
        old = self.m
        with old.lock:  # (closing: the dead manager starts nothing more, as a dead process would)
            journal, old.journal, old.out, old.closing = old.journal, None, Dead(), True
        if journal is not None:
            os.close(journal.fd)  # (no clean stop record: the next start recovers)
        self.m = self.manager()

    def stop_and_start(self) -> None:
        """A clean stop as the bridge's (every command answered, the journal closed with its
        stop record), then a start on that journal."""
        old = self.m
        old.shutdown(5.0)
        with old.lock:
            journal, old.journal, old.out = old.journal, None, Dead()
        if journal is not None:
            journal.close(clean=True)
        self.m = self.manager()

    def cmd(self, s: dict) -> Cmd:
        args = tuple((a["type"], tuple(a["value"]) if isinstance(a["value"], list) else a["value"]) for a in s["args"])
        return Cmd(s["id"], s["src"], s["subsystem"], s["name"], args, s["action"], s["target"], s["src_name"], s["asset"])

    def finished(self, cmd_id: str) -> bool:
        with self.out.cond:
            return any(a[0] == "COMPLETED" for a in self.out.acks.get(cmd_id, []))

    def until(self, what: str, ok, seen) -> None:
        # woken by every write to the outbox and handler call; the manager's own view (pending)
        # changes with them, the short slices only cover a change made between two writes
        end = time.monotonic() + WAIT
        with self.out.cond:
            while not ok() and time.monotonic() < end:
                self.out.cond.wait(0.05)
            if not ok():
                pytest.fail(f"{self.case['file']}:{self.case['line']} {self.case['name']!r}: "
                            f"expected {what}; seen {seen()}")

    def step(self, s: dict) -> None:
        op, out = s["op"], self.out
        if op in ("send", "offer"):
            # a send's behaviour is its command's: a repeat of a cmdId still live must not change it
            if s["id"] not in self.handlers.behaviour or self.finished(s["id"]):
                self.handlers.behaviour[s["id"]] = s["handler"]
            if op == "send":
                self.m.receive(self.cmd(s))
            else:
                self.intake.offer(self.cmd(s), self.writers.setdefault(s["writer"], len(self.writers) + 1))
        elif op == "open":
            self.intake.start()
        elif op == "refuse":
            self.m.refuse(self.cmd(s), s["why"])
        elif op == "release":
            self.handlers.release_of(s["id"]).set()
        elif op == "restart":
            self.stop_and_start() if s["clean"] else self.crash()
        elif op == "idle":
            assert self.m.wait_idle(WAIT), "the manager never became idle"
        elif op == "shutdown":
            self.m.shutdown(s["timeout_ms"] / 1000.0 if s["timeout_ms"] >= 0 else 5.0)
        elif op == "acks":
            want = s["acks"]
            got = lambda: out.acks.get(s["id"], [])  # noqa: E731
            self.until(f"acks of {s['id']}: {want}",
                       lambda: len(got()) == len(want) and all(map(_ack_matches, got(), want)), got)
        elif op == "queue":
            def queue_ok():
                if out.queue is None:
                    return False
                code, pending, active = out.queue
                return (s.get("code", code) == code and s.get("pending", pending) == pending
                        and s.get("active", active) == active and s.get("completed", out.completed) == out.completed
                        and all(
                            out.statuses.get(cid) == status for cid, status in s.get("statuses", {}).items()))
            self.until(f"QueueState {s}", queue_ok, lambda: (out.queue, out.statuses, out.completed))
        elif op == "control":
            def control_ok():
                return out.access is not None and s.get("controller", out.access[0]) == out.access[0] and \
                    s.get("requestors", out.access[1]) == out.access[1]
            self.until(f"AccessControlState {s}", control_ok, lambda: out.access)
        elif op == "calls":
            want = [(c["id"], c["values"]) for c in s["calls"]]
            calls = lambda: self.handlers.calls  # noqa: E731
            self.until(f"handler calls {want}", lambda: len(calls()) == len(want) and all(
                cid == wid and _same(list(vals), wvals) for (cid, vals), (wid, wvals) in zip(calls(), want)), calls)
        elif op == "retired":
            self.until(f"retired {s['ids']}", lambda: out.retired == s["ids"], lambda: out.retired)
        elif op == "pending":
            ids = lambda: [r.cmd.cmd_id for r in self.m.pending.items]  # noqa: E731
            self.until(f"pending {s['ids']}", lambda: ids() == s["ids"], ids)
        elif op == "log":
            self.until(f"a log line with {s['text']!r}", lambda: any(s["text"] in line for line in out.logs),
                       lambda: out.logs[-10:])
        elif op == "log_count":  # (waits for that many, then no more)
            count = lambda: sum(s["text"] in line for line in out.logs)  # noqa: E731
            self.until(f"{s['count']} log lines with {s['text']!r}", lambda: count() >= s["count"], lambda: out.logs[-10:])
            assert count() == s["count"], f"{self.case['name']!r}: {count()} log lines with {s['text']!r}: {out.logs[-10:]}"
        elif op == "disk":
            self.disk.failing, self.disk.full = s["failing"], s["full"]
        elif op == "no_log":  # (at this step: what came before it has been waited for)
            with out.cond:
                found = [line for line in out.logs if s["text"] in line]
            assert not found, f"{self.case['file']}:{self.case['line']} {self.case['name']!r}: logged {found[:3]}"
        elif op == "order":
            firsts = lambda: [cid for cid in out.first if cid in s["ids"]]  # noqa: E731
            self.until(f"first acks in the order {s['ids']}", lambda: len(firsts()) == len(s["ids"]), firsts)
            assert firsts() == s["ids"], f"{self.case['name']!r}: first acks in the order {firsts()}, not {s['ids']}"
        elif op == "stopped":
            self.until(f"the shutdown callback called {s['count']} times", lambda: out.stopped >= s["count"],
                       lambda: out.stopped)
            assert out.stopped == s["count"], f"{self.case['name']!r}: the shutdown callback called {out.stopped} times"
        elif op == "serial":
            ok = abs(self.serial - self.started) <= 2 if s["clock"] else self.serial == s["value"]
            assert ok, f"{self.case['name']!r}: the configs' serial is {self.serial}, not {'the clock' if s['clock'] else s['value']}"
        elif op == "files":
            names = sorted(p.name for p in self.journal_dir.iterdir()) if self.journal_dir.exists() else []
            ok = len(names) == len(s["names"]) and all(any(fnmatch.fnmatchcase(n, p) for p in s["names"]) for n in names) \
                and all(any(fnmatch.fnmatchcase(n, p) for n in names) for p in s["names"])
            assert ok, f"{self.case['name']!r}: the journal folder holds {names}, not {s['names']}"
        elif op == "journal_file":  # (at this step: what came before it has been waited for)
            path = self.journal_dir / s["file"]
            if s["mode"] is not None:
                mode = f"0{path.stat().st_mode & 0o777:03o}"
                assert mode == s["mode"], f"{self.case['name']!r}: the journal's mode is {mode}, not {s['mode']}"
            if s["lines"] is not None:
                lines = path.read_bytes().splitlines(keepends=True)
                if s["tail"]:  # (the file's last lines only)
                    lines = lines[max(0, len(lines) - len(s["lines"])):]
                assert journal_lines_match(lines, s["lines"]), \
                    f"{self.case['name']!r}: the journal holds {[ln.decode(errors='replace') for ln in lines]}, not {s['lines']}"
        else:
            raise AssertionError(f"unknown step {op}")

    def close(self) -> None:
        if self.intake is not None:
            self.intake.stop()
        for event in list(self.handlers.released.values()):
            event.set()
        for cid in list(self.handlers.behaviour):
            self.handlers.release_of(cid).set()
        self.m.shutdown(2.0)


class Disk:
    """The journal's disk for a case's `disk` steps: its fdatasync fails (EIO) while `failing`,
    a write to a journal file (`*.journal*`) fails (ENOSPC) while `full`."""

    def __init__(self) -> None:
        self.failing = self.full = False
        self.real_fdatasync, self.real_write = os.fdatasync, os.write

    def fdatasync(self, fd: int) -> None:
        if self.failing:
            raise OSError(errno.EIO, os.strerror(errno.EIO))
        self.real_fdatasync(fd)

    def write(self, fd: int, data) -> int:
        if self.full:
            try:
                journal = ".journal" in os.readlink(f"/proc/self/fd/{fd}")
            except OSError:
                journal = False
            if journal:
                raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return self.real_write(fd, data)


def journal_lines_match(lines: list[bytes], want: list[list[str]]) -> bool:
    """Each line a sound record (its newline, its CRC) holding the fields `want` spells, between
    `{` or `,` and `,` or `}` (the order of a record's keys is not compared)."""
    if len(lines) != len(want):
        return False
    for raw, fields in zip(lines, want):
        if not raw.endswith(b"\n") or raw[8:9] != b" " or f"{zlib.crc32(raw[9:-1]):08x}".encode() != raw[:8]:
            return False
        body = raw[9:-1].decode("ascii", errors="replace")
        if not all(any(f"{a}{f}{b}" in body for a in "{," for b in ",}") for f in fields):
            return False
    return True


@pytest.mark.parametrize("case", CASES, ids=[f"{c['file'][:-5]}:{c['name']}" for c in CASES])
def test_case(case, tmp_path, monkeypatch):
    if case["state"] is not None:  # (the journal's default folder named by these, in tmp_path)
        for var in case["state"]["unset"]:
            monkeypatch.delenv(var, raising=False)
        for var, rel in case["state"]["set"].items():
            monkeypatch.setenv(var, str(tmp_path / rel))
    if case["steps"][0]["op"] == "refused":  # (its only step: the manager refuses the options)
        with pytest.raises(ValueError) as refused:
            Replay(case, tmp_path)
        assert case["steps"][0]["text"] in str(refused.value), f"{case['name']!r}: refused with {refused.value}"
        return
    disk = Disk()
    if any(s["op"] == "disk" for s in case["steps"]):
        monkeypatch.setattr(os, "fdatasync", disk.fdatasync)
        monkeypatch.setattr(os, "write", disk.write)
    replay = Replay(case, tmp_path)
    replay.disk = disk
    try:
        for s in case["steps"]:
            replay.step(s)
    finally:
        disk.failing = disk.full = False
        replay.close()


@pytest.mark.parametrize("steps, error", [
    ("[{offer: {writer: w, id: a, cmd: Admin/noOp}}]", "`offer` needs the case's `door:`"),
    ("[{open: true}]", "`open` needs the case's `door:`"),
])
def test_a_door_step_without_a_door_is_a_located_error(tmp_path, steps, error):
    from rapidgen.protocol_cases import CaseError, load_file
    path = tmp_path / "bad.yaml"
    path.write_text(f"asset: k10\ncases:\n  - name: no door here\n    steps: {steps}\n")
    with pytest.raises(CaseError, match=rf"bad.yaml:4:\d+: {error}"):
        load_file(path)


def test_a_door_case_cannot_restart(tmp_path):
    from rapidgen.protocol_cases import CaseError, load_file
    path = tmp_path / "bad.yaml"
    path.write_text("asset: k10\ncases:\n  - name: door and restart\n    door: {}\n    steps:\n"
                    "      - open: true\n      - restart: true\n")
    with pytest.raises(CaseError, match=r"bad.yaml:7:\d+: a case with a `door:` cannot restart"):
        load_file(path)
