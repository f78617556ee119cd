"""A long-running asset's memory stays bounded (docs/runtime.md, "Bounded memory"): the
runtime remembers the last N commands only. Duplicates are detected among the last N
cmdIds (and those still pending or running); once more than N commands have completed,
the oldest one's ack instance is unregistered, so DDS frees its history.

Without DDS: the manager's tables never exceed N (the retirements and repeats themselves
are runtime/spec/cases/window.yaml's, the limits' refusals limits.yaml's).
Live: K10's simulated bridge runs with `--command-window 16` and takes 48 commands from a
ground process on loopback (python -m tests.runtime.test_command_window ...); a repeat
within the window is ignored, one after it is answered again, and an ack reader joining
late gets exactly the acks of the last 16 completed commands.
"""
from __future__ import annotations

import json
import subprocess
import sys
import threading
import time

from rapid_runtime.command import Cmd
from rapid_runtime.manager import BYPASS_LIMIT, COMMAND_WINDOW, QUEUE_LIMIT, CommandManager
from tests.runtime.live import ROOT, SEEDS, BridgeProcess, env_for, python_dir
from tests.runtime.tables_of import tables

DOMAIN = 152
WINDOW = 16
COMMANDS = 3 * WINDOW
SOURCE = "RapidWorkbench"  # K10's allow-list lets it send everything
QUIET = 1.0  # seconds a reader waits for what must not come (never asserted on)
WAIT = 20.0


class Outbox:
    """Collects acks and retirements (the bridge unregisters the ack instance)."""

    def __init__(self) -> None:
        self.acks: dict[str, list[str]] = {}
        self.retired: list[str] = []

    def ack(self, cmd, status, completed, message):
        self.acks.setdefault(cmd.cmd_id, []).append(status)

    def retire(self, cmd):
        assert cmd.cmd_id in self.acks and self.acks[cmd.cmd_id][-1] == "ACK_COMPLETED"
        self.retired.append(cmd.cmd_id)

    def queue_state(self, code, pending, active, completed):
        pass

    def access_state(self, controller, requestors):
        pass

    def log(self, text):
        pass


class Blocking:
    """K10's PanCam pointCamera runs until released."""

    def __init__(self) -> None:
        self.release = threading.Event()

    def pan_tilt_camera_point_camera(self, ctx, pan, tilt):
        self.release.wait(WAIT)
        return "pointed"


def _manager(window: int):
    out, handlers = Outbox(), Blocking()
    m = CommandManager(tables("k10"), handlers, out, window=window)

    def send(cid: str, sub: str = "Admin", name: str = "noOp", args=()) -> None:
        m.receive(Cmd(cid, SOURCE, sub, name, tuple(args), "QUEUE_BYPASS", "", SOURCE, "K10Red"))
    send("control", "AccessControl", "requestControl")
    return m, out, handlers, send


def test_default_window_and_limits():
    assert CommandManager(tables("k10"), Blocking(), Outbox()).window == COMMAND_WINDOW == 4096
    assert (QUEUE_LIMIT, BYPASS_LIMIT) == (1024, 64)


def test_tables_stay_within_the_window():
    """What the cases (runtime/spec/cases/window.yaml: retirement order, repeats within and
    after the window, a running command) cannot see: the manager's own tables stay bounded."""
    m, out, _h, send = _manager(5)
    for i in range(40):
        send(f"c{i}")
        assert len(m.seen) <= 5 and len(m.acked) <= 5
    assert all(out.acks[f"c{i}"] == ["ACK_EXECUTING", "ACK_COMPLETED"] for i in range(40))
    assert [c.cmd_id for c in m.acked] == [f"c{i}" for i in range(35, 40)]
    assert out.retired == ["control"] + [f"c{i}" for i in range(35)]


def test_commands_beyond_the_window_through_a_real_bridge():
    pydir, package = python_dir("k10"), SEEDS["k10"]
    bridge = BridgeProcess(pydir, package, DOMAIN, "--command-window", str(WINDOW))
    try:
        bridge.wait_ready()
        res = subprocess.run([sys.executable, "-m", "tests.runtime.test_command_window", str(pydir), package,
                              str(DOMAIN)], cwd=ROOT, env=env_for(pydir, package), capture_output=True, text=True,
                             timeout=240)
        assert bridge.proc.poll() is None, "the bridge stopped"
    finally:
        err = bridge.stop()
    assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-4000:] + err[-2000:]
    got = json.loads(res.stdout.splitlines()[-1])
    why = f"{got}\n{err[-2000:]}"
    ids = [f"w{i}" for i in range(COMMANDS)]
    assert got["answered"] == ids, why  # every command COMPLETED/OK
    assert got["repeat_within"] == ["ACK_COMPLETED"], why  # not run again: its stored final ack again (issue 42)
    assert got["repeat_after"] == ["ACK_EXECUTING", "ACK_COMPLETED"], why  # forgotten: answered as new
    # the late joiner: the last WINDOW completed commands (w0 again, then the newest), no older one
    assert got["late"] == sorted(["w0", *ids[COMMANDS - WINDOW + 1:]]), why
    assert "not unregistered" not in err


# ---- the ground process of the live test ----------------------------------------------------------

def _ground(pydir: str, package: str, domain: int) -> dict:
    from rapid_runtime.commander import Commander
    from tests.runtime.ground import load
    _pkg, rapid, tbl, qos = load(pydir, package)
    c = Commander(rapid, qos, tbl.name, SOURCE, domain)
    assert c.wait_for_asset(WAIT), "no bridge matched"
    assert c.wait_final(c.send("AccessControl", "requestControl"), WAIT)[-1][1] == "ACK_COMPLETED_OK"
    answered = []
    for i in range(COMMANDS):
        cid = c.send("Admin", "noOp", cmd_id=f"w{i}")
        if c.wait_final(cid, WAIT)[-1][:2] == ("ACK_COMPLETED", "ACK_COMPLETED_OK"):
            answered.append(cid)
    last = f"w{COMMANDS - 1}"
    before = len(c.acks[last])
    c.send("Admin", "noOp", cmd_id=last)
    within = [a[0] for a in c.wait_acks(last, QUIET)[before:]]
    c.send("Admin", "noOp", cmd_id="w0")
    with c.cond:
        c.cond.wait_for(lambda: sum(a[0] == "ACK_COMPLETED" for a in c.acks["w0"]) >= 2, WAIT)
        after = [a[0] for a in c.acks["w0"][2:]]

    # a reader created now gets what the ack writer still keeps: read until QUIET passes
    # without a new sample, once it matched the writer and got the first
    reader = c.node.reader("rapid_ack", rapid.Ack, keep_all=True)
    end = time.monotonic() + WAIT
    while not reader.get_matched_publications() and time.monotonic() < end:
        time.sleep(0.02)
    late: set[str] = set()
    last_new = None
    while time.monotonic() < end and (last_new is None or time.monotonic() - last_new < QUIET):
        got = [s.cmdId for s in reader.take(N=256) if isinstance(s, rapid.Ack)]
        if got:
            late.update(got)
            last_new = time.monotonic()
        time.sleep(0.02)
    c.close()
    return {"answered": answered, "repeat_within": within, "repeat_after": after, "late": sorted(late)}


if __name__ == "__main__":
    print(json.dumps(_ground(sys.argv[1], sys.argv[2], int(sys.argv[3]))))
