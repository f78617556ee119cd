"""Handlers on a bad day (issue 42), without DDS: K10's generated tables, a collecting outbox,
handlers that inject one fault each (ignore cancel, crash, write bad text, report progress
after they returned). Each test checks what the commander and the log see: every command
gets exactly one final ack, nothing is lost or undecodable, the queue goes on. Events order
the steps; the bounds are short (a told-to-stop handler's stop bound, the shutdown bound),
and no test asserts how long anything took."""
from __future__ import annotations

import copy
import importlib.util
import threading

import pytest

from rapid_runtime import journal as J
from rapid_runtime.acks import MESSAGE_BYTES
from rapid_runtime.command import Cmd
from rapid_runtime.handlers import CommandFailed
from rapid_runtime.manager import (DID_NOT_STOP, NO_HARDWARE_STOP, SHUTTING_DOWN, STOP_TIMEOUT_MS,
                                   CommandManager)
from rapid_runtime.tables import Tables
from tests.runtime.live import SEEDS, python_dir

WAIT = 20.0  # s: how long an awaited ack may take (generous: a loaded machine)
BOUND_MS = 150  # the stop bound the tests give a command (short: the tests wait for it)
OP = "RapidWorkbench"
F, S = "RAPID_FLOAT", "RAPID_STRING"
POINT = [(F, 0.1), (F, 0.0)]
MOVE = [(S, "site"), ("RAPID_VEC3d", [1.0, 0.0, 0.0])]


def k10_data() -> dict:
    path = python_dir("k10") / SEEDS["k10"] / "asset_tables.py"
    spec = importlib.util.spec_from_file_location("k10_tables_faults", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return copy.deepcopy({k: v for k, v in vars(module).items() if k.isupper()})


def k10_tables(**bounds: int) -> Tables:
    """K10's tables, with stop_timeout_ms declared on the named commands (type__command=ms)."""
    data = k10_data()
    for key, ms in bounds.items():
        type_name, command = key.split("__")
        data["COMMANDS"][type_name][command]["stop_timeout_ms"] = ms
    return Tables(data)


class Outbox:
    def __init__(self) -> None:
        self.acks: dict[str, list[tuple[str, str, str]]] = {}
        self.queue: list = []
        self.logs: list[str] = []
        self.cond = threading.Condition()

    def ack(self, cmd, status, completed, message):
        message.encode("utf-8")  # what cyclonedds does: a lone surrogate would raise here
        assert "\x00" not in message and len(message.encode()) <= MESSAGE_BYTES
        with self.cond:
            self.acks.setdefault(cmd.cmd_id, []).append((status.removeprefix("ACK_"),
                                                         completed.removeprefix("ACK_COMPLETED_"), message))
            self.cond.notify_all()

    def queue_state(self, code, pending, active, completed):
        with self.cond:
            self.queue.append((code, [c.cmd_id for c, *_ in pending], [c.cmd_id for c, *_ in active]))
            self.cond.notify_all()

    def access_state(self, controller, requestors):
        pass

    def retire(self, cmd):
        pass

    def log(self, text):
        with self.cond:
            self.logs.append(text)

    def final(self, cmd_id: str) -> tuple[str, str, str]:
        """The command's COMPLETED ack (waited for)."""
        with self.cond:
            assert self.cond.wait_for(lambda: self.finals(cmd_id), WAIT), (cmd_id, self.acks.get(cmd_id))
            return self.finals(cmd_id)[0]

    def finals(self, cmd_id: str) -> list[tuple[str, str, str]]:
        return [a for a in self.acks.get(cmd_id, []) if a[0] == "COMPLETED"]

    def until(self, cmd_id: str, status: str) -> None:
        with self.cond:
            assert self.cond.wait_for(lambda: any(a[0] == status for a in self.acks.get(cmd_id, [])), WAIT), \
                (cmd_id, status, self.acks.get(cmd_id))

    def lines(self, *words: str) -> list[str]:
        with self.cond:
            return [ln for ln in self.logs if all(w in ln for w in words)]


class Faulty:
    """K10's handlers, each with its fault. `gate` holds the stubborn ones until the test
    opens it; `returned` is set once a stubborn handler has returned (after the runtime
    answered it)."""

    def __init__(self) -> None:
        self.gate = threading.Event()
        self.returned = threading.Event()
        self.started = threading.Event()
        self.ctxs: list = []
        self.lock = threading.Lock()
        self.added = threading.Condition(self.lock)  # a context appended to ctxs
        self.helper_done = threading.Event()
        self.stop_handler = None  # Mobility/stopAllMotion's body, or None: no method (the stub)
        self.runs: dict[str, int] = {}  # simpleMove: runs per cmdId
        self.faults: list[str] = []  # takePicture's next faults, in order (its mode is left, right or stereo)

    def pan_tilt_camera_point_camera(self, ctx, pan, tilt):
        """Ignores ctx.cancelled: returns only when the gate opens."""
        with self.lock:
            self.ctxs.append(ctx)
            self.added.notify_all()
        self.started.set()
        self.gate.wait(WAIT)
        self.returned.set()
        return "pointed (late)"

    def mobility_simple_move(self, ctx, frame, xyt):
        """Honours cancel, unless frame is 'stubborn'."""
        with self.lock:
            self.ctxs.append(ctx)
            self.added.notify_all()
        self.started.set()
        with self.lock:
            self.runs[ctx.cmd.cmd_id] = self.runs.get(ctx.cmd.cmd_id, 0) + 1
            nth = self.runs[ctx.cmd.cmd_id]
        if frame == "stubborn" or frame == "stubborn-second-time" and nth == 2:
            self.gate.wait(WAIT)
            self.returned.set()
            return "arrived"
        while not ctx.cancelled.is_set():
            ctx.sleep(0.01)
        return None

    def pan_tilt_camera_take_picture(self, ctx, mode, exposure):
        mode = self.faults.pop(0) if self.faults else mode  # the fault the test asked for, else a picture
        if mode == "crash":
            return 1 // 0
        if mode == "surrogate":
            ctx.progress("half \udcff done\x00")
            return "bad \udcff text \x00 here"
        if mode == "long":
            return "\u00e9" * 200  # 400 bytes of 2-byte characters
        if mode == "fail-badly":
            raise CommandFailed("no \udce9 luck")
        if mode == "helper":  # a helper thread (a driver's callback) reports after the handler returned
            def late():
                self.gate.wait(WAIT)
                ctx.progress("late progress")
                ctx.progress("\udcff")
                self.helper_done.set()
            threading.Thread(target=late, daemon=True).start()
            return "picture"
        return f"{mode} picture"

    def __getattr__(self, name):
        if name == "mobility_stop_all_motion" and self.stop_handler is not None:
            return self.stop_handler
        raise AttributeError(name)


class Rig:
    def __init__(self, tables: Tables | None = None, journal=None, **kw) -> None:
        self.out, self.h = Outbox(), Faulty()
        self.m = CommandManager(tables or k10_tables(), self.h, self.out, journal=journal, **kw)
        self.n = iter(range(1, 10_000))
        self.final(self.send("AccessControl", "requestControl"))

    def send(self, sub, name, args=(), action="QUEUE_BYPASS", target="", src=OP, cmd_id=None, header=OP):
        cid = cmd_id if cmd_id is not None else f"c{next(self.n)}"
        self.m.receive(Cmd(cid, src, sub, name, tuple(args), action, target, header, "K10Red"))
        return cid

    def final(self, cid):
        return self.out.final(cid)

    def close(self):
        self.h.gate.set()


@pytest.fixture
def rig():
    r = Rig(k10_tables(PanTiltCamera__pointCamera=BOUND_MS), stop_timeout_ms=60_000)
    yield r
    r.close()


def test_the_descriptors_bound_reaches_the_runtime():
    t = k10_tables(PanTiltCamera__pointCamera=BOUND_MS)
    assert t.command("PanCam", "pointCamera").stop_timeout_ms == BOUND_MS
    assert t.command("PanCam", "takePicture").stop_timeout_ms is None
    m = CommandManager(t, Faulty(), Outbox())
    assert m.stop_timeout_ms == STOP_TIMEOUT_MS == 2000
    with pytest.raises(ValueError):
        CommandManager(t, Faulty(), Outbox(), stop_timeout_ms=0)


# ---- 2. a handler that ignores cancel -----------------------------------------------------------

def test_delete_of_a_handler_that_ignores_cancel_is_honest_bounded_and_frees_the_queue(rig):
    m, out, h = rig.m, rig.out, rig.h
    a = rig.send("PanCam", "pointCamera", POINT, "QUEUE_APPEND")
    out.until(a, "EXECUTING")
    d = rig.send("Admin", "noOp", [], "QUEUE_DELETE", target=a)
    # DELETE answers at once, and says the handler has not stopped
    assert rig.final(d) == ("COMPLETED", "OK", f"{a} cancel requested; handler has not stopped yet")
    b = rig.send("PanCam", "takePicture", [(S, "left"), (F, 0.0)], "QUEUE_APPEND")  # waits behind a
    out.until(b, "QUEUED")
    assert out.queue[-1][2] == [a] and out.queue[-1][1] == [b]  # the target's state stays visible
    # at its bound (the descriptor's 150 ms, not the manager's 60 s default): its final ack
    assert rig.final(a) == ("COMPLETED", "EXEC_FAILED", DID_NOT_STOP)
    # the queue goes on (not suspended: the command was told to stop)
    assert rig.final(b) == ("COMPLETED", "OK", "left picture")
    with out.cond:
        assert out.cond.wait_for(lambda: out.queue[-1][0] == 0 and out.queue[-1][2] == [], WAIT), out.queue[-3:]
    lines = out.lines(a, "PanCam/pointCamera", f"{BOUND_MS} ms", "hardware")
    assert len(lines) == 1, out.logs
    # the handler returns later: ignored, no second COMPLETED, its late progress does nothing
    ctx = h.ctxs[0]
    h.gate.set()
    assert h.returned.wait(WAIT)
    ctx.progress("still here")
    assert m.wait_idle(WAIT)
    assert out.finals(a) == [("COMPLETED", "EXEC_FAILED", DID_NOT_STOP)]
    assert [s for s, *_ in out.acks[a]] == ["QUEUED", "EXECUTING", "COMPLETED"]


def test_delete_of_a_handler_that_stops_gets_canceled_and_a_pending_target_keeps_its_text(rig):
    out = rig.out
    move = rig.send("Mobility", "simpleMove", MOVE, "QUEUE_APPEND")
    out.until(move, "EXECUTING")
    waiting = rig.send("PanCam", "takePicture", [(S, "left"), (F, 0.0)], "QUEUE_APPEND")
    d1 = rig.send("Admin", "noOp", [], "QUEUE_DELETE", target=waiting)
    assert rig.final(d1) == ("COMPLETED", "OK", f"{waiting} canceled")
    assert rig.final(waiting) == ("COMPLETED", "CANCELED", f"deleted by {d1}")
    d2 = rig.send("Admin", "noOp", [], "QUEUE_DELETE", target=move)
    assert rig.final(d2) == ("COMPLETED", "OK", f"{move} cancel requested; handler has not stopped yet")
    assert rig.final(move) == ("COMPLETED", "CANCELED", "canceled")
    assert not out.lines(DID_NOT_STOP)


def test_replace_of_a_stuck_command_runs_the_replacement_at_the_bound(rig):
    out = rig.out
    a = rig.send("PanCam", "pointCamera", POINT, "QUEUE_APPEND")
    out.until(a, "EXECUTING")
    r = rig.send("PanCam", "takePicture", [(S, "right"), (F, 0.0)], "QUEUE_REPLACE", target=a)
    out.until(r, "QUEUED")
    assert rig.final(a) == ("COMPLETED", "EXEC_FAILED", DID_NOT_STOP)
    assert rig.final(r) == ("COMPLETED", "OK", "right picture")


def test_a_bypass_command_that_ignores_cancel_frees_its_subsystem(rig):
    out = rig.out
    a = rig.send("PanCam", "pointCamera", POINT)  # BYPASS
    out.until(a, "EXECUTING")
    d = rig.send("Admin", "noOp", [], "QUEUE_DELETE", target=a)
    assert rig.final(d)[2] == f"{a} cancel requested; handler has not stopped yet"
    assert rig.final(a) == ("COMPLETED", "EXEC_FAILED", DID_NOT_STOP)
    assert rig.m.bypass == []
    b = rig.send("PanCam", "takePicture", [(S, "left"), (F, 0.0)], "QUEUE_APPEND")
    assert rig.final(b) == ("COMPLETED", "OK", "left picture")


def test_cancel_all_says_what_it_asked_and_republishes_a_suspended_queue(rig):
    out = rig.out
    rig.h.faults.append("crash")
    failed = rig.send("PanCam", "takePicture", [(S, "left"), (F, 0.0)], "QUEUE_APPEND")
    assert rig.final(failed)[1] == "EXEC_FAILED"
    left = rig.send("PanCam", "takePicture", [(S, "left"), (F, 0.0)], "QUEUE_APPEND")
    out.until(left, "QUEUED")
    assert out.queue[-1][:2] == (-1, [left])  # suspended, the command pending
    seen = len(out.queue)
    c = rig.send("Queue", "cancelAll")  # BYPASS
    assert rig.final(c) == ("COMPLETED", "OK", "")
    assert rig.final(left)[1] == "CANCELED"
    with out.cond:  # republished: no longer suspended, nothing pending
        assert out.cond.wait_for(lambda: any(q[:2] == (0, []) for q in out.queue[seen:]), WAIT), out.queue[seen:]

    stuck = rig.send("PanCam", "pointCamera", POINT, "QUEUE_APPEND")
    out.until(stuck, "EXECUTING")
    beside = rig.send("Mobility", "simpleMove", MOVE)  # abortable, honours cancel
    out.until(beside, "EXECUTING")
    c2 = rig.send("Queue", "cancelAll")
    assert rig.final(c2) == ("COMPLETED", "OK", "2 handler(s) asked to stop, not stopped yet")
    assert rig.final(beside)[:2] == ("COMPLETED", "CANCELED")
    assert rig.final(stuck) == ("COMPLETED", "EXEC_FAILED", DID_NOT_STOP)


def test_stop_all_motion_without_a_handler_is_ok_and_says_what_still_runs():
    r = Rig(k10_tables(Mobility__simpleMove=BOUND_MS), stop_timeout_ms=60_000)
    try:
        out = r.out
        s1 = r.send("Mobility", "stopAllMotion", [], src="Intruder")  # no control, no handler method
        assert r.final(s1) == ("COMPLETED", "OK", NO_HARDWARE_STOP)
        move = r.send("Mobility", "simpleMove", [(S, "stubborn"), MOVE[1]], "QUEUE_APPEND")
        out.until(move, "EXECUTING")
        s2 = r.send("Mobility", "stopAllMotion", [], src="Intruder")
        assert r.final(s2) == ("COMPLETED", "OK", f"{NO_HARDWARE_STOP}; 1 motion handler(s) not stopped yet")
        assert r.final(move) == ("COMPLETED", "EXEC_FAILED", DID_NOT_STOP)
        r.h.gate.set()
        assert r.h.returned.wait(WAIT) and r.m.wait_idle(WAIT)
        assert len(out.finals(move)) == 1
        # the generated stub (raises CommandFailed("not implemented")): the same answer
        r.h.stop_handler = lambda ctx: (_ for _ in ()).throw(CommandFailed("not implemented"))
        assert r.final(r.send("Mobility", "stopAllMotion", [], src="Intruder")) == ("COMPLETED", "OK", NO_HARDWARE_STOP)
        # a real handler keeps its own answer
        r.h.stop_handler = lambda ctx: "brakes on"
        assert r.final(r.send("Mobility", "stopAllMotion", [])) == ("COMPLETED", "OK", "brakes on")
    finally:
        r.close()


def test_a_requeued_command_gets_a_new_stop_bound_when_it_runs_again():
    r = Rig(k10_tables(Mobility__simpleMove=BOUND_MS), stop_timeout_ms=60_000)
    try:
        out = r.out
        a = r.send("Mobility", "simpleMove", [(S, "stubborn-second-time"), MOVE[1]], "QUEUE_APPEND")
        out.until(a, "EXECUTING")
        b = r.send("Mobility", "simpleMove", MOVE)  # preempts a (told to stop: its first bound)
        out.until(a, "REQUEUED")  # it stopped in time
        r.send("Admin", "noOp", [], "QUEUE_DELETE", target=b)
        assert r.final(b)[1] == "CANCELED"
        with out.cond:
            assert out.cond.wait_for(lambda: [s for s, *_ in out.acks[a]].count("EXECUTING") == 2, WAIT)
        r.send("Admin", "noOp", [], "QUEUE_DELETE", target=a)  # told to stop again: it does not
        assert r.final(a) == ("COMPLETED", "EXEC_FAILED", DID_NOT_STOP)
    finally:
        r.close()


# ---- 1. progress after the command is done ------------------------------------------------------

def test_progress_after_a_bypass_handler_returned_does_nothing(rig):
    h, out = rig.h, rig.out
    h.faults.append("helper")
    cid = rig.send("PanCam", "takePicture", [(S, "left"), (F, 0.0)])
    assert rig.final(cid) == ("COMPLETED", "OK", "picture")
    h.gate.set()  # the helper reports now
    assert h.helper_done.wait(WAIT)
    assert rig.m.wait_idle(WAIT)
    assert out.acks[cid] == [("EXECUTING", "NOT", ""), ("COMPLETED", "OK", "picture")]


def test_progress_from_a_preempted_runs_old_context_does_nothing(rig):
    h, out = rig.h, rig.out
    a = rig.send("Mobility", "simpleMove", MOVE, "QUEUE_APPEND")
    out.until(a, "EXECUTING")
    b = rig.send("Mobility", "simpleMove", MOVE)  # preempts a: a is requeued
    out.until(a, "REQUEUED")
    first_ctx = next(c for c in h.ctxs if c.cmd.cmd_id == a)
    n = len(out.acks[a])
    first_ctx.progress("stale")  # a helper thread still holding the first run's context
    assert len(out.acks[a]) == n
    d = rig.send("Admin", "noOp", [], "QUEUE_DELETE", target=b)
    assert rig.final(b)[1] == "CANCELED" and rig.final(d)[1] == "OK"
    with h.added:  # a runs again, with a new context
        assert h.added.wait_for(lambda: len([c for c in h.ctxs if c.cmd.cmd_id == a]) == 2, WAIT)
    first_ctx.progress("stale again")
    second = [c for c in h.ctxs if c.cmd.cmd_id == a][1]
    second.progress("fresh")
    assert [m for *_, m in out.acks[a] if m] == ["preempted; back in the queue", "fresh"]
    rig.send("Admin", "noOp", [], "QUEUE_DELETE", target=a)
    assert rig.final(a)[1] == "CANCELED"


# ---- 3. bad text --------------------------------------------------------------------------------

@pytest.mark.parametrize("mode,want", [
    ("surrogate", ("COMPLETED", "OK", "bad \ufffd text \ufffd here")),
    ("fail-badly", ("COMPLETED", "EXEC_FAILED", "no \ufffd luck")),
    ("long", ("COMPLETED", "OK", "\u00e9" * 63)),  # 126 bytes: a character is never cut
])
def test_handler_text_is_made_valid_and_the_ack_is_written(rig, mode, want):
    rig.h.faults.append(mode)
    cid = rig.send("PanCam", "takePicture", [(S, "left"), (F, 0.0)])
    assert rig.final(cid) == want
    if mode == "surrogate":
        assert rig.out.acks[cid][1] == ("EXECUTING", "NOT", "half \ufffd done\ufffd")


# ---- 4. smaller ones ----------------------------------------------------------------------------

def test_a_handlers_exception_is_answered_and_logged_once(rig):
    rig.h.faults.append("crash")
    cid = rig.send("PanCam", "takePicture", [(S, "left"), (F, 0.0)])
    assert rig.final(cid) == ("COMPLETED", "EXEC_FAILED", "handler error: ZeroDivisionError: integer division or modulo by zero")
    lines = rig.out.lines(cid)
    assert len(lines) == 1, rig.out.logs
    assert "PanCam/takePicture" in lines[0] and "ZeroDivisionError" in lines[0] and "test_handler_faults.py" in lines[0]


def test_a_resent_answered_cmd_id_gets_its_stored_final_ack(rig):
    out = rig.out
    cid = rig.send("PanCam", "takePicture", [(S, "left"), (F, 0.0)])
    first = rig.final(cid)
    rig.send("PanCam", "takePicture", [(S, "right"), (F, 0.0)], cmd_id=cid)  # a fresh tool, the same cmdId
    assert out.finals(cid) == [first, first]  # nothing ran: the same answer again
    assert [a[0] for a in out.acks[cid]] == ["EXECUTING", "COMPLETED", "COMPLETED"]
    rig.send("PanCam", "takePicture", [(S, "left"), (F, 0.0)], cmd_id=cid, header="SomeoneElse")
    assert out.finals(cid) == [first, first]  # another commander's header: ignored, as before
    # a refused command's answer is stored too
    bad = rig.send("PanCam", "noSuchCommand")
    refused = rig.final(bad)
    rig.send("PanCam", "noSuchCommand", cmd_id=bad)
    assert out.finals(bad) == [refused, refused]
    # a running command sent again: ignored (its final ack is not known yet)
    a = rig.send("PanCam", "pointCamera", POINT, "QUEUE_APPEND")
    out.until(a, "EXECUTING")
    rig.send("PanCam", "pointCamera", POINT, "QUEUE_APPEND", cmd_id=a)
    assert [s for s, *_ in out.acks[a]] == ["QUEUED", "EXECUTING"]


# ---- shutdown and the journal -------------------------------------------------------------------

def test_shutdown_answers_everything_in_flight_within_its_bound_and_the_journal_says_so(tmp_path):
    logs: list[str] = []
    j, _ = J.Journal.open(tmp_path, "K10Red", 0, 64, logs.append)
    assert j is not None
    r = Rig(k10_tables(), journal=j)
    try:
        out = r.out
        stuck = r.send("PanCam", "pointCamera", POINT, "QUEUE_APPEND")  # ignores cancel
        out.until(stuck, "EXECUTING")
        waiting = r.send("PanCam", "takePicture", [(S, "left"), (F, 0.0)], "QUEUE_APPEND")
        polite = r.send("Mobility", "simpleMove", MOVE)  # BYPASS, honours cancel
        out.until(polite, "EXECUTING")
        done = threading.Event()
        result: list = []
        threading.Thread(target=lambda: (result.append(r.m.shutdown(0.3)), done.set()), daemon=True).start()
        assert done.wait(WAIT)
        assert result == [(3, 1)]  # three in flight, one handler did not stop
        assert out.finals(waiting) == [("COMPLETED", "CANCELED", SHUTTING_DOWN)]
        assert out.finals(polite) == [("COMPLETED", "CANCELED", "canceled")]
        assert out.finals(stuck) == [("COMPLETED", "EXEC_FAILED", DID_NOT_STOP)]
        assert r.m.handlers_running() == 1  # the stuck thread, left behind
        late = r.send("Admin", "noOp")  # nothing starts once shutting down
        assert r.final(late) == ("COMPLETED", "EXEC_FAILED", SHUTTING_DOWN)
        queued = r.send("PanCam", "takePicture", [(S, "left"), (F, 0.0)], "QUEUE_APPEND")  # nor waits
        assert r.final(queued) == ("COMPLETED", "EXEC_FAILED", SHUTTING_DOWN)
        # the journal holds every outcome: a crash now (no clean close) is answered right at restart
        j.sync()
        r.h.gate.set()
        assert r.h.returned.wait(WAIT)
        assert len(out.finals(stuck)) == 1  # its late return writes nothing
    finally:
        r.close()
        j.close(clean=False)
    j2, rec = J.Journal.open(tmp_path, "K10Red", 0, 64, logs.append)
    try:
        assert rec.crashed and rec.unfinished == []
        got = {e.cmd_id: (e.completion, e.message) for e in rec.finished}
        assert got[stuck] == ("ACK_COMPLETED_EXEC_FAILED", DID_NOT_STOP)
        assert got[waiting] == ("ACK_COMPLETED_CANCELED", SHUTTING_DOWN)
        # after the restart, the stuck command's id sent again gets that answer, not a new run
        m2_out = Outbox()
        m2 = CommandManager(k10_tables(), Faulty(), m2_out, journal=j2)
        m2.restore(rec)
        n = len(m2_out.acks[stuck])
        m2.receive(Cmd(stuck, OP, "PanCam", "pointCamera", tuple(POINT), "QUEUE_APPEND", "", OP, "K10Red"))
        assert m2_out.acks[stuck][n:] == [("COMPLETED", "EXEC_FAILED", DID_NOT_STOP)]
    finally:
        assert j2 is not None
        j2.close(clean=True)


def test_the_stop_bound_outcome_is_journaled_once(tmp_path):
    j, _ = J.Journal.open(tmp_path, "K10Red", 0, 64, lambda t: None)
    assert j is not None
    r = Rig(k10_tables(PanTiltCamera__pointCamera=BOUND_MS), journal=j)
    try:
        a = r.send("PanCam", "pointCamera", POINT, "QUEUE_APPEND")
        r.out.until(a, "EXECUTING")
        r.send("Admin", "noOp", [], "QUEUE_DELETE", target=a)
        assert r.final(a) == ("COMPLETED", "EXEC_FAILED", DID_NOT_STOP)
        r.h.gate.set()
        assert r.h.returned.wait(WAIT) and r.m.wait_idle(WAIT)
    finally:
        r.close()
        j.close(clean=False)
    recs = [J._parse(line) for line in j.path.read_bytes().splitlines(keepends=True)]
    assert [(x["k"], x.get("m")) for x in recs if x and x.get("id") == a] == [("q", None), ("x", None),
                                                                           ("c", DID_NOT_STOP)]


# ---- strings the runtime writes besides acks -------------------------------------------------

def test_text_message_and_config_strings_are_made_valid_and_fit_their_type():
    pytest.importorskip("cyclonedds")
    import sys
    from types import SimpleNamespace

    from rapid_runtime import messages as M
    from rapid_runtime.acks import clip, valid
    from rapid_runtime.bridge import TelemetryPublisher, _valid_strings
    sys.path.insert(0, str(python_dir("k10")))
    try:
        rapid = importlib.import_module(f"{SEEDS['k10']}.rapid")
    finally:
        sys.path.remove(str(python_dir("k10")))
    assert valid("a\x00b\udcffc") == "a\ufffdb\ufffdc" and clip("\udcff" * 100) == "\ufffd" * 42  # 126 bytes
    pub = TelemetryPublisher.__new__(TelemetryPublisher)
    pub.b = SimpleNamespace(rapid=rapid)
    bound = pub._bound("rapid::TextMessage", "message")
    text = pub._clip("rapid::TextMessage", "message", "\udcff\x00" + "\u00fc" * 2000)
    assert text.startswith("\ufffd\ufffd\u00fc") and (bound is None or len(text.encode()) < bound)
    category = pub._clip("rapid::TextMessage", "category", "cat\x00")
    hdr = M.header(rapid, "K10Red", "K10Red", 1)
    sample = rapid.TextMessage(hdr=hdr, level=rapid.MessageLevel["MSG_INFO"], category=category, message=text)
    back = type(sample).deserialize(sample.serialize())  # what cyclonedds writes: it encodes, nothing is lost
    assert (back.message, back.category) == (text, "cat\ufffd")
    # a config's value from a handler: every string made valid, the rest as it was
    value = {"frameName": "site\x00", "valueKeys": [{"key": "k\udcff", "n": 1}], "t": ("a\x00",)}
    assert _valid_strings(value) == {"frameName": "site\ufffd", "valueKeys": [{"key": "k\ufffd", "n": 1}],
                                     "t": ("a\ufffd",)}
    # a custom message's string member (telemetry.custom builds through convert)
    assert M.convert(str, "x\udcff\x00") == "x\ufffd\ufffd"
