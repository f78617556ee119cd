"""The ROS 2 side of an asset package, for a descriptor with a `ros2:` section (issue 27).

    <package>/ros2_map.py   the checked mapping (rapidgen/ros2/section.py) as literals
    <package>/ros2.py       `python -m <package>.ros2`: the runtime's bridge with handlers that
                            publish ROS 2 messages, telemetry fed from ROS 2 subscriptions, and
                            the mapped input streams (Cyclone, DEADLINE) published as ROS 2 messages
    <package>/ros2_ground.py  with `ros2: {ground: ...}`: `python -m <package>.ros2_ground`, the
                            asset's RAPID telemetry republished as standard ROS 2 messages
The two hold only the call: the code is rapid_runtime.ros2 (runtime/), which imports rclpy
when they start.

Descriptor strings (topics, field paths, names, constants) reach the files only through the
literal printer (py_str) or the docstring/comment escapes.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from rapidgen.backends.base import GeneratedFile
from rapidgen.backends.python.asset_tables import literal
from rapidgen.backends.templating import render

if TYPE_CHECKING:
    from rapidgen.asset import LoadedAsset


def generate(loaded: "LoadedAsset", package: str, header: str) -> list[GeneratedFile]:
    mapping = loaded.ros2
    if mapping is None:
        return []
    data = {"NODE": mapping["node"], "TELEMETRY": mapping["telemetry"], "COMMANDS": mapping["commands"],
            "STREAMS": mapping["streams"], "GROUND": mapping["ground"]}
    body = "\n\n".join(f"{name} = {literal(value)}" for name, value in data.items())
    name = loaded.spec.name
    files = [
        GeneratedFile(f"{package}/ros2_map.py", render("python", "ros2_map.py.j2", header=header, asset=name,
                                                       body=body)),
        GeneratedFile(f"{package}/ros2.py", render("python", "ros2.py.j2", header=header, asset=name,
                                                   package=package)),
    ]
    if mapping["ground"] is not None:
        files.append(GeneratedFile(f"{package}/ros2_ground.py", render("python", "ros2_ground.py.j2", header=header,
                                                                       asset=name, package=package)))
    return files
