"""Cyclone DDS side of the QoS tier's live tests (run as a subprocess, CYCLONEDDS_URI set).

    cyclone_peer.py participant DOMAIN HOLD
        start a participant with the domain config, print 'ok', keep it HOLD seconds
    cyclone_peer.py ping DDS_XML DOMAIN PROFILE SECONDS COUNT
        publish rapidtest::Ping on rapidtest_ping until COUNT distinct echoes came back on
        rapidtest_pong (exit 0) or SECONDS passed (exit 1); QoS from the DDS-XML provider
"""

import sys
import time
from dataclasses import dataclass

from cyclonedds.domain import DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.idl.types import int32
from cyclonedds.pub import DataWriter, Publisher
from cyclonedds.qos_provider import QosProvider
from cyclonedds.sub import DataReader, Subscriber
from cyclonedds.topic import Topic


@dataclass
class Ping(IdlStruct, typename="rapidtest.Ping"):  # @final, as tests/qos/cpp/qos_probe.cpp
    seq: int32
    text: str


def ping(xml: str, domain: int, profile: str, seconds: float, count: int) -> int:
    provider = QosProvider(xml)
    key = f"RapidQosLibrary::{profile}"
    dp = DomainParticipant(domain)
    pub = Publisher(dp, qos=provider.get_publisher_qos(key))
    sub = Subscriber(dp, qos=provider.get_subscriber_qos(key))
    writer = DataWriter(pub, Topic(dp, "rapidtest_ping", Ping), qos=provider.get_datawriter_qos(key))
    reader = DataReader(sub, Topic(dp, "rapidtest_pong", Ping), qos=provider.get_datareader_qos(key))
    print("ready", flush=True)
    seen: set[int] = set()
    seq, end, next_ping = 0, time.monotonic() + seconds, 0.0
    while time.monotonic() < end and len(seen) < count:
        if time.monotonic() >= next_ping:
            seq += 1
            writer.write(Ping(seq, f"cyclone ping {seq}"))
            next_ping = time.monotonic() + 0.1
        for s in reader.take(N=16):
            if isinstance(s, Ping) and s.seq not in seen:
                seen.add(s.seq)
                print("got", s.seq, s.text, flush=True)
        time.sleep(0.01)
    print("received", len(seen), flush=True)
    return 0 if len(seen) >= count else 1


def main(argv: list[str]) -> int:
    if argv[1] == "participant":
        dp = DomainParticipant(int(argv[2]))
        print("participant", dp.guid, flush=True)
        print("ok", flush=True)
        time.sleep(float(argv[3]))
        return 0
    if argv[1] == "ping":
        return ping(argv[2], int(argv[3]), argv[4], float(argv[5]), int(argv[6]))
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
