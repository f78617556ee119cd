"""Cyclone DDS side of the QoS tier's live tests (run as a subprocess, CYCLONEDDS_URI set).

    cyclone_peer.py participant DOMAIN HOLD
        start a participant with the domain config, print 'ok', keep it HOLD seconds
    cyclone_peer.py ping DDS_XML DOMAIN PROFILE SECONDS COUNT
        publish rapidtest::Ping on rapidtest_ping until COUNT distinct echoes came back on
        rapidtest_pong (exit 0) or SECONDS passed (exit 1); QoS from the DDS-XML provider

Loopback guard: before any DDS call it refuses to run (exit 2) unless DOMAIN is one of
the tier's (60-79) and CYCLONEDDS_URI names one config file (file://PATH or PATH, as the
tests pass the generated local.xml or 127.0.0.1-pinned wan.xml) whose every domain
section pins the interfaces to 127.0.0.1, turns multicast off and lists only 127.0.0.1
peers (if any).
"""

import os
import sys
import time
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from urllib.parse import unquote, urlparse

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


LOOPBACK = {"127.0.0.1", "localhost"}


def loopback_problem(uri: str | None, domain: int) -> str | None:
    """Why this run might leave loopback, or None when the config keeps it there."""
    if not 60 <= domain <= 79:
        return f"domain {domain} is outside the QoS tier's 60-79"
    if not uri:
        return "CYCLONEDDS_URI is not set (Cyclone's default config uses every interface and multicast)"
    uri = uri.strip()
    if "," in uri or uri.startswith("<"):
        return "CYCLONEDDS_URI must name one config file, not a list or inline XML"
    path = unquote(urlparse(uri).path) if uri.startswith("file://") else uri
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        return f"cannot read the config {path}: {e}"

    def local(tag: str) -> str:
        return tag.rsplit("}", 1)[-1]

    domains = [d for d in root.iter() if local(d.tag) == "Domain"]
    if local(root.tag) != "CycloneDDS" or not domains:
        return f"{path} is not a Cyclone DDS config with a <Domain> section"
    for d in domains:
        where = f"{path} <Domain Id={d.get('Id', 'any')!r}>"
        found = {}
        for e in d.iter():
            found.setdefault(local(e.tag), []).append(e)
        multicast = [(e.text or "").strip().lower() for e in found.get("AllowMulticast", [])]
        if multicast != ["false"]:
            return f"{where}: needs exactly one <AllowMulticast>false</AllowMulticast>, has {multicast}"
        nics = found.get("NetworkInterface", [])
        if not nics or any(n.get("address") not in LOOPBACK and n.get("name") != "lo" for n in nics):
            return f"{where}: every <NetworkInterface> must be 127.0.0.1 (and one must be given)"
        if any((e.text or "").strip() not in LOOPBACK for e in found.get("NetworkInterfaceAddress", [])):
            return f"{where}: <NetworkInterfaceAddress> is not 127.0.0.1"
        peers = [p.get("Address") or p.get("address") for p in found.get("Peer", [])]
        if any(p not in LOOPBACK for p in peers):
            return f"{where}: peers must all be 127.0.0.1, has {peers}"
    return None


def main(argv: list[str]) -> int:
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    if argv[1] in ("participant", "ping"):
        at = 2 if argv[1] == "participant" else 3
        domain = argv[at] if len(argv) > at else ""
        problem = loopback_problem(os.environ.get("CYCLONEDDS_URI"), int(domain) if domain.isdigit() else -1)
        if problem:
            print(f"cyclone_peer: refusing to run, not loopback-only: {problem}", file=sys.stderr)
            return 2
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
