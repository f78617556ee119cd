"""RAPID <-> ROS 2, for an asset whose descriptor has a ros2: section (docs/ros2.md). The
generated package keeps the asset's part (ros2_map.py: the mapping as data; ros2.py and
ros2_ground.py: a few lines calling main() here with its tables); this package holds the
code, written once:

    rotations   ROS 2 quaternions <-> RAPID's rotation encodings (pure arithmetic)
    fields      messages by name and field path; command arguments -> field values
    streams     a mapped RAPID input stream read with Cyclone, its losses and recoveries
    handlers    Ros2Handlers (commands -> ROS 2, ROS 2 -> telemetry) and `<package>.ros2`'s main
    ground      `<package>.ros2_ground`: the asset's RAPID telemetry and configs as ROS 2 messages

rclpy is imported only when handlers or the ground node are made: importing these modules
needs no ROS 2.
"""
