"""Telemetry checks: message types, topics, QoS profiles, and each kind's own fields."""
from __future__ import annotations

from typing import TYPE_CHECKING

from rapidgen.asset.spec import (AgentTelemetry, CustomTelemetry, ImageTelemetry, JointTelemetry,
                                 PositionTelemetry, Telemetry, TextTelemetry, ValueKey)
from rapidgen.asset.topics import QOS_PROFILES, STANDARD_MESSAGES, profile_name
from rapidgen.diagnostics import did_you_mean

if TYPE_CHECKING:
    from rapidgen.asset.check import Checker
    from rapidgen.asset.topics import Publication

_ROLES = {kind: tuple(r for r, _, _ in msgs) for kind, msgs in STANDARD_MESSAGES.items()}


def check_telemetry(c: "Checker") -> None:
    spec = c.spec
    subs = [s.name for s in c.loaded.subsystems]
    for t, msgs in zip(spec.telemetry, c.loaded.telemetry_messages):
        if t.subsystem is not None and t.subsystem not in subs:
            c.sink.error("RG1103", f"unknown subsystem '{t.subsystem}'", t.at("subsystem"),
                         did_you_mean(t.subsystem, subs) or f"subsystems: {', '.join(subs) or 'none'}")
        _qos(c, t)
        _types(c, t, msgs)
        if isinstance(t, PositionTelemetry):
            _position(c, t)
        elif isinstance(t, JointTelemetry):
            _joints(c, t)
        elif isinstance(t, AgentTelemetry):
            _values(c, t.values, "rapid::AgentConfig", "rapid::AgentState", "values")
        elif isinstance(t, ImageTelemetry):
            c.bound(t.sensor, t.at("sensor"), "sensor name", "rapid::ImageMetadata", "sensorName")
            if t.sensor_type:
                c.bound(t.sensor_type, t.at("sensor_type"), "sensor type", "rapid::ImageMetadata", "sensorType")
            c.bound(t.mime, t.at("mime"), "MIME type", "rapid::ImageSensorSample", "mimeType")
        elif isinstance(t, TextTelemetry):
            for i, cat in enumerate(t.categories):
                c.bound(cat, t.at("categories", i), "category", "rapid::TextMessage", "category")
    _topics(c)


def _qos(c: "Checker", t: Telemetry) -> None:
    roles = _ROLES.get(t.kind) or tuple(m.role for m in getattr(t, "messages", ()))
    for role, profile in t.qos:
        loc = t.at("qos", role)
        if role not in roles:
            c.sink.error("RG1308", f"{t.kind} telemetry publishes no {role} topic", loc,
                         f"its topics: {', '.join(roles)}")
        elif profile_name(profile) not in QOS_PROFILES:
            c.sink.error("RG1303", f"unknown QoS profile '{profile}'", loc,
                         did_you_mean(profile_name(profile), QOS_PROFILES)
                         or f"RapidQosLibrary has {', '.join(QOS_PROFILES)}")


def _types(c: "Checker", t: Telemetry, msgs) -> None:
    """Every published type must exist and derive from rapid::Message."""
    if c.facts.model is None:
        return
    for role, type_, topic, loc in msgs:
        if isinstance(t, CustomTelemetry):
            msg = next(m for m in t.messages if m.role == role)
            loc = msg.at("type")
            if "::" in msg.topic and c.facts.string_const(msg.topic) is None:
                c.sink.error("RG1312", f"'{msg.topic}' is not a string constant of the IDL", msg.at("topic"),
                             "give the topic name itself, or the scoped name of a 'const String64 ..._TOPIC'")
        struct = c.facts.struct(type_)
        if struct is None:
            decl = c.facts.model.get(type_)
            if decl is not None:
                article = "an" if decl.kind[0] in "aeiou" else "a"
                c.sink.error("RG1302", f"'{type_}' is {article} {decl.kind}, not a RAPID message", loc,
                             "telemetry types are valuetypes derived from rapid::Message")
                continue
            names = c.facts.struct_names()
            simple = [n for n in names if n.rsplit("::", 1)[-1] == type_.rsplit("::", 1)[-1]]
            hint = (f"did you mean '{simple[0]}'?" if simple else did_you_mean(type_, names)) or \
                ("declare it in an IDL file listed under idl.files")
            c.sink.error("RG1301", f"unknown type '{type_}'", loc, hint)
        elif not c.facts.is_message(type_):
            c.sink.error("RG1302", f"'{type_}' is not a RAPID message: it does not derive from rapid::Message",
                         loc, "declare it as 'valuetype X : rapid::Message' (or a struct with base Message)")


def _topics(c: "Checker") -> None:
    pubs = c.loaded.publications
    first: dict[str, Publication] = {}
    reported: set[int] = set()
    for p in pubs:
        if p.topic in first and id(p.source) not in reported:  # one error per entry
            reported.add(id(p.source))
            prev = first[p.topic]
            where = f"the entry at line {prev.loc.line}" if prev.source is not None else "the asset's subsystems"
            c.sink.error("RG1305", f"topic '{p.topic}' is published twice", p.loc,
                         f"also published by {where}; give one of them a 'suffix'")
        else:
            first.setdefault(p.topic, p)
        if p.source is not None:
            c.bound(p.topic, p.loc, "topic name", "rapid::AgentConfig", "topics")
    if any(isinstance(t, AgentTelemetry) for t in c.spec.telemetry):
        agent = next(t for t in c.spec.telemetry if isinstance(t, AgentTelemetry))
        n = c.facts.seq_bound("rapid::AgentConfig", "topics")
        if n is not None and len(pubs) > n:
            c.sink.error("RG1107", f"the asset publishes {len(pubs)} topics; AgentConfig.topics holds at most {n}",
                         agent.at("kind"), "publish fewer topics")


def _values(c: "Checker", values: tuple[ValueKey, ...], config: str, sample: str, member: str) -> None:
    c.duplicates(values, lambda v: v.name, "value key", "key")
    for bound_of in ((config, "valueKeys"), (sample, member)):
        if not c.count(values, lambda n: values[n].at("key"), "values", *bound_of,
                       hint="publish the rest in another entry with a suffix"):
            break
    for v in values:
        c.bound(v.name, v.at("key"), "value key", "rapid::KeyTypeValueTriple", "key")
        c.values.check(v, "value")


def _position(c: "Checker", t: PositionTelemetry) -> None:
    c.bound(t.frame, t.at("frame"), "frame name", "rapid::PositionConfig", "frameName")
    encodings = c.facts.enumerators("rapid::RotationEncoding")
    for field, enc in (("pose_encoding", t.pose_encoding), ("velocity_encoding", t.velocity_encoding)):
        if encodings is not None and enc not in encodings:
            c.sink.error("RG1201", f"unknown RotationEncoding '{enc}'", t.at(field),
                         did_you_mean(enc, encodings) or f"one of {', '.join(encodings)}")
    _values(c, t.values, "rapid::PositionConfig", "rapid::PositionSample", "values")


def _joints(c: "Checker", t: JointTelemetry) -> None:
    c.bound(t.group, t.at("group"), "joint group name", "rapid::JointConfig", "jointGroupName")
    joints = t.joints
    fields = c.facts.sequence_members("rapid::JointSample")
    for i, f in enumerate(t.fields):
        if fields is not None and f not in fields:
            c.sink.error("RG1311", f"JointSample has no per-joint field '{f}'", t.at("fields", i),
                         did_you_mean(f, fields) or f"fields: {', '.join(fields)}")
    # every JointSample sequence has one element per joint, like jointDefinitions
    for struct, member in [("rapid::JointConfig", "jointDefinitions")] + \
            [("rapid::JointSample", f) for f in t.fields if fields and f in fields]:
        if not c.count(joints, lambda n: joints[n].loc, "joints", struct, member,
                       hint="split them into joint groups with suffixes"):
            break
    c.duplicates(joints, lambda j: (j.frame, j.dof), "joint", "frame")
    for j in joints:
        c.bound(j.frame, j.at("frame"), "joint frame name", "rapid::JointDef", "frameName")
        c.bound(j.dof, j.at("dof"), "joint dof", "rapid::JointDef", "dof")
        if j.min is not None and j.max is not None and j.min > j.max:
            c.sink.error("RG1203", f"min {j.min} is greater than max {j.max} for joint '{j.frame}'",
                         j.at("min"), "swap them")
