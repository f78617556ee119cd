"""The restart journal: what the bridge promised, on disk before the ack that promises it.

A bridge that dies (crash, kill -9, power cut) must not leave a command without an outcome.
Every command the manager answers is written here, one line per step, before its ack goes
out (manager.py holds acks back until sync() returned):

    q   accepted into the queue (before QUEUED)
    x   running (before the first EXECUTING)
    c   its final outcome (before COMPLETED): completion and message
    s   a config serial issued (the next start's serials are larger)
    stop   a clean stop: every command was answered; the next start begins afresh

After a crash (the journal does not end with `stop`) the next start reads it back
(Recovered): each command still `q` is answered COMPLETED/CANCELED, each `x` EXEC_FAILED
(docs/runtime.md says why), the final acks of the last `window` finished commands are
written again (a ground tool that missed them, or joins late, gets them from the new
writer's history), their cmdIds count as seen (a retried command does not run twice), and
config serials continue above the last one issued.

On disk: text lines `<crc32 of the JSON, 8 hex digits> <JSON object>\\n` (ASCII: json.dumps
escapes the wire's strings). A line whose CRC or shape is wrong (a torn write at a power cut,
a damaged disk) is skipped; if any is, the file is reported in one log line and renamed
`<name>.damaged-<time>` (kept for a human), and a new journal is written from the lines that
were sound. The file is compacted (rewritten with the live commands and the last `window`
outcomes, then renamed over the old one) once it holds COMPACT_FACTOR times that many lines.

Durability: one fdatasync per batch of records, before the acks of that batch are written
(the intake hands the manager up to 32 commands at a time, so a flood costs one sync per
batch, not per command). Compaction fsyncs the new file before the rename and the folder
after it. Same format as the C++ runtime's journal (runtime/cpp, when it has one).

Memory: the journal remembers the last `window` outcomes for as long as the bridge runs, so
each is a tuple (Entry) sharing its strings with the command it came from (cmdId, and the
names messages.command_in shares), kept in a plain dict with a deque for its order (an
OrderedDict costs twice as much), and compaction writes its lines a few at a time (one
rewrite building every line at once left ~2 MiB of freed but unreturned memory behind).
"""
from __future__ import annotations

import collections
import fcntl
import json
import os
import re
import time
import zlib

from rapid_runtime.configs import Serials
from dataclasses import dataclass, field
from pathlib import Path
from typing import NamedTuple

COMPACT_FACTOR = 4  # compact once the file holds this many times window lines (plus live ones)
# A journal never grows past a few MB (compaction); a bigger file is not ours to read whole:
# it is set aside unread.
MAX_READ = 64 * 1024 * 1024
REWRITE_CHUNK = 256  # records per write() when compacting (what one write holds in memory)
STATE_ENV = "RAPID_STATE_DIR"  # the journal's default folder, before XDG_STATE_HOME


def default_dir() -> Path:
    """$RAPID_STATE_DIR, else $XDG_STATE_HOME/rapid_runtime, else ~/.local/state/rapid_runtime."""
    if os.environ.get(STATE_ENV):
        return Path(os.environ[STATE_ENV])
    base = os.environ.get("XDG_STATE_HOME") or os.path.join(os.path.expanduser("~"), ".local", "state")
    return Path(base) / "rapid_runtime"


def file_name(asset: str, domain: int) -> str:
    """One journal per asset and domain (a test bridge on another domain has its own)."""
    return f"{re.sub(r'[^A-Za-z0-9_.-]', '_', asset)[:64]}-domain{int(domain)}.journal"


class Entry(NamedTuple):
    """A command as the journal knows it: enough to write its ack again. A tuple: the journal
    keeps `window` of them (a dataclass with a __dict__ costs half as much again)."""
    cmd_id: str
    src_name: str
    asset_name: str
    serial: int
    state: str  # q, x or c
    completion: str = ""
    message: str = ""


@dataclass
class Recovered:
    unfinished: list[Entry] = field(default_factory=list)  # in the order they were accepted
    finished: list[Entry] = field(default_factory=list)  # oldest first, the last `window`
    last_serial: int = 0
    crashed: bool = False  # the journal did not end with a clean stop


def restart_serial(requested: int | None, recovered: Recovered, now: float | None = None) -> int | None:
    """The configs' serial at a start: the one asked for; else, when the journal knows a
    serial, one past it and no smaller than the time in seconds (configs come back with a new
    serial, as the C++ and Rust runtimes' restart_serial); else None (the bridge's default)."""
    if requested is not None or recovered.last_serial <= 0:
        return requested
    return max(int(time.time() if now is None else now), recovered.last_serial + 1)


def start_serials(requested: int | None, recovered: Recovered, journal: Journal | None) -> Serials:
    """The configs' serials at a start, as every bridge chooses them: restart_serial's first
    serial (the start time when it is None), each serial issued recorded in `journal`, which
    gets the start record too."""
    serials = Serials(restart_serial(requested, recovered), issued=journal.serial if journal is not None else None)
    if journal is not None:
        journal.start(serials.start)
    return serials


def _record(e: Entry) -> dict:
    rec = {"k": e.state, "id": e.cmd_id, "src": e.src_name, "asset": e.asset_name, "serial": e.serial}
    if e.state == "c":
        rec.update(c=e.completion, m=e.message)
    return rec


def _line(record: dict) -> bytes:
    text = json.dumps(record, separators=(",", ":"), ensure_ascii=True)
    return f"{zlib.crc32(text.encode()):08x} {text}\n".encode()


_LONE_SURROGATE = re.compile("[\ud800-\udfff]")  # (json.loads joins the pairs: what is left is alone)


def _parse(raw: bytes) -> dict | None:
    """A sound line's record, or None (wrong CRC, not JSON, wrong shape, no newline)."""
    if not raw.endswith(b"\n") or len(raw) < 11 or raw[8:9] != b" ":
        return None
    body = raw[9:-1]
    try:
        if int(raw[:8], 16) != zlib.crc32(body):
            return None
        rec = json.loads(body.decode("ascii"))
    except (ValueError, UnicodeDecodeError):
        return None
    if not isinstance(rec, dict) or not isinstance(rec.get("k"), str):
        return None
    if rec["k"] in ("q", "x", "c"):
        ok = all(isinstance(rec.get(f), str) for f in ("id", "src", "asset")) and isinstance(rec.get("serial"), int)
        if rec["k"] == "c":
            ok = ok and isinstance(rec.get("c"), str) and isinstance(rec.get("m"), str)
        if ok:  # (a surrogate escaped on its own, in a journal no runtime wrote, is U+FFFD as in C++ and Rust)
            for f in ("id", "src", "asset", "c", "m"):
                if f in rec:
                    rec[f] = _LONE_SURROGATE.sub("\ufffd", rec[f])
        return rec if ok else None
    if rec["k"] == "s":
        return rec if isinstance(rec.get("serial"), int) else None
    return rec if rec["k"] in ("start", "stop") else None


class Journal:
    """Open with Journal.open(); None when it cannot be used (said in the log)."""

    def __init__(self, path: Path, fd: int, window: int, log) -> None:
        self.path, self.fd, self.window, self.log = path, fd, window, log
        self.live: dict[str, Entry] = {}  # cmdId -> accepted or running
        self.done: dict[str, Entry] = {}  # cmdId -> the last `window` outcomes, oldest first
        self._order: collections.deque[Entry] = collections.deque()  # done's entries, oldest first (and
        # entries since replaced there: a cmdId finished again), so the oldest goes in O(1)
        self.last_serial = 0
        self.lines = 0  # in the file now
        self.unsynced = False
        self.syncs = 0
        self.unwritten: OSError | None = None  # a record's write refused (a full disk) since the last sync

    # ---- opening and recovery -------------------------------------------------------------------
    @classmethod
    def open(cls, folder: str | Path, asset: str, domain: int, window: int, log) -> tuple["Journal | None", Recovered]:
        path = Path(folder) / file_name(asset, domain)
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_APPEND, 0o600)
        except OSError as exc:
            log(f"journal {path}: cannot be opened ({exc.strerror or exc}); running without one: "
                "commands in flight at a crash will have no outcome")
            return None, Recovered()
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(fd)
            log(f"journal {path}: in use by another bridge of this asset and domain; running without one")
            return None, Recovered()
        j = cls(path, fd, window, log)
        try:
            rec = j._recover()
        except OSError as exc:
            os.close(fd)
            log(f"journal {path}: cannot be read ({exc.strerror or exc}); running without one")
            return None, Recovered()
        return j, rec

    def _recover(self) -> Recovered:
        with open(self.path, "rb") as fh:
            raw = fh.read(MAX_READ + 1)
        records, bad, first_bad = [], 0, 0
        if len(raw) > MAX_READ:  # not a journal this runtime wrote: nothing in it is trusted
            raw, bad, first_bad = b"", 1, 1
        for n, line in enumerate(raw.splitlines(keepends=True), 1):
            rec = _parse(line)
            if rec is None:
                bad += 1
                first_bad = first_bad or n
            else:
                records.append(rec)
        out = Recovered()
        crashed = bool(records) and records[-1]["k"] != "stop"
        for rec in records:
            k = rec["k"]
            if k in ("s", "start") and isinstance(rec.get("serial"), int):
                self.last_serial = max(self.last_serial, rec["serial"])
            if k in ("q", "x", "c"):
                e = Entry(rec["id"], rec["src"], rec["asset"], rec["serial"], k, rec.get("c", ""), rec.get("m", ""))
                self._apply(e)
        out.last_serial = self.last_serial
        if bad:
            aside = self.path.with_name(f"{self.path.name}.damaged-{time.strftime('%Y%m%dT%H%M%S')}-{os.getpid()}")
            os.rename(self.path, aside)
            self.log(f"journal {self.path}: {bad} damaged line(s) (first: line {first_bad}), "
                     f"set aside as {aside.name}; {len(records)} sound record(s) kept")
            crashed = True  # whatever it said, its commands are answered again
        if crashed:
            out.crashed = True
            out.unfinished = list(self.live.values())
            out.finished = list(self.done.values())
        else:
            self.live.clear()
            self.done.clear()
            self._order.clear()
        self._rewrite([{"k": "s", "serial": self.last_serial}] if self.last_serial else [])
        return out

    def _apply(self, e: Entry) -> None:
        if e.state == "c":
            self.live.pop(e.cmd_id, None)
            if self.done.pop(e.cmd_id, None) is not None and len(self._order) > 2 * self.window:
                self._order = collections.deque(self.done.values())  # drop the replaced ones
            self.done[e.cmd_id] = e  # the newest (an id finished again moves to the end)
            self._order.append(e)
            while len(self.done) > self.window:
                old = self._order.popleft()
                if self.done.get(old.cmd_id) is old:  # not since replaced by a newer outcome
                    del self.done[old.cmd_id]
        else:
            self.live[e.cmd_id] = e

    # ---- writing ------------------------------------------------------------------------------------
    def start(self, serial: int) -> None:
        self._append({"k": "start", "serial": serial, "t": int(time.time())})
        self.last_serial = max(self.last_serial, serial)

    def serial(self, serial: int) -> None:
        """A config serial issued: recorded when above the last one recorded."""
        if serial > self.last_serial:
            self.last_serial = serial
            self._append({"k": "s", "serial": serial})

    def note(self, cmd, state: str, completion: str = "", message: str = "") -> Entry | None:
        """The command's step (q, x or c) before its ack; a repeated step is not written again.
        Returns the entry written (None: none), which the manager may keep as the command's
        ack key (the same object, not a second copy)."""
        old = self.live.get(cmd.cmd_id)
        if state != "c" and old is not None and (old.state == state or old.state == "x"):
            return None  # progress acks, REQUEUED then EXECUTING again: it ran already
        e = Entry(cmd.cmd_id, cmd.src_name, cmd.asset_name, int(cmd.serial), state, completion, message)
        self._apply(e)
        self._append(_record(e))
        return e

    def sync(self) -> None:
        """Make what was written durable (before the acks that promise it); compact when due.
        Raises OSError: a refused sync or compaction, or a record's write refused since the last one."""
        if not self.unsynced:
            return
        os.fdatasync(self.fd)
        self.unsynced = False
        self.syncs += 1
        if self.lines > COMPACT_FACTOR * self.window + len(self.live) + 16:
            self._rewrite([])
        if self.unwritten is not None:
            exc, self.unwritten = self.unwritten, None
            raise exc

    def close(self, clean: bool) -> None:
        """clean: every command was answered; the next start begins afresh."""
        try:
            if clean:
                self._append({"k": "stop"})
            os.fdatasync(self.fd)
        finally:
            os.close(self.fd)

    def _append(self, rec: dict) -> None:
        try:
            os.write(self.fd, _line(rec))  # O_APPEND: a kill -9 loses nothing written; a power cut, what was not synced
        except OSError as exc:  # a full disk: the command is answered all the same (as in C++ and Rust);
            self.unwritten = exc  # sync() raises it, and the manager says so
        self.lines += 1
        self.unsynced = True

    def _rewrite(self, head: list[dict]) -> None:
        """Compaction: the serial, the live commands and the last `window` outcomes in a new file,
        fsynced, renamed over the journal, the folder fsynced; the lock moves to the new file."""
        recs = [*head, *([{"k": "s", "serial": self.last_serial}] if self.last_serial and not head else [])]
        entries = [*self.done.values(), *self.live.values()]
        tmp = self.path.with_name(self.path.name + ".new")
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC | os.O_APPEND, 0o600)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            _write_all(fd, b"".join(_line(r) for r in recs))
            for n in range(0, len(entries), REWRITE_CHUNK):  # a few lines at a time: little held at once
                _write_all(fd, b"".join(_line(_record(e)) for e in entries[n:n + REWRITE_CHUNK]))
            os.fsync(fd)
            os.rename(tmp, self.path)
        except BaseException:
            os.close(fd)
            raise
        _fsync_dir(self.path.parent)
        os.close(self.fd)
        self.fd, self.lines, self.unsynced = fd, len(recs) + len(entries), False


def _write_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]


def _fsync_dir(folder: Path) -> None:
    try:
        dfd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(dfd)
    except OSError:
        pass
    finally:
        os.close(dfd)
