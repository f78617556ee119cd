"""A stand-in X-Arm-2 for the tests: a plain Cyclone writer of a setpoint stream, as the
X-Arm-2's bridge writes it (specs/assets/xarm2.yaml streams: handPose): PositionSample on the
stream's topic in the writer's partition, best effort, keep last 1, DEADLINE the stream's.
The pose is xyz and a row-major rotation matrix (RAPID_ROT_M33) of roll/pitch/yaw, worked
out here, not by the bridge. Writes until killed.
usage: stream_writer.py PACKAGE STREAM RATE_HZ X Y Z ROLL PITCH YAW"""
from __future__ import annotations

import importlib
import math
import sys
import time

from cyclonedds.domain import DomainParticipant
from cyclonedds.pub import DataWriter, Publisher
from cyclonedds.qos import Policy, Qos
from cyclonedds.topic import Topic
from cyclonedds.util import duration

from rapid_runtime import messages as M
from rapid_runtime.dds import type_class, use_transport


def m33(r: float, p: float, y: float) -> list[float]:
    """Rz(y) Ry(p) Rx(r), row-major."""
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
            sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
            -sp, cp * sr, cp * cr]


def main() -> int:
    package, stream, rate = sys.argv[1], sys.argv[2], float(sys.argv[3])
    x, y, z, roll, pitch, yaw = (float(v) for v in sys.argv[4:10])
    pkg = importlib.import_module(package)
    tables = importlib.import_module(f"{package}.asset_tables")
    spec = next(s for s in importlib.import_module(f"{package}.ros2_map").STREAMS if s["stream"] == stream)
    use_transport(importlib.import_module(f"{package}.qos").RapidQos(), None)
    rapid = pkg.rapid
    participant = DomainParticipant(tables.ASSET.get("domain", 0))
    publisher = Publisher(participant, qos=Qos(Policy.Partition(partitions=[spec["partition"]])))
    qos = Qos(Policy.Reliability.BestEffort, Policy.Durability.Volatile, Policy.History.KeepLast(1),
              Policy.Deadline(duration(microseconds=int(round(spec["deadline_ms"] * 1000)))))
    cls = type_class(rapid, spec["type"])
    writer = DataWriter(publisher, Topic(participant, spec["topic"], cls), qos=qos)
    pose = rapid.Transform3D(xyz=[x, y, z], rot=m33(roll, pitch, yaw))
    still = rapid.Transform3D(xyz=[0.0, 0.0, 0.0], rot=[0.0] * 9)
    print(f"stream_writer ready: {spec['topic']} in partition {spec['partition']} at {rate:g} Hz", flush=True)
    period, due, n = 1.0 / rate, time.monotonic(), 0
    while True:
        writer.write(cls(hdr=M.header(rapid, spec["partition"], spec["partition"], 0), pose=pose, velocity=still,
                         values=[]))
        n += 1
        if n == 1 or n % int(rate) == 0:
            print(f"stream_writer: {n} samples", flush=True)
        due += period
        time.sleep(max(0.0, due - time.monotonic()))


if __name__ == "__main__":
    sys.exit(main())
