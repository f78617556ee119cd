"""The bridge's setpoint streams (LoadedAsset.streams) for the C++ templates: the typed
callback of each input stream (class Streams in handlers.hpp), the free functions of each
output stream, and the rapid_runtime::StreamSpec the glue hands the runtime. Names go
through C++ Scopes, descriptor text through cpp_str / cpp_comment.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from rapidgen.backends.cpp import namer
from rapidgen.backends.escape import cpp_comment, cpp_str

if TYPE_CHECKING:
    from rapidgen.asset import LoadedAsset
    from rapidgen.backends.cpp.view import Builder

_ACTIONS = {"stop": "Stop", "hold": "Hold", "none": "None"}
STREAMS_CLASS = "Streams"
STATE_HOOK = "on_state"


@dataclass
class StreamView:
    index: int
    input: bool
    method: str  # input: the virtual method of class Streams
    sample_fn: str  # output: <name>_sample()
    send_fn: str  # output: send_<name>()
    type: str  # qualified C++ type of a sample
    spec: str  # C++ expression: the rapid_runtime::StreamSpec
    doc: list[str]  # comment lines


@dataclass
class StreamsView:
    cls: str  # the abstract class (input callbacks)
    impl: str  # the user's class in handlers.cpp
    member: str  # HandlerSet member holding it
    values: str  # HandlerSet member: the asset's own agent values
    state_hook: str
    simulate: str  # the glue's function: the streams on the simulated robot
    streams: list[StreamView]

    @property
    def inputs(self) -> list[StreamView]:
        return [s for s in self.streams if s.input]

    @property
    def outputs(self) -> list[StreamView]:
        return [s for s in self.streams if not s.input]


def _ms(x: float) -> str:
    return repr(float(x))


def build(loaded: "LoadedAsset", b: "Builder", top: namer.Scope, members: namer.Scope) -> StreamsView | None:
    if not loaded.streams:
        return None
    cls = top.claim(STREAMS_CLASS, "the setpoint streams' callbacks")
    impl = top.claim("SetpointStreams", "the user's stream callbacks")
    scope = namer.Scope(f"class {cls}", namer.RESERVED | {cls, STATE_HOOK})
    out = []
    for i, s in enumerate(loaded.streams):
        ident = s.name  # the schema allows identifiers only
        spec = (f"::rapid_runtime::StreamSpec{{{cpp_str(s.name)}, {'true' if s.direction == 'input' else 'false'}, "
                f"{cpp_str(s.type)}, {cpp_str(s.topic)}, {cpp_str(s.partition)}, {cpp_str(s.profile)}, "
                f"{_ms(s.rate)}, {_ms(s.deadline_ms)}, {_ms(s.liveliness_ms)}, "
                f"::rapid_runtime::LossAction::{_ACTIONS[s.on_loss]}, {cpp_str(s.subsystem or '')}, "
                f"{cpp_str(s.state_key or '')}, {cpp_str(s.missed_key or '')}}}")
        where = f" from {s.partition}" if s.direction == "input" else ""
        doc = [f"{s.name}: {s.type} on '{s.topic}'{where}, {s.rate:g} Hz, deadline {s.deadline_ms:g} ms, "
               f"lease {s.liveliness_ms:g} ms" + (f", on loss: {s.on_loss}" if s.direction == "input" else "")]
        if s.subsystem:
            doc.append(f"Drives subsystem {s.subsystem}.")
        if s.description:
            doc.append(s.description)
        if s.direction == "input":
            method = scope.claim(ident, s.name)
            out.append(StreamView(i, True, method, "", "", b.qualified(s.type), spec, [cpp_comment(d) for d in doc]))
        else:
            sample_fn = top.claim(f"{ident}_sample", f"output stream {s.name}")
            send_fn = top.claim(f"send_{ident}", f"output stream {s.name}")
            out.append(StreamView(i, False, "", sample_fn, send_fn, b.qualified(s.type), spec,
                                  [cpp_comment(d) for d in doc]))
    return StreamsView(cls, impl, members.claim("streams", "(streams)"), members.claim("agent_values", "(agent values)"),
                       STATE_HOOK, top.claim("simulated_streams", "the streams under --simulate"), out)
