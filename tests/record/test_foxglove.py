"""`rapidgen record --foxglove` (docs/foxglove.md): a live recording of K10's simulated bridge
(domain 69, loopback) while `rapidgen cmd` takes pictures, read back under Node by Foxglove's
own libraries (tests/node/read_mcap.js: @mcap/core + @mcap/support, zstd as written): every
RAPID message decoded, every derived message valid against the JSON Schema @foxglove/schemas
publishes, and each derived message's values equal to its RAPID sample's as Foxglove's omgidl
reader decodes it (not rapidgen's). Robonaut 2 likewise (domain 95): joint states named by its
JointConfig, hand poses in RAPID_ROT_M33. The derivations with no K10 sample (joints, rotation
encodings, raw images, hostile samples) are checked on built samples; rapidgen's copy of
Foxglove's schemas equals the npm package's."""
from __future__ import annotations

import base64
import json
import math
import signal
import subprocess
import time
from types import SimpleNamespace as NS

import pytest

from rapidgen.foxglove.derive import Deriver, rotation
from rapidgen.foxglove.schemas import SCHEMAS
from tests.node.runner import run_json
from tests.record.test_record import K10, PKG, PYDIR, RAPIDGEN, ROOT, Proc, BridgeProcess, ENV

DOMAIN = 69
CMD = [*RAPIDGEN, "cmd", K10, "--domain", str(DOMAIN), "--source", "RapidWorkbench", "--timeout", "20"]
LEVELS = {"MSG_DEBUG": 1, "MSG_INFO": 2, "MSG_ATTENTION": 3, "MSG_WARN": 3, "MSG_ERROR": 4, "MSG_CRITICAL": 5}


def _stamp(hdr) -> dict:
    us = int(hdr["timeStamp"])
    return {"sec": us // 1_000_000, "nsec": us % 1_000_000 * 1000}


@pytest.fixture(scope="module")
def recording(tmp_path_factory):
    pytest.importorskip("cyclonedds")
    pytest.importorskip("mcap")
    out = tmp_path_factory.mktemp("foxglove") / "fox.mcap"
    rec = Proc([*RAPIDGEN, "record", "--asset", K10, "--domain", str(DOMAIN), "-o", str(out), "--foxglove",
                "--quiet"])
    bridge = None
    try:
        rec.wait_for("rapidgen record: recording domain")
        bridge = BridgeProcess(PYDIR, PKG, DOMAIN, "--sim-speed", "4")
        bridge.wait_ready()
        cmds = [subprocess.run(CMD + argv, cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=120)
                for argv in (["AccessControl", "requestControl"], ["PanCam", "takePicture", "mode=stereo"],
                             ["Mobility", "simpleMove", "frame=site", "xyt=1,1,0.5"])]
        time.sleep(3)  # a few 1 Hz positions and GPS fixes, a 0.5 Hz HazCam picture
        bridge.stop()
        bridge = None
        time.sleep(0.5)
        code = rec.end()
    finally:
        if bridge is not None:
            bridge.stop()
        if rec.proc.poll() is None:
            rec.proc.kill()
            rec.proc.wait()
    assert code == 0, "".join(rec.err)[-3000:]
    for c in cmds:
        assert c.returncode == 0, c.stdout[-1000:] + c.stderr[-1000:]
    return {"file": out, "err": "".join(rec.err), "read": run_json("read_mcap.js", "--all", str(out))}


def _pairs(got, derived_topic: str, rapid_topic: str):
    """(RAPID message, derived message) in file order: one derived message per RAPID sample."""
    rapid, derived = got["messages"].get(rapid_topic, []), got["derived"].get(derived_topic, [])
    assert rapid and len(rapid) == len(derived), (rapid_topic, len(rapid), derived_topic, len(derived))
    return list(zip(rapid, (d["message"] for d in derived)))


def _pairs_once_configured(got, derived_topic: str, rapid_topic: str):
    """As _pairs for joints, derived only once their JointConfig is seen (docs/foxglove.md): the
    recorder's config reader may hear the config after the first samples, which then have no
    derived message. Those are a prefix, a few at most; every later sample has its message."""
    rapid, derived = got["messages"].get(rapid_topic, []), got["derived"].get(derived_topic, [])
    late = len(rapid) - len(derived)
    assert derived and 0 <= late <= 10, (rapid_topic, len(rapid), derived_topic, len(derived))
    pairs = list(zip(rapid[late:], (d["message"] for d in derived)))
    assert all(d["timestamp"] == _stamp(r["hdr"]) for r, d in pairs)  # the same samples, in order
    return pairs


def test_derived_messages_valid_and_equal_to_the_rapid_samples(recording):
    got = recording["read"]
    assert got["failed"] == [] and got["compression"] == ["zstd"], got["failed"][:3]
    assert got["invalid"] == [], got["invalid"][:3]  # every derived message valid per @foxglove/schemas
    schemas = {t: {d["schema"] for d in ds} for t, ds in got["derived"].items()}
    want = {"/K10Red/rapid_position_sample/transform": {"foxglove.FrameTransform"},
            "/K10Red/rapid_position_sample/pose": {"foxglove.PoseInFrame"},
            "/K10Red/rapid_ext_arc_gps_sample/location": {"foxglove.LocationFix"},
            "/K10Red/rapid_textmessage/log": {"foxglove.Log"},
            "/K10Red/rapid_imagesensor_sample-panCamLeft/image": {"foxglove.CompressedImage"},
            "/K10Red/rapid_imagesensor_sample-panCamRight/image": {"foxglove.CompressedImage"},
            "/K10Red/rapid_imagesensor_sample-hazCam/image": {"foxglove.CompressedImage"}}
    assert schemas == want, schemas

    moved = False
    for kind in ("transform", "pose"):
        for r, d in _pairs(got, f"/K10Red/rapid_position_sample/{kind}", "rapid_position_sample"):
            assert d["timestamp"] == _stamp(r["hdr"])
            xyz, rot = r["pose"]["xyz"], r["pose"]["rot"]  # K10: RAPID_ROT_QUAT, x y z w first
            q = d["rotation"] if kind == "transform" else d["pose"]["orientation"]
            p = d["translation"] if kind == "transform" else d["pose"]["position"]
            assert [p["x"], p["y"], p["z"]] == xyz
            n = math.sqrt(sum(c * c for c in rot[:4]))
            assert [q["x"], q["y"], q["z"], q["w"]] == pytest.approx([c / n for c in rot[:4]], abs=1e-12)
            if kind == "transform":
                assert (d["parent_frame_id"], d["child_frame_id"]) == ("site", "K10Red")
            else:
                assert d["frame_id"] == "site"
            moved |= xyz[0] != 0.0
    assert moved  # the drive moved it: the values are the samples', not a constant

    fixes = _pairs(got, "/K10Red/rapid_ext_arc_gps_sample/location", "rapid_ext_arc_gps_sample")
    for r, d in fixes:
        assert (d["latitude"], d["longitude"], d["altitude"]) == (r["latitude"], r["longitude"], r["altitude"])
        assert d["timestamp"] == _stamp(r["hdr"]) and d["frame_id"] == "K10Red"

    for r, d in _pairs(got, "/K10Red/rapid_textmessage/log", "rapid_textmessage"):
        assert d["message"] == r["message"] and d["timestamp"] == _stamp(r["hdr"])
        assert d["name"] == f"{r['hdr']['assetName']}/{r['category']}" if r["category"] else r["hdr"]["assetName"]
        level = r["level"] if isinstance(r["level"], str) else list(LEVELS)[r["level"]]
        assert d["level"] == LEVELS[level]

    pictures = 0
    for suffix, fmt in (("panCamLeft", "jpeg"), ("panCamRight", "jpeg"), ("hazCam", "png")):
        for r, d in _pairs(got, f"/K10Red/rapid_imagesensor_sample-{suffix}/image",
                           f"rapid_imagesensor_sample-{suffix}"):
            assert base64.b64decode(d["data"]) == bytes(r["data"]) and len(r["data"]) > 0
            assert d["format"] == fmt == r["mimeType"].split("/")[1]
            assert d["frame_id"] == r["meta"]["sensorName"] and d["timestamp"] == _stamp(r["hdr"])
            pictures += 1
    assert pictures >= 3
    assert "derived Foxglove messages" in recording["err"]


def test_info_lists_the_derived_channels(recording):
    res = subprocess.run([*RAPIDGEN, "record", "--info", str(recording["file"])], cwd=ROOT, env=ENV,
                         capture_output=True, text=True, timeout=60)
    assert res.returncode == 0, res.stderr[-2000:]
    assert "/K10Red/rapid_position_sample/pose" in res.stdout


def test_rapidgen_copy_of_the_schemas_equals_the_npm_package():
    got = run_json("dump_schemas.js", *SCHEMAS)
    assert got == SCHEMAS


def _hdr(us: int = 1_700_000_000_123_456) -> NS:
    return NS(timeStamp=us, assetName="R2", srcName="R2")


def test_joint_states_need_a_joint_config_and_take_its_names():
    d = Deriver()
    sample = NS(hdr=_hdr(), anglePos=[0.5, -1.0], angleVel=[0.1, 0.2], angleAcc=[], torque=[3.0], current=[],
                temperature=[], status=[], auxFloat=[])
    assert d.feed("rapid_joint_sample-rightArm", "R2", "rapid::JointSample", sample, 0) == []
    cfg = NS(hdr=_hdr(), jointGroupName="rightArm",
             jointDefinitions=[NS(frameName="r2/right_arm/j0", dof="RZ"), NS(frameName="r2/right_arm/j1", dof="RY")])
    assert d.feed("rapid_joint_config-rightArm", "R2", "rapid::JointConfig", cfg, 0) == []
    assert d.feed("rapid_joint_sample-leftArm", "R2", "rapid::JointSample", sample, 0) == []  # another group
    [out] = d.feed("rapid_joint_sample-rightArm", "R2", "rapid::JointSample", sample, 0)
    assert out.schema == "foxglove.JointStates" and out.topic == "/R2/rapid_joint_sample-rightArm/joints"
    # torque has one value for two joints: no effort; velocities are complete
    assert out.message == {"timestamp": {"sec": 1_700_000_000, "nsec": 123_456_000},
                           "joints": [{"name": "r2/right_arm/j0", "position": 0.5, "velocity": 0.1},
                                      {"name": "r2/right_arm/j1", "position": -1.0, "velocity": 0.2}]}


@pytest.mark.parametrize("encoding,rot,want", [
    ("RAPID_ROT_NONE", [9.0] * 9, (0, 0, 0, 1)),
    ("RAPID_ROT_QUAT", [0, 0, 2, 0, 0, 0, 0, 0, 0], (0, 0, 1, 0)),  # normalised
    ("RAPID_ROT_M33", [0, -1, 0, 1, 0, 0, 0, 0, 1, ], (0, 0, math.sqrt(0.5), math.sqrt(0.5))),  # 90 deg about z
    ("RAPID_ROT_M33", [-1, 0, 0, 0, -1, 0, 0, 0, 1], (0, 0, 1, 0)),  # 180 deg about z
    ("RAPID_ROT_M33", [0.0] * 9, (0, 0, 0, 1)),  # not a rotation (nothing filled in): identity
    ("RAPID_ROT_M33", [2, 0, 0, 0, 2, 0, 0, 0, 2], (0, 0, 0, 1)),  # a scale, not a rotation
    ("RAPID_ROT_XYZ", [math.pi / 2, 0, 0, 0, 0, 0, 0, 0, 0], (math.sqrt(0.5), 0, 0, math.sqrt(0.5))),
    ("RAPID_ROT_ZYX", [math.pi, 0, 0, 0, 0, 0, 0, 0, 0], (0, 0, 1, 0)),  # the first angle about z
    ("RAPID_ROT_QUAT", [0, 0, 0, 0, 0, 0, 0, 0, 0], (0, 0, 0, 1)),  # no rotation at all: identity
    ("RAPID_ROT_QUAT", [math.nan, 0, 0, 1, 0, 0, 0, 0, 0], (0, 0, 0, 1)),
])
def test_rotation_encodings(encoding, rot, want):
    assert rotation(encoding, rot) == pytest.approx(want, abs=1e-12)


def test_position_frame_from_the_config_over_the_descriptor_and_none_without_either():
    pose = NS(hdr=_hdr(-5), pose=NS(xyz=[1.0, 2.0, math.inf], rot=[0.0] * 9))
    d = Deriver({("K", "rapid_position_sample"): ("site", "RAPID_ROT_QUAT")})
    assert d.feed("rapid_position_sample-arm", "K", "rapid::PositionSample", pose, 0) == []  # no frame known
    tf, p = d.feed("rapid_position_sample", "K", "rapid::PositionSample", pose, 7_000_000_001)
    assert tf.message["parent_frame_id"] == "site" and p.message["frame_id"] == "site"
    assert tf.message["timestamp"] == {"sec": 7, "nsec": 1}  # negative stamp: the receive time
    assert tf.message["translation"] == {"x": 1.0, "y": 2.0, "z": 0.0}  # not finite: 0 (JSON has no inf)
    d.feed("rapid_position_config", "K", "rapid::PositionConfig",
           NS(frameName="world<script>", poseEncoding="RAPID_ROT_M33"), 0)
    tf, p = d.feed("rapid_position_sample", "K", "rapid::PositionSample", pose, 0)
    assert tf.message["parent_frame_id"] == "world<script>"  # a string, JSON-escaped where written


def test_images_raw_and_unknown_and_a_sample_of_another_shape():
    d = Deriver()
    meta = NS(sensorName="cam", width=2, height=1)
    raw = NS(hdr=_hdr(), meta=meta, mimeType="image/x-rgb8", data=bytes(range(6)))
    [img] = d.feed("rapid_imagesensor_sample-c", "A", "rapid::ImageSensorSample", raw, 0)
    assert img.schema == "foxglove.RawImage"
    assert (img.message["encoding"], img.message["step"], base64.b64decode(img.message["data"])) == \
        ("rgb8", 6, bytes(range(6)))
    short = NS(hdr=_hdr(), meta=meta, mimeType="image/x-rgb8", data=bytes(5))  # not width*height*3
    assert d.feed("rapid_imagesensor_sample-c", "A", "rapid::ImageSensorSample", short, 0) == []
    tiff = NS(hdr=_hdr(), meta=meta, mimeType="image/tiff", data=b"II*")
    assert d.feed("rapid_imagesensor_sample-c", "A", "rapid::ImageSensorSample", tiff, 0) == []
    assert d.feed("rapid_textmessage", "A", "rapid::TextMessage", NS(hdr=_hdr()), 0) == []  # no level/message


def test_built_messages_validate_under_node(tmp_path):
    """The built samples' derived messages, and a hostile text, valid per @foxglove/schemas."""
    d = Deriver({("A", "rapid_position_sample"): ("site", "RAPID_ROT_XYZ")})
    msgs = []
    msgs += d.feed("rapid_position_sample", "A", "rapid::PositionSample",
                   NS(hdr=_hdr(), pose=NS(xyz=[1.0, 2.0, 3.0], rot=[0.1, 0.2, 0.3] + [0.0] * 6)), 0)
    msgs += d.feed("rapid_textmessage", "A", "rapid::TextMessage",
                   NS(hdr=_hdr(), level=NS(name="MSG_CRITICAL"), category="", message='"\u202e</script>\x00'), 0)
    msgs += d.feed("gps", "A", "x::Gps", NS(hdr=_hdr(), latitude=37.4, longitude=-122.06), 0)
    d.feed("rapid_joint_config", "A", "rapid::JointConfig", NS(jointDefinitions=[NS(frameName="j")]), 0)
    msgs += d.feed("rapid_joint_sample", "A", "rapid::JointSample",
                   NS(hdr=_hdr(), anglePos=[1.0], angleVel=[], torque=[]), 0)
    assert len(msgs) == 5
    path = tmp_path / "msgs.json"
    path.write_text(json.dumps([[m.schema, m.message] for m in msgs], ensure_ascii=True), encoding="ascii")
    got = run_json("validate.js", str(path))
    assert got == {"valid": 5, "invalid": []}
    bad = tmp_path / "bad.json"  # the validator can say no
    bad.write_text(json.dumps([["foxglove.Log", {"level": 9}]]), encoding="ascii")
    assert run_json("validate.js", str(bad))["valid"] == 0


def _layout_check(name: str, derived: dict, frames: set[str]) -> None:
    """docs/foxglove/NAME opens on channels the recording has, its panels all placed, its 3D
    panel following a frame the transforms name."""
    layout = json.loads((ROOT / "docs" / "foxglove" / name).read_text(encoding="utf-8"))
    names: list[str] = []

    def walk(v):
        if isinstance(v, dict):
            for x in v.values():
                walk(x)
        elif isinstance(v, list):
            for x in v:
                walk(x)
        elif isinstance(v, str) and v.startswith("/"):
            names.append(v.split(".", 1)[0])
    walk(layout["configById"])
    assert names and set(names) <= set(derived), set(names) - set(derived)
    [follow] = [c["followTf"] for k, c in layout["configById"].items() if k.startswith("3D!")]
    assert follow in frames, (follow, frames)
    panels = set()

    def leaves(node):
        if isinstance(node, str):
            panels.add(node)
        else:
            leaves(node["first"])
            leaves(node["second"])
    leaves(layout["layout"])
    assert panels == set(layout["configById"])


def _frames(derived: dict) -> set[str]:
    return {d["message"][k] for ds in derived.values() for d in ds if d["schema"] == "foxglove.FrameTransform"
            for k in ("parent_frame_id", "child_frame_id")}


def test_the_k10_layout_names_the_recorded_channels(recording):
    derived = recording["read"]["derived"]
    _layout_check("k10-layout.json", derived, _frames(derived))


R2_DOMAIN = 95


@pytest.fixture(scope="module")
def r2_recording(tmp_path_factory):
    """Robonaut 2's simulated bridge (joints at 50 Hz named by its JointConfig, two hand poses
    in RAPID_ROT_M33) recorded with --foxglove for a few seconds, read under Node."""
    pytest.importorskip("cyclonedds")
    from tests.runtime.live import SEEDS, python_dir
    out = tmp_path_factory.mktemp("foxglove-r2") / "r2.mcap"
    r2 = str(ROOT / "specs" / "assets" / "robonaut2.yaml")
    rec = Proc([*RAPIDGEN, "record", "--asset", r2, "--domain", str(R2_DOMAIN), "-o", str(out), "--foxglove",
                "--quiet"])
    bridge = None
    try:
        rec.wait_for("rapidgen record: recording domain")
        bridge = BridgeProcess(python_dir("robonaut2"), SEEDS["robonaut2"], R2_DOMAIN)
        bridge.wait_ready()
        time.sleep(3)
        bridge.stop()
        bridge = None
        time.sleep(0.5)
        code = rec.end()
    finally:
        if bridge is not None:
            bridge.stop()
        if rec.proc.poll() is None:
            rec.proc.kill()
            rec.proc.wait()
    assert code == 0, "".join(rec.err)[-3000:]
    return run_json("read_mcap.js", "--all", str(out))


def _m33(q: dict) -> list[float]:
    """The row-major rotation matrix of a unit quaternion (to compare with RAPID_ROT_M33)."""
    x, y, z, w = q["x"], q["y"], q["z"], q["w"]
    return [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),
            2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
            2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]


def test_robonaut2_joints_named_by_its_joint_config_and_m33_hand_poses(r2_recording):
    got = r2_recording
    assert got["failed"] == [] and got["invalid"] == [], (got["failed"][:3], got["invalid"][:3])
    [config] = got["messages"]["rapid_joint_config"]
    names = [d["frameName"] for d in config["jointDefinitions"]]
    assert len(names) == 18 and names[0] == "LeftArm/Joint0"
    pairs = _pairs_once_configured(got, "/Robonaut2/rapid_joint_sample/joints", "rapid_joint_sample")
    assert len(pairs) >= 20
    for r, d in pairs:
        assert d["timestamp"] == _stamp(r["hdr"])
        assert [j["name"] for j in d["joints"]] == names
        assert [j["position"] for j in d["joints"]] == r["anglePos"]
        for key, column in (("velocity", "angleVel"), ("effort", "torque")):  # given for every joint, or not at all
            if len(r[column]) == len(names):
                assert [j[key] for j in d["joints"]] == r[column]
            else:
                assert not any(key in j for j in d["joints"])
    for arm in ("leftArm", "rightArm"):
        poses = _pairs(got, f"/Robonaut2/rapid_position_sample-{arm}/transform", f"rapid_position_sample-{arm}")
        for r, d in poses:
            assert (d["parent_frame_id"], d["child_frame_id"]) == ("R2OriginFrame", f"Robonaut2/{arm}")
            assert [d["translation"][k] for k in "xyz"] == r["pose"]["xyz"]
            if any(r["pose"]["rot"]):
                assert _m33(d["rotation"]) == pytest.approx(r["pose"]["rot"], abs=1e-5)  # float32 matrix
            else:  # the simulator fills no matrix: not a rotation, the identity
                assert d["rotation"] == {"x": 0, "y": 0, "z": 0, "w": 1}


def test_the_robonaut2_layout_names_the_recorded_channels(r2_recording):
    derived = r2_recording["derived"]
    _layout_check("robonaut2-layout.json", derived, _frames(derived))


SEEDS_DOMAIN = 39
OTHER_SEEDS = ("athlete", "chariot", "eva-suit", "xarm2")


@pytest.fixture(scope="module")
def seeds_recording(tmp_path_factory):
    """The four other seeds' simulated bridges recorded together with --foxglove for a few
    seconds (one domain, one asset per partition), read under Node: their layouts' channels."""
    pytest.importorskip("cyclonedds")
    from tests.runtime.live import SEEDS, python_dir
    out = tmp_path_factory.mktemp("foxglove-seeds") / "seeds.mcap"
    assets = [a for s in OTHER_SEEDS for a in ("--asset", str(ROOT / "specs" / "assets" / f"{s}.yaml"))]
    rec = Proc([*RAPIDGEN, "record", *assets, "--domain", str(SEEDS_DOMAIN), "-o", str(out), "--foxglove", "--quiet"])
    bridges = []
    try:
        rec.wait_for("rapidgen record: recording domain")
        for seed in OTHER_SEEDS:
            bridges.append(BridgeProcess(python_dir(seed), SEEDS[seed], SEEDS_DOMAIN))
        for b in bridges:
            b.wait_ready()
        time.sleep(3)  # two or three 1 Hz poses, a few 2 Hz Chariot pictures
        for b in bridges:
            b.stop()
        bridges = []
        time.sleep(0.5)
        code = rec.end()
    finally:
        for b in bridges:
            b.stop()
        if rec.proc.poll() is None:
            rec.proc.kill()
            rec.proc.wait()
    assert code == 0, "".join(rec.err)[-3000:]
    got = run_json("read_mcap.js", "--all", str(out))
    assert got["failed"] == [] and got["invalid"] == [], (got["failed"][:3], got["invalid"][:3])
    return got["derived"]


@pytest.mark.parametrize("seed, partition, follow", [("athlete", "ATHLETE", "ATHLETE"), ("chariot", "Chariot", "Chariot"),
                                                     ("eva-suit", "EvaSuitA", "EvaSuitA"),
                                                     ("xarm2", "XArm2", "XArm2Base")])
def test_each_seeds_layout_names_its_recorded_channels(seeds_recording, seed, partition, follow):
    """docs/foxglove/SEED-layout.json: only that seed's channels (each one recorded), its 3D
    panel following a frame its transforms name."""
    derived = {t: ds for t, ds in seeds_recording.items() if t.startswith(f"/{partition}/")}
    assert derived, sorted(seeds_recording)
    _layout_check(f"{seed}-layout.json", derived, _frames(derived))
    layout = json.loads((ROOT / "docs" / "foxglove" / f"{seed}-layout.json").read_text(encoding="utf-8"))
    assert [c["followTf"] for k, c in layout["configById"].items() if k.startswith("3D!")] == [follow]


def test_desktop_origins_are_refused_unless_given():
    """Foxglove's desktop app is an Electron page loaded from file:// (docs/foxglove.md): its
    WebSocket carries `Origin: file://` (or `null`), refused like any browser Origin unless
    given with --foxglove-origin; a client with no Origin (a program) is accepted."""
    from rapidgen.monitor.foxglove_server import FoxgloveServer
    default = FoxgloveServer()
    assert default._origin_ok(None)
    assert not any(default._origin_ok(o) for o in ("file://", "null", "https://app.foxglove.dev"))
    desktop = FoxgloveServer(origins=("file://", "null"))
    assert desktop._origin_ok("file://") and desktop._origin_ok("null") and desktop._origin_ok(None)
    assert not desktop._origin_ok("https://app.foxglove.dev") and not desktop._origin_ok("http://localhost:8080")
