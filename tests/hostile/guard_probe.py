"""The one guarded reader (rapid_runtime.untrusted) as the bridge uses it (logging, "runtime")
and as the tools do (deduping republished bytes, "tool") on one real Cyclone domain, fed the
same good and bad samples by a rogue writer in this process; prints what each delivered and
dropped as JSON.

    python -m tests.hostile.guard_probe PYDIR PACKAGE DOMAIN"""
import json
import sys
import time


def main() -> int:
    pydir, package, domain = sys.argv[1], sys.argv[2], int(sys.argv[3])
    from cyclonedds.sub import DataReader, Subscriber
    from cyclonedds.qos import Policy, Qos
    from cyclonedds.topic import Topic

    from rapid_runtime.untrusted import GuardedReader
    from tests.hostile.rogue import Rogue

    r = Rogue(pydir, package, domain)
    sub = Subscriber(r.dp, qos=Qos(Policy.Partition([r.partition])))
    topic = Topic(r.dp, "rapid_command", r.rapid.Command)
    readers = [DataReader(sub, topic, qos=r.qos.reader("rapid_command")) for _ in range(2)]
    logs: list[str] = []
    guards = {"runtime": GuardedReader(readers[0], logs.append, batch=4),
              "tool": GuardedReader(readers[1], batch=4, dedupe=True)}
    time.sleep(0.5)
    for i in range(10):  # bad ones among good ones, in one batch and across batches
        if i % 3 == 1:
            r.raw("rapid_command", r.rapid.Command, r.bad_utf8_command(i))
        else:
            r.writer("rapid_command", r.rapid.Command).write(r.command(f"good-{i}"))
    time.sleep(1.0)
    out = {}
    for name, g in guards.items():
        got = []
        for _ in range(10):
            got += [s.cmdId for s in g.take()]
        out[name] = {"got": got, "dropped": g.dropped, "writers": [d.writer for d in g.drops.values()],
                     "counts": [d.count for d in g.drops.values()]}
    out["logs"] = logs
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
