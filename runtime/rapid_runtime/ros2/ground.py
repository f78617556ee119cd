"""An asset seen from ROS 2: reads its RAPID telemetry (Cyclone DDS, the package's QoS and
partition) and republishes it as standard ROS 2 messages, as the package's ros2_map.GROUND
says. A generated `<package>/ros2_ground.py` calls main() with its tables.

- JointSample   -> sensor_msgs/JointState, names the JointConfig's joint frames, positions,
                   and velocities and efforts (angleVel, torque) when filled for every joint;
- PositionSample -> geometry_msgs/PoseStamped in the entry's frame (RAPID_ROT_QUAT,
                   RAPID_ROT_M33 and Euler XYZ, ZYX, ZYZ poses; another encoding gives the
                   identity rotation);
- AgentState    -> diagnostic_msgs/DiagnosticArray, one status per value ("Asset/key"),
                   level ERROR past its critical threshold, WARN past its warning one, else OK
                   (rapid_runtime.thresholds, the monitor's rule);
- ImageSensorSample -> sensor_msgs/CompressedImage, the picture's bytes as they are, format
                   from the MIME type ("png", "jpeg", else its subtype), frame_id the sensor;
- TextMessage   -> rcl_interfaces/Log on /rosout (name "Asset/category", levels mapped);
- each config   -> std_msgs/String on NS/config/<name> (agent, command, position/<suffix>,
                   ...), the sample as JSON (rapid_runtime.plain), latched (reliable, transient
                   local, depth 1) as /robot_description is: a late `ros2 topic echo` gets the
                   latest one.

Stamps are the samples' own (Header.timeStamp, microseconds). ROS 2 traffic follows
ROS_DOMAIN_ID and the RMW's settings; the RAPID side the package's transport (local by default).
"""
from __future__ import annotations

import argparse
import importlib
import json
import re
import signal
import sys
import threading
from types import ModuleType
from typing import Any

from rapid_runtime.dds import Node, ReaderThread, type_class, use_transport
from rapid_runtime.plain import plain
from rapid_runtime.ros2.fields import message_class
from rapid_runtime.ros2.rotations import quat_of_pose
from rapid_runtime.tables import Tables
from rapid_runtime.thresholds import CRITICAL, WARNING, threshold_level

SAMPLE = {"joint": ("sample", "rapid::JointSample"), "position": ("sample", "rapid::PositionSample"),
          "agent": ("state", "rapid::AgentState"), "image": ("sample", "rapid::ImageSensorSample"),
          "text": ("sample", "rapid::TextMessage")}
# rapid::MessageLevel -> rcl_interfaces/Log levels
LOG_LEVELS = {"MSG_DEBUG": 10, "MSG_INFO": 20, "MSG_ATTENTION": 20, "MSG_WARN": 30, "MSG_ERROR": 40,
              "MSG_CRITICAL": 50}
# diagnostic_msgs/DiagnosticStatus levels
OK, WARN, ERROR = 0, 1, 2
DIAGNOSTIC_LEVELS = {CRITICAL: ERROR, WARNING: WARN}


def stamp(ros_time: Any, micros: int) -> None:
    ros_time.sec, ros_time.nanosec = int(micros // 1_000_000), int(micros % 1_000_000) * 1000


def image_format(mime):
    """CompressedImage.format of a MIME type: "png" and "jpeg" as image_transport writes them."""
    sub = mime.split("/", 1)[-1].strip().lower()
    return {"jpg": "jpeg", "pjpeg": "jpeg"}.get(sub, sub)


def config_topic(namespace, topic):
    """NS/config/<name> of a RAPID config topic: rapid_position_config-rightArm ->
    NS/config/position/rightArm (ROS 2 names take letters, digits, _ and /)."""
    base, _, suffix = topic.partition("-")
    name = re.sub(r"^rapid_|_config$", "", base) + ("/" + suffix if suffix else "")
    return namespace + "/config/" + re.sub(r"[^A-Za-z0-9_/]", "_", name)



def union_value(u: Any) -> Any:
    value = u.value
    return [float(x) for x in value] if isinstance(value, (list, tuple)) else value


class Ground:
    """The ROS 2 publishers and RAPID readers of one asset: `rapid` is its generated types
    module, `ground` its ros2_map.GROUND (node, namespace, entries)."""

    def __init__(self, tables: Tables, node: Node, ros_node: Any, rapid: ModuleType, ground: dict) -> None:
        self.tables, self.node, self.ros = tables, node, ros_node
        self.threads: list[ReaderThread] = []
        self.JointState = message_class("sensor_msgs/msg/JointState")
        self.PoseStamped = message_class("geometry_msgs/msg/PoseStamped")
        self.DiagnosticArray = message_class("diagnostic_msgs/msg/DiagnosticArray")
        self.DiagnosticStatus = message_class("diagnostic_msgs/msg/DiagnosticStatus")
        self.KeyValue = message_class("diagnostic_msgs/msg/KeyValue")
        self.Log = message_class("rcl_interfaces/msg/Log")
        self.CompressedImage = message_class("sensor_msgs/msg/CompressedImage")
        self.String = message_class("std_msgs/msg/String")
        from rclpy.qos import DurabilityPolicy, QoSProfile
        # /rosout's own QoS (what rclpy's loggers and rqt_console use): reliable, transient local
        self.rosout_qos = QoSProfile(depth=1000, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        for entry in ground["entries"]:
            kind = entry["kind"]
            declared = [t for t in tables.telemetry if t["kind"] == kind][entry["index"]]
            role, type_name = SAMPLE[kind]
            cls = type_class(rapid, type_name)
            out_type = {"joint": self.JointState, "position": self.PoseStamped, "agent": self.DiagnosticArray,
                        "image": self.CompressedImage, "text": self.Log}[kind]
            pub = ros_node.create_publisher(out_type, entry["topic"], self.rosout_qos if kind == "text" else 10)
            convert = getattr(self, "_" + kind)
            reader = node.reader(declared["topics"][role], cls)
            on_sample = (lambda s, e=entry, p=pub, c=convert: p.publish(c(e, s)))
            self.threads.append(ReaderThread(node, reader, cls, on_sample, f"ground-{kind}-{entry['index']}",
                                             log=self._log).start())
        latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        for topic, (type_name, _value) in sorted(tables.configs.items()):
            cls = type_class(rapid, type_name)
            pub = ros_node.create_publisher(self.String, config_topic(ground["namespace"], topic), latched)
            on_config = (lambda s, p=pub: p.publish(self.String(data=json.dumps(plain(s)))))
            self.threads.append(ReaderThread(node, node.reader(topic, cls), cls, on_config, f"ground-{topic}",
                                             log=self._log).start())

    def _log(self, text):
        print(f"ros2_ground: {text}", file=sys.stderr, flush=True)

    def _joint(self, entry, s):
        n = len(entry["names"])
        msg = self.JointState(name=list(entry["names"]), position=[float(x) for x in s.anglePos])
        if len(s.angleVel) == n:
            msg.velocity = [float(x) for x in s.angleVel]
        if len(s.torque) == n:
            msg.effort = [float(x) for x in s.torque]
        stamp(msg.header.stamp, s.hdr.timeStamp)
        return msg

    def _position(self, entry, s):
        msg = self.PoseStamped()
        stamp(msg.header.stamp, s.hdr.timeStamp)
        msg.header.frame_id = entry["frame"]
        p = msg.pose.position
        p.x, p.y, p.z = (float(v) for v in s.pose.xyz)
        o = msg.pose.orientation
        o.x, o.y, o.z, o.w = quat_of_pose([float(v) for v in s.pose.rot], entry["encoding"])
        return msg

    def _image(self, entry, s):
        msg = self.CompressedImage(format=image_format(s.mimeType), data=bytes(s.data))
        stamp(msg.header.stamp, s.hdr.timeStamp)
        msg.header.frame_id = s.meta.sensorName
        return msg

    def _text(self, entry, s):
        msg = self.Log(level=LOG_LEVELS.get(getattr(s.level, "name", str(s.level)), 20), msg=s.message,
                       name=f"{self.tables.name}/{s.category}" if s.category else self.tables.name)
        stamp(msg.stamp, s.hdr.timeStamp)
        return msg

    def _agent(self, entry, s):
        msg = self.DiagnosticArray()
        stamp(msg.header.stamp, s.hdr.timeStamp)
        for (key, dtype, unit, warning, critical), u in zip(entry["values"], s.values):
            value = union_value(u)
            lvl, why = threshold_level(value, warning, critical)
            msg.status.append(self.DiagnosticStatus(
                level=bytes([DIAGNOSTIC_LEVELS.get(lvl, OK)]), name=f"{self.tables.name}/{key}", message=why or "ok",
                hardware_id=self.tables.name,
                values=[self.KeyValue(key="value", value=str(value)), self.KeyValue(key="type", value=dtype),
                        self.KeyValue(key="unit", value=unit)]))
        return msg


def main(asset_tables: ModuleType, rapid: ModuleType, ros2_map: Any, package: str,
         argv: list[str] | None = None) -> int:
    """`python -m <package>.ros2_ground`: until --seconds pass or SIGINT/SIGTERM."""
    tables = Tables(asset_tables)
    p = argparse.ArgumentParser(prog=f"python -m {package}.ros2_ground",
                                description=f"asset {tables.name}'s RAPID telemetry as ROS 2 messages")
    p.add_argument("--domain", type=int, default=None, help=f"RAPID DDS domain (default {tables.domain})")
    p.add_argument("--transport", default=None, help="Cyclone transport of the package: local (default), lan, wan")
    p.add_argument("--seconds", type=float, default=None, help="stop after this long")
    args = p.parse_args(argv)
    qos_mod = importlib.import_module(f"{package}.qos")
    try:
        qos = qos_mod.RapidQos()
        use_transport(qos, args.transport)
    except qos_mod.RapidQosError as exc:
        print(f"ros2_ground: {exc}", file=sys.stderr)
        return 2
    import rclpy
    from rclpy.executors import SingleThreadedExecutor

    rclpy.init()
    ros_node = rclpy.create_node(ros2_map.GROUND["node"])
    node = Node(rapid, qos, tables.domain if args.domain is None else args.domain)
    ground = Ground(tables, node, ros_node, rapid, ros2_map.GROUND)
    stop = threading.Event()
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: stop.set())
    executor = SingleThreadedExecutor()
    executor.add_node(ros_node)
    threading.Thread(target=executor.spin, daemon=True, name="ros2-spin").start()
    print(f"ros2_ground ready: asset {tables.name}, {len(ground.threads)} topic(s)", flush=True)
    stop.wait(args.seconds)
    for t in ground.threads:
        t.stop()
    executor.shutdown(timeout_sec=1.0)
    ros_node.destroy_node()
    rclpy.try_shutdown()
    node.close()  # the DDS participant deleted now, not left to exit (rapid_runtime/teardown.py)
    print("ros2_ground stopped", flush=True)
    return 0
