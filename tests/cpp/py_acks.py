"""The Cyclone side of tests/cpp/test_fastdds_limits.py: ack readers with K10's generated
Python bindings and QoS, as a ground tool has them. Line by line on stdin, one answer line
each on stdout (the protocol of tests/cpp/src/ack_flood.cpp):

    reader NAME volatile|durable     an ack reader, KEEP_ALL, created now (volatile: as
                                     rapidgen conform's and a commander's relaxed reader)
    matched NAME N SECONDS           wait until reader NAME matched N writers -> "matched K"
    expect NAME FIRST LAST SECONDS   wait until NAME took a COMPLETED ack of each of
                                     ack-FIRST .. ack-(LAST-1) -> "got NAME K of N"
    quit

    py_acks.py DOMAIN       (CYCLONEDDS_URI: the generated loopback configuration)
"""
from __future__ import annotations

import sys
import time

from cyclonedds.domain import DomainParticipant
from cyclonedds.qos import Policy, Qos
from cyclonedds.sub import DataReader, Subscriber
from cyclonedds.topic import Topic

from rapid_k10red import rapid
from rapid_k10red.qos import RapidQos


def main() -> int:
    qos = RapidQos()
    dp = DomainParticipant(int(sys.argv[1]))
    sub = Subscriber(dp, qos=qos.subscriber("rapid_ack"))
    topic = Topic(dp, "rapid_ack", rapid.Ack)
    readers: dict[str, tuple[DataReader, set[str]]] = {}
    for line in sys.stdin:
        words = line.split()
        if not words:
            continue
        if words[0] == "quit":
            break
        if words[0] == "reader":
            name, durability = words[1], words[2]
            q = qos.reader("rapid_ack") + Qos(Policy.History.KeepAll)
            if durability == "volatile":
                q = q + Qos(Policy.Durability.Volatile)
            readers[name] = (DataReader(sub, topic, qos=q), set())
            answer = f"reader {name}"
        elif words[0] == "matched":
            reader = readers[words[1]][0]
            end = time.monotonic() + float(words[3])
            while len(reader.get_matched_publications()) < int(words[2]) and time.monotonic() < end:
                time.sleep(0.02)
            answer = f"matched {len(reader.get_matched_publications())}"
        elif words[0] == "expect":
            reader, got = readers[words[1]]
            first, last = int(words[2]), int(words[3])
            want = {f"ack-{i}" for i in range(first, last)}
            end = time.monotonic() + float(words[4])
            while True:
                for a in reader.take(N=256):
                    if hasattr(a, "cmdId") and a.status == rapid.AckStatus.ACK_COMPLETED:
                        got.add(a.cmdId)
                if want <= got or time.monotonic() >= end:
                    break
                time.sleep(0.02)
            answer = f"got {words[1]} {len(want & got)} of {len(want)}"
        else:
            answer = f"bad command: {line.strip()}"
        print(answer, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
