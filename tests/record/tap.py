"""An independent raw reader for tests/record (nothing of rapidgen.record): every topic of a
generated asset package, in its partition, with the package's own profile QoS (RapidQos),
the CDR bytes taken raw. Prints "tap ready" once its readers exist; on SIGTERM writes
{topic: [hex bytes, ...]} as JSON to OUT and exits 0.

    python -m tests.record.tap PYDIR PACKAGE DOMAIN OUT
"""
from __future__ import annotations

import importlib
import json
import signal
import sys
import threading


def main() -> int:
    pydir, package, domain, out = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
    sys.path.insert(0, pydir)
    from cyclonedds._clayer import ddspy_take
    from cyclonedds.core import InstanceState, SampleState, ViewState
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.qos import Policy, Qos
    from cyclonedds.sub import DataReader, Subscriber
    from cyclonedds.topic import Topic

    qos = importlib.import_module(f"{package}.qos").RapidQos()
    with open(qos.topics_file, encoding="utf-8") as fh:
        entries = json.load(fh)["topics"]
    dp = DomainParticipant(domain)
    sub = Subscriber(dp, qos=Qos(Policy.Partition([qos.partition])))
    readers = {}
    for e in entries:
        module, _, name = e["type"].replace("::", ".").rpartition(".")
        cls = getattr(importlib.import_module(f"{package}.{module}"), name)
        rq = qos.reader(e["topic"]) + Qos(Policy.History.KeepLast(1024))
        readers[e["topic"]] = DataReader(sub, Topic(dp, e["topic"], cls), qos=rq)
    got: dict[str, list[str]] = {t: [] for t in readers}
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    print("tap ready", flush=True)
    mask = SampleState.Any | ViewState.Any | InstanceState.Any
    while True:
        done = stop.is_set()
        for topic, r in readers.items():
            raw = ddspy_take(r._ref, mask, 256)
            if isinstance(raw, list):
                got[topic] += [bytes(d).hex() for d, info in raw if info.valid_data]
        if done:
            break
        stop.wait(0.01)
    with open(out, "w", encoding="utf-8") as fh:
        json.dump(got, fh)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
