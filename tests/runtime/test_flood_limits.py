"""A flood of commands does not grow the runtime without bound (docs/runtime.md, "Bounded
memory"): past QUEUE_LIMIT commands waiting in the queue, or BYPASS_LIMIT running beside it,
a command is answered COMPLETED/EXEC_FAILED at once; nothing accepted is dropped and the
queue is not suspended by the refusal. Tables only (K10's), no DDS."""
from __future__ import annotations

from rapid_runtime.command import Cmd
from rapid_runtime.manager import BYPASS_LIMIT, QUEUE_LIMIT, CommandManager
from tests.runtime.tables_of import tables
from tests.runtime.test_command_window import SOURCE, WAIT, Blocking
from tests.runtime.test_command_window import Outbox as WindowOutbox

POINT = (("RAPID_FLOAT", 0.1), ("RAPID_FLOAT", 0.0))


class Outbox(WindowOutbox):
    """Also keeps each command's last completion and message."""

    def __init__(self) -> None:
        super().__init__()
        self.final: dict[str, tuple[str, str]] = {}

    def ack(self, cmd, status, completed, message):
        super().ack(cmd, status, completed, message)
        if status == "ACK_COMPLETED":
            self.final[cmd.cmd_id] = (completed, message)


def _manager(**limits):
    out, handlers = Outbox(), Blocking()
    m = CommandManager(tables("k10"), handlers, out, **limits)

    def send(cid: str, action: str = "QUEUE_BYPASS", sub: str = "Admin", name: str = "noOp", args=()) -> None:
        m.receive(Cmd(cid, SOURCE, sub, name, tuple(args), action, "", SOURCE, "K10Red"))
    send("control", sub="AccessControl", name="requestControl")
    return m, out, handlers, send


def test_defaults():
    assert (QUEUE_LIMIT, BYPASS_LIMIT) == (1024, 64)


def test_a_full_queue_refuses_new_commands_and_keeps_the_queued_ones():
    m, out, h, send = _manager(queue_limit=3)
    send("long", "QUEUE_APPEND", "PanCam", "pointCamera", POINT)  # runs, holding the queue
    for i in range(3):
        send(f"q{i}", "QUEUE_APPEND")
    assert len(m.pending) == 3
    send("over", "QUEUE_APPEND")
    assert out.acks["over"] == ["ACK_COMPLETED"]
    completed, message = out.final["over"]
    assert completed == "ACK_COMPLETED_EXEC_FAILED" and "queue full (3 pending)" in message
    assert len(message.encode()) <= 127 and len(m.pending) == 3
    h.release.set()
    assert m.wait_idle(WAIT)
    assert not m.suspended
    assert all(out.final[f"q{i}"][0] == "ACK_COMPLETED_OK" for i in range(3))
    send("after", "QUEUE_APPEND")  # room again
    assert m.wait_idle(WAIT) and out.final["after"][0] == "ACK_COMPLETED_OK"


def test_too_many_bypass_commands_at_once_are_refused():
    m, out, h, send = _manager(bypass_limit=2)
    send("b0", sub="PanCam", name="pointCamera", args=POINT)
    send("b1", sub="PanCam", name="pointCamera", args=POINT)  # takes PanCam over: b0 is canceled,
    # but its handler has not returned, so two run beside the queue
    send("b2")
    assert out.final["b2"][0] == "ACK_COMPLETED_EXEC_FAILED"
    assert "2 commands already running" in out.final["b2"][1]
    h.release.set()
    assert m.wait_idle(WAIT)
    assert out.final["b0"][0] == "ACK_COMPLETED_CANCELED" and out.final["b1"][0] == "ACK_COMPLETED_OK"
    send("b3")
    assert m.wait_idle(WAIT) and out.final["b3"][0] == "ACK_COMPLETED_OK"
