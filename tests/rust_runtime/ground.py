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


def main() -> int:
    check, pydir, package, domain = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    _pkg, rapid, tables, qos = load(pydir, package)
    if check == "late-acks":
        out = late_acks(rapid, tables, qos, domain, int(sys.argv[5]))
    elif check == "every":
        out = commands(rapid, tables, qos, domain)
    else:
        raise SystemExit(f"unknown check {check!r}")
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
