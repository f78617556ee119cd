"""Live: every seed asset's generated package runs its simulated bridge (python -m
<package>.bridge --simulate) as a real DDS process on loopback; a separate ground process
joins late and checks configs, then commands every entry of the dictionary; K10 takes the
malformed and unauthorized kinds docs/runtime.md lists and keeps running."""
from __future__ import annotations

import pytest

from tests.runtime.live import SEEDS, BridgeProcess, ground, python_dir
from tests.runtime.tables_of import entries

OK_SEQ = [["ACK_EXECUTING", "ACK_COMPLETED_NOT"], ["ACK_COMPLETED", "ACK_COMPLETED_OK"]]


@pytest.mark.parametrize("asset", sorted(SEEDS))
def test_late_joiner_gets_every_config_and_every_command_is_answered(asset):
    domain = 100 + sorted(SEEDS).index(asset)
    pydir, package = python_dir(asset), SEEDS[asset]
    bridge = BridgeProcess(pydir, package, domain)
    try:
        bridge.wait_ready()
        got = ground("configs", pydir, package, domain)  # a reader created after the configs were written
        assert sorted(got["got"]) == got["expected"] and got["expected"]
        for topic, c in got["got"].items():
            assert c["same"], topic  # exactly the computed config
            assert c["src"] == c["asset"] != "" and c["serial"] > 1_600_000_000  # serial = start time [s]
        # a telemetry-only asset (the EVA suit) takes no commands
        res = ground("commands", pydir, package, domain) if entries(asset) else {"results": []}
    finally:
        err = bridge.stop()
    for r in res["results"]:
        acks = [a[:2] for a in r["acks"]]
        assert acks == OK_SEQ, (r, err[-2000:])
        assert all(len(a[2].encode()) <= 127 for a in r["acks"])
    every = {f"{sub}/{e.name}" for sub, e in entries(asset)}
    assert {r["command"] for r in res["results"]} == every


EXPECTED = {  # kind -> (acks as (status, completion), a word the message must hold)
    "wrong asset": ([], None),
    "first of a repeated id": (OK_SEQ, None),
    # not run again ("y" is not echoed): the first one's acks, then its stored final ack again (issue 42)
    "repeated cmdId": (OK_SEQ + [["ACK_COMPLETED", "ACK_COMPLETED_OK"]], "x"),
    "unknown subsystem": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "unknown subsystem"),
    "unknown command": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "unknown command"),
    "too few arguments": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "takes 2 arguments, got 1"),
    "too many arguments": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "got 3"),
    "wrong type": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "must be RAPID_FLOAT, got RAPID_DOUBLE"),
    "out of range": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "not in [-3.05, 3.05]"),
    "not a number": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "nan not in"),
    "not allowed": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "not one of left|right|stereo"),
    "source not allowed this command": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]],
                                        "RAPID access violation: ScienceBackroom may not send Mobility/simpleMove"),
    "unknown source": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "Intruder may not send"),
    "source without control": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "does not have control"),
    "bypass with target": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "QUEUE_BYPASS takes no targetCmdId"),
    "append with target": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "QUEUE_APPEND takes no targetCmdId"),
    "insert without target": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "QUEUE_INSERT needs a targetCmdId"),
    "replace unknown target": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "unknown targetCmdId 'no-such-id'"),
    "delete unknown target": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "unknown targetCmdId 'no-such-id'"),
    "empty cmdId": ([["ACK_COMPLETED", "ACK_COMPLETED_BAD_SYNTAX"]], "empty cmdId"),
    "release by non-controller": ([["ACK_EXECUTING", "ACK_COMPLETED_NOT"],
                                   ["ACK_COMPLETED", "ACK_COMPLETED_EXEC_FAILED"]], "does not have control"),
    "stopAllMotion from anyone": (OK_SEQ, None),
    "still running": (OK_SEQ, "alive"),
}


def test_malformed_and_unauthorized_commands_get_their_answer_and_the_bridge_keeps_running():
    pydir, package, domain = python_dir("k10"), SEEDS["k10"], 120
    bridge = BridgeProcess(pydir, package, domain)
    try:
        bridge.wait_ready()
        got = ground("malformed", pydir, package, domain)
        assert bridge.proc.poll() is None, "the bridge stopped"
    finally:
        err = bridge.stop()
    assert len(EXPECTED) >= 15 + 3
    for kind, (seq, word) in EXPECTED.items():
        acks = got[kind]
        assert [a[:2] for a in acks] == seq, (kind, acks, err[-1500:])
        if word is not None:
            assert word in acks[-1][2], (kind, acks)
        assert all(len(a[2].encode()) <= 127 for a in acks)
