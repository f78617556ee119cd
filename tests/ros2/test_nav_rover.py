"""RAPID's own moves on a plain ROS 2 rover, live (issue 39 item 3): tests/ros2/nav_rover_node.py
(real rclpy) served as NavRover by the generated bridge of tests/ros2/rover-nav.yaml.
`rapidgen cmd ... Mobility simpleMove xyt=3,-4,1.57` reaches the rover as a nav2-style goal
whose orientation is the heading; the rover's Odometry comes back as a RAPID_ROT_ZYX pose
(rot[0] the heading) with its body-frame twist turned into the odom frame, its BatteryState's
0-1 percentage as %, its localiser's heading in degrees.

One private network namespace holding only lo (tests/ros2/netns.py); the ROS side's Python
is tests/ros2/rosenv.py's venv. What is asserted are values, never times."""
from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.ros2 import netns, rosenv

ROOT = Path(__file__).resolve().parents[2]
DESCRIPTOR = "tests/ros2/rover-nav.yaml"
PACKAGE = "rapid_navrover"
WAIT = 60.0  # s: a guard against a hang, never what is asserted

pytestmark = pytest.mark.skipif(os.geteuid() != 0, reason="network namespaces need root")


def _wait_for(path: Path, text: str, proc: subprocess.Popen) -> None:
    end = time.monotonic() + WAIT
    while time.monotonic() < end:
        if text in path.read_text(errors="replace"):
            return
        if proc.poll() is not None:
            break
        time.sleep(0.1)
    pytest.fail(f"no '{text}' in {path.name}:\n{path.read_text(errors='replace')[-3000:]}")


@pytest.fixture(scope="module")
def rover(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("navrover")
    python = rosenv.ensure()
    gen = subprocess.run([sys.executable, "-m", "rapidgen", "generate", DESCRIPTOR, "--lang", "python", "-o",
                          str(tmp / "gen")], cwd=ROOT, capture_output=True, text=True)
    assert gen.returncode == 0, gen.stderr
    env = {**os.environ, "PYTHONPATH": f"{ROOT / 'runtime'}{os.pathsep}{tmp / 'gen' / 'python'}",
           "PYTHONUNBUFFERED": "1", "RAPID_STATE_DIR": str(tmp)}
    with netns.namespace() as ns:
        procs = []
        try:
            for name, args, ready in (("node", [str(ROOT / "tests/ros2/nav_rover_node.py")], "nav rover ready"),
                                      ("bridge", ["-m", f"{PACKAGE}.ros2"], "bridge ready")):
                log = tmp / f"{name}.log"
                with open(log, "w") as out:
                    procs.append(subprocess.Popen([*ns, str(python), *args], stdout=out, stderr=subprocess.STDOUT,
                                                  env=env, cwd=tmp))
                _wait_for(log, ready, procs[-1])
            yield ns, tmp, python, env
        finally:
            for p in reversed(procs):
                p.terminate()
                try:
                    p.wait(10)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()


def _cmd(rover, *args: str) -> subprocess.CompletedProcess:
    ns, tmp, _, _ = rover
    return subprocess.run([*ns, sys.executable, "-m", "rapidgen", "cmd", "--from-descriptor", PACKAGE, "--source", "ops",
                           *args], cwd=ROOT, capture_output=True, text=True, timeout=WAIT,
                          env={**os.environ, "PYTHONPATH": str(tmp / "gen" / "python")})


def test_simple_move_reaches_the_rover_as_a_goal_facing_its_heading(rover):
    _, tmp, _, _ = rover
    refused = _cmd(rover, "Mobility", "simpleMove", "frame=odom", "xyt=[3,-4,1.57]")
    assert "does not have control (send requestControl)" in refused.stdout, refused.stdout + refused.stderr
    got = _cmd(rover, "AccessControl", "requestControl")
    assert got.returncode == 0, got.stdout + got.stderr
    res = _cmd(rover, "Mobility", "simpleMove", "frame=odom", "xyt=[3,-4,1.57]")
    assert res.returncode == 0 and "published on /goal_pose" in res.stdout, res.stdout + res.stderr
    log = tmp / "node.log"
    end = time.monotonic() + WAIT
    while "goal frame=" not in log.read_text() and time.monotonic() < end:
        time.sleep(0.1)
    [goal] = [ln for ln in log.read_text().splitlines() if ln.startswith("goal ")]
    want = "goal frame=odom x=3.000000 y=-4.000000 q=(0.000000, 0.000000, {:.6f}, {:.6f})".format(
        math.sin(0.785), math.cos(0.785))
    assert goal == want


def test_odometry_battery_and_heading_come_back_as_declared(rover):
    ns, tmp, python, env = rover
    end = time.monotonic() + WAIT
    while True:  # an AgentState taken before both of its topics were heard holds a default heading (0)
        res = subprocess.run([*ns, str(python), str(ROOT / "tests/ros2/rapid_listener.py"), PACKAGE,
                              "rapid_position_sample=rapid::PositionSample", "rapid_agent_state=rapid::AgentState"],
                             capture_output=True, text=True, timeout=WAIT, env=env)
        assert res.returncode == 0, res.stderr
        got = {m["topic"]: m["sample"] for m in map(json.loads, res.stdout.splitlines())}
        if got["rapid_agent_state"]["values"][2] != 0 or time.monotonic() > end:
            break
    pose = got["rapid_position_sample"]
    assert pose["xyz"] == pytest.approx([5.0, 6.0, 0.0])
    assert pose["rot"][:3] == pytest.approx([2.0, 0.0, 0.0], abs=1e-6)  # RAPID_ROT_ZYX: the heading first
    assert pose["vxyz"] == pytest.approx([math.cos(2.0), math.sin(2.0), 0.0], abs=1e-6)  # odom frame, not body
    assert pose["vrot"][:3] == pytest.approx([0.0, 0.0, 0.3], abs=1e-6)
    charge, voltage, heading = got["rapid_agent_state"]["values"]
    assert (charge, voltage) == pytest.approx((42.0, 24.5), abs=1e-4)  # BatteryState's 0.42 as %
    assert heading == pytest.approx(-45.0, abs=1e-6)  # /amcl_pose's quaternion, in degrees
