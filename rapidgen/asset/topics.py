"""Every topic an asset publishes: message type, full topic name, QoS profile, rate.

Topic names come from the IDL's topic constants (POSITION_SAMPLE_TOPIC, ...) plus the
entry's '-suffix'; default QoS profiles follow RAPID's per-topic map (rapid-protocol.md
section 6) unless the entry overrides them.
"""
from __future__ import annotations

from dataclasses import dataclass

from collections.abc import Sequence

from rapidgen.asset.facts import Facts
from rapidgen.asset.spec import AssetSpec, CustomTelemetry, SubsystemTypeSpec, Telemetry
from rapidgen.asset.standard import IMPLICIT_STATE_TOPICS
from rapidgen.diagnostics import SourceLoc

QOS_LIBRARY = "RapidQosLibrary"
QOS_PROFILES = ("RapidDefaultQos", "RapidBestEffortQos", "RapidReliableQos", "RapidReliableDurableQos",
                "RapidConfigQos", "RapidStateQos", "RapidSampleQos", "RapidPointCloudQos")

# kind -> (role, message type, topic constant), config first
STANDARD_MESSAGES: dict[str, tuple[tuple[str, str, str], ...]] = {
    "position": (("config", "rapid::PositionConfig", "POSITION_CONFIG_TOPIC"),
                 ("sample", "rapid::PositionSample", "POSITION_SAMPLE_TOPIC")),
    "joint": (("config", "rapid::JointConfig", "JOINT_CONFIG_TOPIC"),
              ("sample", "rapid::JointSample", "JOINT_SAMPLE_TOPIC")),
    "agent": (("config", "rapid::AgentConfig", "AGENT_CONFIG_TOPIC"),
              ("state", "rapid::AgentState", "AGENT_STATE_TOPIC")),
    "image": (("state", "rapid::ImageSensorState", "IMAGESENSOR_STATE_TOPIC"),
              ("sample", "rapid::ImageSensorSample", "IMAGESENSOR_SAMPLE_TOPIC")),
    "text": (("sample", "rapid::TextMessage", "TEXTMESSAGE_TOPIC"),),
}

# Used only when the IDL lacks the constant (e.g. a trimmed RAPID set).
FALLBACK_TOPICS = {
    "POSITION_CONFIG_TOPIC": "rapid_position_config", "POSITION_SAMPLE_TOPIC": "rapid_position_sample",
    "JOINT_CONFIG_TOPIC": "rapid_joint_config", "JOINT_SAMPLE_TOPIC": "rapid_joint_sample",
    "AGENT_CONFIG_TOPIC": "rapid_agent_config", "AGENT_STATE_TOPIC": "rapid_agent_state",
    "IMAGESENSOR_STATE_TOPIC": "rapid_imagesensor_state",
    "IMAGESENSOR_SAMPLE_TOPIC": "rapid_imagesensor_sample", "TEXTMESSAGE_TOPIC": "rapid_textmessage",
    "COMMAND_CONFIG_TOPIC": "rapid_command_config", "ACK_TOPIC": "rapid_ack",
    "ACCESSCONTROL_STATE_TOPIC": "rapid_accesscontrol_state", "QUEUE_STATE_TOPIC": "rapid_queue_state",
}


@dataclass(frozen=True)
class Publication:
    role: str  # config | sample | state | ack
    type: str  # scoped IDL name
    topic: str
    qos: str
    rate: float | None  # Hz; None: on start-up and on change
    loc: SourceLoc
    source: Telemetry | None = None  # None for topics implied by the subsystems


def default_qos(role: str, type_: str) -> str:
    if role == "config":
        return "RapidConfigQos"
    if type_ in ("rapid::TextMessage", "rapid::Ack"):
        return "RapidReliableDurableQos"
    if role == "state" and type_ != "rapid::AgentState":  # AgentState is sampled telemetry
        return "RapidStateQos"
    return "RapidSampleQos"


def profile_name(text: str) -> str:
    """'RapidQosLibrary::RapidSampleQos' and 'RapidSampleQos' name the same profile."""
    prefix = QOS_LIBRARY + "::"
    return text[len(prefix):] if text.startswith(prefix) else text


def topic_constant(facts: Facts, const: str) -> str:
    return facts.string_const("rapid::" + const) or FALLBACK_TOPICS[const]


def messages_of(t: Telemetry, facts: Facts) -> list[tuple[str, str, str, SourceLoc]]:
    """(role, type, base topic, loc) of one telemetry entry."""
    if isinstance(t, CustomTelemetry):
        out = []
        for m in t.messages:
            topic = facts.string_const(m.topic) if "::" in m.topic else m.topic
            out.append((m.role, m.type, topic or m.topic, m.loc))
        return out
    return [(role, type_, topic_constant(facts, const), t.at("kind"))
            for role, type_, const in STANDARD_MESSAGES.get(t.kind, ())]


def publications(spec: AssetSpec, facts: Facts, used: "Sequence[SubsystemTypeSpec]") -> list[Publication]:
    """Every topic the asset publishes (resolved.LoadedAsset.publications is the one caller)."""
    out: list[Publication] = []
    if used:
        out.append(Publication("config", "rapid::CommandConfig", topic_constant(facts, "COMMAND_CONFIG_TOPIC"),
                               "RapidConfigQos", None, spec.loc))
        out.append(Publication("ack", "rapid::Ack", topic_constant(facts, "ACK_TOPIC"),
                               "RapidReliableDurableQos", None, spec.loc))
    for st in used:
        if st.standard and st.name in IMPLICIT_STATE_TOPICS:
            type_, const = IMPLICIT_STATE_TOPICS[st.name]
            out.append(Publication("state", type_, topic_constant(facts, const), "RapidStateQos", None, spec.loc))
    for t in spec.telemetry:
        overrides = dict(t.qos)
        for role, type_, topic, loc in messages_of(t, facts):
            full = f"{topic}-{t.suffix}" if t.suffix else topic
            qos = profile_name(overrides.get(role, default_qos(role, type_)))
            rate = None if role == "config" else t.rate
            out.append(Publication(role, type_, full, qos, rate, loc, t))
    return out
