"""Which QoS profile each topic uses: the map the generated runtimes read (topics.json).

With an asset: every topic it publishes (rapidgen.asset.topics, descriptor overrides
included) and the command topic it reads. Without one: every RAPID message type that
has a topic constant in its module (POSITION_SAMPLE_TOPIC <-> PositionSample), with
the library's per-type profile.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from rapidgen.diagnostics import UNKNOWN_LOC, SourceLoc
from rapidgen.model import ir
from rapidgen.model.ir import Model, Struct
from rapidgen.qos.spec import QosSpec

MESSAGE = "rapid::Message"


@dataclass(frozen=True, slots=True)
class TopicEntry:
    topic: str
    type: str  # scoped IDL name, as registered (a::B)
    profile: str
    role: str  # config | sample | state | ack | command | message
    direction: str  # publish | subscribe (for the asset); both (no asset)
    loc: SourceLoc = field(default=UNKNOWN_LOC, compare=False)  # what chose the profile


def _is_message(model: Model, struct: Struct) -> bool:
    """Derived from rapid::Message (a base, not the struct itself)."""
    return any(b.scoped_name == MESSAGE for b in model.lineage(struct)[:-1])


def _role(type_name: str) -> str:
    short = type_name.rsplit("::", 1)[-1]
    for suffix, role in (("Config", "config"), ("Sample", "sample"), ("State", "state")):
        if short.endswith(suffix):
            return role
    return {"Command": "command", "Ack": "ack"}.get(short, "message")


def from_model(model: Model, spec: QosSpec) -> list[TopicEntry]:
    structs = {}
    for d in model.declarations:
        if isinstance(d, Struct) and _is_message(model, d):
            module = d.scoped_name.rsplit("::", 1)[0] if "::" in d.scoped_name else ""
            structs[(module, d.name.upper())] = d
    out = []
    for d in model.declarations:
        if not isinstance(d, ir.Const) or not d.name.endswith("_TOPIC") or not isinstance(d.value, str):
            continue
        module = d.scoped_name.rsplit("::", 1)[0] if "::" in d.scoped_name else ""
        struct = structs.get((module, d.name[: -len("_TOPIC")].replace("_", "")))
        if struct is None:
            continue
        profile = spec.profile_for_type(struct.scoped_name)
        if profile is not None:
            out.append(TopicEntry(d.value, struct.scoped_name, profile, _role(struct.scoped_name), "both", d.loc))
    return sorted(out, key=lambda e: (e.topic, e.type))


def from_asset(asset, spec: QosSpec) -> list[TopicEntry]:
    from rapidgen.asset.topics import profile_name

    out = [TopicEntry(p.topic, p.type, profile_name(p.qos), p.role, "publish", p.loc)
           for p in asset.publications]
    if asset.command_topic is not None:  # an asset with subsystems reads commands
        command = "rapid::Command"
        out.append(TopicEntry(asset.command_topic, command, spec.profile_for_type(command) or "RapidReliableQos",
                              "command", "subscribe", asset.spec.loc))
    return sorted(set(out), key=lambda e: (e.topic, e.type, e.direction))
