"""A plain RAPID subscriber for the tests (Cyclone, the generated package's QoS and
transport): prints one JSON line per topic (its first sample), then exits.
usage: rapid_listener.py PACKAGE TOPIC=rapid::Type ..."""
from __future__ import annotations

import hashlib
import importlib
import json
import sys
import time

from rapid_runtime.dds import Node, type_class, use_transport


def plain(s) -> dict:
    kind = type(s).__name__
    if kind == "JointSample":
        return {"anglePos": list(s.anglePos), "angleVel": list(s.angleVel), "torque": list(s.torque)}
    if kind == "PositionSample":
        return {"xyz": list(s.pose.xyz), "rot": list(s.pose.rot), "vxyz": list(s.velocity.xyz),
                "vrot": list(s.velocity.rot)}
    if kind == "AgentState":
        return {"values": [list(u.value) if isinstance(u.value, (list, tuple)) else u.value for u in s.values]}
    if kind == "ImageSensorSample":
        return {"mime": s.mimeType, "sensor": s.meta.sensorName, "width": s.meta.width, "height": s.meta.height,
                "sha256": hashlib.sha256(bytes(s.data)).hexdigest()}
    raise TypeError(kind)


def main() -> int:
    package = importlib.import_module(sys.argv[1])
    qos = importlib.import_module(f"{sys.argv[1]}.qos").RapidQos()
    tables = importlib.import_module(f"{sys.argv[1]}.asset_tables")
    use_transport(qos, None)
    node = Node(package.rapid, qos, tables.ASSET.get("domain", 0))
    readers = {}
    for arg in sys.argv[2:]:
        topic, type_name = arg.split("=")
        readers[topic] = node.reader(topic, type_class(package.rapid, type_name))
    got: dict[str, dict] = {}
    while len(got) < len(readers):
        for topic, reader in readers.items():
            if topic not in got:
                samples = reader.take(N=1)
                if samples:
                    got[topic] = plain(samples[0])
        time.sleep(0.02)
    for topic, sample in got.items():
        print(json.dumps({"topic": topic, "sample": sample}), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
