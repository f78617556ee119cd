"""Deliberately broken assets for the conformance tests: a seed asset's simulated bridge
with one protocol rule broken by patching the runtime in this process only.

    python -m tests.conformance.broken KIND GENERATED_PYTHON_DIR PACKAGE DOMAIN

Prints "bridge ready" like the real bridge. KINDS maps each kind to the check it aims at
(None: a variant the suite must accept, e.g. Astrobee's ack habits)."""
from __future__ import annotations

import collections
import dataclasses
import importlib
import math
import os
import sys
import time

KINDS = {
    "volatile-config": "CFG-02",
    "wrong-config": "CFG-03",
    "zero-serial": "CFG-05",
    "wrong-serial": "TEL-02",
    "misaligned-values": "TEL-03",
    "millisecond-stamps": "TEL-04",
    "slow-rate": "TEL-06",
    "wrong-ack-order": "CMD-03",
    "ack-after-final": "CMD-04",
    "long-ack-message": "CMD-11",
    "no-dedup": "CMD-10",
    "other-asset-accepted": "CMD-09",
    "volatile-acks": "CMD-13",
    "crash-on-bad-input": "CMD-14",
    "sample-qos": "DDS-01",
    "command-reader-qos": "DDS-02",
    "no-control-gate": "ACC-03",
    "wrong-partition": "DDS-05",
    "queue-status-code": "QUE-01",
    "queue-record-status": "QUE-05",
    "astrobee-acks": None,
}
# What a kind may break besides its check, depending on timing: a keep-last-1 command
# reader drops queued commands only when several arrive before it takes them.
MAY_ALSO = {"command-reader-qos": {"QUE-02"}}


def main() -> int:
    kind, pydir, package, domain = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    sys.path.insert(0, pydir)
    from cyclonedds.qos import Policy, Qos

    from rapid_runtime import bridge as B
    from rapid_runtime import messages as M
    from rapid_runtime.dds import use_transport
    from rapid_runtime.simulate import Simulator
    from rapid_runtime.tables import Tables

    rapid = importlib.import_module(f"{package}.rapid")
    tables = Tables(importlib.import_module(f"{package}.asset_tables"))
    qos = importlib.import_module(f"{package}.qos").RapidQos()
    use_transport(qos, None)

    class PatchedQos:  # the package's QoS with some topics' writer or reader QoS changed
        def __init__(self, base, writers=None, readers=None):
            self.base, self.writers, self.readers = base, writers or {}, readers or {}

        def writer(self, topic):
            q = self.base.writer(topic)
            return q + self.writers[topic] if topic in self.writers else q

        def reader(self, topic):
            q = self.base.reader(topic)
            return q + self.readers[topic] if topic in self.readers else q

        def __getattr__(self, name):
            return getattr(self.base, name)

    if kind == "volatile-config":
        qos = PatchedQos(qos, {t: Qos(Policy.Durability.Volatile) for t in tables.configs})
    elif kind == "volatile-acks":
        qos = PatchedQos(qos, {"rapid_ack": Qos(Policy.Durability.Volatile)})
    elif kind == "sample-qos":  # reliable where the profile says best effort: compatible, but not the profile
        topic = next(p["topic"] for p in tables.publications if p["qos"] == "RapidSampleQos" and p.get("rate"))
        qos = PatchedQos(qos, {topic: Qos(Policy.Reliability.Reliable(duration_ms := 100_000_000))})  # noqa: F841
    elif kind == "command-reader-qos":  # keeps only the last 2 commands: commands can be dropped
        # (not KeepLast(1): discovery shows an unannounced history as KeepLast(1), see DDS-02)
        qos = PatchedQos(qos, readers={"rapid_command": Qos(Policy.History.KeepLast(2))})
    elif kind == "wrong-config":
        cfg = tables.configs["rapid_command_config"]
        value = dict(cfg[1], availableSubsystems=cfg[1]["availableSubsystems"][:-1])
        tables.configs["rapid_command_config"] = (cfg[0], value)
    elif kind == "slow-rate":
        tables.telemetry = [dict(t, rate=t["rate"] / 2) if t.get("rate") else t for t in tables.telemetry]

    bridge = B.Bridge(tables, rapid, Simulator(tables, speed=20), qos, domain=domain)

    if kind == "zero-serial":
        bridge.serials.start = 0
        bridge.serials._last = 0
    elif kind == "wrong-serial":
        hdr = B.TelemetryPublisher._hdr

        def off_by_one(self, entry, stamp=None):
            h = hdr(self, entry, stamp)
            h.serial += 1
            return h
        B.TelemetryPublisher._hdr = off_by_one
    elif kind == "millisecond-stamps":
        hdr = B.TelemetryPublisher._hdr
        B.TelemetryPublisher._hdr = lambda self, entry, stamp=None: hdr(self, entry, time.time_ns() // 1_000_000)
    elif kind == "misaligned-values":
        values = B.TelemetryPublisher._values
        B.TelemetryPublisher._values = lambda self, entry, v: list(reversed(values(self, entry, v))) + \
            [M.union(rapid, "RAPID_BOOL", True)]

    ack = bridge.ack

    def patched_ack(cmd, status, completed, message):
        if kind == "wrong-ack-order" and status == "ACK_EXECUTING":
            ack(cmd, status, completed, message)
            return ack(cmd, "ACK_QUEUED", "ACK_COMPLETED_NOT", "")
        if kind == "ack-after-final" and status == "ACK_COMPLETED":
            ack(cmd, status, completed, message)
            return ack(cmd, "ACK_EXECUTING", "ACK_COMPLETED_NOT", "")
        if kind == "long-ack-message" and message:
            message = (message + " " + "x" * 128)[:128]  # Astrobee's bug: 128 bytes, no terminator
        if kind == "astrobee-acks":  # never QUEUED; the asset's own header on acks
            if status == "ACK_QUEUED":
                return None
            cmd = dataclasses.replace(cmd, src_name=tables.name)
        return ack(cmd, status, completed, message)
    bridge.ack = patched_ack

    m = bridge.manager
    if kind == "no-dedup":
        class Forgetful(collections.OrderedDict):
            def __contains__(self, key):
                return False
        m.seen = Forgetful()
    elif kind == "other-asset-accepted":
        receive = m.receive
        m.receive = lambda cmd: receive(dataclasses.replace(cmd, asset_name=tables.name))
    elif kind == "no-control-gate":  # the allow-list still holds; control is never asked for
        authorize = m._authorize

        def no_gate(cmd, entry):
            why = authorize(cmd, entry)
            return None if why and "does not have control" in why else why
        m._authorize = no_gate
    elif kind == "crash-on-bad-input":
        on_command = bridge._on_command

        def fragile(sample):
            if any(isinstance(a.value, float) and math.isnan(a.value) for a in sample.arguments):
                os._exit(70)  # what an unchecked float conversion in a robot's C++ bridge does
            on_command(sample)
        bridge._on_command = fragile

    if kind == "queue-status-code":  # 2 is none of suspended (-1), idle (0), active (1)
        queue_state = bridge.queue_state
        bridge.queue_state = lambda code, *lists: queue_state(2, *lists)
    elif kind == "queue-record-status":  # pending commands reported as already succeeded
        records = M.queue_state

        def succeeded(rapid_, hdr, pending, active, completed):
            return records(rapid_, hdr, [(c, r, "Q_STATUS_SUCCEEDED") for c, r, _ in pending], active, completed)
        M.queue_state = succeeded

    bridge.start()
    if kind == "wrong-partition":  # one more agent-state writer, in the default partition
        from cyclonedds.pub import DataWriter, Publisher
        stray = DataWriter(Publisher(bridge.node.participant), bridge.node.topic("rapid_agent_state", rapid.AgentState),
                           qos=qos.writer("rapid_agent_state"))
        stray.write(rapid.AgentState(hdr=M.header(rapid, tables.name, tables.name, bridge.serials.start)))
    print(f"bridge ready: broken asset ({kind}) {tables.name}, domain {domain}", flush=True)
    try:
        bridge.wait(float(os.environ.get("BROKEN_SECONDS", "120")))
    finally:
        bridge.stop()
    return 0


if __name__ == "__main__":
    sys.exit(main())
