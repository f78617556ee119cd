"""The seed asset a kind breaks: its tables, types and QoS, and its simulated bridge, built
but not started, so a kind can patch any of them before anything is written."""
from __future__ import annotations

import importlib

from rapid_runtime import bridge as B
from rapid_runtime import manager as manager_module
from rapid_runtime import messages as M
from rapid_runtime.dds import type_class, use_transport
from rapid_runtime.simulate import Simulator
from rapid_runtime.tables import Tables

PAIRED = ("agent", "position", "joint")


class PatchedQos:
    """The package's QoS with some topics' writer or reader QoS changed, and topics the
    package does not know answered with another topic's profile (alias)."""

    def __init__(self, base, writers=None, readers=None, alias=None) -> None:
        self.base, self.writers, self.readers, self.alias = base, writers or {}, readers or {}, alias or {}

    def writer(self, topic):
        q = self.base.writer(self.alias.get(topic, topic))
        return q + self.writers[topic] if topic in self.writers else q

    def reader(self, topic):
        q = self.base.reader(self.alias.get(topic, topic))
        return q + self.readers[topic] if topic in self.readers else q

    def __getattr__(self, name):
        return getattr(self.base, name)


class Asset:
    B, M, manager_module = B, M, manager_module

    def __init__(self, package: str, domain: int) -> None:
        self.rapid = importlib.import_module(f"{package}.rapid")
        self.package = package
        self.tables = Tables(importlib.import_module(f"{package}.asset_tables"))
        qos = importlib.import_module(f"{package}.qos").RapidQos()
        use_transport(qos, None)
        self.bridge = B.Bridge(self.tables, self.rapid, Simulator(self.tables, speed=20), qos, domain=domain)
        self.manager = self.bridge.manager
        self.quiet: set[str] = set()  # other-telemetry topics left silent (see start)
        self.keep: list = []  # DDS entities a kind made itself: alive as long as the bridge

    def patch_qos(self, writers=None, readers=None, alias=None) -> None:
        """Before start: the node creates every writer and reader from this QoS."""
        self.bridge.node.qos = PatchedQos(self.bridge.node.qos, writers, readers, alias)

    def entry(self, kind: str) -> dict:
        return next(t for t in self.tables.telemetry if t["kind"] == kind)

    def publication(self, topic: str) -> dict:
        return next(p for p in self.tables.publications if p["topic"] == topic)

    def writer(self, topic: str):
        """The bridge's writer of a declared topic (created now if it is not yet)."""
        return self.bridge.node.writer(topic, type_class(self.rapid, self.publication(topic)["type"]))

    def start(self) -> None:
        """Start the bridge. The simulator publishes every declared telemetry topic
        (docs/runtime.md, Simulation); a kind leaves a topic in `quiet`: its writer exists
        but nothing is ever written on it."""
        others = [p for p in self.tables.publications if p.get("rate") and p["role"] in ("sample", "state")
                  and (e := self._entry_of(p["topic"])) is not None and e["kind"] not in PAIRED]
        # Writers first, from this thread: the simulator's thread creates its own as it starts,
        # and cyclonedds' QosProvider called from two threads at once can answer one topic
        # with another's profile (seen: a position writer made TransientLocal).
        for p in others:
            self.writer(p["topic"])
        if self.quiet:
            node, real = self.bridge.node, self.bridge.node.writer

            def writer(topic, cls, keep_last=None):
                w = real(topic, cls, keep_last)
                return Silent(w) if topic in self.quiet else w
            node.writer = writer
        self.bridge.start()

    def _entry_of(self, topic: str) -> dict | None:
        return next((t for t in self.tables.telemetry if topic in t["topics"].values()), None)


class Silent:
    """A writer that exists (matched, discovered) and writes nothing."""

    def __init__(self, writer) -> None:
        self._writer = writer

    def write(self, sample) -> None:
        pass

    def __getattr__(self, name):
        return getattr(self._writer, name)
