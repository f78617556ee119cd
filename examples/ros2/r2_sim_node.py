"""A stand-in for Robonaut 2's ROS 2 simulation side (seed 001's outlook), plain rclpy.

Subscribes /r2_controller/right/pose_command (geometry_msgs/PoseStamped),
/r2_controller/right/joint_command (sensor_msgs/JointState, positions in joint order) and
/r2_controller/right/stop (std_msgs/String), serves /r2_controller/right/home
(std_srvs/Trigger: fails while disabled) and /r2_controller/right/enable (std_srvs/SetBool),
runs /r2_controller/right/wave goals (test_msgs/action/Fibonacci: `order` waves of 0.1 s,
feedback after each, cancellable),
drives the right arm's seven joints toward the target at --speed rad/s; publishes
/joint_states (both arms' and the waist's joints, the right arm's in reverse order: a
subscriber must match by name), the tool pose, the wrist wrench and force magnitude, and
/r2_controller/right/status ("moving" on a new target, "reached" on arrival, "stopped")
and a head camera's PNG on /r2/head/image/compressed (sensor_msgs/CompressedImage).

Its kinematics are a toy, chosen so a test can check values end to end: the tool pose's
position is joints 0-2 and its roll, pitch, yaw are joints 3-5 (joint 6 turns nothing), so
a pose command's x, y, z, roll, pitch, yaw come back as the first six joint angles.

    python examples/ros2/r2_sim_node.py [--speed 1.0] [--rate 50] [--force N]
"""
from __future__ import annotations

import argparse
import hashlib
import math
import struct
import sys
import time
import zlib

import rclpy
from geometry_msgs.msg import PoseStamped, WrenchStamped
from rclpy.action import ActionServer, CancelResponse
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import MultiThreadedExecutor
from rclpy.node import Node
from sensor_msgs.msg import CompressedImage, JointState
from std_msgs.msg import Float64, String
from std_srvs.srv import SetBool, Trigger
from test_msgs.action import Fibonacci

RIGHT = [f"r2/right_arm/joint{i}" for i in range(7)]
OTHERS = [f"r2/left_arm/joint{i}" for i in range(7)] + ["r2/waist/joint0"]


def png(width: int, height: int) -> bytes:
    """A small RGB gradient as PNG (what a head camera's compressed stream would carry)."""
    def chunk(kind: bytes, body: bytes) -> bytes:
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    rows = b"".join(b"\0" + bytes(c for x in range(width) for c in (x * 255 // max(width - 1, 1),
                                                                      y * 255 // max(height - 1, 1), 128))
                    for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


HEAD_IMAGE = png(8, 4)


def rpy_from_quat(x: float, y: float, z: float, w: float) -> tuple[float, float, float]:
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return roll, pitch, yaw


def quat_from_rpy(r: float, p: float, y: float) -> tuple[float, float, float, float]:
    cr, sr, cp, sp = math.cos(r / 2), math.sin(r / 2), math.cos(p / 2), math.sin(p / 2)
    cy, sy = math.cos(y / 2), math.sin(y / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


class R2Sim(Node):
    def __init__(self, speed: float, rate: float, force: float) -> None:
        super().__init__("r2_sim")
        self.speed, self.dt, self.force = speed, 1.0 / rate, force
        self.joints = [0.0] * 7
        self.target: list[float] | None = None
        self.frame = "R2OriginFrame"
        self.pub_joints = self.create_publisher(JointState, "/joint_states", 10)
        self.pub_pose = self.create_publisher(PoseStamped, "/r2_controller/right/tool_pose", 10)
        self.pub_wrench = self.create_publisher(WrenchStamped, "/r2_controller/right/wrench", 10)
        self.pub_force = self.create_publisher(Float64, "/r2_controller/right/force_magnitude", 10)
        self.pub_status = self.create_publisher(String, "/r2_controller/right/status", 10)
        self.pub_image = self.create_publisher(CompressedImage, "/r2/head/image/compressed", 10)
        self.steps = 0
        self.create_subscription(PoseStamped, "/r2_controller/right/pose_command", self.on_pose, 10)
        self.create_subscription(JointState, "/r2_controller/right/joint_command", self.on_joints, 10)
        self.create_subscription(String, "/r2_controller/right/stop", self.on_stop, 10)
        self.create_service(Trigger, "/r2_controller/right/home", self.on_home)
        self.create_service(SetBool, "/r2_controller/right/enable", self.on_enable)
        self.enabled = True
        # the goal runs in its own thread while the timer keeps publishing
        ActionServer(self, Fibonacci, "/r2_controller/right/wave", self.on_wave,
                     cancel_callback=lambda _goal: CancelResponse.ACCEPT, callback_group=ReentrantCallbackGroup())
        self.create_timer(self.dt, self.step)

    def status(self, text: str) -> None:
        self.pub_status.publish(String(data=text))
        print(f"r2_sim: {text} {[round(j, 4) for j in self.joints]}", flush=True)

    def on_pose(self, msg: PoseStamped) -> None:
        if not self.enabled:
            return
        p, q = msg.pose.position, msg.pose.orientation
        self.frame = msg.header.frame_id or self.frame
        print(f"r2_sim: pose_command frame={msg.header.frame_id} xyz=({p.x}, {p.y}, {p.z}) "
              f"quat=({q.x:.6f}, {q.y:.6f}, {q.z:.6f}, {q.w:.6f})", flush=True)
        self.target = [p.x, p.y, p.z, *rpy_from_quat(q.x, q.y, q.z, q.w), self.joints[6]]
        self.status("moving")

    def on_stop(self, msg: String) -> None:
        print(f"r2_sim: stop {msg.data!r}", flush=True)
        self.target = None
        self.status("stopped")

    def on_home(self, request: Trigger.Request, response: Trigger.Response) -> Trigger.Response:
        response.success = self.enabled
        response.message = "homing" if self.enabled else "arm disabled: enable it first"
        if self.enabled:
            self.target = [0.0] * 7
        return response

    def on_enable(self, request: SetBool.Request, response: SetBool.Response) -> SetBool.Response:
        self.enabled = bool(request.data)
        response.success, response.message = True, "enabled" if self.enabled else "disabled"
        print(f"r2_sim: {response.message}", flush=True)
        return response

    def on_wave(self, goal):
        """Wave `order` times, 0.1 s each; feedback: the Fibonacci numbers so far."""
        seq = [0, 1][:max(goal.request.order, 0)]
        print(f"r2_sim: wave goal order={goal.request.order}", flush=True)
        for i in range(goal.request.order):
            if goal.is_cancel_requested:
                goal.canceled()
                print(f"r2_sim: wave canceled after {i}", flush=True)
                return Fibonacci.Result(sequence=seq)
            while len(seq) <= i:
                seq.append(seq[-1] + seq[-2])
            goal.publish_feedback(Fibonacci.Feedback(sequence=seq[:i + 1]))
            time.sleep(0.1)
        goal.succeed()
        return Fibonacci.Result(sequence=seq[:goal.request.order])

    def on_joints(self, msg: JointState) -> None:
        print(f"r2_sim: joint_command {list(msg.position)}", flush=True)
        if len(msg.position) == 7:
            self.target = [float(v) for v in msg.position]
            self.status("moving")

    def step(self) -> None:
        vel = [0.0] * 7
        if self.target is not None:
            reach = self.speed * self.dt
            for i, goal in enumerate(self.target):
                delta = max(-reach, min(reach, goal - self.joints[i]))
                self.joints[i] += delta
                vel[i] = delta / self.dt
            if all(abs(g - j) < 1e-9 for g, j in zip(self.target, self.joints)):
                self.target = None
                self.status("reached")
        now = self.get_clock().now().to_msg()
        names = list(reversed(RIGHT)) + OTHERS
        right = dict(zip(RIGHT, zip(self.joints, vel)))
        js = JointState(name=names, position=[right[n][0] if n in right else 0.1 for n in names],
                        velocity=[right[n][1] if n in right else 0.0 for n in names],
                        effort=[2.5 if n in right else 0.0 for n in names])
        js.header.stamp = now
        self.pub_joints.publish(js)
        pose = PoseStamped()
        pose.header.stamp, pose.header.frame_id = now, self.frame
        pose.pose.position.x, pose.pose.position.y, pose.pose.position.z = self.joints[:3]
        o = pose.pose.orientation
        o.x, o.y, o.z, o.w = quat_from_rpy(*self.joints[3:6])
        self.pub_pose.publish(pose)
        w = WrenchStamped()
        w.header.stamp = now
        w.wrench.force.x, w.wrench.force.y, w.wrench.force.z = 1.0, 2.0, -19.6
        w.wrench.torque.x, w.wrench.torque.y, w.wrench.torque.z = 0.1, 0.2, 0.3
        self.pub_wrench.publish(w)
        self.pub_force.publish(Float64(data=self.force))
        self.steps += 1
        if self.steps % 10 == 1:  # the head camera at a fifth of the rate
            image = CompressedImage(format="png", data=HEAD_IMAGE)
            image.header.stamp, image.header.frame_id = now, "r2/head/camera_left"
            self.pub_image.publish(image)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--speed", type=float, default=1.0, help="joint speed [rad/s]")
    ap.add_argument("--rate", type=float, default=50.0, help="publication rate [Hz]")
    ap.add_argument("--force", type=float, default=math.sqrt(1.0 + 4.0 + 19.6 ** 2),
                    help="the wrist force magnitude published [N] (default: that of the wrench)")
    args = ap.parse_args(argv)
    rclpy.init()
    node = R2Sim(args.speed, args.rate, args.force)
    print(f"r2_sim: head image sha256={hashlib.sha256(HEAD_IMAGE).hexdigest()}", flush=True)
    print("r2_sim ready", flush=True)
    executor = MultiThreadedExecutor()
    executor.add_node(node)
    try:
        executor.spin()
    except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
