"""The bridge's door (rapid_runtime/intake.py), without DDS: per-writer FIFOs served
round-robin, control commands first, a flooding writer's surplus answered "bridge busy"
and, past the answers' bound, dropped and counted; the manager's refuse()."""
from __future__ import annotations

import contextlib
import threading

from rapid_runtime.command import Cmd
from rapid_runtime.intake import Intake
from rapid_runtime.manager import CommandManager
from tests.runtime.tables_of import tables as tables_of

SOURCE = "RapidWorkbench"


class Recorder:
    """A manager stand-in that records what the intake hands it, blocking until released."""

    def __init__(self, tables) -> None:
        self.tables = tables
        self.got: list[tuple[str, str]] = []
        self.gate = threading.Event()
        self.done = threading.Condition()

    def batch(self):
        return contextlib.nullcontext()  # the real manager's holds acks until its journal is synced

    def receive(self, cmd: Cmd) -> None:
        self.gate.wait()
        with self.done:
            self.got.append(("run", cmd.cmd_id))
            self.done.notify_all()

    def refuse(self, cmd: Cmd, why: str) -> None:
        self.gate.wait()
        with self.done:
            self.got.append(("busy", cmd.cmd_id))
            self.done.notify_all()

    def wait_for(self, n: int) -> list[tuple[str, str]]:
        with self.done:
            assert self.done.wait_for(lambda: len(self.got) >= n, 10), self.got
            return list(self.got)


def cmd(cid: str, sub: str = "Admin", name: str = "noOp") -> Cmd:
    return Cmd(cid, SOURCE, sub, name, (), "QUEUE_BYPASS", "", SOURCE, "K10Red")


def test_writers_take_turns_and_control_goes_first():
    rec = Recorder(tables_of("k10"))
    logs: list[str] = []
    intake = Intake(rec, logs.append, per_writer=100)
    for i in range(5):
        intake.offer(cmd(f"flood-{i}"), writer=1)
    intake.offer(cmd("op-1"), writer=2)
    intake.offer(cmd("op-stop", "Mobility", "stopAllMotion"), writer=3)
    intake.offer(cmd("op-2"), writer=2)
    intake.start()
    rec.gate.set()
    got = [cid for _, cid in rec.wait_for(8)]
    intake.stop()
    assert got[0] == "op-stop"  # the control command first, whoever was there before
    assert got.index("op-1") <= 2 and got.index("op-2") <= 4  # one flood command between operator turns
    assert [c for c in got if c.startswith("flood")] == [f"flood-{i}" for i in range(5)]  # a writer's order kept


def test_a_writer_keeps_its_own_order_even_around_control():
    rec = Recorder(tables_of("k10"))
    intake = Intake(rec, lambda text: None)
    intake.offer(cmd("a-1"), writer=7)
    intake.offer(cmd("a-release", "AccessControl", "releaseControl"), writer=7)
    intake.start()
    rec.gate.set()
    assert [cid for _, cid in rec.wait_for(2)] == ["a-1", "a-release"]
    intake.stop()


def test_a_flood_is_answered_busy_then_dropped_and_counted():
    rec = Recorder(tables_of("k10"))
    logs: list[str] = []
    intake = Intake(rec, logs.append, per_writer=4, shed_answers=3)
    for i in range(10):
        intake.offer(cmd(f"f{i}"), writer=9)
    intake.offer(cmd("op"), writer=2)
    assert intake.waiting() == 4 + 1 + 3  # 4 + the operator's in FIFOs, 3 busy answers
    assert intake.unanswered[9] == 3 and intake.shed_count[9] == 3
    assert len(logs) == 2 and "floods" in logs[0] and "unanswered" in logs[1]  # once each, not per command
    intake.start()
    rec.gate.set()
    got = rec.wait_for(8)
    intake.stop()
    assert ("run", "op") in got[:3]
    assert [cid for kind, cid in got if kind == "busy"] == ["f4", "f5", "f6"]
    assert [cid for kind, cid in got if kind == "run" and cid != "op"] == ["f0", "f1", "f2", "f3"]


class Outbox:
    def __init__(self) -> None:
        self.acks: list[tuple[str, str, str, str]] = []

    def ack(self, c, status, completed, message):
        self.acks.append((c.cmd_id, status, completed, message))

    def queue_state(self, *a):
        pass

    def access_state(self, *a):
        pass

    def retire(self, c):
        pass

    def log(self, text):
        pass


def test_refuse_answers_busy_once_and_forgets_the_id():
    out = Outbox()
    m = CommandManager(tables_of("k10"), object(), out)
    m.refuse(cmd("x1"), "bridge busy")
    assert out.acks == [("x1", "ACK_COMPLETED", "ACK_COMPLETED_EXEC_FAILED", "bridge busy")]
    m.refuse(Cmd("other", SOURCE, "Admin", "noOp", asset_name="K10Blue"), "bridge busy")  # not ours: silent
    m.refuse(cmd(""), "bridge busy")
    assert len(out.acks) == 1
    m.receive(cmd("x1"))  # sent again once the flood is over: a new command, judged
    assert len(out.acks) == 2 and out.acks[-1][0] == "x1" and out.acks[-1][3] != "bridge busy"
    m.refuse(cmd("x1"), "bridge busy")  # a seen id: its acks belong to that command
    assert len(out.acks) == 2
