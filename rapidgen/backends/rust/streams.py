"""The bridge's setpoint streams (LoadedAsset.streams) for the Rust templates: the typed
method of each input stream (trait Streams in dispatch.rs, default bodies: a handlers.rs
written before the stream existed still compiles), the `<name>_sample()` / `send_<name>()`
functions of each output stream, and the rapid_runtime::stream::StreamSpec constants the
glue hands rapid_dds. Names go through Rust Scopes, descriptor text through rust_str /
rust_comment.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from rapidgen.backends.escape import rust_comment, rust_str
from rapidgen.backends.rust import namer

if TYPE_CHECKING:
    from rapidgen.asset import LoadedAsset

_ACTIONS = {"stop": "Stop", "hold": "Hold", "none": "None"}
TRAIT = "Streams"  # the input streams' callbacks (dispatch.rs)
IMPL = "SetpointStreams"  # the user's, in handlers.rs
DISPATCH = "Dispatch"  # HandlerSet with the streams (make_handlers() may return either)
STATE_HOOK = "on_state"
VALUES_HOOK = "agent_values"
# the glue's own items in dispatch.rs
GLUE = {TRAIT, IMPL, DISPATCH, "STREAMS", "decode", "encode", "finite_position", "finite_joint", "finite_any",
        "header_of", "stream_glue"}
# setpoint kinds: how the finite check and the simulated robot read a sample
KINDS = {"rapid::PositionSample": "position", "rapid::JointSample": "joint"}


@dataclass
class StreamView:
    index: int
    input: bool
    name: str  # literal (the descriptor's)
    method: str  # input: the trait method
    static: str  # output: the OutputStream static
    sample_fn: str  # output: <name>_sample()
    send_fn: str  # output: send_<name>()
    type: str  # the sample's Rust path
    kind: str  # position | joint | other
    period: str  # s, a Rust f64 literal
    spec: str  # a StreamSpec literal
    doc: list[str]


@dataclass
class StreamsView:
    trait: str
    impl: str
    dispatch: str
    state_hook: str
    values_hook: str
    rapid: str  # the crate's rapid module path (ParameterUnion of the finite check)
    streams: list[StreamView]

    @property
    def inputs(self) -> list[StreamView]:
        return [s for s in self.streams if s.input]

    @property
    def outputs(self) -> list[StreamView]:
        return [s for s in self.streams if not s.input]

    def kinds(self, *, inputs: bool) -> set[str]:
        return {s.kind for s in self.streams if s.input == inputs}


def _f64(x: float) -> str:
    r = repr(float(x))
    return r if ("." in r or "e" in r or "inf" in r or "nan" in r) else r + ".0"


def build(loaded: "LoadedAsset", crate: str, types: dict[str, str], top: namer.Scope) -> StreamsView | None:
    """`types`: scoped IDL name -> its path in the types crate (crate::rapid::X); `top`: the
    bridge's crate-root scope (GLUE reserved in it; the output functions are claimed there)."""
    if not loaded.streams:
        return None
    methods = namer.Scope(f"trait {TRAIT}", namer.KEYWORDS | {STATE_HOOK, VALUES_HOOK})
    out = []
    for i, s in enumerate(loaded.streams):
        ident = namer.snake(s.name)
        ident = ident if ident[:1].isalpha() else f"stream_{ident}"
        rtype = crate + types[s.type][len("crate"):]
        inp = s.direction == "input"
        spec = (f"StreamSpec {{ name: {rust_str(s.name)}, input: {'true' if inp else 'false'}, "
                f"type_name: {rust_str(s.type)}, topic: {rust_str(s.topic)}, partition: {rust_str(s.partition)}, "
                f"rate_hz: {_f64(s.rate)}, deadline_ms: {_f64(s.deadline_ms)}, liveliness_ms: {_f64(s.liveliness_ms)}, "
                f"on_loss: LossAction::{_ACTIONS[s.on_loss]}, subsystem: {rust_str(s.subsystem or '')}, "
                f"state_key: {rust_str(s.state_key or '')}, missed_key: {rust_str(s.missed_key or '')} }}")
        where = f" from {s.partition}" if inp else ""
        doc = [f"{s.name}: {s.type} on '{s.topic}'{where}, {s.rate:g} Hz, deadline {s.deadline_ms:g} ms, "
               f"lease {s.liveliness_ms:g} ms" + (f", on loss: {s.on_loss}" if inp else "")]
        if s.subsystem:
            doc.append(f"Drives subsystem {s.subsystem}.")
        if s.description:
            doc.append(s.description)
        kind = KINDS.get(s.type, "other")
        view = StreamView(i, inp, rust_str(s.name), "", "", "", "", rtype, kind, _f64(1.0 / s.rate), spec,
                          [rust_comment(d) for d in doc])
        if inp:
            view.method = methods.claim(ident, s.name)
        else:
            view.static = top.claim(namer.upper(s.name) + "_STREAM", f"output stream {s.name}")
            view.sample_fn = top.claim(f"{ident}_sample", f"output stream {s.name}")
            view.send_fn = top.claim(f"send_{ident}", f"output stream {s.name}")
        out.append(view)
    return StreamsView(TRAIT, IMPL, DISPATCH, STATE_HOOK, VALUES_HOOK, f"{crate}::rapid", out)
