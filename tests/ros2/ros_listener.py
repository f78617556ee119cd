"""A plain rclpy subscriber for the tests: prints one JSON line per topic (its first
message), then exits. usage: ros_listener.py TOPIC=pkg/msg/Type ...
/rosout is read as rqt_console does (transient local), keeping the first Log whose name
starts with ROSOUT_NAME (environment); a topic with /config/ in its name is read transient
local too (ros2_ground's latched configs, std_msgs/String holding JSON)."""
from __future__ import annotations

import hashlib
import importlib
import json
import os
import sys

import rclpy
from rclpy.qos import DurabilityPolicy, QoSProfile


def plain(msg) -> dict:
    kind = type(msg).__name__
    if kind == "JointState":
        return {"name": list(msg.name), "position": list(msg.position), "velocity": list(msg.velocity),
                "effort": list(msg.effort), "stamp": msg.header.stamp.sec}
    if kind == "PoseStamped":
        p, o = msg.pose.position, msg.pose.orientation
        return {"frame": msg.header.frame_id, "xyz": [p.x, p.y, p.z], "quat": [o.x, o.y, o.z, o.w],
                "stamp": msg.header.stamp.sec}
    if kind == "DiagnosticArray":
        return {"status": [{"name": s.name, "level": s.level[0], "message": s.message, "hardware_id": s.hardware_id,
                            "values": {kv.key: kv.value for kv in s.values}} for s in msg.status]}
    if kind == "CompressedImage":
        return {"format": msg.format, "frame": msg.header.frame_id, "sha256": hashlib.sha256(bytes(msg.data)).hexdigest(),
                "stamp": msg.header.stamp.sec}
    if kind == "String":  # a config (ros2_ground): its JSON
        return json.loads(msg.data)
    if kind == "Log":
        return {"name": msg.name, "level": msg.level, "msg": msg.msg, "stamp": msg.stamp.sec}
    raise TypeError(kind)


def main() -> int:
    rclpy.init()
    node = rclpy.create_node("rapidgen_test_listener")
    wanted = {}
    for arg in sys.argv[1:]:
        topic, type_name = arg.split("=")
        package, sub, name = type_name.split("/")
        cls = getattr(importlib.import_module(f"{package}.{sub}"), name)
        wanted[topic] = None
        if topic == "/rosout":
            prefix = os.environ.get("ROSOUT_NAME", "")
            node.create_subscription(cls, topic, lambda m, t=topic: wanted.__setitem__(
                t, wanted[t] or (plain(m) if m.name.startswith(prefix) else None)),
                QoSProfile(depth=1000, durability=DurabilityPolicy.TRANSIENT_LOCAL))
            continue
        latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)  # ros2_ground's configs
        node.create_subscription(cls, topic, lambda m, t=topic: wanted.__setitem__(t, wanted[t] or plain(m)),
                                 latched if "/config/" in topic else 10)
    while any(v is None for v in wanted.values()):
        rclpy.spin_once(node, timeout_sec=0.5)
    for topic, got in wanted.items():
        print(json.dumps({"topic": topic, "msg": got}), flush=True)
    node.destroy_node()
    rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
