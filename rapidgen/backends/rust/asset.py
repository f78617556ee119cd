"""The asset as Rust data (src/asset.rs): name, domain, partition, subsystems, the topics
it publishes, the command dictionary, and the computed configs as values of the generated
types. Literals only; every string goes through rust_str."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from rapidgen.asset.spec import CustomTelemetry
from rapidgen.backends.escape import rust_str
from rapidgen.backends.rust import namer
from rapidgen.backends.plausible import plausible
from rapidgen.backends.rust.typemap import float_literal
from rapidgen.model import ir

if TYPE_CHECKING:
    from rapidgen.asset import LoadedAsset
    from rapidgen.qos.spec import Policies, QosSpec
    from rapidgen.backends.rust.view import Builder


@dataclass
class ParameterView:
    name: str
    data_type: str
    unit: str
    min: str
    max: str


@dataclass
class CommandView:
    subsystem_type: str
    name: str
    abortable: bool
    suspendable: bool
    parameters: list[ParameterView]


@dataclass
class ConfigView:
    function: str
    type: str
    topic: str
    type_name: str
    value: str


@dataclass
class CustomView:
    topic: str  # literal
    type: str  # the type's path
    value: str  # a Rust expression of the type (header default)


@dataclass
class QosView:
    name: str
    writer: str  # a crate::asset::QosSide literal
    reader: str


@dataclass
class AssetView:
    name: str
    domain: int
    partition: str
    subsystems: list[tuple[str, str]]
    topics: list[tuple[str, str, str, str, str]]  # role, type, topic, qos profile, rate
    commands: list[CommandView]
    configs: list[ConfigView]
    profiles: list[QosView]  # the QoS library's profiles the topics name (none without a library)
    simulated: list[CustomView]  # extension telemetry a simulated robot publishes
    # scoped IDL name -> the type's path (crate::rapid::PositionSample), of the streams' types
    stream_types: dict[str, str] = field(default_factory=dict)


def _opt_str(text: str | None) -> str:
    return "None" if text is None else f"Some({rust_str(text)})"


def _opt_f64(x: float | int | None) -> str:
    return "None" if x is None else f"Some({float_literal(float(x), 'f64')})"


def _side(policies: "Policies") -> str:
    h = policies.history
    history = "QosHistory::KeepAll" if h is not None and h.kind == "keep_all" else \
        f"QosHistory::KeepLast({h.depth if h is not None and h.depth else 1})"
    return (f"QosSide {{ reliable: {'true' if policies.reliability == 'reliable' else 'false'}, "
            f"transient_local: {'true' if policies.durability == 'transient_local' else 'false'}, "
            f"history: {history} }}")


def _profiles(names: list[str], library: "QosSpec | None") -> list[QosView]:
    """Each named profile resolved for writers and readers (QosSpec.effective, as the qos
    target writes them); a name the library lacks is left out (the qos target reports it)."""
    if library is None:
        return []
    out = []
    for name in dict.fromkeys(names):
        if library.has_profile(name):
            writer, reader = library.effective(name)
            out.append(QosView(rust_str(name), _side(writer), _side(reader)))
    return out


def build(loaded: "LoadedAsset", b: "Builder", library: "QosSpec | None" = None) -> AssetView:
    spec = loaded.spec
    commands = [CommandView(rust_str(t.name), rust_str(c.name), c.abortable, c.suspendable,
                            [ParameterView(rust_str(p.name), rust_str(p.type), _opt_str(p.unit), _opt_f64(p.min),
                                           _opt_f64(p.max)) for p in c.parameters])
                for t in loaded.used_types for c in t.commands]
    pubs = loaded.publications
    topics = [(rust_str(p.role), rust_str(p.type), rust_str(p.topic), rust_str(p.qos), _opt_f64(p.rate))
              for p in pubs]
    scope = namer.Scope("asset", {"NAME", "DOMAIN", "PARTITION", "SUBSYSTEMS", "TOPICS", "COMMANDS", "Topic",
                                  "Command", "Parameter", "QosSide", "QosHistory", "QosProfile",
                                  "QOS_PROFILES", "qos_profile", "topic_qos", "configs", "simulated"})
    views = []
    for topic, (type_name, value) in loaded.configs.items():
        t = ir.TypeRef(type_name, "struct")
        views.append(ConfigView(scope.claim("config_" + namer.snake(topic), topic), b.path(type_name),
                                rust_str(topic), rust_str(type_name), b.value(t, value)))
    return AssetView(rust_str(spec.name), spec.domain, rust_str(spec.partition),
                     [(rust_str(s.name), rust_str(s.type)) for s in loaded.subsystems], topics, commands, views,
                     _profiles([p.qos for p in pubs], library), _simulated(loaded, b),
                     {s.type: b.path(s.type) for s in loaded.streams})


def _simulated(loaded: "LoadedAsset", b: "Builder") -> list[CustomView]:
    """Extension telemetry's messages with plausible values of the asset's own types
    (plausible.py); a config the tables compute is among configs()."""
    out = []
    for t, topics, msgs in zip(loaded.spec.telemetry, loaded.telemetry_topics, loaded.telemetry_messages):
        if not isinstance(t, CustomTelemetry):
            continue
        for role, type_name, _base, _loc in msgs:
            topic = topics[role]
            if role == "config" and topic in loaded.configs:
                continue
            d = b.model.get(type_name)
            if not isinstance(d, ir.Struct):
                continue
            value = b.value(ir.TypeRef(type_name, "struct"), plausible(b, d, loaded.spec.name, 0))
            out.append(CustomView(rust_str(topic), b.path(type_name), value))
    return out
