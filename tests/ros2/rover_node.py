"""A plain rclpy rover for tests/ros2/test_stale.py: nav_msgs/Odometry on /odom at 20 Hz
(x grows 0.01 m a message) and sensor_msgs/BatteryState on /battery at 5 Hz. Prints
"rover ready" once publishing."""
from __future__ import annotations

import rclpy
from nav_msgs.msg import Odometry
from sensor_msgs.msg import BatteryState


def main() -> None:
    rclpy.init()
    node = rclpy.create_node("stale_rover")
    odom = node.create_publisher(Odometry, "/odom", 10)
    battery = node.create_publisher(BatteryState, "/battery", 10)
    count = [0]

    def tick() -> None:
        count[0] += 1
        msg = Odometry()
        msg.header.stamp = node.get_clock().now().to_msg()
        msg.header.frame_id = "odom"
        msg.pose.pose.position.x = 0.01 * count[0]
        msg.pose.pose.orientation.w = 1.0
        odom.publish(msg)
        if count[0] % 4 == 0:
            b = BatteryState()
            b.header.stamp = msg.header.stamp
            b.voltage = 24.0
            battery.publish(b)

    node.create_timer(0.05, tick)
    print("rover ready", flush=True)
    rclpy.spin(node)


if __name__ == "__main__":
    main()
