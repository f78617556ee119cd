"""Broken assets: QoS, partitions, type names and layouts, writers (conformance/dds.py).
The text topic (no rate: no telemetry check reads it) carries the type and ownership faults."""
# (no `from __future__ import annotations`: cyclonedds resolves the member types below at run time)
from dataclasses import dataclass, field
from importlib import import_module

from . import kind


def _text_topic(a) -> str:
    return a.entry("text")["topics"]["sample"]


@kind("sample-qos", "DDS-01")
def sample_qos(a):
    """Reliable where the profile says best effort: compatible, but not the profile."""
    from cyclonedds.qos import Policy, Qos
    topic = next(p["topic"] for p in a.tables.publications if p["qos"] == "RapidSampleQos" and p.get("rate"))
    a.patch_qos({topic: Qos(Policy.Reliability.Reliable(100_000_000))})


@kind("command-reader-qos", "DDS-02")
def command_reader_qos(a):
    """Keeps only the last 64 unread commands: a burst past 64 is dropped (commands cannot
    be: KeepAll). Deep enough that the run's own bursts (3 appended at once) are never
    dropped, so no other check sees it (a depth of 2 once made QUE-02 fail too). Not
    KeepLast(1): discovery shows an unannounced history as KeepLast(1), see DDS-02."""
    from cyclonedds.qos import Policy, Qos
    a.patch_qos(readers={"rapid_command": Qos(Policy.History.KeepLast(64))})


@kind("exclusive-ownership", "DDS-03")
def exclusive_ownership(a):
    """A text writer with EXCLUSIVE ownership (set for fail-over between redundant computers):
    every RAPID reader asks for SHARED, so none of them matches it."""
    from cyclonedds.qos import Policy, Qos
    topic = _text_topic(a)
    a.patch_qos({topic: Qos(Policy.Ownership.Exclusive)})
    a.writer(topic).write(a.rapid.TextMessage(hdr=_hdr(a), message="bridge up"))


def _hdr(a):
    return a.M.header(a.rapid, a.tables.name, a.tables.name, a.bridge.serials.start)


def _text_class(a, typename: str, old_layout: bool = False):
    """rapid::TextMessage's layout under another type name, or under its own name with the
    level member an int32 (an older IDL revision): final types, so that one matches nothing."""
    import cyclonedds.idl as idl
    import cyclonedds.idl.annotations as annotate
    import cyclonedds.idl.types as types
    base = import_module(f"{a.package}._idl.BaseTypes")
    String64, String2K, Header, Level = base.String64, base.String2K, a.rapid.Header, a.rapid.MessageLevel

    if old_layout:
        @dataclass
        @annotate.final
        class OldText(idl.IdlStruct, typename=typename):
            hdr: Header = field(default_factory=Header)
            annotate.key("hdr")
            level: types.int32 = 1
            category: String64 = ""
            message: String2K = ""
        return OldText

    @dataclass
    @annotate.final
    class Text(idl.IdlStruct, typename=typename):
        hdr: Header = field(default_factory=Header)
        annotate.key("hdr")
        level: Level = Level.MSG_INFO
        category: String64 = ""
        message: String2K = ""
    return Text


@kind("wrong-type-name", "DDS-04")
def wrong_type_name(a):
    """TextMessage registered as rapid_TextMessage (an IDL compiler's C-style name); the
    layout is RAPID's, so Cyclone still matches it."""
    topic, cls = _text_topic(a), _text_class(a, "rapid_TextMessage")
    a.bridge.node.writer(topic, cls).write(cls(hdr=_hdr(a), message="bridge up"))


@kind("wrong-partition", "DDS-05")
def wrong_partition(a):
    """One more agent-state writer, in the default partition."""
    from cyclonedds.pub import DataWriter, Publisher
    node = a.bridge.node
    stray = DataWriter(Publisher(node.participant), node.topic("rapid_agent_state", a.rapid.AgentState),
                       qos=node.qos.writer("rapid_agent_state"))
    stray.write(a.rapid.AgentState(hdr=_hdr(a)))
    a.keep.append(stray)


@kind("no-queue-state-writer", "DDS-06")
def no_queue_state_writer(a):
    """A queue, but no QueueState writer at all (QUE-01, QUE-05 are then BLOCKED)."""
    a.bridge.queue_state = lambda code, *lists: None


@kind("old-type-layout", "DDS-07")
def old_type_layout(a):
    """TextMessage under its RAPID name with an older layout (level an int32): right name,
    so DDS-04 passes; no RAPID reader matches it."""
    topic, cls = _text_topic(a), _text_class(a, "rapid.TextMessage", old_layout=True)
    a.bridge.node.writer(topic, cls).write(cls(hdr=_hdr(a), message="bridge up"))
