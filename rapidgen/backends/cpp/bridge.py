"""The asset's bridge on the C++ runtime (runtime/cpp, issue 21): what an asset package
adds beside its types, under `bridge/`, built as the CMake target `<package>_bridge` when
find_package(rapid_runtime_cpp) succeeds.

    bridge/tables.cpp     the asset as rapid_runtime::Tables (one brace initializer per
                          part: subsystems, the command dictionary with units, ranges,
                          allowed values and defaults, the allow-list, telemetry entries)
    bridge/handlers.hpp   one abstract handler class per subsystem type, one pure virtual
                          method per command with named, typed parameters (units and
                          ranges in the doc comments); HandlerSet; the glue class Dispatch
    bridge/dispatch.cpp   the glue: ctx.arg<T>(i) unpacked into the typed calls
    bridge/main.cpp       main(): the configs (asset.hpp), extension telemetry for
                          --simulate, rapid_runtime::dds::run_bridge
    bridge/profiles.cpp   the asset's Fast DDS profiles, built in (the qos target's XML,
                          added by embed())
    bridge/handlers.cpp   the user's: written once (user_owned), stubs answering
                          EXEC_FAILED "not implemented"

Nothing here is protocol logic: the runtime holds it. Every descriptor string reaches the
files through cpp_str / cpp_comment, every name through a C++ Scope.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING

from rapidgen.asset.spec import (CustomTelemetry, ImageTelemetry, JointTelemetry, PositionTelemetry, TextTelemetry,
                                 TypedValue)
from rapidgen.backends.cpp import asset as asset_tables
from rapidgen.backends.cpp import namer, streams
from rapidgen.backends.escape import cpp_comment, cpp_str
from rapidgen.backends.naming import param_summary
from rapidgen.backends.plausible import plausible
from rapidgen.model import ir

if TYPE_CHECKING:
    from rapidgen.asset import LoadedAsset
    from rapidgen.backends.cpp.view import Builder

PROFILES_XML = "fastdds/rapid_qos_profiles.xml"  # in the qos target's output
DATA_TYPES = {  # RAPID DataType -> (rapid_runtime::DataType, handler parameter, ctx.arg<T>)
    "RAPID_BOOL": ("Bool", "bool", "bool"),
    "RAPID_DOUBLE": ("Double", "double", "double"),
    "RAPID_FLOAT": ("Float", "float", "float"),
    "RAPID_INT": ("Int", "::std::int32_t", "::std::int32_t"),
    "RAPID_LONGLONG": ("LongLong", "::std::int64_t", "::std::int64_t"),
    "RAPID_STRING": ("String", "const ::std::string&", "::std::string"),
    "RAPID_VEC3d": ("Vec3d", "const ::rapid_runtime::Vec3d&", "::rapid_runtime::Vec3d"),
    "RAPID_MAT33f": ("Mat33f", "const ::rapid_runtime::Mat33f&", "::rapid_runtime::Mat33f"),
}
# Standard commands the runtime answers itself (runtime/cpp/src/manager.cpp BUILTINS, less
# stopAllMotion: the runtime cancels motion, then the handler stops the hardware).
RUNTIME_BUILTINS = {("Admin", "echo"), ("Admin", "noOp"), ("Admin", "shutdown"), ("Queue", "cancelAll"),
                    ("AccessControl", "requestControl"), ("AccessControl", "grabControl"),
                    ("AccessControl", "releaseControl"), ("AccessControl", "transferControl")}
# Names the generated bridge declares in namespace <package>::bridge.
BRIDGE_NAMES = {"tables", "HandlerSet", "Dispatch", "make_handlers", "PROFILES_XML"}
CONTEXT = "ctx"  # every handler method's context parameter


@dataclass
class ParamView:
    name: str  # C++ parameter name
    ctype: str  # as the method takes it
    get: str  # ctx.arg<get>(i)
    doc: str  # one comment line


@dataclass
class MethodView:
    name: str
    command: str  # C++ literal of the command name
    params: list[ParamView]
    doc: list[str]  # comment lines


@dataclass
class HandlerView:
    type: str  # C++ literal of the subsystem type name
    title: str  # comment
    cls: str  # the abstract class
    impl: str  # the user's class in handlers.cpp
    member: str  # HandlerSet member
    methods: list[MethodView]


@dataclass
class CustomView:
    entry: int  # index in Tables::telemetry
    role: str  # literal
    type: str  # qualified C++ type
    topic: str  # literal
    qos: str  # literal
    config_topic: str  # literal ("" when the entry has no config)
    value: str  # C++ expression: a plausible message
    has_hdr: bool
    is_config: bool


@dataclass
class ConfigCall:
    topic: str
    function: str
    qos: str


@dataclass
class BridgeView:
    package: str
    ns: str  # <package>::bridge
    asset: str  # for comments
    tables: list[str]  # the body of the tables' build function, lines
    handlers: list[HandlerView]
    configs: list[ConfigCall]
    custom: list[CustomView]
    on_start: str  # HandlerSet hook names
    on_stop: str
    streams: streams.StreamsView | None = None  # setpoint streams (streams.py)


# ---- literals ---------------------------------------------------------------------------------

def text(value: str) -> str:
    """A std::string expression holding value exactly (a NUL inside keeps its length)."""
    return f"::std::string({cpp_str(value)}, {len(value.encode('utf-8'))}u)" if "\x00" in value else cpp_str(value)


def double(x: float | int) -> str:
    v = float(x)
    if math.isnan(v):
        return "::std::numeric_limits<double>::quiet_NaN()"
    if math.isinf(v):
        return f"{'-' if v < 0 else ''}::std::numeric_limits<double>::infinity()"
    return repr(v)


def optional(x: float | int | None) -> str:
    return "::std::nullopt" if x is None else double(x)


def value(dtype: str, v: object) -> str:
    """A rapid_runtime::Value of the DataType holding the descriptor's value."""
    if dtype == "RAPID_BOOL":
        return f"::rapid_runtime::Value({'true' if v else 'false'})"
    if dtype == "RAPID_DOUBLE":
        return f"::rapid_runtime::Value({double(float(v))})"  # type: ignore[arg-type]
    if dtype == "RAPID_FLOAT":
        return f"::rapid_runtime::Value(static_cast<float>({double(float(v))}))"  # type: ignore[arg-type]
    if dtype == "RAPID_INT":
        return f"::rapid_runtime::Value(::std::int32_t{{{int(v)}}})"  # type: ignore[call-overload]
    if dtype == "RAPID_LONGLONG":
        n = int(v)  # type: ignore[call-overload]
        lit = "-9223372036854775807LL - 1" if n == -2**63 else f"{n}LL"
        return f"::rapid_runtime::Value(::std::int64_t{{{lit}}})"
    if dtype == "RAPID_STRING":
        return f"::rapid_runtime::Value(::std::string({text(str(v))}))"
    if dtype == "RAPID_VEC3d":
        return "::rapid_runtime::Value(::rapid_runtime::Vec3d{" + ", ".join(double(float(x)) for x in v) + "})"  # type: ignore[attr-defined]
    if dtype == "RAPID_MAT33f":
        return ("::rapid_runtime::Value(::rapid_runtime::Mat33f{" +
                ", ".join(f"static_cast<float>({double(float(x))})" for x in v) + "})")  # type: ignore[attr-defined]
    raise ValueError(f"unknown DataType {dtype}")


def param_expr(p: TypedValue, pad: str) -> str:
    """A rapid_runtime::Param aggregate."""
    allowed = ", ".join(value(p.type, a) for a in p.allowed)
    default = value(p.type, p.default) if p.has_default else "::std::nullopt"
    return (f"{pad}::rapid_runtime::Param{{{text(p.name)}, ::rapid_runtime::DataType::{DATA_TYPES[p.type][0]}, "
            f"{text(p.unit or '')}, {optional(p.min)}, {optional(p.max)}, {{{allowed}}}, {default}, "
            f"{text(p.description or '')}}},")


def strings(items) -> str:
    return "{" + ", ".join(text(s) for s in items) + "}"


# ---- names ------------------------------------------------------------------------------------

def identifier(name: str, fallback: str = "x") -> str:
    """A C++ identifier from a descriptor name: letters, digits and underscores as they are,
    anything else '_', no leading or doubled underscore (reserved to the implementation),
    not starting with a digit."""
    s = re.sub(r"[^A-Za-z0-9_]", "_", name)
    s = re.sub(r"_+", "_", s).strip("_")
    if not s:
        return fallback
    return fallback + "_" + s if s[0].isdigit() else s


def snake(name: str) -> str:
    s = re.sub(r"([a-z0-9])([A-Z])", r"\1_\2", identifier(name))
    s = re.sub(r"([A-Z]+)([A-Z][a-z])", r"\1_\2", s)
    return re.sub(r"_+", "_", s).lower()


# ---- the view ---------------------------------------------------------------------------------

def build(loaded: "LoadedAsset", b: "Builder", package: str, assets: asset_tables.AssetView) -> BridgeView:
    """The bridge's view; `assets` is asset.hpp's (its config functions are called)."""
    ns = f"{package}::bridge"
    spec = loaded.spec
    qos_of = {p.topic: p.qos for p in loaded.publications}
    top = namer.Scope(f"namespace {ns}", namer.NAMESPACE_RESERVED | BRIDGE_NAMES)
    members = namer.Scope("HandlerSet", namer.RESERVED | {"HandlerSet"})
    on_start, on_stop = members.claim("on_start", "(on_start)"), members.claim("on_stop", "(on_stop)")
    subs_of: dict[str, list[str]] = {}
    for s in loaded.subsystems:
        subs_of.setdefault(s.type, []).append(s.name)

    handlers = []
    for t in loaded.used_types:
        cmds = [c for c in t.commands if not (t.standard and (t.name, c.name) in RUNTIME_BUILTINS)]
        if not cmds:
            continue
        cls = top.claim(identifier(t.name, "Type") + "Handler", f"handler class of {t.name}")
        impl = top.claim(identifier(t.name, "Type"), f"implementation of {t.name}")
        scope = namer.Scope(f"class {cls}", namer.RESERVED | BRIDGE_NAMES | {cls})
        methods = []
        for c in cmds:
            method = scope.claim(identifier(c.name, "command"), c.name)
            args = namer.Scope(f"{cls}::{method}", namer.RESERVED | {CONTEXT})
            params = []
            for p in c.parameters:
                name = args.claim(identifier(p.name, "arg"), p.name)
                params.append(ParamView(name, DATA_TYPES[p.type][1], DATA_TYPES[p.type][2], _param_doc(name, p)))
            doc = [f"{t.name}/{c.name}: {c.description or 'no description'}"]
            flags = [f for f in ("abortable", "suspendable") if getattr(c, f)]
            if flags:
                doc.append(f"{' and '.join(flags).capitalize()}: watch ctx.cancelled() (ctx.sleep() returns false).")
            if (t.name, c.name) == ("Mobility", "stopAllMotion") and t.standard:
                doc.append("The runtime has already canceled every Mobility command; stop the hardware here.")
            methods.append(MethodView(method, cpp_str(c.name), params, [cpp_comment(d) for d in doc]))
        title = f"Subsystem type {t.name}: {t.description or 'no description'} (subsystems: " \
                f"{', '.join(subs_of.get(t.name, []))})"
        handlers.append(HandlerView(cpp_str(t.name), cpp_comment(title), cls, impl,
                                    members.claim(snake(t.name) or "type", t.name), methods))

    config_fn = {c.topic: c.function for c in assets.configs}  # literal topic -> function
    configs = [ConfigCall(cpp_str(topic), config_fn[cpp_str(topic)], cpp_str(qos_of.get(topic, "RapidConfigQos")))
               for topic in loaded.configs]
    return BridgeView(package, ns, cpp_comment(spec.name), _tables(loaded, qos_of), handlers, configs,
                      _custom(loaded, b, qos_of), on_start, on_stop, streams.build(loaded, b, top, members))


def _param_doc(name: str, p: TypedValue) -> str:
    return cpp_comment(param_summary(name, p))


def _tables(loaded: "LoadedAsset", qos_of: dict[str, str]) -> list[str]:
    spec = loaded.spec
    out = [f"t.name = {text(spec.name)};", f"t.kind = {text(spec.kind)};", f"t.domain = {int(spec.domain)};",
           f"t.partition = {text(spec.partition or spec.name)};"]
    out.append("t.subsystems = {")
    out += [f"    {{{text(s.name)}, {text(s.type)}}}," for s in loaded.subsystems]
    out.append("};")
    out.append("t.types = {")
    for t in loaded.used_types:
        out.append(f"    {{{text(t.name)}, {{")
        for c in t.commands:
            out.append(f"        {{{text(c.name)}, {{")
            out += [param_expr(p, " " * 12) for p in c.parameters]
            # stop_timeout_ms only when declared (0, the member's default: the bridge's --stop-timeout)
            bound = "" if c.stop_timeout_ms is None else f", /* stop_timeout_ms */ {int(c.stop_timeout_ms)}"
            out.append(f"        }}, {_bool(c.abortable)}, {_bool(c.suspendable)}, {_bool(t.standard)}, "
                       f"{text(c.description or '')}{bound}}},")
        out.append("    }},")
    out.append("};")
    acc = spec.access_control
    if acc is not None:
        out.append(f"t.access = ::rapid_runtime::AccessSpec{{{_bool(acc.default == 'allow')}, {{")
        out += [f"    {{{text(r.source)}, {strings(r.allow)}}}," for r in acc.rules]
        out.append("}};")
    out.append("t.telemetry = {")
    for entry, topics in zip(spec.telemetry, loaded.telemetry_topics):
        out += _telemetry(entry, topics, qos_of)
    out.append("};")
    return out


def _bool(x: bool) -> str:
    return "true" if x else "false"


def _telemetry(t, topics: dict[str, str], qos_of: dict[str, str]) -> list[str]:
    pad = " " * 8
    tops = ", ".join(f"{{{text(role)}, {text(topic)}, {text(qos_of.get(topic, ''))}}}" for role, topic in topics.items())
    rate = "::std::nullopt" if t.rate is None else double(t.rate)
    lines = ["    ::rapid_runtime::TelemetrySpec{", f"{pad}{text(t.kind)},", f"{pad}{{{tops}}},", f"{pad}{rate},",
             f"{pad}{text(t.subsystem or '')},"]
    values = getattr(t, "values", ())
    lines.append(f"{pad}{{" if values else f"{pad}{{}},")
    if values:
        lines += [param_expr(v, pad + "    ") for v in values]
        lines.append(f"{pad}}},")
    pos = t if isinstance(t, PositionTelemetry) else None
    lines.append(f"{pad}{text(pos.frame if pos else '')}, {text(pos.pose_encoding if pos else '')}, "
                 f"{text(pos.velocity_encoding if pos else '')},")
    j = t if isinstance(t, JointTelemetry) else None
    joints = ", ".join(f"{{{text(x.frame)}, {text(x.dof)}, {text(x.unit or '')}, {optional(x.min)}, {optional(x.max)}}}"
                       for x in (j.joints if j else ()))
    lines.append(f"{pad}{text(j.group if j else '')}, {strings(j.fields if j else ())}, {{{joints}}},")
    im = t if isinstance(t, ImageTelemetry) else None
    lines.append(f"{pad}{text(im.sensor if im else '')}, {text(im.sensor_type if im else '')}, "
                 f"{text(im.mime if im else '')}, {int(im.width or 0) if im else 0}, {int(im.height or 0) if im else 0},")
    tx = t if isinstance(t, TextTelemetry) else None
    lines.append(f"{pad}{strings(tx.categories if tx else ())},")
    types = ", ".join(f"{{{text(m.role)}, {text(m.type)}}}" for m in t.messages) if isinstance(t, CustomTelemetry) \
        else ""
    # stale_after_ms only when declared (0, the member's default: derived from the rate, freshness.hpp)
    bound = "" if t.stale_after_ms is None else f", /* stale_after_ms */ {double(t.stale_after_ms)}"
    lines.append(f"{pad}{{{types}}}{bound}}},")
    return lines


# ---- extension telemetry: plausible messages of the asset's own types ---------------------------

def _custom(loaded: "LoadedAsset", b: "Builder", qos_of: dict[str, str]) -> list[CustomView]:
    out = []
    for i, (t, topics, msgs) in enumerate(zip(loaded.spec.telemetry, loaded.telemetry_topics,
                                              loaded.telemetry_messages)):
        if not isinstance(t, CustomTelemetry):
            continue
        config = topics.get("config", "")
        for role, type_name, _base, _loc in msgs:
            topic = topics[role]
            if role == "config" and topic in loaded.configs:
                continue  # computed: published with the others
            d = b.model.get(type_name)
            if not isinstance(d, ir.Struct):
                continue
            names = b._member_names(d)
            has_hdr = names.get("hdr") == "hdr" and any(m.name == "hdr" for m in b.model.all_members(d))
            plain = plausible(b, d, loaded.spec.name, 0)
            expr = asset_tables.value_expr(b, ir.TypeRef(type_name, "struct"), plain, 3)
            out.append(CustomView(i, cpp_str(role), b.qualified(type_name), cpp_str(topic),
                                  cpp_str(qos_of.get(topic, "RapidConfigQos" if role == "config" else "RapidSampleQos")),
                                  cpp_str(config), expr, has_hdr, role == "config"))
    return out
