"""RAPID's own moves mapped faithfully (issue 39 item 3), and the telemetry that comes back,
without ROS 2: tests/ros2/rover-nav.yaml's generated bridge (imported, no rclpy needed) turns
simpleMove's xyt (x, y, heading) into a goal pose whose orientation is the heading, picks and
scales elements; Odometry comes back as a Z-Y-X pose (heading first) with its twist turned from
the body frame into the pose's; BatteryState's 0-1 percentage as %; bad mappings are located
errors. Also the bridge's own --help and its one-line error without rclpy."""
from __future__ import annotations

import importlib
import math
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace as NS

import pytest

from rapidgen.asset.load import load_asset
from rapidgen.diagnostics import DiagnosticSink
from rapidgen.ros2 import msgdefs

from tests.ros2 import runtime_ros2

ROOT = Path(__file__).resolve().parents[2]
ROVER = ROOT / "tests/ros2/rover-nav.yaml"


@pytest.fixture(scope="module")
def rover(tmp_path_factory):
    """(the generated package's folder, the bridge's code (rapid_runtime.ros2, which the
    generated rapid_navrover.ros2 calls), its ros2_map)."""
    out = tmp_path_factory.mktemp("navrover")
    res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(ROVER), "--lang", "python", "-o",
                          str(out)], cwd=ROOT, capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    sys.path.insert(0, str(out / "python"))
    try:
        importlib.import_module("rapid_navrover.ros2")
        yield out / "python", runtime_ros2(), importlib.import_module("rapid_navrover.ros2_map")
    finally:
        sys.path.remove(str(out / "python"))
        for name in [n for n in sys.modules if n == "rapid_navrover" or n.startswith("rapid_navrover.")]:
            del sys.modules[name]


def _pose_stamped():
    v3 = lambda: NS(x=0.0, y=0.0, z=0.0)  # noqa: E731
    return NS(header=NS(frame_id="", stamp=None),
              pose=NS(position=v3(), orientation=NS(x=0.0, y=0.0, z=0.0, w=1.0)))


def _build(ros2, fields, args):
    """The message a command publishes, built by the bridge's own code."""
    msg = _pose_stamped()
    return ros2.Ros2Handlers._build(None, msg, "geometry_msgs/msg/PoseStamped", fields, args)


def test_simple_move_heading_becomes_the_goal_orientation(rover):
    _, ros2, ros2_map = rover
    pub = ros2_map.COMMANDS["Mobility/simpleMove"]["publish"]
    assert pub["fields"] == [["header.frame_id", "str", [0]], ["pose.position.x", "float", [[1, 0, 1]]],
                             ["pose.position.y", "float", [[1, 1, 1]]],
                             ["pose.orientation", "quat_euler", [None, None, [1, 2, 1]]]]
    for heading in (0.0, 0.5, math.pi / 2, -2.5, math.pi):
        msg = _build(ros2, pub["fields"], ["site", [3.0, -4.0, heading]])
        assert (msg.header.frame_id, msg.pose.position.x, msg.pose.position.y, msg.pose.position.z) == \
            ("site", 3.0, -4.0, 0.0)
        q = msg.pose.orientation  # a rotation about z by the heading, nothing else
        assert (q.x, q.y, q.z, q.w) == pytest.approx((0, 0, math.sin(heading / 2), math.cos(heading / 2)), abs=1e-12)
        assert ros2.yaw_from_quat(q.x, q.y, q.z, q.w) == pytest.approx(math.atan2(math.sin(heading),
                                                                                  math.cos(heading)))


def test_elements_scaled(rover):
    _, ros2, ros2_map = rover
    pub = ros2_map.COMMANDS["Mobility/move"]["publish"]
    msg = _build(ros2, pub["fields"], ["site", [1.5, -0.25, 1.0], [0.1, 0.1, 0.1]])
    assert (msg.pose.position.x, msg.pose.position.y) == (1500.0, -250.0)
    assert msg.pose.orientation.z == pytest.approx(math.sin(0.5))
    # the plain forms are as before: a whole RAPID_VEC3d to a Point, a RAPID_MAT33f to a quaternion
    pub6 = ros2_map.COMMANDS["Mobility/move6DOF"]["publish"]
    msg = _build(ros2, pub6["fields"], ["site", [1.0, 2.0, 3.0], [0, -1, 0, 1, 0, 0, 0, 0, 1]])
    assert (msg.pose.position.x, msg.pose.position.y, msg.pose.position.z) == (1.0, 2.0, 3.0)
    assert msg.pose.orientation.z == pytest.approx(math.sqrt(0.5))


def test_scaled_vectors_and_angles(rover):
    _, ros2, _ = rover
    args = [[1.0, 2.0, 3.0], 90.0]
    assert ros2.argument(args, [0, None, 0.001]) == pytest.approx([0.001, 0.002, 0.003])
    assert ros2.argument(args, [0, 2, -2]) == -6.0 and ros2.argument(args, 1) == 90.0
    q = ros2.field_value("quat_euler", [None, None, [1, None, math.pi / 180]], args, NS(x=0, y=0, z=0, w=1))
    assert (q.z, q.w) == pytest.approx((math.sqrt(0.5), math.sqrt(0.5)))  # 90 degrees as radians


def test_odometry_comes_back_heading_first_with_its_twist_in_the_pose_frame(rover):
    """The position entry declares RAPID_ROT_ZYX: rot[0] is the heading. Odometry's twist is in
    child_frame_id (the body); RAPID's velocity is in the pose's frame, so it is turned."""
    _, ros2, ros2_map = rover
    [feed] = [f for f in ros2_map.TELEMETRY if f["feeds"] == "position"]
    h = ros2.Ros2Handlers.__new__(ros2.Ros2Handlers)
    heading = 2.0
    q = ros2.quat_from_rpy(0.0, 0.0, heading)
    v3 = lambda x, y, z: NS(x=x, y=y, z=z)  # noqa: E731
    odom = NS(pose=NS(pose=NS(position=v3(5.0, 6.0, 0.0), orientation=NS(x=q[0], y=q[1], z=q[2], w=q[3]))),
              twist=NS(twist=NS(linear=v3(1.0, 0.0, 0.0), angular=v3(0.0, 0.0, 0.3))))
    xyz, rot, vxyz, vrot = h._read_position(feed, odom, None)
    assert xyz == [5.0, 6.0, 0.0] and rot[:3] == pytest.approx([heading, 0.0, 0.0]) and rot[3:] == [0.0] * 6
    assert vxyz == pytest.approx([math.cos(heading), math.sin(heading), 0.0])  # driving forward, heading 2 rad
    assert vrot[:3] == pytest.approx([0.0, 0.0, 0.3])  # a turn about z is one in both frames


@pytest.mark.parametrize("encoding", ["RAPID_ROT_ZYX", "RAPID_ROT_XYZ"])
def test_euler_encodings_agree_with_the_foxglove_derivation(rover, encoding):
    """The bridge's quaternion -> Euler angles, read back by rapidgen's own reader of RAPID
    rotations (rapidgen/foxglove/derive.py, intrinsic in the encoding's order): the same rotation."""
    from rapidgen.foxglove.derive import rotation
    _, ros2, _ = rover
    for rpy in [(0.1, 0.2, 0.3), (2.5, -1.1, 3.0), (-3.0, 0.4, -2.9), (0.0, 0.0, -1.2)]:
        q = ros2.quat_from_rpy(*rpy)
        rot = ros2.rapid_rot(NS(x=q[0], y=q[1], z=q[2], w=q[3]), encoding)
        back = rotation(encoding, rot)
        sign = 1 if sum(a * b for a, b in zip(back, q)) >= 0 else -1
        assert [sign * b for b in back] == pytest.approx(list(q), abs=1e-9), (encoding, rpy)


@pytest.mark.parametrize("encoding", ["RAPID_ROT_ZYX", "RAPID_ROT_XYZ", "RAPID_ROT_ZYZ"])
def test_euler_poses_go_to_ros2_as_their_quaternion(rover, encoding):
    """ros2_ground: a PositionSample in Euler angles (Chariot's and the EVA suit's ZYX heading)
    becomes the PoseStamped quaternion rapidgen's Foxglove derivation reads from it."""
    from rapidgen.foxglove.derive import rotation
    pydir, ros2, _ = rover
    importlib.import_module("rapid_navrover.ros2_ground")
    from rapid_runtime.ros2 import ground
    g = ground.Ground.__new__(ground.Ground)
    for angles in [(0.3, 0.0, 0.0), (2.5, -1.1, 3.0), (-3.0, 0.4, -2.9)]:
        sample = NS(hdr=NS(timeStamp=1_700_000_000_123_456), pose=NS(xyz=[1.0, 2.0, 3.0], rot=[*angles] + [0.0] * 6))
        g.PoseStamped = lambda: NS(header=NS(frame_id="", stamp=NS(sec=0, nanosec=0)),  # noqa: E731
                                   pose=NS(position=NS(x=0.0, y=0.0, z=0.0), orientation=NS(x=0, y=0, z=0, w=1)))
        msg = g._position({"frame": "utm", "encoding": encoding}, sample)
        o = msg.pose.orientation
        want = rotation(encoding, sample.pose.rot)
        sign = 1 if sum(a * b for a, b in zip(want, (o.x, o.y, o.z, o.w))) >= 0 else -1
        assert [sign * v for v in (o.x, o.y, o.z, o.w)] == pytest.approx(list(want), abs=1e-9)
        assert msg.header.frame_id == "utm" and (msg.header.stamp.sec, msg.header.stamp.nanosec) == \
            (1_700_000_000, 123_456_000)
    if encoding == "RAPID_ROT_ZYX":  # a heading alone: a rotation about z
        q = ros2.quat_from_euler([0.7, 0.0, 0.0], "ZYX")
        assert q == pytest.approx((0.0, 0.0, math.sin(0.35), math.cos(0.35)))


def test_battery_percentage_scaled_and_heading_from_a_quaternion(rover):
    _, ros2, ros2_map = rover
    h = ros2.Ros2Handlers.__new__(ros2.Ros2Handlers)
    battery, amcl = [f for f in ros2_map.TELEMETRY if f["feeds"] == "agent"]
    got = h._read_agent(battery, NS(percentage=0.42, voltage=24.5), None)
    assert got == pytest.approx({"batteryCharge": 42.0, "batteryVoltage": 24.5})
    q = ros2.quat_from_rpy(0.0, 0.0, -math.pi / 4)
    got = h._read_agent(amcl, NS(pose=NS(pose=NS(orientation=NS(x=q[0], y=q[1], z=q[2], w=q[3])))), got)
    assert got["heading"] == pytest.approx(-45.0) and got["batteryCharge"] == pytest.approx(42.0)


# -- located errors ---------------------------------------------------------------------------
def _errors(tmp_path, old: str, new: str):
    """rover-nav.yaml with one text replaced: its diagnostics, and the replacement's 1-based line."""
    text = ROVER.read_text()
    assert text.count(old) == 1, old
    at = text[:text.index(old)].count("\n") + 1
    path = tmp_path / "rover.yaml"
    path.write_text(text.replace(old, new))
    msgdefs.lookup.cache_clear()
    sink = DiagnosticSink()
    load_asset(str(path), sink)
    return sink.diagnostics, at


@pytest.mark.parametrize("old, new, code, col, words", [
    ("yaw: xyt[2]", "yaw: xyt[3]", "RG1503", 18, "xyt[3]: a RAPID_VEC3d has elements 0 to 2"),
    ("yaw: xyt[2]", "yaw: frame[0]", "RG1503", 18, "frame (RAPID_STRING) has no elements"),
    ("yaw: xyt[2]", "yaw: xyt", "RG1503", 18, "xyt (RAPID_VEC3d) is not one angle"),
    ("yaw: xyt[2]", "yaw: xyz[2]", "RG1504", 18, "the command has no parameter 'xyz'"),
    ("yaw: xyt[2]", "heading: xyt[2]", "RG1505", 13, "unknown key 'heading' in a roll/pitch/yaw orientation"),
    ("pose.position.x: xyt[0]", "pose.position.x: {yaw: \"xyt[0]\"}", "RG1503", 28,
     "roll/pitch/yaw make a quaternion; geometry_msgs/msg/PoseStamped field 'pose.position.x' is float64"),
    ("{from: \"xyt[0]\", scale: 1000}", "{from: \"xyt[0]\", scale: 0}", "RG1503", 52,
     "scale 0 is not a finite number other than 0"),
    ("{from: \"xyt[0]\", scale: 1000}", "{form: \"xyt[0]\", scale: 1000}", "RG1505", 28,
     "a scaled argument is written {from: PARAMETER, scale: NUMBER}"),
    ("header.frame_id: frame\n          pose.position.x: xyt[0]",
     "header.frame_id: {from: frame, scale: 2}\n          pose.position.x: xyt[0]", "RG1503", 28,
     "frame (RAPID_STRING) cannot be scaled"),
    ("pose.orientation: rot}", "pose.orientation: {from: rot, scale: 2}}", "RG1503", 80,
     "a geometry_msgs/msg/Quaternion field cannot be scaled"),
    ("{yaw: pose.pose.orientation, scale: 57.29577951308232}", "{yaw: pose.pose.position, scale: 57.3}", "RG1503",
     24, "yaw takes a geometry_msgs/Quaternion field"),
    ("batteryCharge: {field: percentage, scale: 100}", "batteryCharge: {field: percentage, scale: 100%}", "RG1503",
     51, "scale '100%' is not a finite number other than 0"),
])
def test_a_bad_mapping_is_a_located_error(tmp_path, old, new, code, col, words):
    got, line = _errors(tmp_path, old, new)
    errors = [d for d in got if d.severity.name.lower() == "error"] if hasattr(got[0], "severity") else got
    assert [(d.code, d.loc.line, d.loc.col) for d in errors] == [(code, line, col)], [str(d) for d in got]
    assert words in errors[0].message, errors[0].message


def test_battery_percentage_unscaled_into_a_percent_value_is_warned(tmp_path):
    got, line = _errors(tmp_path, "batteryCharge: {field: percentage, scale: 100}", "batteryCharge: percentage")
    assert [(d.code, d.loc.line) for d in got] == [("RG1509", line)], [str(d) for d in got]
    assert "scale: 100" in got[0].hint
    got, _ = _errors(tmp_path, '{key: batteryCharge, type: RAPID_FLOAT, unit: "%"}',
                     "{key: batteryCharge, type: RAPID_FLOAT}")
    assert got == []  # scaled, and no % declared: nothing to say


# -- the bridge's command line ------------------------------------------------------------------
def test_the_ros2_bridge_has_its_own_help(rover):
    pydir, _, _ = rover
    res = subprocess.run([sys.executable, "-m", "rapid_navrover.ros2", "--help"], cwd=pydir, capture_output=True,
                         text=True, timeout=60)
    assert res.returncode == 0, res.stderr
    assert res.stdout.startswith("usage: python -m rapid_navrover.ros2 ")
    assert "served from the ROS 2 node nav_rover_bridge" in res.stdout and "ROS_DOMAIN_ID" in res.stdout
    assert "--simulate" not in res.stdout and "--sim-speed" not in res.stdout and "--journal" in res.stdout
    res = subprocess.run([sys.executable, "-m", "rapid_navrover.ros2", "--simulate"], cwd=pydir,
                         capture_output=True, text=True, timeout=60)
    assert res.returncode == 2 and "unrecognized arguments: --simulate" in res.stderr


def test_without_rclpy_one_line_says_what_to_install(rover):
    pydir, _, _ = rover
    if importlib.util.find_spec("rclpy") is not None:
        pytest.skip("rclpy is installed in this Python")
    res = subprocess.run([sys.executable, "-m", "rapid_navrover.ros2", "--no-journal", "--seconds", "1"], cwd=pydir,
                         capture_output=True, text=True, timeout=60)
    assert res.returncode == 2
    lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
    assert lines == ["python -m rapid_navrover.ros2: cannot import rclpy (ROS 2 Python): install ros-rclpy "
                     "ros-rmw-fastrtps-cpp (pip, the PyPI ROS wheels; docs/ros2.md) or source a ROS 2 install"], \
        res.stderr


def test_describe_shows_the_ros2_section():
    run = lambda *a: subprocess.run([sys.executable, "-m", "rapidgen", "describe", *a], cwd=ROOT,  # noqa: E731
                                    capture_output=True, text=True, timeout=120)
    res = run(str(ROVER))
    assert res.returncode == 0, res.stderr
    text = res.stdout[res.stdout.index("\nROS 2 (node nav_rover_bridge; python -m <package>.ros2)"):]
    assert "/battery_state  sensor_msgs/msg/BatteryState" in text and "batteryCharge <- percentage x 100" in text
    assert "heading <- yaw of pose.pose.orientation x 57.2958" in text
    assert "twist twist.twist turned into the pose's frame" in text
    assert "pose.position.x <- xyt[0]; pose.position.y <- xyt[1]; pose.orientation <- quaternion of yaw xyt[2]" \
        in text
    assert "pose.position.x <- xyt[0] x 1000" in text
    data = __import__("json").loads(run("--json", str(ROVER)).stdout)
    assert data["ros2"]["node"] == "nav_rover_bridge"
    assert data["ros2"]["commands"]["Mobility/simpleMove"]["publish"]["topic"] == "/goal_pose"
    plain = run(str(ROOT / "specs/assets/k10.yaml"))
    assert plain.returncode == 0 and "\nROS 2 (" not in plain.stdout
    assert __import__("json").loads(run("--json", str(ROOT / "specs/assets/k10.yaml")).stdout)["ros2"] is None


def test_xyt_whole_on_a_quaternion_is_refused(tmp_path):
    """The issue's trap: `pose.orientation: xyt` took x, y, heading as roll, pitch, yaw. xyt's
    unit (m, m, rad) says it is not three angles: a located error pointing at the heading."""
    got, line = _errors(tmp_path, "          pose.orientation:                                # the heading as a "
                        "quaternion about z\n            yaw: xyt[2]", "          pose.orientation: xyt")
    assert [(d.code, d.loc.line, d.loc.col) for d in got] == [("RG1503", line, 29)], [str(d) for d in got]
    assert got[0].message == "xyt (m, m, rad) is not roll, pitch, yaw: a quaternion from it would turn its lengths " \
        "into angles"
    assert got[0].hint == 'pick its angle: pose.orientation: {yaw: "xyt[2]"}'
