"""The ground side of the Rust bridge tests, run as its own process against a running bridge:
`python -m tests.rust_runtime.ground CHECK GENERATED_PYTHON_DIR PACKAGE DOMAIN [N]`.
Prints one JSON document; the test asserts on it. CHECK:

  late-acks N  sends N Admin/noOp commands one after the other (each awaited to its final
               ack), then joins late with an ack reader of the asset's profile
               (transient-local, keep-last 1 per instance): for each cmdId sent, the last ack
               the late reader got. With one ack instance per command it gets every
               command's final ack; with one instance for all (a writer history of the last
               few acks, whatever their command) only those of the last commands.
  every        every command of the dictionary with valid arguments (tests.runtime.ground's
               `commands`): the acks of each
  ack-writers N  sends N Admin/noOp commands, then counts the asset's live rapid_ack writers
               (DCPSPublication, rapidgen.live.discovery)
  position     the latest rapid_position_sample: its pose's xyz and its values by key
  picture TOPIC  the first ImageSensorSample on TOPIC: its MIME type, the metadata's size and
               the picture's own (tests.runtime.test_simulate_telemetry decodes it whole)
  restart BRIDGE JOURNAL  starts the bridge (BRIDGE: its argv, JSON) on the journal folder,
               has a noOp answered, a 200 s drive running and a noOp queued behind it, kills
               the bridge (SIGKILL) and starts it again on the same journal: the final acks
               then seen for each, what a repeat of the first noOp's cmdId gets, the
               CommandConfig's serial at each start, and how the second bridge ended on SIGTERM
"""
from __future__ import annotations

import json
import sys
import time

from tests.runtime.ground import commands, load


def late_acks(rapid, tables, qos, domain: int, n: int) -> dict:
    from rapid_runtime.commander import Commander
    from rapid_runtime.dds import Node
    c = Commander(rapid, qos, tables.name, "RapidWorkbench", domain)
    assert c.wait_for_asset(10), "no bridge matched"
    sent = []
    for _ in range(n):
        cid = c.send("Admin", "noOp", [])
        c.wait_final(cid, 10)
        sent.append(cid)
    c.close()
    node = Node(rapid, qos, domain)
    reader = node.reader("rapid_ack", rapid.Ack)
    last: dict[str, str] = {}
    end = time.monotonic() + 10
    while time.monotonic() < end and not all(last.get(cid, "").startswith("ACK_COMPLETED ") for cid in sent):
        for a in reader.take(N=256):
            last[a.cmdId] = f"{a.status.name} {a.completedStatus.name}"
        time.sleep(0.05)
    return {"sent": sent, "last": {cid: last.get(cid) for cid in sent}}


def ack_writers(rapid, tables, qos, domain: int, n: int) -> dict:
    from cyclonedds.domain import DomainParticipant

    from rapid_runtime.acks import COMPLETED
    from rapid_runtime.commander import Commander
    from rapidgen.live.discovery import Discovery
    c = Commander(rapid, qos, tables.name, "RapidWorkbench", domain)
    assert c.wait_for_asset(10), "no bridge matched"
    finals = 0
    for _ in range(n):
        cid = c.send("Admin", "noOp", [])
        finals += any(a[0] == COMPLETED for a in c.wait_final(cid, 10))
    c.close()
    dp = DomainParticipant(domain)  # kept: the built-in readers die with it
    d = Discovery(dp)
    counts: list[int] = []
    end = time.monotonic() + 8
    # discovery, and deletions (after the readers acknowledged), take a moment: until the
    # count has held for 1.5 s
    while time.monotonic() < end and not (len(counts) >= 4 and len(set(counts[-4:])) == 1):
        time.sleep(0.5)
        d.poll()
        counts.append(sum(1 for e in d.endpoints.values() if e.kind == "writer" and e.topic == "rapid_ack"
                          and tables.partition in e.partitions))
    return {"answered": finals, "ack_writers": counts[-1] if counts else 0}


def position(rapid, tables, qos, domain: int) -> dict:
    from rapid_runtime.dds import Node
    reader = Node(rapid, qos, domain).reader("rapid_position_sample", rapid.PositionSample)
    keys = next(t for t in tables.telemetry if t["kind"] == "position")["values"]
    got: list = []
    end = time.monotonic() + 5
    while time.monotonic() < end and not got:
        time.sleep(1.2)  # at 1 Hz: one sent after the drive
        got = reader.take(N=16)
    if not got:
        return {"xyz": None}
    s = got[-1]
    return {"xyz": [round(x, 3) for x in s.pose.xyz],
            "values": {k["name"]: round(v.value, 3) for k, v in zip(keys, s.values)
                       if isinstance(v.value, float)}}


def picture(rapid, qos, domain: int, topic: str) -> dict:
    from rapid_runtime.dds import Node
    from tests.runtime.test_simulate_telemetry import picture_size
    reader = Node(rapid, qos, domain).reader(topic, rapid.ImageSensorSample)
    got: list = []
    end = time.monotonic() + 15
    while time.monotonic() < end and not got:
        got = reader.take(N=4)
        time.sleep(0.05)
    if not got:
        return {"picture": None}
    s = got[-1]
    return {"mime": s.mimeType, "meta": [s.meta.width, s.meta.height], "picture": picture_size(s.mimeType, bytes(s.data))}


def _started(argv: list[str]):
    import os
    import subprocess
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}  # the bridge's own `local` transport
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    line = proc.stdout.readline() if proc.stdout else ""
    if "ready" not in line:
        proc.kill()
        raise SystemExit(f"the bridge did not start: {line!r} {proc.stderr.read() if proc.stderr else ''}")
    return proc


def _config_serial(rapid, qos, domain: int, timeout: float = 10) -> int | None:
    """The CommandConfig's serial (transient-local: a new reader gets the last one)."""
    from rapid_runtime.dds import Node
    node = Node(rapid, qos, domain)
    reader = node.reader("rapid_command_config", rapid.CommandConfig)
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        got = reader.take(N=8)
        if got:
            return int(got[-1].hdr.serial)
        time.sleep(0.05)
    return None


def restart(rapid, tables, qos, domain: int, argv: list[str]) -> dict:
    import signal
    from rapid_runtime.commander import Commander
    out: dict = {"serials": []}
    first = _started(argv)
    try:
        c = Commander(rapid, qos, tables.name, "RapidWorkbench", domain)
        assert c.wait_for_asset(10), "no bridge matched"
        out["serials"].append(_config_serial(rapid, qos, domain))
        c.wait_final(c.send("AccessControl", "requestControl", []), 10)
        done = c.send("Admin", "noOp", [], cmd_id="done-before")
        out["before"] = c.wait_final(done, 10)
        drive = c.send("Mobility", "simpleMove", [("RAPID_STRING", "site"), ("RAPID_VEC3d", (100.0, 0.0, 0.0))],
                       action="QUEUE_APPEND", cmd_id="drive")
        behind = c.send("Admin", "noOp", [], action="QUEUE_APPEND", cmd_id="behind")
        end = time.monotonic() + 10
        with c.cond:  # the drive running, the noOp queued behind it
            while not (any(a[0] == "ACK_EXECUTING" for a in c.acks.get(drive, ())) and
                       any(a[0] == "ACK_QUEUED" for a in c.acks.get(behind, ()))) and time.monotonic() < end:
                c.cond.wait(0.05)
        out["at_kill"] = {cid: [list(a) for a in c.acks.get(cid, ())] for cid in (drive, behind)}
    finally:
        first.kill()
        first.wait()
    second = _started(argv)
    try:
        out["after"] = {cid: [list(a) for a in c.wait_final(cid, 15)] for cid in (drive, behind)}
        out["serials"].append(_config_serial(rapid, qos, domain))
        out["before_repeat"] = [list(a) for a in c.wait_acks(done, 1)]  # (restore writes its final ack again)
        c.send("Admin", "noOp", [], cmd_id=done)  # answered already: its final ack again, nothing run
        out["repeat"] = [list(a) for a in c.wait_acks(done, 2)]
        c.close()
    finally:
        second.send_signal(signal.SIGTERM)
        try:
            out["stop_code"] = second.wait(20)
        except Exception:
            second.kill()
            out["stop_code"] = second.wait()
        out["log"] = second.stderr.read().splitlines()[-20:] if second.stderr else []
    return out


def main() -> int:
    check, pydir, package, domain = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    _pkg, rapid, tables, qos = load(pydir, package)
    if check == "late-acks":
        out = late_acks(rapid, tables, qos, domain, int(sys.argv[5]))
    elif check == "ack-writers":
        out = ack_writers(rapid, tables, qos, domain, int(sys.argv[5]))
    elif check == "position":
        out = position(rapid, tables, qos, domain)
    elif check == "picture":
        out = picture(rapid, qos, domain, sys.argv[5])
    elif check == "restart":
        out = restart(rapid, tables, qos, domain, json.loads(sys.argv[5]))
    elif check == "every":
        out = commands(rapid, tables, qos, domain)
    else:
        raise SystemExit(f"unknown check {check!r}")
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
