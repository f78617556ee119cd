"""ROS 2 interop: the descriptor's `ros2:` section (section.py) checked against ROS 2
message definitions (msgdefs.py); the Python back end turns it into `<pkg>/ros2.py`.
Nothing here imports rclpy: validation works without ROS 2 installed."""
