"""The ROS 2 side's Python: a venv of its own (rclpy and the standard messages from the
PyPI ROS wheels, cyclonedds for the RAPID side), made once and kept under .venv/ros2
(ignored by git, beside the main venv) so the main venv stays light.

A stamp file records what was installed; a changed list or a half-made venv is rebuilt.
"""
from __future__ import annotations

import fcntl
import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
VENV = ROOT / ".venv" / "ros2"
PACKAGES = ("ros-rclpy", "ros-rmw-fastrtps-cpp", "ros-std-msgs", "ros-sensor-msgs", "ros-geometry-msgs",
            "ros-nav-msgs", "ros-diagnostic-msgs", "ros-std-srvs", "ros-test-msgs", "cyclonedds==11.0.1")
STAMP = VENV / "rapidgen-ros2.stamp"


def python() -> Path:
    return VENV / "bin" / "python"


def ensure() -> Path:
    """The ROS 2 venv's python, installing it first when missing or stale."""
    wanted = "\n".join(PACKAGES) + "\n"
    VENV.parent.mkdir(parents=True, exist_ok=True)
    with open(VENV.parent / "ros2.lock", "w") as lock:  # test processes running side by side build it once
        fcntl.flock(lock, fcntl.LOCK_EX)
        if STAMP.is_file() and STAMP.read_text() == wanted and python().is_file():
            return python()
        if VENV.exists():
            shutil.rmtree(VENV)
        subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True)
        subprocess.run([str(python()), "-m", "pip", "install", "-q", "--disable-pip-version-check", "--no-compile",
                        *PACKAGES],
                       check=True, env={**os.environ, "PIP_NO_INPUT": "1"})
        STAMP.write_text(wanted)
    return python()


if __name__ == "__main__":
    print(ensure())
