"""One side of the live test; run as a subprocess whose CYCLONEDDS_URI pins DDS to loopback.

    python -m tests.python_backend.live_peer sub|pub --domain N --partition P [--timeout S]

sub: creates a reader per RAPID message topic, prints READY, then one JSON line per
     received message {"topic", "type", "type_name", "value"} (type_name as announced by
     the remote writer's discovery data), then DONE, or TIMEOUT with what is missing.
pub: creates a writer per topic, waits until each is matched, writes one filled sample
     per message type, waits until they are acknowledged, prints PUBLISHED, and stays
     until the subscriber has gone.

Both build the generated package's classes from generated/rapid/python (PYTHONPATH).
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time
import xml.etree.ElementTree as ET


def loopback_refusal(uri: str | None) -> str | None:
    """Why CYCLONEDDS_URI does not keep Cyclone on loopback, or None when it does.

    It must be `file://PATH` of exactly one configuration file (not inline XML, not a
    list, no ${VAR}) whose every <Domain> sets <AllowMulticast>false</AllowMulticast>,
    pins every network interface to 127.0.0.1 and has no peer but 127.0.0.1.
    """
    uri = (uri or "").strip()
    if not uri:
        return "CYCLONEDDS_URI is not set (Cyclone's default uses every interface and multicast)"
    if uri.startswith("<"):
        return "CYCLONEDDS_URI holds inline XML; point it at a configuration file (file://PATH)"
    if "," in uri or "$" in uri:
        return f"CYCLONEDDS_URI={uri!r} is a list or uses ${{VAR}}; give exactly one file (file://PATH)"
    path = uri[len("file://"):] if uri.startswith("file://") else uri
    if not uri.startswith("file://") or "://" in path:
        return f"CYCLONEDDS_URI={uri!r} is not a file URI (file://PATH)"
    try:
        root = ET.parse(path).getroot()  # XML comments are dropped: only live settings count
    except (OSError, ValueError, ET.ParseError) as exc:
        return f"cannot read {path!r} as a Cyclone DDS configuration: {exc}"

    def tag(e) -> str:
        return e.tag.rsplit("}", 1)[-1] if isinstance(e.tag, str) else ""

    domains = [e for e in root.iter() if tag(e) == "Domain"]
    if tag(root) != "CycloneDDS" or not domains:
        return f"{path} is not a Cyclone DDS configuration with a <Domain> section"
    for d in domains:
        where = f"{path} <Domain Id={d.get('Id', 'any')!r}>"
        multicast = [(e.text or "").strip().lower() for e in d.iter() if tag(e) == "AllowMulticast"]
        nics = [e.get("address") if tag(e) == "NetworkInterface" else (e.text or "").strip()
                for e in d.iter() if tag(e) in ("NetworkInterface", "NetworkInterfaceAddress")]
        peers = [e.get("Address") or e.get("address") for e in d.iter() if tag(e) == "Peer"]
        if multicast != ["false"]:
            return f"{where}: needs <AllowMulticast>false</AllowMulticast> (once), has {multicast}"
        if not nics or any(n != "127.0.0.1" for n in nics):
            return f'{where}: must pin every interface to 127.0.0.1 (<NetworkInterface address="127.0.0.1"/>)'
        if any(p != "127.0.0.1" for p in peers):
            return f"{where}: every <Peer> must be 127.0.0.1, has {peers}"
    return None


def _require_loopback_config() -> None:
    refusal = loopback_refusal(os.environ.get("CYCLONEDDS_URI"))
    if refusal is not None:
        sys.exit(f"live_peer: {refusal}; refusing to start DDS")


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser()
    p.add_argument("role", choices=["sub", "pub"])
    p.add_argument("--domain", type=int, required=True)
    p.add_argument("--partition", required=True)
    p.add_argument("--timeout", type=float, default=30.0)
    args = p.parse_args(argv)
    if not 40 <= args.domain <= 49:
        sys.exit("live_peer: python back-end tests use DDS domains 40-49 only")
    _require_loopback_config()

    # cyclonedds is imported only now, with the loopback configuration in the environment
    from cyclonedds.core import Policy, Qos
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.sub import DataReader, Subscriber
    from cyclonedds.topic import Topic
    from cyclonedds.util import duration

    from tests.python_backend.fill import Filler, message_types, plain, rapid_model, topic_of

    model = rapid_model()
    filler = Filler(model)
    messages = message_types(model)
    qos = Qos(Policy.Reliability.Reliable(duration(seconds=1)), Policy.Durability.TransientLocal,
              Policy.History.KeepLast(1))
    group_qos = Qos(Policy.Partition([args.partition]))
    dp = DomainParticipant(args.domain)
    topics = {s.scoped_name: Topic(dp, topic_of(model, s), filler.cls(s.scoped_name)) for s in messages}
    deadline = time.monotonic() + args.timeout

    if args.role == "sub":
        sub = Subscriber(dp, qos=group_qos)
        readers = {name: DataReader(sub, topic, qos=qos) for name, topic in topics.items()}
        print("READY", flush=True)
        pending = set(readers)
        announced: dict[str, set[str]] = {name: set() for name in readers}
        while pending and time.monotonic() < deadline:
            for name in sorted(pending):
                # a sample arrives only from a matched writer; note its type name while it exists
                for handle in readers[name].get_matched_publications():
                    data = readers[name].get_matched_publication_data(handle)
                    if data is not None:
                        announced[name].add(data.type_name)
                samples = readers[name].take(N=4)
                if not samples:
                    continue
                print(json.dumps({"topic": topics[name].name, "type": name, "type_name": sorted(announced[name]),
                                  "value": plain(samples[-1])}, ensure_ascii=False), flush=True)
                pending.discard(name)
            time.sleep(0.02)
        print("DONE" if not pending else f"TIMEOUT missing={sorted(pending)}", flush=True)
        return 0 if not pending else 1

    pub = Publisher(dp, qos=group_qos)
    writers = {name: DataWriter(pub, topic, qos=qos) for name, topic in topics.items()}
    unmatched = set(writers)
    while unmatched and time.monotonic() < deadline:
        unmatched = {n for n in unmatched if writers[n].get_publication_matched_status().current_count < 1}
        time.sleep(0.02)
    if unmatched:
        print(f"TIMEOUT unmatched={sorted(unmatched)}", flush=True)
        return 1
    for s in messages:
        writers[s.scoped_name].write(filler.message(s))
    remaining = max(1.0, deadline - time.monotonic())
    acked = all(w.wait_for_acks(duration(seconds=remaining)) for w in writers.values())
    print("PUBLISHED" if acked else "TIMEOUT acknowledgements", flush=True)
    # stay until the subscriber has left, so it can still look at these writers
    while time.monotonic() < deadline and any(
            w.get_publication_matched_status().current_count > 0 for w in writers.values()):
        time.sleep(0.02)
    return 0 if acked else 1


if __name__ == "__main__":
    raise SystemExit(main())
