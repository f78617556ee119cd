"""The neutral QoS library: rapid-protocol.md section 6, the loader and its diagnostics."""
from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest
import yaml

from rapidgen.asset.topics import QOS_PROFILES, default_qos
from rapidgen.diagnostics import DiagnosticSink
from rapidgen.qos import History, default_library, load_qos, parse_qos
from rapidgen.qos.spec import schema

ROOT = Path(__file__).resolve().parents[2]
SPEC = ROOT / "specs" / "qos" / "rapid.yaml"

# rapid-protocol.md section 6, written from the doc: profile -> (base, reliability,
# durability, history). None: "DDS default"; inherited rows repeat their base's values.
SECTION_6 = {
    "RapidDefaultQos": (None, None, None, None),
    "RapidBestEffortQos": ("RapidDefaultQos", "best_effort", "volatile", ("keep_last", 5)),
    "RapidReliableQos": ("RapidDefaultQos", "reliable", "volatile", ("keep_all", None)),
    "RapidReliableDurableQos": ("RapidDefaultQos", "reliable", "transient_local", ("keep_last", 1)),
    "RapidConfigQos": ("RapidReliableDurableQos", "reliable", "transient_local", ("keep_last", 1)),
    "RapidStateQos": ("RapidReliableDurableQos", "reliable", "transient_local", ("keep_last", 1)),
    "RapidSampleQos": ("RapidBestEffortQos", "best_effort", "volatile", ("keep_last", 5)),
}
# The DDS specification's defaults, which "DDS default" stands for.
DDS_DEFAULT = {"writer": ("reliable", "volatile", ("keep_last", 1)),
               "reader": ("best_effort", "volatile", ("keep_last", 1))}
# Section 6's per-topic map (type -> profile), from the doc.
SECTION_6_TOPICS = {
    "rapid::Command": "RapidReliableQos",
    "rapid::Ack": "RapidReliableDurableQos",
    "rapid::CommandConfig": "RapidConfigQos", "rapid::AgentConfig": "RapidConfigQos",
    "rapid::PositionConfig": "RapidConfigQos", "rapid::JointConfig": "RapidConfigQos",
    "rapid::AgentState": "RapidSampleQos",
    "rapid::ImageSensorState": "RapidStateQos", "rapid::AccessControlState": "RapidStateQos",
    "rapid::QueueState": "RapidStateQos",
    "rapid::PositionSample": "RapidSampleQos", "rapid::ImageSensorSample": "RapidSampleQos",
    "rapid::TextMessage": "RapidReliableDurableQos",
    "rapid::JointSample": "RapidSampleQos",
}


def expected(profile: str, side: str) -> tuple:
    """(reliability, durability, (history kind, depth)) section 6 gives a profile's side."""
    _, rel, dur, hist = SECTION_6[profile]
    if rel is None:
        return DDS_DEFAULT[side]
    return rel, dur, hist


def as_tuple(p) -> tuple:
    return p.reliability, p.durability, (p.history.kind, p.history.depth)


@pytest.mark.parametrize("profile", sorted(SECTION_6))
def test_profiles_follow_section_6(profile):
    spec = default_library()
    assert spec.library == "RapidQosLibrary"
    assert spec.profile(profile).base == SECTION_6[profile][0]
    writer, reader = spec.effective(profile)
    assert as_tuple(writer) == expected(profile, "writer")
    assert as_tuple(reader) == expected(profile, "reader")


def test_point_clouds_keep_10_written_and_100_read():
    writer, reader = default_library().effective("RapidPointCloudQos")
    assert writer.history == History("keep_last", 10) and reader.history == History("keep_last", 100)


def test_default_profile_participant_settings():
    spec = default_library()
    assert spec.default_profile.name == "RapidDefaultQos"
    for name in SECTION_6:  # every profile inherits them
        part = spec.participant(name)
        assert part.type_information is False and part.max_message_size == 1250
        p = part.ports
        assert (p.base, p.domain_gain, p.participant_gain, p.d0, p.d1, p.d2, p.d3) == (7400, 250, 2, 0, 10, 1, 11)
        assert spec.effective(name)[0].publish_mode == "asynchronous"


@pytest.mark.parametrize("type_name", sorted(SECTION_6_TOPICS))
def test_topic_map_follows_section_6(type_name):
    assert default_library().profile_for_type(type_name) == SECTION_6_TOPICS[type_name]


@pytest.mark.parametrize("type_name,role", [
    ("rapid::PositionConfig", "config"), ("rapid::AgentState", "state"), ("rapid::ImageSensorState", "state"),
    ("rapid::TextMessage", "sample"), ("rapid::JointSample", "sample"), ("rapid::ImageSensorSample", "sample"),
    ("rapid::QueueState", "state"), ("rapid::AccessControlState", "state"), ("rapid::ext::arc::GpsSample", "sample"),
    ("rapid::ext::arc::GpsConfig", "config"), ("rapid::Ack", "ack")])
def test_topic_map_agrees_with_the_asset_defaults(type_name, role):
    """The descriptor loader's defaults (rapidgen.asset.topics) and the library say the same."""
    assert default_library().profile_for_type(type_name) == default_qos(role, type_name)


def test_library_has_every_profile_descriptors_may_name():
    spec = default_library()
    assert all(spec.has_profile(p) for p in QOS_PROFILES)


def test_partition_and_transports():
    spec = default_library()
    assert spec.partition == "{asset}"
    assert [t.name for t in spec.transports] == ["local", "lan", "wan"]
    local, lan, wan = spec.transports
    assert spec.default_transport is local
    assert local.interfaces == ("127.0.0.1",) and not local.multicast and local.peers == ("127.0.0.1",)
    assert lan.multicast and lan.tcp is None
    assert not wan.multicast and wan.peers and wan.tcp is not None and wan.tcp.discovery_server.port == 11811


def test_packaged_library_is_specs_qos_rapid_yaml():
    packaged = ROOT / "rapidgen" / "qos" / "rapid.yaml"
    assert packaged.read_bytes() == SPEC.read_bytes()


def test_spec_satisfies_the_shipped_schema():
    jsonschema.Draft202012Validator.check_schema(schema())
    jsonschema.Draft202012Validator(schema()).validate(yaml.safe_load(SPEC.read_text()))
    assert json.loads((ROOT / "rapidgen" / "qos" / "qos.schema.json").read_text())["title"]


def test_load_qos_from_a_path():
    sink = DiagnosticSink()
    spec = load_qos(str(SPEC), sink)
    assert spec is not None and not sink.diagnostics
    def strip(s):
        return [(p.name, p.base, p.both, p.writer, p.reader, p.participant) for p in s.profiles]
    assert strip(spec) == strip(default_library())
    assert spec.profiles[0].loc.file == str(SPEC)


# ------------------------------------------------------------------ diagnostics

BASE = SPEC.read_text(encoding="utf-8")


def errors(text: str) -> list[str]:
    sink = DiagnosticSink()
    assert parse_qos(text, "q.yaml", sink) is None
    return [f"{d.loc.line}:{d.loc.col} {d.code} {d.message}" + (f" ({d.hint})" if d.hint else "")
            for d in sink.errors]


def line_of(text: str, needle: str) -> int:
    return next(i for i, line in enumerate(text.splitlines(), 1) if needle in line)


def test_unknown_key_points_at_the_key():
    text = BASE.replace("    reliability: reliable\n    durability: volatile\n",
                        "    reliabilty: reliable\n    durability: volatile\n", 1)
    (err,) = errors(text)
    assert err.startswith(f"{line_of(text, 'reliabilty')}:5 RG1602 unknown key 'reliabilty' in profiles.RapidReliableQos")
    assert "did you mean 'reliability'?" in err


def test_bad_enum_value():
    text = BASE.replace("reliability: best_effort", "reliability: besteffort", 1)
    (err,) = errors(text)
    assert f"{line_of(text, 'besteffort')}:18 RG1602" in err and "'besteffort' is not one of reliable, best_effort" in err


def test_keep_last_needs_a_depth_and_keep_all_takes_none():
    text = BASE.replace("history: {kind: keep_last, depth: 5}", "history: {kind: keep_last}", 1)
    assert "missing key 'depth'" in errors(text)[0]
    text = BASE.replace("history: {kind: keep_all}", "history: {kind: keep_all, depth: 3}", 1)
    assert "keep_all history takes no depth" in errors(text)[0]


def test_unknown_base_with_hint():
    text = BASE.replace("base: RapidReliableDurableQos\n    description: '*Config",
                        "base: RapidReliableDurabelQos\n    description: '*Config", 1)
    (err,) = errors(text)
    assert err.startswith(f"{line_of(text, 'DurabelQos')}:11 RG1603 profile 'RapidConfigQos': unknown base profile")
    assert "did you mean 'RapidReliableDurableQos'?" in err


def test_inheritance_cycle():
    text = BASE.replace("  RapidDefaultQos:\n    description:", "  RapidDefaultQos:\n    base: RapidSampleQos\n    description:", 1)
    errs = errors(text)
    assert any("RG1604 profile 'RapidDefaultQos' inherits from itself: RapidDefaultQos -> RapidSampleQos -> "
               "RapidBestEffortQos -> RapidDefaultQos" in e for e in errs)


def test_unknown_profile_in_topic_map():
    text = BASE.replace("{type: 'rapid::Ack', profile: RapidReliableDurableQos}",
                        "{type: 'rapid::Ack', profile: RapidAckQos}", 1)
    (err,) = errors(text)
    assert err.startswith(f"{line_of(text, 'RapidAckQos')}:")
    assert "RG1605 unknown profile 'RapidAckQos' for type 'rapid::Ack'" in err


def test_exactly_one_default_transport():
    text = BASE.replace("    multicast: true\n", "    default: true\n    multicast: true\n", 1)
    (err,) = errors(text)
    assert "RG1606 more than one default transport (local, lan)" in err
    assert err.startswith(f"{line_of(text, 'multicast: true') - 1}:")
    text = BASE.replace("    default: true\n", "", 1)
    assert "RG1606 no default transport" in errors(text)[0]


@pytest.mark.parametrize("text,needle", [
    ("", "RG1602 the QoS library is empty"),
    ("version: 1\nlibrary: [\n", "RG1010 YAML syntax error"),
    ("version: 2\n", "missing key"),
    ("- a\n- b\n", "expected a mapping"),
])
def test_broken_files_give_diagnostics(text, needle):
    assert any(needle in e for e in errors(text))


def test_unreadable_file(tmp_path):
    sink = DiagnosticSink()
    assert load_qos(str(tmp_path / "missing.yaml"), sink) is None
    assert sink.errors[0].code == "RG1601"
    (tmp_path / "bin.yaml").write_bytes(b"version: 1\0")
    assert load_qos(str(tmp_path / "bin.yaml"), sink) is None


def test_mutated_libraries_give_diagnostics_never_exceptions():
    import random

    rng = random.Random(6)
    lines = BASE.splitlines(True)
    for _ in range(400):
        text = list(lines)
        for _ in range(rng.randint(1, 4)):
            k = rng.randrange(len(text))
            op = rng.random()
            if op < 0.4:
                del text[k]
            elif op < 0.7:
                text.insert(k, rng.choice(lines))
            else:
                j = rng.randrange(len(text[k]) + 1)
                text[k] = text[k][:j] + rng.choice(["x", ":", "-", " ", "{", "[", "5", "null", "\t", "base: X "]) + text[k][j:]
        sink = DiagnosticSink()
        spec = parse_qos("".join(text), "m.yaml", sink)
        assert (spec is None) == bool(sink.errors)


def test_packaged_library_passes_its_schema():
    """default_library() skips the schema check each run; this is where it happens."""
    from importlib import resources

    from rapidgen.diagnostics import DiagnosticSink
    text = resources.files("rapidgen.qos").joinpath("rapid.yaml").read_text("utf-8")
    sink = DiagnosticSink()
    assert parse_qos(text, "rapid.yaml", sink) is not None, sink.diagnostics
    assert not sink.diagnostics
