"""The Python side of the live interop tests (tests/cpp, tests/rust): K10's generated
cyclonedds bindings and QoS.

    py_peer.py pub|sub DOMAIN SECONDS [--default-partition]
    stdin: "topic type profile le_hex" lines (profile "-": none, the DDS default QoS)

Each topic gets its generated QoS: an asset topic its own (RapidQos), another one the
line's profile from the same QoS files. --default-partition leaves out the asset's
partition (RustDDS 0.15 has none, so a RAPID partition would keep the two sides apart).
pub writes each topic's sample every 200 ms for SECONDS; sub reads until every topic
delivered a sample, printing "ok TOPIC" (field-equal to the decoded vector) or
"MISMATCH TOPIC", and exits 0 when all are equal. CYCLONEDDS_URI must name the generated
loopback configuration (the tests set it).
"""
from __future__ import annotations

import importlib
import os
import sys
import time

from cyclonedds.domain import DomainParticipant
from cyclonedds.pub import DataWriter, Publisher
from cyclonedds.qos_provider import QosProvider
from cyclonedds.sub import DataReader, Subscriber
from cyclonedds.topic import Topic

from rapid_k10red.qos import RapidQos, UnknownTopic, default_qos_dir

LIBRARY = "RapidQosLibrary::"


def type_of(scoped: str) -> type:
    *mods, name = scoped.split("::")
    return getattr(importlib.import_module(".".join(["rapid_k10red", *mods])), name)


def qos_of(qos: RapidQos, provider: QosProvider, mode: str, topic: str, profile: str, partition: bool):
    """(group QoS, endpoint QoS) of a line; None is the DDS default."""
    pub = mode == "pub"
    try:
        qos.key(topic)
        group = (qos.publisher(topic) if pub else qos.subscriber(topic)) if partition else None
        return group, qos.writer(topic) if pub else qos.reader(topic)
    except UnknownTopic:  # a message type the asset does not publish: the line's profile
        if profile == "-":
            return None, None
        key = LIBRARY + profile
        group = (provider.get_publisher_qos(key) if pub else provider.get_subscriber_qos(key)) if partition else None
        return group, provider.get_datawriter_qos(key) if pub else provider.get_datareader_qos(key)


def main() -> int:
    mode, domain, seconds = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
    partition = "--default-partition" not in sys.argv[4:]
    qos = RapidQos()
    provider = QosProvider(os.path.join(default_qos_dir(), "dds-xml", "rapid_qos.xml"))
    dp = DomainParticipant(domain)
    ends = []
    for line in sys.stdin.read().splitlines():
        topic, scoped, profile, hexbytes = line.split()
        cls = type_of(scoped)
        expected = cls.deserialize(bytes.fromhex(hexbytes))
        t = Topic(dp, topic, cls)
        group, endpoint = qos_of(qos, provider, mode, topic, profile, partition)
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
