"""A plain rclpy differential-drive rover for tests/ros2/test_nav_rover.py (the issue-39 user's
robot): nav_msgs/Odometry on /odom at 20 Hz (at (5, 6), heading 2 rad, driving forward at
1 m/s and turning at 0.3 rad/s: its twist in the body frame, as REP 105 says), BatteryState
on /battery_state (percentage 0.42 of 1, 24.5 V) and the localiser's pose on /amcl_pose
(heading -45 degrees) at 5 Hz; each goal on /goal_pose printed as
"goal frame=F x=X y=Y q=(x, y, z, w)". Prints "nav rover ready" once publishing."""
from __future__ import annotations

import math

import rclpy
from geometry_msgs.msg import PoseStamped, PoseWithCovarianceStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import BatteryState

HEADING, AMCL_HEADING = 2.0, -math.pi / 4


def main() -> None:
    rclpy.init()
    node = rclpy.create_node("nav_rover")
    odom = node.create_publisher(Odometry, "/odom", 10)
    battery = node.create_publisher(BatteryState, "/battery_state", 10)
    amcl = node.create_publisher(PoseWithCovarianceStamped, "/amcl_pose", 10)
    count = [0]

    def on_goal(msg: PoseStamped) -> None:
        p, q = msg.pose.position, msg.pose.orientation
        print(f"goal frame={msg.header.frame_id} x={p.x:.6f} y={p.y:.6f} q=({q.x:.6f}, {q.y:.6f}, {q.z:.6f}, "
              f"{q.w:.6f})", flush=True)

    node.create_subscription(PoseStamped, "/goal_pose", on_goal, 10)

    def tick() -> None:
        count[0] += 1
        msg = Odometry()
        msg.header.stamp = node.get_clock().now().to_msg()
        msg.header.frame_id, msg.child_frame_id = "odom", "base_link"
        msg.pose.pose.position.x, msg.pose.pose.position.y = 5.0, 6.0
        msg.pose.pose.orientation.z, msg.pose.pose.orientation.w = math.sin(HEADING / 2), math.cos(HEADING / 2)
        msg.twist.twist.linear.x, msg.twist.twist.angular.z = 1.0, 0.3
        odom.publish(msg)
        if count[0] % 4 == 0:
            b = BatteryState()
            b.header.stamp = msg.header.stamp
            b.voltage, b.percentage = 24.5, 0.42
            battery.publish(b)
            a = PoseWithCovarianceStamped()
            a.header = msg.header
            a.pose.pose.orientation.z, a.pose.pose.orientation.w = math.sin(AMCL_HEADING / 2), math.cos(AMCL_HEADING / 2)
            amcl.publish(a)

    node.create_timer(0.05, tick)
    print("nav rover ready", flush=True)
    rclpy.spin(node)


if __name__ == "__main__":
    main()
