"""What rapidgen generates for setpoint streams, without building: the resolved facts, the
Fast DDS profile (DEADLINE, LIVELINESS, preallocated histories, partitions), the bridge's
typed callback, output functions and StreamSpec, and describe --json."""
from __future__ import annotations

import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from rapidgen.asset import load_asset
from rapidgen.asset.describe import describe_data
from rapidgen.diagnostics import DiagnosticSink

ROOT = Path(__file__).resolve().parents[2]
ARM = ROOT / "bench" / "setpoint" / "arm.yaml"
PILOT = ROOT / "bench" / "setpoint" / "pilot.yaml"
NS = "{http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles}"


def generate(descriptor: Path, out: Path, lang: str) -> Path:
    subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(descriptor), "--lang", lang, "-o", str(out)],
                   check=True, cwd=ROOT, capture_output=True)
    return out


@pytest.fixture(scope="module")
def arm_out(tmp_path_factory) -> Path:
    return generate(ARM, tmp_path_factory.mktemp("arm"), "cpp,qos")


def test_resolved_defaults():
    sink = DiagnosticSink()
    arm = load_asset(str(ARM), sink)
    assert arm is not None and not sink.has_errors
    (s,) = arm.streams
    assert (s.direction, s.type, s.topic, s.partition) == ("input", "rapid::JointSample",
                                                           "rapid_joint_sample-setpoints", "Pilot64")
    assert (s.rate, s.deadline_ms, s.liveliness_ms, s.on_loss, s.profile) == (1000.0, 3.0, 100.0, "hold",
                                                                            "RapidStream_setpoints")
    pilot = load_asset(str(PILOT), sink)
    assert pilot is not None and pilot.streams[0].partition == "Pilot64" and pilot.streams[0].on_loss == "none"
    assert not any(p.topic == s.topic for p in arm.publications)  # a stream is not a publication


def profile(xml: Path, kind: str, name: str) -> ET.Element:
    root = ET.parse(xml).getroot()
    found = [e for e in root.iter(f"{NS}{kind}") if e.get("profile_name") == name]
    assert len(found) == 1, f"{kind} {name}"
    return found[0]


def text(e: ET.Element, path: str) -> str:
    got = e.find("/".join(NS + p for p in path.split("/")))
    assert got is not None, path
    return got.text or ""


def test_fastdds_profile(arm_out):
    xml = arm_out / "qos" / "fastdds" / "rapid_qos_profiles.xml"
    for kind in ("data_writer", "data_reader"):
        p = profile(xml, kind, "RapidStream_setpoints")
        assert text(p, "qos/deadline/period/nanosec") == "3000000" and text(p, "qos/deadline/period/sec") == "0"
        assert text(p, "qos/liveliness/kind") == "AUTOMATIC"
        assert text(p, "qos/liveliness/lease_duration/nanosec") == "100000000"
        assert text(p, "qos/reliability/kind") == "BEST_EFFORT"
        assert text(p, "topic/historyQos/depth") == "1"
        assert text(p, "historyMemoryPolicy") == "PREALLOCATED_WITH_REALLOC"
        assert text(p, "topic/resourceLimitsQos/allocated_samples") == text(p, "topic/resourceLimitsQos/max_samples")
    assert text(profile(xml, "data_reader", "RapidStream_setpoints"), "qos/partition/names/name") == "Pilot64"
    assert text(profile(xml, "data_writer", "RapidStream_setpoints"), "qos/partition/names/name") == "Arm64"
    assert text(profile(xml, "data_writer", "RapidStream_setpoints"), "qos/publishMode/kind") == "SYNCHRONOUS"


def test_bridge_code(arm_out, tmp_path):
    bridge = arm_out / "cpp" / "bridge"
    hpp = (bridge / "handlers.hpp").read_text()
    assert "virtual void setpoints(const ::rapid::JointSample& sample)" in hpp
    assert "virtual void on_state(const ::rapid_runtime::StreamSpec& stream, ::rapid_runtime::StreamState state)" in hpp
    dispatch = (bridge / "dispatch.cpp").read_text()
    assert ('::rapid_runtime::StreamSpec{"setpoints", true, "rapid::JointSample", "rapid_joint_sample-setpoints", '
            '"Pilot64", "RapidStream_setpoints", 1000.0, 3.0, 100.0, ::rapid_runtime::LossAction::Hold, "", "", ""}'
            in dispatch)
    assert "streams_->read<::rapid::JointSample>(0u" in dispatch
    assert "void setpoints(" in (bridge / "handlers.cpp").read_text()  # the user's stub
    out = generate(PILOT, tmp_path / "pilot", "cpp") / "cpp" / "bridge"
    assert "::rapid::JointSample& setpoints_sample();\nbool send_setpoints();" in (out / "handlers.hpp").read_text()
    assert "streams_->writer<::rapid::JointSample>(0u);" in (out / "dispatch.cpp").read_text()


def test_describe_data():
    loaded = load_asset(str(ROOT / "specs" / "assets" / "robonaut2.yaml"), DiagnosticSink())
    assert loaded is not None
    (s,) = describe_data(loaded)["streams"]
    assert (s["name"], s["partition"], s["deadline_ms"], s["on_loss"], s["state_key"]) == (
        "handPose", "XArm2", 10.0, "stop", "handPoseStream")
