"""The asset's bridge on the Rust runtime (runtime/rust, issue 38): a Cargo crate
`<crate>_bridge` under `bridge/`, beside the types crate it depends on.

    bridge/Cargo.toml          the binary `<crate>_bridge`; the types crate (`..`), rapid_runtime
                               and rapid_dds by path (runtime/rust of this repository: see
                               RUNTIME and docs/rust-backend.md)
    bridge/tables.json         the asset's tables (tables.py), embedded by main.rs
    bridge/src/dispatch.rs     one trait per subsystem type, one method per command with named,
                               typed parameters (units and ranges in the doc comments);
                               HandlerSet; the glue unpacking ctx.args() into the typed calls
    bridge/src/main.rs         main(): the configs (asset::configs), QoS, transports and
                               extension telemetry for --simulate (asset::simulated),
                               rapid_dds::bridge::run
    bridge/src/cmd.rs          main() of `<crate>_cmd`, the ground-side program (rapid_dds::cmd on
                               the same tables and transports)
    bridge/src/transports.rs   the qos target's Cyclone DDS XML per transport (added by embed())
    bridge/src/handlers.rs     the user's: written once (user_owned), stubs answering
                               EXEC_FAILED "not implemented"

Nothing here is protocol logic: the runtime holds it. Every descriptor string reaches the
files through rust_str / rust_comment, every name through a Rust Scope.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from rapidgen.asset.spec import TypedValue
from rapidgen.backends.escape import rust_comment, rust_str
from rapidgen.backends.naming import param_summary
from rapidgen.backends.rust import namer, streams

if TYPE_CHECKING:
    from rapidgen.asset import LoadedAsset

BRIDGE = "bridge"
# runtime/rust of this repository, from <out>/rust/bridge when <out> is generated/<seed>
# (the committed bridges); a bridge generated elsewhere points these at its checkout.
RUNTIME = "../../../../runtime/rust"
TRANSPORTS = ("local", "lan", "wan")  # the qos target's cyclonedds/<transport>.xml
TRANSPORT_MARK = '""; // rapidgen embeds cyclonedds/{}.xml here'  # transports.rs.j2, filled by embed()
DATA_TYPES = {  # RAPID DataType -> (the method's parameter type, the Value variant)
    "RAPID_BOOL": ("bool", "Bool"),
    "RAPID_DOUBLE": ("f64", "Double"),
    "RAPID_FLOAT": ("f32", "Float"),
    "RAPID_INT": ("i32", "Int"),
    "RAPID_LONGLONG": ("i64", "LongLong"),
    "RAPID_STRING": ("&str", "String"),
    "RAPID_VEC3d": ("[f64; 3]", "Vec3d"),
    "RAPID_MAT33f": ("[f32; 9]", "Mat33f"),
}
# Standard commands the runtime answers itself (rapid_runtime's manager), less stopAllMotion:
# the runtime cancels motion, then the handler stops the hardware (as the C++ bridge's).
RUNTIME_BUILTINS = {("Admin", "echo"), ("Admin", "noOp"), ("Admin", "shutdown"), ("Queue", "cancelAll"),
                    ("AccessControl", "requestControl"), ("AccessControl", "grabControl"),
                    ("AccessControl", "releaseControl"), ("AccessControl", "transferControl")}
CONTEXT = "ctx"  # every handler method's context parameter
BRIDGE_NAMES = {"HandlerSet", "make_handlers", "Context", "Outcome", "Value", "Handlers"}


@dataclass
class ParamView:
    name: str  # Rust parameter name
    rtype: str  # as the method takes it
    variant: str  # rapid_runtime::Value::<variant>
    by_ref: bool  # a String: passed as &str
    doc: str


@dataclass
class MethodView:
    name: str
    command: str  # Rust literal of the command name
    params: list[ParamView]
    doc: list[str]


@dataclass
class HandlerView:
    type: str  # Rust literal of the subsystem type name
    title: str  # comment
    trait: str
    impl: str  # the user's struct in handlers.rs
    member: str  # HandlerSet field
    methods: list[MethodView]


@dataclass
class ConfigView:
    topic: str  # literal
    type_name: str  # literal
    function: str  # asset::<function>


@dataclass
class BridgeView:
    crate: str  # the types crate
    bridge: str  # this crate (and binary)
    cmd: str  # the ground-side binary
    asset: str  # for comments
    runtime_path: str  # runtime/rust, relative to the bridge's folder
    handlers: list[HandlerView]
    configs: list[ConfigView]
    transports: list[tuple[str, str, str]]  # (name, its literal, const name)
    streams: "streams.StreamsView | None" = None  # the setpoint streams (streams.py)


def _snake(name: str, fallback: str) -> str:
    """A snake_case Rust name from a descriptor name; one that would start with a digit gets
    `fallback_` before it (`9lives` -> `arg_9lives`, as the C++ bridge's)."""
    s = namer.snake(name)
    return s if s[:1].isalpha() else f"{fallback}_{s}"


def _camel(name: str, fallback: str) -> str:
    s = namer.camel(name)
    return s if s[:1].isalpha() else fallback + s


def _param_doc(name: str, p: TypedValue) -> str:
    return rust_comment(param_summary(name, p, quote="`"))


def build(loaded: "LoadedAsset", crate: str, configs: list, stream_types: dict[str, str] | None = None) -> BridgeView:
    """The bridge's view; `configs` are asset.rs's ConfigViews (their functions are called);
    `stream_types`: the streams' types' paths (asset.py's AssetView.stream_types)."""
    glue = streams.GLUE if loaded.streams else set()
    top = namer.Scope("crate root of the bridge", namer.KEYWORDS | BRIDGE_NAMES | glue | {"dispatch", "handlers",
                                                                                          "transports", "main"})
    members = namer.Scope("HandlerSet", namer.KEYWORDS)
    subs_of: dict[str, list[str]] = {}
    for s in loaded.subsystems:
        subs_of.setdefault(s.type, []).append(s.name)
    handlers = []
    for t in loaded.used_types:
        cmds = [c for c in t.commands if not (t.standard and (t.name, c.name) in RUNTIME_BUILTINS)]
        if not cmds:
            continue
        trait = top.claim(_camel(t.name, "Type") + "Handler", f"handler trait of {t.name}")
        impl = top.claim(_camel(t.name, "Type"), f"implementation of {t.name}")
        scope = namer.Scope(f"trait {trait}", namer.KEYWORDS)
        methods = []
        for c in cmds:
            method = scope.claim(_snake(c.name, "command"), c.name)
            args = namer.Scope(f"{trait}::{method}", namer.KEYWORDS | {CONTEXT})
            params = []
            for p in c.parameters:
                name = args.claim(_snake(p.name, "arg"), p.name)
                rtype, variant = DATA_TYPES[p.type]
                params.append(ParamView(name, rtype, variant, p.type == "RAPID_STRING", _param_doc(name, p)))
            doc = [f"{t.name}/{c.name}: {c.description or 'no description'}"]
            flags = [f for f in ("abortable", "suspendable") if getattr(c, f)]
            if flags:
                doc.append(f"{' and '.join(flags).capitalize()}: watch ctx.cancelled() (ctx.sleep() returns false).")
            if (t.name, c.name) == ("Mobility", "stopAllMotion") and t.standard:
                doc.append("The runtime has already canceled every Mobility command; stop the hardware here.")
            methods.append(MethodView(method, rust_str(c.name), params, [rust_comment(d) for d in doc]))
        title = f"Subsystem type {t.name}: {t.description or 'no description'} (subsystems: " \
                f"{', '.join(subs_of.get(t.name, []))})"
        handlers.append(HandlerView(rust_str(t.name), rust_comment(title), trait, impl,
                                    members.claim(_snake(t.name, "type"), t.name), methods))
    function = {c.topic: c.function for c in configs}  # literal topic -> function
    config_views = [ConfigView(rust_str(topic), rust_str(type_name), function[rust_str(topic)])
                    for topic, (type_name, _value) in loaded.configs.items()]
    consts = namer.Scope("transports", namer.KEYWORDS)
    return BridgeView(crate, crate + "_bridge", crate + "_cmd", rust_comment(loaded.spec.name), RUNTIME, handlers,
                      config_views,
                      [(t, rust_str(t), consts.claim(namer.upper(t), t)) for t in TRANSPORTS],
                      streams.build(loaded, crate, stream_types or {}, top))
