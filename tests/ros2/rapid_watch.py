"""A plain RAPID subscriber for tests/ros2/test_stale.py: prints one JSON line per sample of
the position, agent and text topics as it arrives (its arrival time, monotonic seconds,
and the header stamp), until killed. usage: rapid_watch.py PACKAGE"""
from __future__ import annotations

import importlib
import json
import sys
import time

from rapid_runtime.dds import Node, type_class, use_transport


def main() -> int:
    package = importlib.import_module(sys.argv[1])
    qos = importlib.import_module(f"{sys.argv[1]}.qos").RapidQos()
    tables = importlib.import_module(f"{sys.argv[1]}.asset_tables")
    use_transport(qos, None)
    node = Node(package.rapid, qos, tables.ASSET.get("domain", 0))
    readers = {topic: node.reader(topic, type_class(package.rapid, type_name)) for topic, type_name in (
        ("rapid_position_sample", "rapid::PositionSample"), ("rapid_agent_state", "rapid::AgentState"),
        ("rapid_textmessage", "rapid::TextMessage"))}
    print(json.dumps({"ready": True}), flush=True)
    while True:
        for topic, reader in readers.items():
            for s in reader.take(N=64):
                line = {"topic": topic, "at": time.monotonic(), "stamp": s.hdr.timeStamp}
                if topic == "rapid_position_sample":
                    line["x"] = s.pose.xyz[0]
                elif topic == "rapid_agent_state":
                    line["values"] = [u.value for u in s.values]
                else:
                    line["message"] = s.message
                print(json.dumps(line), flush=True)
        time.sleep(0.02)


if __name__ == "__main__":
    sys.exit(main())
