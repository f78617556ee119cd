"""The ros2 section without ROS 2: message definitions (installed .msg files first, the
built-in table otherwise), the generated ros2_map.py (deterministic, descriptor strings
as exact literals) and the mapping it carries."""
from __future__ import annotations

import ast
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from rapidgen.asset.load import load_asset
from rapidgen.diagnostics import DiagnosticSink
from rapidgen.ros2 import msgdefs

from tests.ros2 import runtime_ros2

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples/ros2/robonaut2-ros2.yaml"

HOSTILE = 'x"); import os  # \\ \u202e'
DESCRIPTOR = f"""\
version: 1
asset: {{name: Probe, kind: manipulator}}
idl: {{rapid: {ROOT / 'specs/rapid'}}}
subsystem_types:
  - name: Arm
    commands:
      - name: say
        parameters: [{{name: text, type: RAPID_STRING}}, {{name: rot, type: RAPID_MAT33f}}]
subsystems: [{{name: Admin}}, {{name: Arm1, type: Arm}}]
ros2:
  commands:
    - command: Arm1/say
      publish:
        topic: /arm/say
        type: my_msgs/msg/Say
        fields: {{text: text, note: {{value: {json.dumps(HOSTILE)}}}, pose.orientation: rot}}
      until: {{topic: /arm/said, type: std_msgs/String, field: data, equals: {json.dumps(HOSTILE)}}}
"""


def _share(tmp_path: Path) -> Path:
    """An installed interface package the built-in table does not know."""
    msg = tmp_path / "prefix" / "share" / "my_msgs" / "msg"
    msg.mkdir(parents=True)
    (msg / "Say.msg").write_text("# a custom message\nuint8 LOUD=1\nstring text\nstring note\n"
                                 "geometry_msgs/Pose pose\nfloat64[3] gains\n")
    return tmp_path / "prefix"


def _load(path: Path, monkeypatch, prefix: Path | None):
    if prefix is not None:
        monkeypatch.setenv("AMENT_PREFIX_PATH", str(prefix))
    msgdefs.lookup.cache_clear()
    sink = DiagnosticSink()
    loaded = load_asset(str(path), sink)
    msgdefs.lookup.cache_clear()
    return loaded, sink


def test_installed_definitions_are_read_before_the_built_in_table(tmp_path, monkeypatch):
    prefix = _share(tmp_path)
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(prefix))
    msgdefs.lookup.cache_clear()
    say = msgdefs.lookup("my_msgs/msg/Say")
    assert say is not None and say.source.endswith("Say.msg")
    assert [(f.name, f.type, f.array, f.size) for f in say.fields] == [
        ("text", "string", False, None), ("note", "string", False, None),
        ("pose", "geometry_msgs/msg/Pose", False, None), ("gains", "float64", True, 3)]
    assert msgdefs.resolve_path(say, "pose.orientation.w")[0].type == "float64"
    assert msgdefs.resolve_path(say, "gains[3]")[0] is None  # past a fixed array
    monkeypatch.delenv("AMENT_PREFIX_PATH")
    msgdefs.lookup.cache_clear()
    assert msgdefs.lookup("my_msgs/msg/Say") is None or sys.prefix in msgdefs.lookup("my_msgs/msg/Say").source


def test_the_built_in_table_parses_as_the_wheels_do():
    msgdefs.lookup.cache_clear()
    for name in msgdefs.BUILTIN:
        got = msgdefs.lookup(name)
        assert got is not None, name
        for f in got.fields:  # every nested type is itself known
            assert f.primitive or msgdefs.lookup(f.type) is not None, (name, f)


def test_custom_message_validates_only_where_it_is_installed(tmp_path, monkeypatch):
    desc = tmp_path / "probe.yaml"
    desc.write_text(DESCRIPTOR)
    loaded, sink = _load(desc, monkeypatch, None)
    assert [d.code for d in sink.diagnostics] == ["RG1501"] and loaded.ros2 is None
    loaded, sink = _load(desc, monkeypatch, _share(tmp_path))
    assert not sink.diagnostics, [str(d) for d in sink.diagnostics]
    pub = loaded.ros2["commands"]["Arm1/say"]["publish"]
    assert pub["fields"] == [["text", "str", [0]], ["note", "const", HOSTILE], ["pose.orientation", "quat_m33", [1]]]
    assert pub["stamp"] is False  # no std_msgs/Header


def test_generated_map_is_deterministic_and_holds_strings_exactly(tmp_path, monkeypatch):
    desc = tmp_path / "probe.yaml"
    desc.write_text(DESCRIPTOR)
    env = {**os.environ, "AMENT_PREFIX_PATH": str(_share(tmp_path))}
    outs = []
    for seed in ("1", "2"):
        out = tmp_path / f"out{seed}"
        res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(desc), "--lang", "python", "-o",
                              str(out)], cwd=tmp_path, env={**env, "PYTHONHASHSEED": seed},
                             capture_output=True, text=True)
        assert res.returncode == 0, res.stderr
        outs.append({p.name: p.read_bytes() for p in (out / "python" / "rapid_probe").glob("ros2*.py")})
    assert outs[0] == outs[1] and set(outs[0]) == {"ros2.py", "ros2_map.py"}
    source = outs[0]["ros2_map.py"].decode()
    tree = ast.parse(source)  # the hostile text is a literal, not code
    assigned = {t.targets[0].id: ast.literal_eval(t.value) for t in tree.body if isinstance(t, ast.Assign)}
    cmd = assigned["COMMANDS"]["Arm1/say"]
    assert cmd["publish"]["fields"][1] == ["note", "const", HOSTILE]
    assert cmd["until"]["equals"] == HOSTILE
    assert all(isinstance(t, (ast.Assign, ast.Expr)) for t in tree.body)  # a docstring and literals only
    bridge = ast.parse(outs[0]["ros2.py"].decode())  # the call only: the code is rapid_runtime.ros2
    assert not [n for n in ast.walk(bridge) if isinstance(n, (ast.FunctionDef, ast.ClassDef, ast.Lambda))]
    assert "rapid_runtime.ros2.handlers" in {n.module for n in ast.walk(bridge) if isinstance(n, ast.ImportFrom)}
    assert b"rclpy" not in b"".join(v for k, v in outs[0].items() if k != "ros2.py")


def test_no_ros2_section_no_ros2_files(tmp_path):
    res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(ROOT / "specs/assets/k10.yaml"),
                          "--lang", "python", "-o", str(tmp_path)], cwd=ROOT, capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    assert not list(tmp_path.rglob("ros2*.py"))


def test_the_example_maps_what_the_seed_scenario_needs(monkeypatch):
    loaded, sink = _load(EXAMPLE, monkeypatch, None)
    assert not sink.has_errors
    feeds = {(f["feeds"], f["topic"]) for f in loaded.ros2["telemetry"]}
    assert ("joint", "/joint_states") in feeds and ("position", "/r2_controller/right/tool_pose") in feeds
    pose = loaded.ros2["commands"]["RightArm/Setpoint for Tool"]["publish"]
    assert pose["topic"] == "/r2_controller/right/pose_command" and pose["stamp"] is True


@pytest.fixture(scope="module")
def example_bridge(tmp_path_factory):
    """The example generated and importable; the bridge's code (rapid_runtime.ros2, which the
    generated rapid_r2ros.ros2 calls) as one namespace. Neither needs rclpy to import."""
    import importlib
    out = tmp_path_factory.mktemp("r2ros")
    res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(EXAMPLE), "--lang", "python", "-o",
                          str(out)], cwd=ROOT, capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    sys.path.insert(0, str(out / "python"))
    try:
        importlib.import_module("rapid_r2ros.ros2")
        yield runtime_ros2()
    finally:
        sys.path.remove(str(out / "python"))
        for name in [n for n in sys.modules if n == "rapid_r2ros" or n.startswith("rapid_r2ros.")]:
            del sys.modules[name]


def test_generated_rotations_agree(example_bridge):
    """The generated bridge's rotation helpers: tf2's setRPY quaternion, and matrix <->
    quaternion round trips."""
    import math
    ros2 = example_bridge
    assert ros2.quat_from_rpy(0.1, 0.2, 0.3) == pytest.approx((0.0342708, 0.1060205, 0.1435722, 0.9833474), abs=1e-7)
    assert ros2.quat_from_rpy(0, 0, math.pi / 2) == pytest.approx((0, 0, math.sqrt(0.5), math.sqrt(0.5)))
    for q in [(0, 0, 0, 1), (1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), ros2.quat_from_rpy(2.5, -1.1, 3.0),
              ros2.quat_from_rpy(-3.0, 0.4, -2.9)]:
        back = ros2.quat_from_m33(ros2.m33_from_quat(*q))
        sign = 1 if sum(a * b for a, b in zip(back, q)) >= 0 else -1  # q and -q are one rotation
        assert [sign * b for b in back] == pytest.approx(list(q), abs=1e-9)
    m = ros2.m33_from_quat(*ros2.quat_from_rpy(0, 0, math.pi / 2))  # yaw 90 degrees: x -> y
    assert m == pytest.approx([0, -1, 0, 1, 0, 0, 0, 0, 1], abs=1e-12)


def test_raw_images_become_pnm(example_bridge):
    """The bridge's raw Image -> PNM: rows cut at `step` (padding dropped), BGR swapped to RGB,
    mono8 as PGM; the runtime reads the size back from the PNM header."""
    from types import SimpleNamespace
    ros2 = example_bridge
    read = ros2.Ros2Handlers._read_image
    bgr = SimpleNamespace(encoding="bgr8", width=2, height=2, step=8,
                          data=bytes([1, 2, 3, 4, 5, 6, 0, 0, 7, 8, 9, 10, 11, 12, 0, 0]))
    assert read(None, None, bgr, None) == b"P6\n2 2\n255\n" + bytes([3, 2, 1, 6, 5, 4, 9, 8, 7, 12, 11, 10])
    mono = SimpleNamespace(encoding="mono8", width=3, height=1, step=3, data=b"abc")
    assert read(None, None, mono, None) == b"P5\n3 1\n255\nabc"
    compressed = SimpleNamespace(format="png", data=b"\x89PNG...")
    assert read(None, None, compressed, None) == b"\x89PNG..."
    from rapid_runtime.images import describe
    info = describe(read(None, None, bgr, None))
    assert (info.mime, info.width, info.height) == ("image/x-portable-pixmap", 2, 2)
    with pytest.raises(ValueError, match="rgb8, bgr8 and mono8"):
        read(None, None, SimpleNamespace(encoding="16UC1", width=1, height=1, step=2, data=b"\0\0"), None)


def test_feeds_read_odometry_split_joint_states_and_fields(example_bridge):
    """The bridge's readers on message-shaped objects: Odometry's pose and twist (RAPID_ROT_M33,
    RAPID_ROT_VEL; the twist turned from child_frame_id into the pose's frame), JointState split over messages (a joint not in one keeps its value), agent
    fields through paths."""
    from types import SimpleNamespace as NS
    ros2 = example_bridge
    h = ros2.Ros2Handlers.__new__(ros2.Ros2Handlers)  # the readers use no ROS 2 state
    v3 = lambda x, y, z: NS(x=x, y=y, z=z)  # noqa: E731
    odom = NS(pose=NS(pose=NS(position=v3(1.0, 2.0, 3.0), orientation=NS(x=0.0, y=0.0, z=1.0, w=0.0))),
              twist=NS(twist=NS(linear=v3(0.5, 0.0, 0.0), angular=v3(0.0, 0.0, 0.25))))
    feed = {"pose": "pose.pose", "twist": "twist.twist", "encoding": "RAPID_ROT_M33",
            "velocity_encoding": "RAPID_ROT_VEL"}
    xyz, rot, vxyz, vrot = h._read_position(feed, odom, None)
    assert xyz == [1.0, 2.0, 3.0] and vxyz == pytest.approx([-0.5, 0.0, 0.0])  # body-forward, facing -x
    assert rot == pytest.approx([-1, 0, 0, 0, -1, 0, 0, 0, 1])  # half a turn about z
    assert vrot == [0.0, 0.0, 0.25] + [0.0] * 6
    joints = {"joints": ["a", "b", "c"]}
    first = h._read_joint(joints, NS(name=["c", "x", "a"], position=[3.0, 9.0, 1.0], velocity=[], effort=[]), None)
    assert first[0] == [1.0, 0.0, 3.0]
    second = h._read_joint(joints, NS(name=["b"], position=[2.0], velocity=[0.5], effort=[7.0]), first)
    assert second == ([1.0, 2.0, 3.0], [0.0, 0.5, 0.0], [0.0, 7.0, 0.0])
    agent = {"values": [["force", "wrench.force", "vec3"], ["ok", "status[1]", "bool"], ["n", "count", "int"]]}
    msg = NS(wrench=NS(force=v3(1.0, 2.0, 3.0)), status=[False, True], count=7)
    assert h._read_agent(agent, msg, {"other": 1.5}) == {"other": 1.5, "force": [1.0, 2.0, 3.0], "ok": True, "n": 7}


def _stream_errors(tmp_path, monkeypatch, old: str, new: str):
    """The example with one text of its ros2.streams mapping replaced: its errors, and the
    1-based line of the replacement."""
    text = EXAMPLE.read_text()
    assert text.count(old) == 1
    at = text[:text.index(old)].count("\n") + 1
    path = tmp_path / "r2.yaml"
    path.write_text(text.replace(old, new).replace("version: 1", f"version: 1\nidl: {{rapid: {ROOT / 'specs/rapid'}}}",
                                                   1))
    _, sink = _load(path, monkeypatch, None)
    return sink.errors, at + 1  # the idl line shifts everything below by one


def test_the_example_maps_its_input_stream(monkeypatch):
    loaded, sink = _load(EXAMPLE, monkeypatch, None)
    assert not sink.has_errors
    (stream,) = loaded.ros2["streams"]
    assert (stream["stream"], stream["topic"], stream["partition"]) == ("handPose", "rapid_position_sample-handPose",
                                                                        "XArm2")
    assert stream["deadline_ms"] == 100.0 and stream["on_loss"] == "stop"
    assert stream["ros2"] == {"topic": "/r2_controller/right/pose_command", "type": "geometry_msgs/msg/PoseStamped",
                              "pose": "pose", "stamp": True, "frame": "R2OriginFrame", "encoding": "RAPID_ROT_M33"}
    # on_loss stop without a stop message of its own: RightArm's mapped cancel message
    assert stream["stop"]["topic"] == "/r2_controller/right/stop"


@pytest.mark.parametrize("old, new, code, words", [
    ("- stream: handPose", "- stream: footPose", "RG1504", "'footPose' is no input stream"),
    ("      type: geometry_msgs/msg/PoseStamped\n      frame:", "      type: sensor_msgs/msg/JointState\n      frame:",
     "RG1503", "rapid::PositionSample (stream 'handPose') cannot become sensor_msgs/msg/JointState"),
    ("pose_encoding: RAPID_ROT_M33 ", "pose_encoding: RAPID_ROT_EULER ", "RG1503", "cannot become a ROS 2 quaternion"),
])
def test_a_stream_mapping_error_is_located(tmp_path, monkeypatch, old, new, code, words):
    errors, line = _stream_errors(tmp_path, monkeypatch, old, new)
    assert [(e.code, e.loc.line) for e in errors] == [(code, line)], errors  # at the replaced key's line
    assert words in errors[0].message


@pytest.fixture(scope="module")
def example_ground(example_bridge):
    """The ground node's code, rapid_runtime.ros2.ground (rclpy only in its main), beside the
    example's generated package (its generated rapid_r2ros.ros2_ground imports)."""
    import importlib
    importlib.import_module("rapid_r2ros.ros2_ground")
    from rapid_runtime.ros2 import ground
    return ground


def test_ground_config_topics_and_json(example_ground):
    """Configs go to ROS 2 as JSON on NS/config/<name>: the name from the RAPID topic, the
    JSON the sample's members (rapid_runtime.plain: enums by name, unions as discriminator and
    value, octets as hex, NaN as "NaN"): each config built from the tables reads back as the
    tables' computed value."""
    import importlib
    import json

    from rapid_runtime import messages
    from rapid_runtime.tables import Tables

    g = example_ground
    assert g.config_topic("/r2ros", "rapid_agent_config") == "/r2ros/config/agent"
    assert g.config_topic("/r2ros", "rapid_position_config-rightArm") == "/r2ros/config/position/rightArm"
    assert g.config_topic("", "rapid_ext_arc_gps_config") == "/config/ext_arc_gps"
    assert g.config_topic("/r", "rapid_joint_config-a.b") == "/r/config/joint/a_b"
    assert g.plain(float("nan")) == "NaN" and g.plain(b"\x00\xff") == "00ff"
    tables = Tables(importlib.import_module("rapid_r2ros.asset_tables"))
    rapid = importlib.import_module("rapid_r2ros.rapid")
    assert set(tables.configs) >= {"rapid_command_config", "rapid_agent_config", "rapid_joint_config"}
    for topic, (type_name, value) in tables.configs.items():
        sample = messages.config(rapid, type_name, value, messages.header(rapid, "R2Ros", "R2Ros", 7))
        got = json.loads(json.dumps(g.plain(sample)))
        assert got["hdr"]["assetName"] == "R2Ros" and got["hdr"]["serial"] == 7, topic
        assert {k: v for k, v in got.items() if k != "hdr"} == value, topic
