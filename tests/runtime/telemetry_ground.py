"""The ground side of tests/runtime/test_simulate_telemetry.py, its own process against a
running simulated bridge: `python -m tests.runtime.telemetry_ground GENERATED_PYTHON_DIR
PACKAGE DOMAIN SECONDS`.

Reads every topic of every declared telemetry entry (config, sample, state) with the
generated class and the topic's generated reader QoS, for at most SECONDS or until each
topic has samples enough to judge (rated topics: a few seconds' worth). Cameras without a
rate are asked for a picture by each picture command on their subsystem (valid arguments;
a source the allow-list lets send everything, control requested first where there is
access control). Prints one JSON document: per topic the type, the arrivals (monotonic
seconds) and the first and last samples in plain form, image data base64-encoded.
"""
from __future__ import annotations

import base64
import enum
import json
import re
import sys
import time

from tests.runtime.ground import load, source_for, valid_value

PICTURE = re.compile(r"picture|image|photo|snap|capture|panorama|acquire|shoot", re.I)


def plain(value):
    """A received sample as JSON-able data: structs as dicts, enums by name, octets base64."""
    from cyclonedds.idl import IdlUnion
    if isinstance(value, IdlUnion):
        return {"discriminator": plain(value.discriminator), "value": plain(value.value)}
    if hasattr(value, "__dataclass_fields__"):
        return {k: plain(getattr(value, k)) for k in value.__dataclass_fields__}
    if isinstance(value, enum.Enum):
        return value.name
    if isinstance(value, (bytes, bytearray)):
        return {"base64": base64.b64encode(bytes(value)).decode()}
    if isinstance(value, (list, tuple)):
        if value and all(isinstance(x, int) and not isinstance(x, bool) and 0 <= x < 256 for x in value) \
                and len(value) > 64:
            return {"base64": base64.b64encode(bytes(value)).decode()}
        return [plain(x) for x in value]
    return value


def topics_of(tables) -> dict[str, tuple[str, dict, str]]:
    """topic -> (scoped type name, its telemetry entry, role), for every role of every entry."""
    types = {p["topic"]: p["type"] for p in tables.publications}
    out = {}
    for t in tables.telemetry:
        for role, topic in t["topics"].items():
            out[topic] = (t.get("types", {}).get(role) or types[topic], t, role)
    return out


def main() -> int:
    python_dir, package, domain, seconds = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
    _pkg, rapid, tables, qos = load(python_dir, package)
    from rapid_runtime.commander import Commander
    from rapid_runtime.dds import Node, type_class

    node = Node(rapid, qos, domain)
    wanted = topics_of(tables)
    readers = {topic: node.reader(topic, type_class(rapid, ty)) for topic, (ty, _e, _r) in wanted.items()}
    got: dict[str, dict] = {topic: {"type": ty, "kind": e["kind"], "role": role, "rate": e.get("rate"), "at": [],
                                    "first": None, "last": None} for topic, (ty, e, role) in wanted.items()}
    asked = []
    cameras = {t.get("subsystem") for t in tables.telemetry if t["kind"] == "image" and not t.get("rate")}
    commands = [(sub, e) for sub, e in tables.entries() if sub in cameras and PICTURE.search(e.name)]
    if commands:
        c = Commander(rapid, qos, tables.name, source_for(tables), domain)
        assert c.wait_for_asset(10), "no bridge matched"
        if tables.has_type("AccessControl"):
            c.wait_final(c.send("AccessControl", "requestControl"), 10)
        for sub, e in commands:
            cid = c.send(sub, e.name, [(p.type, valid_value(p)) for p in e.params])
            asked.append({"command": f"{sub}/{e.name}", "acks": c.wait_final(cid, 20)})
        c.close()

    def enough(topic: str) -> bool:
        g = got[topic]
        if not g["at"]:
            return False
        if not g["rate"] or g["role"] == "config":
            return True
        return g["at"][-1] - g["at"][0] >= 3.0 and len(g["at"]) >= 3  # a few seconds of samples

    start = time.monotonic()
    end = start + seconds
    while time.monotonic() < end and not all(enough(t) for t in got):
        for topic, r in readers.items():
            for s in r.take(N=64):  # raises if a sample does not decode: the test fails on it
                g = got[topic]
                g["at"].append(time.monotonic() - start)
                g["last"] = plain(s)
                if g["first"] is None:
                    g["first"] = g["last"]
        time.sleep(0.01)
    print(json.dumps({"topics": got, "asked": asked, "asset": tables.name}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
