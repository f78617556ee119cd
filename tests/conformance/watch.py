"""A second participant beside a conformance run (tests/conformance/test_safety.py): it can
take control first as another operator, and it reads every command on rapid_command and the
asset's AccessControlState.

    python -m tests.conformance.watch PYDIR PACKAGE DOMAIN [OPERATOR]

With OPERATOR it sends AccessControl/requestControl as that source and waits until
AccessControlState names it. Prints "watch ready" once its readers exist (and the operator
holds control), then one JSON line per command seen ({"src", "subsystem", "name", "args"}),
and, once stdin closes, {"controller": ...} (the latest AccessControlState's controller,
read after two seconds' quiet) and exits.
"""
from __future__ import annotations

import importlib
import json
import sys
import threading
import time


def main() -> int:
    pydir, package, domain = sys.argv[1], sys.argv[2], int(sys.argv[3])
    operator = sys.argv[4] if len(sys.argv) > 4 else ""
    sys.path.insert(0, pydir)
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.qos import Policy, Qos
    from cyclonedds.sub import DataReader, Subscriber
    from cyclonedds.topic import Topic

    rapid = importlib.import_module(f"{package}.rapid")
    qos = importlib.import_module(f"{package}.qos").RapidQos()
    tables = importlib.import_module(f"{package}.asset_tables")
    asset, partition = tables.ASSET["name"], tables.ASSET["partition"]
    dp = DomainParticipant(domain)
    part = Qos(Policy.Partition([partition]))
    sub, pub = Subscriber(dp, qos=part), Publisher(dp, qos=part)
    keep_all = Qos(Policy.History.KeepAll)
    commands = DataReader(sub, Topic(dp, "rapid_command", rapid.Command), qos=qos.reader("rapid_command") + keep_all)
    state = DataReader(sub, Topic(dp, "rapid_accesscontrol_state", rapid.AccessControlState),
                       qos=qos.reader("rapid_accesscontrol_state"))
    latest: list = [None]
    lock = threading.Lock()

    def poll(show: bool = True) -> None:
        for c in commands.take(N=256):
            # (an instance's state: conform deletes its writer as it ends, which unregisters)
            if not show or not isinstance(c, rapid.Command):  # (the operator's own request is not the run's)
                continue
            args = [getattr(a, "value", None) for a in c.arguments]
            print(json.dumps({"src": c.cmdSrc, "subsystem": c.subsysName, "name": c.cmdName,
                              "args": [list(a) if isinstance(a, (list, tuple)) else a for a in args]},
                             default=str), flush=True)
        for s in state.take(N=64):
            if not isinstance(s, rapid.AccessControlState):
                continue
            with lock:
                latest[0] = s.controller

    if operator:
        writer = DataWriter(pub, Topic(dp, "rapid_command", rapid.Command), qos=qos.writer("rapid_command"))
        time.sleep(1.0)  # discovery
        end = time.monotonic() + 20
        while time.monotonic() < end and latest[0] != operator:
            hdr = rapid.Header(srcName=operator, assetName=asset, timeStamp=time.time_ns() // 1000, statusCode=0,
                               serial=0)
            writer.write(rapid.Command(hdr=hdr, cmdName="requestControl", cmdId=f"watch-{time.time_ns()}",
                                       cmdSrc=operator, subsysName="AccessControl", arguments=[],
                                       cmdAction=rapid.QueueAction["QUEUE_BYPASS"], targetCmdId=""))
            stop = time.monotonic() + 2
            while time.monotonic() < stop and latest[0] != operator:
                poll(show=False)
                time.sleep(0.05)
        if latest[0] != operator:
            print(f"watch: {operator} did not get control (controller {latest[0]!r})", file=sys.stderr)
            return 1
        poll(show=False)
    print("watch ready", flush=True)
    done = threading.Event()
    threading.Thread(target=lambda: (sys.stdin.read(), done.set()), daemon=True).start()
    while not done.is_set():
        poll()
        time.sleep(0.05)
    quiet = time.monotonic() + 2.0
    while time.monotonic() < quiet:
        poll()
        time.sleep(0.05)
    print(json.dumps({"controller": latest[0]}), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
