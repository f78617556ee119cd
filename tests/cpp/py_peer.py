"""The Python side of the C++ interop test: K10's generated cyclonedds bindings and QoS.

    py_peer.py pub|sub DOMAIN SECONDS     stdin: "topic type profile le_hex" lines

pub writes each topic's sample every 200 ms for SECONDS; sub reads until every topic
delivered a sample, printing "ok TOPIC" (field-equal to the decoded vector) or
"MISMATCH TOPIC", and exits 0 when all are equal. CYCLONEDDS_URI must name the generated
loopback configuration (the test sets it).
"""
from __future__ import annotations

import importlib
import os
import sys
import time

from cyclonedds.domain import DomainParticipant
from cyclonedds.pub import DataWriter, Publisher
from cyclonedds.sub import DataReader, Subscriber
from cyclonedds.topic import Topic

from cyclonedds.qos_provider import QosProvider

from rapid_k10red.qos import RapidQos, UnknownTopic, default_qos_dir

LIBRARY = "RapidQosLibrary::"


def type_of(scoped: str) -> type:
    *mods, name = scoped.split("::")
    return getattr(importlib.import_module(".".join(["rapid_k10red", *mods])), name)


def main() -> int:
    mode, domain, seconds = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
    qos = RapidQos()
    # message types K10 does not publish (JointSample, ...): the line's profile, from the same files
    provider = QosProvider(os.path.join(default_qos_dir(), "dds-xml", "rapid_qos.xml"))
    dp = DomainParticipant(domain)
    ends = []
    for line in sys.stdin.read().splitlines():
        topic, scoped, profile, hexbytes = line.split()
        cls = type_of(scoped)
        expected = cls.deserialize(bytes.fromhex(hexbytes))
        t = Topic(dp, topic, cls)
        try:
            qos.key(topic)
            group, endpoint = ((qos.publisher(topic), qos.writer(topic)) if mode == "pub"
                               else (qos.subscriber(topic), qos.reader(topic)))
        except UnknownTopic:
            key = LIBRARY + profile
            group, endpoint = ((provider.get_publisher_qos(key), provider.get_datawriter_qos(key)) if mode == "pub"
                               else (provider.get_subscriber_qos(key), provider.get_datareader_qos(key)))
        if mode == "pub":
            ends.append((topic, DataWriter(Publisher(dp, qos=group), t, qos=endpoint), expected))
        else:
            ends.append((topic, DataReader(Subscriber(dp, qos=group), t, qos=endpoint), expected))
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
