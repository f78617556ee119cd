"""The ROS 2 bridge's tests. Its code is rapid_runtime.ros2 (the generated ros2.py and
ros2_ground.py only call it): runtime_ros2() gathers the names the tests use."""
from types import SimpleNamespace


def runtime_ros2() -> SimpleNamespace:
    """rapid_runtime.ros2's rotations, fields and Ros2Handlers as one namespace (no rclpy needed)."""
    from rapid_runtime.ros2 import fields, handlers, rotations
    names = {k: v for m in (rotations, fields) for k, v in vars(m).items() if not k.startswith("_")}
    return SimpleNamespace(**names, Ros2Handlers=handlers.Ros2Handlers)
