"""The protocol logic without DDS: K10's and Chariot's generated tables, a collecting
outbox, handlers the test controls. Events, not sleeps, order the steps."""
from __future__ import annotations

import threading

import pytest

from rapid_runtime.acks import clip
from rapid_runtime.command import Cmd
from rapid_runtime.configs import Serials
from rapid_runtime.handlers import CommandFailed
from rapid_runtime.manager import CommandManager
from rapid_runtime.telemetry import TelemetryError, ordered_values
from tests.runtime.tables_of import tables

WAIT = 10.0


class Outbox:
    def __init__(self) -> None:
        self.acks: dict[str, list[tuple[str, str, str]]] = {}
        self.queue: list = []
        self.access: list = []
        self.cond = threading.Condition()

    def ack(self, cmd, status, completed, message):
        with self.cond:
            self.acks.setdefault(cmd.cmd_id, []).append((status.removeprefix("ACK_"),
                                                         completed.removeprefix("ACK_COMPLETED_"), message))
            self.cond.notify_all()

    def queue_state(self, code, pending, active, completed):
        self.queue.append((code, [c.cmd_id for c, *_ in pending], [c.cmd_id for c, *_ in active]))

    def access_state(self, controller, requestors):
        self.access.append((controller, list(requestors)))

    def log(self, text):
        pass

    def seq(self, cmd_id: str) -> list[tuple[str, str]]:
        return [a[:2] for a in self.acks.get(cmd_id, [])]

    def final(self, cmd_id: str) -> list[tuple[str, str]]:
        with self.cond:
            self.cond.wait_for(lambda: any(a[0] == "COMPLETED" for a in self.acks.get(cmd_id, [])), WAIT)
        return self.seq(cmd_id)

    def until(self, cmd_id: str, status: str) -> None:
        with self.cond:
            assert self.cond.wait_for(lambda: any(a[0] == status for a in self.acks.get(cmd_id, [])), WAIT)


class Camera:
    """K10's PanCam handlers: pointCamera blocks until released (or canceled)."""

    def __init__(self) -> None:
        self.release = threading.Event()
        self.calls: list = []

    def pan_tilt_camera_point_camera(self, ctx, pan, tilt):
        self.calls.append(("point", pan, tilt))
        while not self.release.is_set():
            if not ctx.sleep(0.01):
                return None  # canceled
        return "pointed"

    def pan_tilt_camera_take_picture(self, ctx, mode, exposure):
        if mode == "right":
            raise CommandFailed("right camera offline")
        return f"{mode} picture"

    def mobility_simple_move(self, ctx, frame, xyt):
        while not ctx.cancelled.is_set():
            ctx.sleep(0.01)


OP = "RapidWorkbench"
F, S = "RAPID_FLOAT", "RAPID_STRING"


@pytest.fixture
def k10():
    out, h = Outbox(), Camera()
    m = CommandManager(tables("k10"), h, out)
    n = iter(range(1, 10_000))

    def send(sub, name, args=(), action="QUEUE_BYPASS", target="", src=OP, cmd_id=None, asset="K10Red"):
        cid = cmd_id if cmd_id is not None else f"c{next(n)}"
        m.receive(Cmd(cid, src, sub, name, tuple(args), action, target, "ground", asset))
        return cid

    assert out.final(send("AccessControl", "requestControl")) == [("EXECUTING", "NOT"), ("COMPLETED", "OK")]
    yield m, out, h, send
    h.release.set()


def point(pan=0.1):
    return [(F, pan), (F, 0.0)]


def test_queue_order_insert_replace_delete(k10):
    m, out, h, send = k10
    a = send("PanCam", "pointCamera", point(), "QUEUE_APPEND")
    out.until(a, "EXECUTING")
    b = send("PanCam", "pointCamera", point(0.2), "QUEUE_APPEND")
    c = send("PanCam", "pointCamera", point(0.3), "QUEUE_INSERT", target="head")  # before b
    d = send("PanCam", "pointCamera", point(0.4), "QUEUE_REPLACE", target=b)  # b canceled, d in its place
    e = send("Admin", "noOp", [], "QUEUE_DELETE", target=c)  # c canceled before it ran
    assert out.seq(b) == [("QUEUED", "NOT"), ("COMPLETED", "CANCELED")]
    assert out.seq(c) == [("QUEUED", "NOT"), ("COMPLETED", "CANCELED")]
    assert out.final(e) == [("EXECUTING", "NOT"), ("COMPLETED", "OK")]
    assert m.pending.items[0].cmd.cmd_id == d
    h.release.set()
    assert out.final(a) == [("QUEUED", "NOT"), ("EXECUTING", "NOT"), ("COMPLETED", "OK")]
    assert out.final(d) == [("QUEUED", "NOT"), ("EXECUTING", "NOT"), ("COMPLETED", "OK")]
    assert [p for p in h.calls] == [("point", 0.1, 0.0), ("point", 0.4, 0.0)]
    assert out.queue[-1][0] == 0  # idle


def test_delete_aborts_a_running_abortable_command(k10):
    m, out, h, send = k10
    a = send("PanCam", "pointCamera", point(), "QUEUE_APPEND")
    out.until(a, "EXECUTING")
    d = send("Admin", "noOp", [], "QUEUE_DELETE", target=a)
    assert out.final(a)[-1] == ("COMPLETED", "CANCELED")
    assert out.final(d)[-1] == ("COMPLETED", "OK")


def test_bypass_preempts_a_suspendable_queued_command_which_is_requeued(k10):
    m, out, h, send = k10
    move = [(S, "site"), ("RAPID_VEC3d", [1.0, 0.0, 0.0])]
    a = send("Mobility", "simpleMove", move, "QUEUE_APPEND")
    out.until(a, "EXECUTING")
    b = send("Mobility", "simpleMove", move)  # BYPASS on the same subsystem
    out.until(a, "REQUEUED")
    out.until(b, "EXECUTING")
    stop = send("Mobility", "stopAllMotion", [], src="Intruder")  # always allowed; cancels b
    assert out.final(b)[-1] == ("COMPLETED", "CANCELED")
    # no handler method: not a failure, the runtime canceled the motion (issue 42; ACC-06)
    assert out.final(stop) == [("EXECUTING", "NOT"), ("COMPLETED", "OK")]
    # b's handler may not have returned yet when stopAllMotion completes (it is then said)
    assert out.acks[stop][-1][2] in ("motion commands canceled; no hardware stop handler",
                                     "motion commands canceled; no hardware stop handler; "
                                     "1 motion handler(s) not stopped yet")
    assert out.seq(a)[:3] == [("QUEUED", "NOT"), ("EXECUTING", "NOT"), ("REQUEUED", "NOT")]
    assert out.final(a)[-1] == ("COMPLETED", "CANCELED")  # requeued, then stopAllMotion canceled it


def test_a_failure_suspends_the_queue_until_cancel_all(k10):
    m, out, h, send = k10
    a = send("PanCam", "takePicture", [(S, "right"), (F, 0.0)], "QUEUE_APPEND")
    assert out.final(a)[-1] == ("COMPLETED", "EXEC_FAILED")
    assert out.acks[a][-1][2] == "right camera offline"
    b = send("PanCam", "takePicture", [(S, "left"), (F, 0.0)], "QUEUE_APPEND")
    assert out.seq(b) == [("QUEUED", "NOT")] and out.queue[-1][0] == -1  # suspended
    c = send("Queue", "cancelAll")
    assert out.final(c)[-1] == ("COMPLETED", "OK")
    assert out.final(b)[-1] == ("COMPLETED", "CANCELED")
    d = send("PanCam", "takePicture", [(S, "left"), (F, 0.0)], "QUEUE_APPEND")
    assert out.final(d)[-1] == ("COMPLETED", "OK") and out.acks[d][-1][2] == "left picture"


def test_access_control_request_queue_release_transfer(k10):
    m, out, h, send = k10
    other = "MultiCenterCockpit"
    r = send("AccessControl", "requestControl", src=other)
    assert out.final(r)[-1] == ("COMPLETED", "OK") and m.control.requestors == [other]
    assert out.final(send("AccessControl", "releaseControl", src=other))[-1] == ("COMPLETED", "EXEC_FAILED")
    assert out.final(send("AccessControl", "releaseControl"))[-1] == ("COMPLETED", "OK")
    assert m.control.controller == other and out.access[-1] == (other, [])
    g = send("AccessControl", "grabControl")
    assert out.final(g)[-1] == ("COMPLETED", "OK") and m.control.controller == OP
    t = send("AccessControl", "transferControl", [(S, other)])
    assert out.final(t)[-1] == ("COMPLETED", "OK") and m.control.controller == other
    denied = send("Admin", "echo", [(S, "x")])
    assert out.final(denied) == [("COMPLETED", "BAD_SYNTAX")]
    assert out.acks[denied][0][2].startswith("RAPID access violation: ")


def test_asset_without_queue_takes_bypass_only():
    out = Outbox()
    m = CommandManager(tables("chariot"), object(), out)
    m.receive(Cmd("q1", "RapidWorkbench", "Admin", "noOp", (), "QUEUE_APPEND", "", "g", "Chariot"))
    assert out.final("q1") == [("COMPLETED", "BAD_SYNTAX")] and "no command queue" in out.acks["q1"][0][2]
    m.receive(Cmd("q2", "RapidWorkbench", "Admin", "noOp", (), "QUEUE_BYPASS", "", "g", "Chariot"))
    assert out.final("q2") == [("EXECUTING", "NOT"), ("COMPLETED", "OK")]


def test_messages_fit_127_bytes_even_for_long_hostile_names(k10):
    m, out, h, send = k10
    long = "\u00e9" * 60 + "\x1b[31m"
    a = send(long, long)
    assert out.final(a) == [("COMPLETED", "BAD_SYNTAX")]
    assert len(out.acks[a][0][2].encode()) <= 127 and "\x1b" not in out.acks[a][0][2]
    e = send("Admin", "echo", [(S, "\u00e9" * 100)])
    assert len(out.acks[e][-1][2].encode()) <= 127
    assert clip("\u00e9" * 64) == "\u00e9" * 63  # never half a character


def test_serials_change_with_content_only():
    s = Serials(start=1_700_000_000)
    assert s.update("t", {"a": 1}) == (1_700_000_000, True)
    assert s.update("t", {"a": 1}) == (1_700_000_000, False)
    serial, changed = s.update("t", {"a": 2})
    assert changed and serial > 1_700_000_000 and s.of("t") == serial


def test_telemetry_values_checked_against_declared_types():
    agent = next(t for t in tables("k10").telemetry if t["kind"] == "agent")
    values = ordered_values(agent["values"], {"batteryCharge": 80, "estop": True})
    assert values[0] == ("RAPID_FLOAT", 80.0) and ("RAPID_BOOL", True) in values
    assert ("RAPID_STRING", "idle") in values  # a declared default fills what was not given
    with pytest.raises(TelemetryError, match="undeclared"):
        ordered_values(agent["values"], {"fuel": 1.0})
    with pytest.raises(TelemetryError, match="estop: not a boolean"):
        ordered_values(agent["values"], {"estop": "yes"})
