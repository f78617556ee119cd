"""The Python side of the RustDDS interop test: K10's generated cyclonedds bindings.

    py_peer.py pub|sub DOMAIN SECONDS     stdin: "topic type profile le_hex" lines
                                          (profile "-": not one of the asset's topics)

As tests/cpp/py_peer.py, with the generated reader and writer QoS of each topic (the
default QoS for a topic the asset does not publish), but in
the default partition: RustDDS 0.15 has no Partition QoS, so a RAPID partition would
keep the two sides apart. pub writes each topic's sample every 200 ms for SECONDS; sub
reads until every topic delivered a sample, printing "ok TOPIC" (field-equal to the
decoded vector) or "MISMATCH TOPIC", and exits 0 when all are equal. CYCLONEDDS_URI must
name the generated loopback configuration (the test sets it).
"""
from __future__ import annotations

import importlib
import sys
import time

from cyclonedds.domain import DomainParticipant
from cyclonedds.pub import DataWriter, Publisher
from cyclonedds.sub import DataReader, Subscriber
from cyclonedds.topic import Topic

from rapid_k10red.qos import RapidQos


def type_of(scoped: str) -> type:
    *mods, name = scoped.split("::")
    return getattr(importlib.import_module(".".join(["rapid_k10red", *mods])), name)


def main() -> int:
    mode, domain, seconds = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
    qos = RapidQos()
    dp = DomainParticipant(domain)
    publisher, subscriber = Publisher(dp), Subscriber(dp)
    ends = []
    for line in sys.stdin.read().splitlines():
        topic, scoped, profile, hexbytes = line.split()
        cls = type_of(scoped)
        expected = cls.deserialize(bytes.fromhex(hexbytes))
        t = Topic(dp, topic, cls)
        known = profile != "-"  # "-": a topic the asset does not publish
        if mode == "pub":
            ends.append((topic, DataWriter(publisher, t, qos=qos.writer(topic) if known else None), expected))
        else:
            ends.append((topic, DataReader(subscriber, t, qos=qos.reader(topic) if known else None), expected))
    end = time.monotonic() + seconds
    done: set[str] = set()
    while time.monotonic() < end:
        for topic, ep, expected in ends:
            if mode == "pub":
                ep.write(expected)
            elif topic not in done:
                for got in ep.take(N=16):
                    if isinstance(got, type(expected)):
                        print(("ok " if got == expected else "MISMATCH ") + topic, flush=True)
                        done.add(topic)
                        break
        if mode == "sub" and len(done) == len(ends):
            return 0
        time.sleep(0.2 if mode == "pub" else 0.02)
    return 0 if mode == "pub" else 1


if __name__ == "__main__":
    sys.exit(main())
