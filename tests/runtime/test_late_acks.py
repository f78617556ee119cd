"""A commander that joins late gets a command's whole ack sequence (docs/runtime.md): acks are
transient-local, and Cyclone keeps for a late-joining reader what the writer's
durability_service history says (by default the last sample per instance), not its history.
Without that, a commander whose reader the bridge's ack writer had not yet discovered got
COMPLETED without the EXECUTING before it (seen in CI under load: test_live's late joiner).

K10's Python bridge on loopback (domain 65); one commander takes control and waits for its
answer; once the bridge's writer has had both acks acknowledged, a reader made afterwards, in
another participant, must still read both."""
from __future__ import annotations

import json
import subprocess
import sys

from tests.runtime.live import ROOT, SEEDS, BridgeProcess, env_for, python_dir

DOMAIN = 65
LATE = """
import json, sys, time
from rapid_k10red import rapid
from rapid_k10red.qos import RapidQos
from rapid_runtime.commander import Commander
from rapid_runtime.dds import Node, use_transport
qos = RapidQos(); use_transport(qos, None)
c = Commander(rapid, qos, "K10Red", "RapidWorkbench", int(sys.argv[1]))
assert c.wait_for_asset(20), "no bridge"
cid = c.send("AccessControl", "requestControl")
first = [a[0] for a in c.wait_final(cid, 20)]
time.sleep(1.5)  # the bridge's writer has the acks acknowledged: what it keeps now is for late joiners
late = Node(rapid, qos, int(sys.argv[1])).reader("rapid_ack", rapid.Ack, keep_all=True)
seen, end = [], time.monotonic() + 10
while time.monotonic() < end and len(seen) < len(first):
    seen += [s.status.name for s in late.take(N=64) if s.cmdId == cid]
    time.sleep(0.05)
print(json.dumps({"first": first, "late": seen}))
"""


def test_a_late_reader_gets_every_ack_of_an_answered_command():
    pydir, package = python_dir("k10"), SEEDS["k10"]
    bridge = BridgeProcess(pydir, package, DOMAIN, "--no-journal")
    try:
        bridge.wait_ready()
        res = subprocess.run([sys.executable, "-c", LATE, str(DOMAIN)], cwd=ROOT, env=env_for(pydir, package),
                             capture_output=True, text=True, timeout=120)
    finally:
        bridge.stop()
    assert res.returncode == 0, res.stderr[-3000:]
    got = json.loads(res.stdout.splitlines()[-1])
    assert got["first"] == ["ACK_EXECUTING", "ACK_COMPLETED"], got
    assert got["late"] == got["first"], got  # not only the last one
