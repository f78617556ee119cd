"""The protocol logic without DDS that the protocol specification's cases
(runtime/spec/cases, replayed by test_spec_cases.py) cannot state: UTF-8 clipping of
hostile names, config serials, telemetry values. K10's generated tables, a collecting
outbox, handlers the test controls. Events, not sleeps, order the steps."""
from __future__ import annotations

import threading

import pytest

from rapid_runtime.acks import clip
from rapid_runtime.command import Cmd
from rapid_runtime.configs import Serials
from rapid_runtime.manager import CommandManager
from rapid_runtime.telemetry import TelemetryError, ordered_values
from tests.runtime.tables_of import tables

WAIT = 10.0


class Outbox:
    def __init__(self) -> None:
        self.acks: dict[str, list[tuple[str, str, str]]] = {}
        self.cond = threading.Condition()

    def ack(self, cmd, status, completed, message):
        with self.cond:
            self.acks.setdefault(cmd.cmd_id, []).append((status.removeprefix("ACK_"),
                                                         completed.removeprefix("ACK_COMPLETED_"), message))
            self.cond.notify_all()

    def queue_state(self, code, pending, active, completed):
        pass

    def access_state(self, controller, requestors):
        pass

    def log(self, text):
        pass

    def final(self, cmd_id: str) -> list[tuple[str, str]]:
        with self.cond:
            self.cond.wait_for(lambda: any(a[0] == "COMPLETED" for a in self.acks.get(cmd_id, [])), WAIT)
            return [a[:2] for a in self.acks.get(cmd_id, [])]


OP = "RapidWorkbench"
S = "RAPID_STRING"


@pytest.fixture
def k10():
    out = Outbox()
    m = CommandManager(tables("k10"), object(), out)
    n = iter(range(1, 10_000))

    def send(sub, name, args=()):
        cid = f"c{next(n)}"
        m.receive(Cmd(cid, OP, sub, name, tuple(args), "QUEUE_BYPASS", "", "ground", "K10Red"))
        return cid

    assert out.final(send("AccessControl", "requestControl")) == [("EXECUTING", "NOT"), ("COMPLETED", "OK")]
    yield out, send
    m.shutdown(2.0)


def test_messages_fit_127_bytes_even_for_long_hostile_names(k10):
    out, send = k10
    long = "\u00e9" * 60 + "\x1b[31m"
    a = send(long, long)
    assert out.final(a) == [("COMPLETED", "BAD_SYNTAX")]
    assert len(out.acks[a][0][2].encode()) <= 127 and "\x1b" not in out.acks[a][0][2]
    e = send("Admin", "echo", [(S, "\u00e9" * 100)])
    assert out.final(e) == [("COMPLETED", "BAD_SYNTAX")]  # (200 bytes: over 127)
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
