"""specs/rapid/*.idl against the protocol facts of rapid-protocol.md, table by table.

The tables below are written from the protocol document, not from the IDL files: real
assets depend on these bytes (member order, types, bounds, enum order, keys, topics).
"""
import glob
import json
from pathlib import Path

import pytest

from tests.helpers import rapidgen

ROOT = Path(__file__).parents[2]
S = "rapid::"


@pytest.fixture(scope="module")
def model():
    import os
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        files = sorted(glob.glob("specs/rapid/*.idl"))
        res = rapidgen("ir", "--no-loc", "-I", "specs/rapid", *files)
    finally:
        os.chdir(cwd)
    assert res.code == 0, res.err
    assert res.err == "", "the RAPID set must resolve without warnings"
    return {d["name"]: d for d in json.loads(res.out)["declarations"]}


def resolve(model, t: str) -> str:
    """Follow typedefs to the underlying IDL type string."""
    for _ in range(10):
        d = model.get(t)
        if d is None or d["kind"] != "typedef":
            return t
        t = d["type"]
    return t


# -- section 2: common types ----------------------------------------------------------
STRINGS = {"String16": 16, "String32": 32, "String64": 64, "String128": 128, "String256": 256,
           "String1K": 1024, "String2K": 2048}
ARRAYS = {"Vec2d": "double[2]", "Vec3d": "double[3]", "Vec2f": "float[2]", "Vec3f": "float[3]",
          "Mat33f": "float[9]", "Color3f": "float[3]", "Color4f": "float[4]"}
SEQUENCES = {
    "String32Sequence16": ("rapid::String32", 16), "FloatSequence64": ("float", 64),
    "LongSequence64": ("long", 64), "OctetSequence1K": ("octet", 1024),
    "ParameterSequence16": ("rapid::ParameterUnion", 16), "KeyTypeSequence16": ("rapid::KeyTypePair", 16),
    "KeyTypeValueSequence64": ("rapid::KeyTypeValueTriple", 64), "ValueSequence64": ("rapid::ParameterUnion", 64),
    "KeyTypeValueSequence16": ("rapid::KeyTypeValueTriple", 16), "String16Sequence16": ("rapid::String16", 16),
    "String128Sequence64": ("rapid::String128", 64),
}
ENUMS = {
    "DataType": ["RAPID_BOOL", "RAPID_DOUBLE", "RAPID_FLOAT", "RAPID_INT", "RAPID_LONGLONG", "RAPID_STRING",
                 "RAPID_VEC3d", "RAPID_MAT33f"],
    "RotationEncoding": ["RAPID_ROT_NONE", "RAPID_ROT_M33", "RAPID_ROT_QUAT", "RAPID_ROT_XYZ", "RAPID_ROT_ZYX",
                         "RAPID_ROT_ZYZ", "RAPID_ROT_VEL"],
    "QueueAction": ["QUEUE_BYPASS", "QUEUE_APPEND", "QUEUE_DELETE", "QUEUE_INSERT", "QUEUE_REPLACE"],
    "AckStatus": ["ACK_QUEUED", "ACK_EXECUTING", "ACK_REQUEUED", "ACK_COMPLETED"],
    "AckCompletedStatus": ["ACK_COMPLETED_NOT", "ACK_COMPLETED_OK", "ACK_COMPLETED_BAD_SYNTAX",
                           "ACK_COMPLETED_EXEC_FAILED", "ACK_COMPLETED_CANCELED"],
    "MessageLevel": ["MSG_DEBUG", "MSG_INFO", "MSG_ATTENTION", "MSG_WARN", "MSG_ERROR", "MSG_CRITICAL"],
    "ResultType": ["Q_RESULT_INIT", "Q_RESULT_SUCCEEDED", "Q_RESULT_FAILED"],
    "StatusType": ["Q_STATUS_" + s for s in ("INIT", "OUTBOUND", "LOST", "INLINE", "PREEMPTED", "INPROCESS",
                   "PAUSED", "CANCELED", "SUCCEEDED", "FAILED", "ALIEN_PENDING", "ALIEN_ACTIVE",
                   "ALIEN_COMPLETED", "FORGOTTEN_BY_ROBOT")],
}
UNION = [("RAPID_BOOL", "b", "boolean"), ("RAPID_DOUBLE", "d", "double"), ("RAPID_FLOAT", "f", "float"),
         ("RAPID_INT", "i", "long"), ("RAPID_LONGLONG", "ll", "long long"), ("RAPID_STRING", "s", "string<128>"),
         ("RAPID_VEC3d", "vec3d", "double[3]"), ("RAPID_MAT33f", "mat33f", "float[9]")]

# Structs and messages: (member, type as the protocol names it), in order; keys; topic.
STRUCTS = {
    "KeyTypePair": [("key", "String32"), ("type", "DataType")],
    "KeyTypeValueTriple": [("key", "String32"), ("padding", "long"), ("value", "ParameterUnion")],
    "Transform3D": [("xyz", "Vec3d"), ("rot", "Mat33f")],
    "NamedFloatSequence": [("name", "String16"), ("values", "FloatSequence64")],
    "FloatRange": [("min", "float"), ("max", "float")],
    "FloatRangeValue": [("min", "float"), ("max", "float"), ("value", "float")],
    "OptionSetValue": [("index", "long"), ("options", "String32Sequence16")],
    "NamedFloatRangeValue": [("name", "String16"), ("range", "FloatRangeValue")],
    "NamedOptionSetValue": [("name", "String16"), ("option", "OptionSetValue")],
    "Header": [("srcName", "String32"), ("assetName", "String32"), ("timeStamp", "long long"),
               ("statusCode", "long"), ("serial", "long")],
    "SubsystemType": [("name", "String32"), ("commands", "sequence<CommandDef, 100>")],
    "CommandDef": [("name", "String64"), ("abortable", "boolean"), ("suspendable", "boolean"),
                   ("parameters", "KeyTypeSequence16")],
    "Subsystem": [("name", "String32"), ("subsystemTypeName", "String32")],
    "JointDef": [("frameName", "String128"), ("dof", "String64")],
    "ImageMetadata": [("sensorName", "String32"), ("sensorType", "String32"), ("offset", "Transform3D"),
                      ("width", "long"), ("height", "long"),
                      ("rangeSettings", "sequence<NamedFloatRangeValue, 16>"),
                      ("optionSettings", "sequence<NamedOptionSetValue, 16>"), ("extras", "KeyTypeValueSequence16")],
}
MESSAGES = {
    "Command": ([("cmdName", "String64"), ("cmdId", "String64"), ("cmdSrc", "String32"), ("subsysName", "String32"),
                 ("arguments", "ParameterSequence16"), ("cmdAction", "QueueAction"), ("targetCmdId", "String64")],
                [], "rapid_command"),
    "Ack": ([("cmdId", "String64"), ("status", "AckStatus"), ("completedStatus", "AckCompletedStatus"),
             ("message", "String128")], ["cmdId"], "rapid_ack"),
    "CommandConfig": ([("availableSubsystemTypes", "sequence<SubsystemType, 64>"),
                       ("availableSubsystems", "sequence<Subsystem, 128>")], [], "rapid_command_config"),
    "AgentConfig": ([("agentTags", "String16Sequence16"), ("topics", "String128Sequence64"),
                     ("valueKeys", "KeyTypeValueSequence64")], [], "rapid_agent_config"),
    "AgentState": ([("values", "ValueSequence64")], [], "rapid_agent_state"),
    "PositionConfig": ([("frameName", "String128"), ("poseEncoding", "RotationEncoding"),
                        ("velocityEncoding", "RotationEncoding"), ("valueKeys", "KeyTypeValueSequence64")],
                       [], "rapid_position_config"),
    "PositionSample": ([("pose", "Transform3D"), ("velocity", "Transform3D"), ("values", "ValueSequence64")],
                       [], "rapid_position_sample"),
    "JointConfig": ([("jointGroupName", "String32"), ("jointDefinitions", "sequence<JointDef, 64>")],
                    [], "rapid_joint_config"),
    "JointSample": ([(n, "FloatSequence64") for n in ("anglePos", "angleVel", "angleAcc", "current", "torque",
                                                      "temperature")]
                    + [("status", "LongSequence64"), ("auxFloat", "sequence<NamedFloatSequence, 16>")],
                    [], "rapid_joint_sample"),
    "ImageSensorSample": ([("meta", "ImageMetadata"), ("mimeType", "String32"), ("data", "sequence<octet, 1048576>")],
                          [], "rapid_imagesensor_sample"),
    "ImageSensorState": ([("meta", "ImageMetadata")], [], "rapid_imagesensor_state"),
    "TextMessage": ([("level", "MessageLevel"), ("category", "String64"), ("message", "String2K")],
                    [], "rapid_textmessage"),
    "AccessControlState": ([("controller", "String32"), ("requestors", "String32Sequence16")],
                           [], "rapid_accesscontrol_state"),
    "FileAnnounce": ([("fileUuid", "String64"), ("fileLocator", "String256"), ("fileSize", "long long"),
                      ("metaData", "KeyTypeValueSequence16")], ["fileUuid"], "rapid_fileannounce"),
    "QueueState": ([(n, "SingleQueue") for n in ("pending", "active", "completed", "sent")], [], "rapid_queue_state"),
}
JOINT_FLAGS = {"JOINT_ENABLED": 0x0000, "JOINT_DISABLED": 0x0001, "JOINT_FROZEN": 0x0003, "JOINT_ESTOP": 0x0005,
               "JOINT_FAILURE": 0x0100, "JOINT_OVER_CURRENT": 0x0300, "JOINT_POSITION_ERROR": 0x0500}
PRIMITIVES = {"long", "long long", "float", "double", "boolean", "octet"}


def qualify(t: str) -> str:
    """The protocol's short type names as the IR spells them (scoped)."""
    if t in PRIMITIVES:
        return t
    if t.startswith("sequence<"):
        inner, bound = t[len("sequence<"):-1].rsplit(", ", 1)
        return f"sequence<{qualify(inner)}, {bound}>"
    return S + t


@pytest.mark.parametrize("name,bound", STRINGS.items())
def test_string_typedefs(model, name, bound):
    assert model[S + name]["type"] == f"string<{bound}>"


@pytest.mark.parametrize("name,array", ARRAYS.items())
def test_array_typedefs(model, name, array):
    assert model[S + name]["type"] == array


@pytest.mark.parametrize("name,spec", SEQUENCES.items())
def test_sequence_typedefs(model, name, spec):
    assert model[S + name]["type"] == f"sequence<{spec[0]}, {spec[1]}>"


@pytest.mark.parametrize("name,values", ENUMS.items())
def test_enum_order(model, name, values):
    assert [(e["name"], e["value"]) for e in model[S + name]["enumerators"]] == list(zip(values, range(len(values))))


def test_parameter_union(model):
    u = model[S + "ParameterUnion"]
    assert u["discriminator"] == S + "DataType"
    got = [(c["labels"][0]["name"], c["name"], resolve(model, c["type"])) for c in u["cases"]]
    assert got == UNION
    assert not any(c["default"] for c in u["cases"]) and all(len(c["labels"]) == 1 for c in u["cases"])


@pytest.mark.parametrize("name,members", STRUCTS.items())
def test_structs(model, name, members):
    d = model[S + name]
    assert d["kind"] == "struct"
    assert [(m["name"], m["type"]) for m in d["members"]] == [(n, qualify(t)) for n, t in members]


def test_header_and_message(model):
    assert model[S + "Header"]["keys"] == ["srcName", "assetName"]
    msg = model[S + "Message"]
    assert msg["origin"] == "valuetype" and msg["base"] is None
    assert [(m["name"], m["type"], m.get("key")) for m in msg["members"]] == [("hdr", S + "Header", True)]
    assert msg["keys"] == ["hdr.srcName", "hdr.assetName"]


@pytest.mark.parametrize("name,spec", MESSAGES.items())
def test_messages(model, name, spec):
    members, extra_keys, _topic = spec
    d = model[S + name]
    assert d["origin"] == "valuetype" and d["base"] == S + "Message"
    assert [(m["name"], m["type"]) for m in d["members"]] == [(n, qualify(t)) for n, t in members]
    assert d["keys"] == ["hdr.srcName", "hdr.assetName"] + extra_keys


# Section 4: the topic constants by name (`const String64 X_TOPIC = "..."`), and which
# message each one names (the message/topic table).
TOPIC_CONSTANTS = {
    "COMMAND_TOPIC": "rapid_command", "ACK_TOPIC": "rapid_ack", "COMMAND_CONFIG_TOPIC": "rapid_command_config",
    "AGENT_CONFIG_TOPIC": "rapid_agent_config", "AGENT_STATE_TOPIC": "rapid_agent_state",
    "POSITION_CONFIG_TOPIC": "rapid_position_config", "POSITION_SAMPLE_TOPIC": "rapid_position_sample",
    "JOINT_CONFIG_TOPIC": "rapid_joint_config", "JOINT_SAMPLE_TOPIC": "rapid_joint_sample",
    "IMAGESENSOR_SAMPLE_TOPIC": "rapid_imagesensor_sample", "IMAGESENSOR_STATE_TOPIC": "rapid_imagesensor_state",
    "TEXTMESSAGE_TOPIC": "rapid_textmessage", "ACCESSCONTROL_STATE_TOPIC": "rapid_accesscontrol_state",
    "FILEANNOUNCE_TOPIC": "rapid_fileannounce", "QUEUE_STATE_TOPIC": "rapid_queue_state",
}
TOPIC_OF = {
    "Command": "COMMAND_TOPIC", "Ack": "ACK_TOPIC", "CommandConfig": "COMMAND_CONFIG_TOPIC",
    "AgentConfig": "AGENT_CONFIG_TOPIC", "AgentState": "AGENT_STATE_TOPIC",
    "PositionConfig": "POSITION_CONFIG_TOPIC", "PositionSample": "POSITION_SAMPLE_TOPIC",
    "JointConfig": "JOINT_CONFIG_TOPIC", "JointSample": "JOINT_SAMPLE_TOPIC",
    "ImageSensorSample": "IMAGESENSOR_SAMPLE_TOPIC", "ImageSensorState": "IMAGESENSOR_STATE_TOPIC",
    "TextMessage": "TEXTMESSAGE_TOPIC", "AccessControlState": "ACCESSCONTROL_STATE_TOPIC",
    "FileAnnounce": "FILEANNOUNCE_TOPIC", "QueueState": "QUEUE_STATE_TOPIC",
}


def test_protocol_tables_agree():
    """The constant table and the message table (both section 4) tell the same story."""
    assert set(TOPIC_OF) == set(MESSAGES) and sorted(TOPIC_OF.values()) == sorted(TOPIC_CONSTANTS)
    assert {m: TOPIC_CONSTANTS[c] for m, c in TOPIC_OF.items()} == {m: spec[2] for m, spec in MESSAGES.items()}


def test_topic_constants(model):
    """By name, so that two constants with swapped values fail."""
    got = {d["name"]: d["value"] for d in model.values() if d["kind"] == "const" and d["name"].endswith("_TOPIC")}
    assert got == {S + name: value for name, value in TOPIC_CONSTANTS.items()}
    for name in TOPIC_CONSTANTS:
        assert resolve(model, model[S + name]["type"]) == "string<64>", name


@pytest.fixture(scope="module")
def declared_in():
    """{scoped name: IDL file} of the RAPID set (the IR with locations)."""
    import os
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        res = rapidgen("ir", "-I", "specs/rapid", *sorted(glob.glob("specs/rapid/*.idl")))
    finally:
        os.chdir(cwd)
    assert res.code == 0, res.err
    return {d["name"]: Path(d["loc"].split(":", 1)[0]).name for d in json.loads(res.out)["declarations"]}


@pytest.mark.parametrize("message,const", TOPIC_OF.items())
def test_each_message_pairs_with_its_topic_constant(model, declared_in, message, const):
    """RAPID declares a message's topic constant beside it, in the message's own file."""
    assert model[S + const]["value"] == MESSAGES[message][2]
    assert declared_in[S + const] == declared_in[S + message] == f"{message}.idl"


def test_generator_pairs_messages_with_their_topic_constants():
    """rapidgen's own message -> constant tables (asset topics) agree with section 4."""
    from rapidgen.asset.standard import IMPLICIT_STATE_TOPICS
    from rapidgen.asset.topics import FALLBACK_TOPICS, STANDARD_MESSAGES

    pairs = [(type_, const) for entries in STANDARD_MESSAGES.values() for _role, type_, const in entries]
    pairs += list(IMPLICIT_STATE_TOPICS.values())
    for type_, const in pairs:
        assert TOPIC_OF[type_.removeprefix(S)] == const, (type_, const)
    assert FALLBACK_TOPICS.items() <= TOPIC_CONSTANTS.items()


def test_command_record_and_single_queue(model):
    rec = model[S + "CommandRecord"]
    assert rec["origin"] == "valuetype" and rec["base"] is None
    assert [(m["name"], m["type"]) for m in rec["members"]] == [
        ("cmd", S + "Command"), ("trResult", S + "ResultType"), ("trStatus", S + "StatusType")]
    (only,) = model[S + "SingleQueue"]["members"]
    assert only["type"] == f"sequence<{S}CommandRecord, 64>"


def test_joint_status_flags(model):
    assert {n: model[S + n]["value"] for n in JOINT_FLAGS} == JOINT_FLAGS


def test_mime_constants(model):
    mimes = {d["value"] for d in model.values() if d["kind"] == "const" and str(d["value"]).startswith("image/")}
    assert {"image/jpeg", "image/png"} <= mimes
