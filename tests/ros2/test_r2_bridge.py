"""ROS 2 -> RAPID, live: Robonaut 2's ROS 2 side (examples/ros2/r2_sim_node.py, real rclpy
from the PyPI ROS wheels) served as the RAPID asset R2Ros by the generated
`rapid_r2ros.ros2` bridge (examples/ros2/robonaut2-ros2.yaml), driven by `rapidgen cmd`,
watched by plain RAPID and rclpy subscribers and judged by `rapidgen conform`.

Everything runs in one private network namespace holding only lo (tests/ros2/netns.py).
The ROS side's Python is its own venv (tests/ros2/rosenv.py: made once, then cached).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.ros2 import netns, rosenv

ROOT = Path(__file__).resolve().parents[2]
DESCRIPTOR = "examples/ros2/robonaut2-ros2.yaml"
PACKAGE = "rapid_r2ros"  # what rapidgen generates from it
WAIT = 60.0  # s: a guard against a hang, never what is asserted
# tf2's setRPY(0.1, 0.2, 0.3) as (x, y, z, w), worked out independently of the bridge
QUAT_RPY = (0.0342708, 0.1060205, 0.1435722, 0.9833474)
FORCE = 180.0  # N: the wrist force magnitude the ROS 2 node reports, past R2Ros's warning threshold (150)
JOINTS = [f"RightArm/Joint{i}" for i in range(7)]  # the descriptor's joint frames

pytestmark = pytest.mark.skipif(os.geteuid() != 0, reason="network namespaces need root")


def _wait_for(path: Path, text: str, proc: subprocess.Popen | None = None) -> None:
    """Until text is in the file proc writes (a guard against a hang: fails at WAIT)."""
    end = time.monotonic() + WAIT
    while time.monotonic() < end:
        if text in path.read_text(errors="replace"):
            return
        if proc is not None and proc.poll() is not None:
            break
        time.sleep(0.1)
    pytest.fail(f"no '{text}' in {path.name}:\n{path.read_text(errors='replace')}")


class Scene:
    def __init__(self, ns: list[str], tmp: Path) -> None:
        self.ns, self.tmp = ns, tmp
        self.env = {**os.environ, "PYTHONPATH": str(tmp / "gen" / "python")}
        self.python = rosenv.python()
        self.controlling = False  # whether `rapidgen` (cmd's default source) holds control

    def rapidgen(self, *args: str, check: bool = False) -> subprocess.CompletedProcess:
        res = subprocess.run([*self.ns, sys.executable, "-m", "rapidgen", *args], cwd=ROOT, capture_output=True,
                             text=True, timeout=WAIT, env=self.env)
        if check:
            assert res.returncode == 0, res.stdout + res.stderr
        return res

    def cmd(self, *args: str) -> subprocess.CompletedProcess:
        """`rapidgen cmd` with the generated package (no bindings to generate each time)."""
        return self.rapidgen("cmd", "--from-descriptor", PACKAGE, *args)

    def take_control(self) -> None:
        """R2Ros has access control: commands come from its controller (conform takes it)."""
        if not self.controlling:
            res = self.cmd("AccessControl", "grabControl")
            assert res.returncode == 0, res.stdout + res.stderr
            self.controlling = True

    def at_rest(self) -> None:
        """Until the simulated arm's last status is not "moving" (fails at WAIT). A command that
        waits for "reached" starts from rest: an earlier motion ending after the command's pose
        was published would answer its wait (the status names no target)."""
        log, end = self.tmp / "sim.log", time.monotonic() + WAIT
        while True:
            states = [ln.split()[1] for ln in log.read_text(errors="replace").splitlines()
                      if ln.startswith("r2_sim: ") and ln.split()[1:2] in (["moving"], ["reached"], ["stopped"])]
            if not states or states[-1] != "moving":
                return
            if time.monotonic() > end:
                pytest.fail(f"the simulated arm still moving after {WAIT:g} s:\n{log.read_text()[-2000:]}")
            time.sleep(0.1)

    def samples(self, **topics: str) -> dict[str, dict]:
        """The next sample of each R2Ros topic (topic=rapid::Type), read by a plain RAPID
        subscriber in another process (tests/ros2/rapid_listener.py)."""
        env = {**os.environ, "PYTHONPATH": f"{ROOT / 'runtime'}{os.pathsep}{self.tmp / 'gen' / 'python'}"}
        res = subprocess.run([*self.ns, str(self.python), str(ROOT / "tests/ros2/rapid_listener.py"), PACKAGE,
                              *(f"{t}={ty}" for t, ty in topics.items())], capture_output=True, text=True,
                             timeout=WAIT, env=env)
        assert res.returncode == 0, res.stderr
        return {m["topic"]: m["sample"] for m in map(json.loads, res.stdout.splitlines())}


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("ros2")
    python = rosenv.ensure()
    gen = subprocess.run([sys.executable, "-m", "rapidgen", "generate", DESCRIPTOR, "--lang", "python", "-o",
                          str(tmp / "gen")], cwd=ROOT, capture_output=True, text=True)
    assert gen.returncode == 0, gen.stderr
    env = {**os.environ, "PYTHONPATH": f"{ROOT / 'runtime'}{os.pathsep}{tmp / 'gen' / 'python'}",
           "PYTHONUNBUFFERED": "1"}
    with netns.namespace() as ns:
        procs = []
        try:
            for name, args, ready in (
                    ("sim", [str(ROOT / "examples/ros2/r2_sim_node.py"), "--speed", "1.0", "--force", str(FORCE)],
                     "r2_sim ready"),
                    ("bridge", ["-m", "rapid_r2ros.ros2"], "bridge ready"),
                    ("ground", ["-m", "rapid_r2ros.ros2_ground"], "ros2_ground ready")):
                log = tmp / f"{name}.log"
                with open(log, "w") as out:
                    procs.append(subprocess.Popen([*ns, str(python), *args], stdout=out, stderr=subprocess.STDOUT,
                                                  env=env, cwd=tmp))
                _wait_for(log, ready, procs[-1])
            yield Scene(ns, tmp)
        finally:
            for p in reversed(procs):
                p.terminate()
                try:
                    p.wait(10)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()


def test_conform_passes_every_required_check(scene):
    report = scene.tmp / "conform.json"
    res = scene.rapidgen("conform", DESCRIPTOR, "--json", str(report))
    scene.controlling = False
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr
    checks = json.loads(report.read_text())["checks"]
    required = [c for c in checks if c["level"] == "required"]
    assert required and all(c["outcome"] in ("PASS", "UNSUPPORTED") for c in required)
    passed = {c["id"] for c in required if c["outcome"] == "PASS"}
    # the telemetry fed from ROS 2 and the command path are judged, not skipped
    assert {"TEL-01", "TEL-03", "TEL-04", "TEL-06", "CMD-02", "CMD-03", "QUE-02", "ACC-02"} <= passed
    camera = next(c for c in checks if c["id"] == "TEL-08")  # recommended: the camera fed from ROS 2
    assert camera["outcome"] == "PASS", camera


def test_pose_command_moves_the_ros2_arm_and_its_joints_come_back(scene):
    scene.take_control()
    scene.at_rest()
    res = scene.cmd("RightArm", "Setpoint for Tool", "xyz=[0.3,0.2,-0.1]", "rpy=[0.1,0.2,0.3]")
    assert res.returncode == 0, res.stdout + res.stderr
    acks = [line.split()[0] for line in res.stdout.splitlines()[1:] if line.strip()]
    assert acks[0] == "EXECUTING" and acks[-1] == "COMPLETED", res.stdout
    assert "published on /r2_controller/right/pose_command" in res.stdout
    assert "/r2_controller/right/status: data == 'reached'" in res.stdout
    # the ROS 2 node got the pose as PoseStamped: frame, position, quaternion from roll/pitch/yaw
    sim = (scene.tmp / "sim.log").read_text()
    assert "pose_command frame=R2OriginFrame xyz=(0.3, 0.2, -0.1)" in sim
    assert "quat=({:.6f}, {:.6f}, {:.6f}, {:.6f})".format(*QUAT_RPY) in sim
    # its joint states (published in another order, with other joints) come back as RAPID
    # JointSample in the JointConfig's order: the toy kinematics put x, y, z, r, p, y in joints 0-5
    got = scene.samples(**{"rapid_joint_sample": "rapid::JointSample",
                           "rapid_position_sample-rightArm": "rapid::PositionSample",
                           "rapid_agent_state": "rapid::AgentState",
                           "rapid_imagesensor_sample-headCam": "rapid::ImageSensorSample"})
    joints = got["rapid_joint_sample"]
    assert joints["anglePos"][:6] == pytest.approx([0.3, 0.2, -0.1, 0.1, 0.2, 0.3], abs=1e-6)
    assert joints["torque"] == pytest.approx([2.5] * 7)
    assert len(joints["angleVel"]) == 7
    pose = got["rapid_position_sample-rightArm"]
    assert pose["xyz"] == pytest.approx([0.3, 0.2, -0.1], abs=1e-6)
    assert pose["rot"][:4] == pytest.approx(QUAT_RPY, abs=1e-6)  # RAPID_ROT_QUAT: x, y, z, w
    # AgentState values from two ROS 2 topics, in valueKeys order: force, torque, magnitude
    values = got["rapid_agent_state"]["values"]
    assert values[0] == pytest.approx([1.0, 2.0, -19.6])
    assert values[1] == pytest.approx([0.1, 0.2, 0.3])
    assert values[2] == pytest.approx(FORCE)
    # the head camera's CompressedImage arrives as ImageSensorSample, bytes unchanged
    image = got["rapid_imagesensor_sample-headCam"]
    sim = (scene.tmp / "sim.log").read_text()
    assert f"head image sha256={image['sha256']}" in sim
    assert (image["mime"], image["sensor"], image["width"], image["height"]) == ("image/png", "HeadCamLeft", 8, 4)


def test_joint_command_publishes_the_arguments_in_order(scene):
    scene.take_control()
    target = [0.05, -0.1, 0.15, -0.2, 0.25, -0.3, 0.35]
    res = scene.cmd("RightArm", "Setpoint for single joint",
                    *(f"{k}={v}" for k, v in zip(("abduction", "extension", "upperArmOuterRotation", "elbowFlexion",
                                                  "forearmOuterRotation", "wristFlexion", "wristUlnarFlexion"),
                                                 target)))
    assert res.returncode == 0 and "COMPLETED OK" in res.stdout, res.stdout + res.stderr
    sim = (scene.tmp / "sim.log").read_text()
    line = next(ln for ln in sim.splitlines() if "joint_command" in ln)
    got = json.loads(line.split("joint_command ", 1)[1])
    assert got == pytest.approx(target, abs=1e-6)  # RAPID_FLOAT arguments: float32 precision


def test_cancel_reaches_the_waiting_command(scene):
    """A queued pose command waits for the arm (50 rad away at 1 rad/s); Queue/cancelAll
    makes it CANCELED."""
    scene.take_control()
    scene.at_rest()  # the joint command's motion may still run on a loaded machine
    log = scene.tmp / "long.log"
    with open(log, "w") as out:
        long = subprocess.Popen([*scene.ns, sys.executable, "-m", "rapidgen", "cmd", "--action", "APPEND",
                                 "--from-descriptor", PACKAGE, "RightArm", "Setpoint for Tool", "xyz=[50,-50,50]",
                                 "rpy=[0,0,0]"],
                                cwd=ROOT, stdout=out, stderr=subprocess.STDOUT, text=True, env=scene.env)
        _wait_for(log, "waiting for data on /r2_controller/right/status", long)
        cancel = scene.cmd("Queue", "cancelAll")
        assert cancel.returncode == 0, cancel.stdout + cancel.stderr
        assert long.wait(WAIT) == 1
    acks = [line.split()[:2] for line in log.read_text().splitlines()[1:] if line.strip()]
    assert [a[0] for a in acks] == ["QUEUED", "EXECUTING", "EXECUTING", "COMPLETED"], log.read_text()
    assert acks[-1] == ["COMPLETED", "CANCELED"]
    # the mapping's cancel message reached the ROS 2 node, which stopped the arm
    _wait_for(scene.tmp / "sim.log", "r2_sim: stop 'stop'")


def test_service_calls_answer_with_their_response(scene):
    """std_srvs services: SetBool from a RAPID_BOOL argument; the response's success decides
    COMPLETED/OK or EXEC_FAILED, its message becomes the ack's."""
    scene.take_control()
    steps = [(("Enable", "enable=false"), 0, "COMPLETED OK  disabled"),
             (("Home",), 1, "COMPLETED EXEC_FAILED  /r2_controller/right/home: arm disabled: enable it first"),
             (("Enable", "enable=true"), 0, "COMPLETED OK  enabled")]
    for args, code, final in steps:
        res = scene.cmd("RightArm", *args)
        assert res.returncode == code and final in res.stdout, res.stdout + res.stderr


def test_rapid_telemetry_comes_back_to_ros2_as_standard_messages(scene):
    """RAPID -> ROS 2: the ground node republishes R2Ros's RAPID telemetry; a plain rclpy
    subscriber sees joint states named as the JointConfig, the pose, diagnostics whose
    levels follow the descriptor's thresholds, the head camera's picture, the configs
    (latched JSON) and the asset's text on /rosout."""
    res = subprocess.run([*scene.ns, str(scene.python), str(ROOT / "tests/ros2/ros_listener.py"),
                          "/r2ros/joint_states=sensor_msgs/msg/JointState",
                          "/r2ros/rightArm/pose=geometry_msgs/msg/PoseStamped",
                          "/r2ros/headCam/image/compressed=sensor_msgs/msg/CompressedImage",
                          "/r2ros/config/joint=std_msgs/msg/String", "/r2ros/config/command=std_msgs/msg/String",
                          "/diagnostics=diagnostic_msgs/msg/DiagnosticArray", "/rosout=rcl_interfaces/msg/Log"],
                         capture_output=True, text=True, timeout=WAIT, env={**os.environ, "ROSOUT_NAME": "R2Ros"})
    assert res.returncode == 0, res.stderr
    got = {m["topic"]: m["msg"] for m in map(json.loads, res.stdout.splitlines())}
    joints = got["/r2ros/joint_states"]
    assert joints["name"] == JOINTS and len(joints["position"]) == 7
    assert joints["effort"] == pytest.approx([2.5] * 7) and len(joints["velocity"]) == 7
    assert joints["stamp"] > 1_700_000_000  # the RAPID sample's own time, in seconds
    pose = got["/r2ros/rightArm/pose"]
    assert pose["frame"] == "R2OriginFrame" and len(pose["xyz"]) == 3
    assert sum(q * q for q in pose["quat"]) == pytest.approx(1.0, abs=1e-5)
    status = {s["name"]: s for s in got["/diagnostics"]["status"]}
    assert list(status) == ["R2Ros/rightWristForce", "R2Ros/rightWristTorque", "R2Ros/rightForceMagnitude"]
    force = status["R2Ros/rightForceMagnitude"]
    assert force["level"] == 1 and force["message"] == "above warning threshold 150"  # WARN: 150 < 180 <= 250
    assert float(force["values"]["value"]) == pytest.approx(FORCE) and force["values"]["unit"] == "N"
    assert status["R2Ros/rightWristForce"]["level"] == 0  # no thresholds: OK
    assert all(s["hardware_id"] == "R2Ros" for s in status.values())
    # the picture went ROS 2 -> RAPID -> ROS 2: the same bytes the ROS 2 camera published
    image = got["/r2ros/headCam/image/compressed"]
    assert f"head image sha256={image['sha256']}" in (scene.tmp / "sim.log").read_text()
    assert (image["format"], image["frame"]) == ("png", "HeadCamLeft") and image["stamp"] > 1_700_000_000
    # the configs, latched, as the JSON of what the asset published
    joint_config = got["/r2ros/config/joint"]
    assert [j["frameName"] for j in joint_config["jointDefinitions"]] == JOINTS
    assert joint_config["hdr"]["assetName"] == "R2Ros" and joint_config["hdr"]["serial"] > 0
    subsystems = {s["name"]: s["subsystemTypeName"] for s in got["/r2ros/config/command"]["availableSubsystems"]}
    assert "RightArm" in subsystems, subsystems
    # the asset's TextMessage (durable, written at the bridge's start) on /rosout, as rqt_console reads it
    log = got["/rosout"]
    assert log == {"name": "R2Ros/system", "level": 20, "msg": "R2Ros served from ROS 2 node r2_rapid_bridge",
                   "stamp": log["stamp"]} and log["stamp"] > 1_700_000_000


def test_action_goal_feedback_result_and_delete(scene):
    """An action goal (test_msgs/Fibonacci on the ROS 2 side): its feedback comes back as
    EXECUTING acks, its result as COMPLETED/OK; DELETE of a running goal cancels it on the
    ROS 2 side and answers CANCELED."""
    scene.take_control()
    res = scene.cmd("RightArm", "Wave", "count=3")
    assert res.returncode == 0, res.stdout + res.stderr
    acks = [line.strip() for line in res.stdout.splitlines()[1:] if line.strip()]
    assert [a.split()[0] for a in acks] == ["EXECUTING"] * 4 + ["COMPLETED"], res.stdout
    assert acks[1:4] == ["EXECUTING  sequence=[0]", "EXECUTING  sequence=[0, 1]", "EXECUTING  sequence=[0, 1, 1]"]
    assert acks[-1] == "COMPLETED OK  /r2_controller/right/wave succeeded: sequence=[0, 1, 1]"

    log = scene.tmp / "wave.log"
    with open(log, "w") as out:
        long = subprocess.Popen([*scene.ns, sys.executable, "-m", "rapidgen", "cmd", "--action", "APPEND",
                                 "--id", "wave-long", "--from-descriptor", PACKAGE, "RightArm", "Wave", "count=1000"],
                                cwd=ROOT, stdout=out, stderr=subprocess.STDOUT, text=True, env=scene.env)
        _wait_for(log, "sequence=[0, 1, 1]", long)  # the goal is running on the ROS 2 side
        delete = scene.cmd("--action", "DELETE", "--target", "wave-long", "RightArm", "Wave", "count=1")
        assert delete.returncode == 0, delete.stdout + delete.stderr
        assert long.wait(WAIT) == 1
    lines = [line.split()[:2] for line in log.read_text().splitlines()[1:] if line.strip()]
    assert lines[0] == ["QUEUED"] and lines[-1] == ["COMPLETED", "CANCELED"], log.read_text()
    assert all(kind == ["EXECUTING"] or kind[0] == "EXECUTING" for kind in lines[1:-1])
    _wait_for(scene.tmp / "sim.log", "r2_sim: wave canceled after")


def test_xarm2_pose_stream_drives_the_ros2_arm_beside_a_command(scene):
    """Seed 001: X-Arm-2's hand pose stream (a stand-in Cyclone writer, tests/ros2/stream_writer.py,
    100 Hz in partition XArm2) reaches the ROS 2 node as PoseStamped on the arm's pose command
    topic through the bridge, while a RAPID command still works; the writer's loss (killed: no
    sample within the 100 ms deadline) runs on_loss stop, the mapped cancel message; its return
    is reported. Last in the file: the stream moves the simulated arm."""
    env = {**os.environ, "PYTHONPATH": f"{ROOT / 'runtime'}{os.pathsep}{scene.tmp / 'gen' / 'python'}",
           "PYTHONUNBUFFERED": "1"}
    sim_log, bridge_log = scene.tmp / "sim.log", scene.tmp / "bridge.log"

    def writer(name: str) -> subprocess.Popen:
        log = scene.tmp / f"{name}.log"
        with open(log, "w") as out:
            proc = subprocess.Popen([*scene.ns, str(scene.python), str(ROOT / "tests/ros2/stream_writer.py"), PACKAGE,
                                     "handPose", "100", "0.4", "-0.25", "0.15", "0.1", "0.2", "0.3"],
                                    stdout=out, stderr=subprocess.STDOUT, env=env)
        _wait_for(log, "stream_writer ready", proc)
        return proc

    xarm = writer("xarm")
    try:
        _wait_for(bridge_log, "stream handPose active: publishing on /r2_controller/right/pose_command")
        _wait_for(sim_log, "pose_command frame=R2OriginFrame xyz=(0.4, -0.25, 0.15)")
        line = next(ln for ln in sim_log.read_text().splitlines()
                    if "pose_command frame=R2OriginFrame xyz=(0.4, -0.25, 0.15)" in ln)
        quat = [float(v) for v in line.split("quat=(", 1)[1].rstrip(")").split(",")]
        assert quat == pytest.approx(QUAT_RPY, abs=2e-6)  # the writer's rotation matrix, as a quaternion
        # a RAPID command from rapidgen cmd beside the stream
        scene.take_control()
        res = scene.cmd("RightArm", "Enable", "enable=true")
        assert res.returncode == 0 and "COMPLETED OK  enabled" in res.stdout, res.stdout + res.stderr
        stops = sim_log.read_text().count("r2_sim: stop 'stop'")
        received = sim_log.read_text().count("xyz=(0.4, -0.25, 0.15)")
        _wait_for_count(sim_log, "xyz=(0.4, -0.25, 0.15)", received + 20)  # still streaming
    finally:
        xarm.kill()  # the link is lost: no unregister, only the deadline tells
        xarm.wait()
    _wait_for(bridge_log, "stream handPose lost: no sample within 100 ms; stopped (published on "
                          "/r2_controller/right/stop)")
    _wait_for_count(sim_log, "r2_sim: stop 'stop'", stops + 1)  # the mapped cancel message reached the node
    again = writer("xarm2")
    try:
        _wait_for(bridge_log, "stream handPose recovered")
    finally:
        again.kill()
        again.wait()


def _wait_for_count(path: Path, text: str, count: int) -> None:
    end = time.monotonic() + WAIT
    while time.monotonic() < end:
        if path.read_text(errors="replace").count(text) >= count:
            return
        time.sleep(0.1)
    pytest.fail(f"fewer than {count} '{text}' in {path.name}")
