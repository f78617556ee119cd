"""Watches an asset's AgentState and TextMessage over DDS (Cyclone, loopback only) and
prints one JSON line per sample: {"agent": {key: value}} or {"text": message}.

    python -m tests.streams.watch PACKAGE_DIR PACKAGE DOMAIN [PARTITION [TOPIC ...]]

Acks too: {"ack": cmdId, "status": ..., "completed": ...}. PARTITION: another asset's (any
package holds the RAPID types); default (or ""): the package's own. TOPICs: position or
joint sample topics of the package's telemetry, printed as {"position": topic, "xyz": [..]}
or {"joint": topic, "pos": [..]}.

Run as its own process (CYCLONEDDS_URI is read when cyclonedds loads): the test sets it
to the package's qos_files/cyclonedds/local.xml."""
from __future__ import annotations

import importlib
import json
import sys
import time


def main() -> None:
    pydir, package, domain = sys.argv[1], sys.argv[2], int(sys.argv[3])
    partition = sys.argv[4] if len(sys.argv) > 4 and sys.argv[4] else None
    sampled = sys.argv[5:]
    sys.path.insert(0, pydir)
    from cyclonedds.core import Policy, Qos
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.sub import DataReader, Subscriber
    from cyclonedds.topic import Topic
    rapid = importlib.import_module(f"{package}.rapid")
    qos = importlib.import_module(f"{package}.qos").RapidQos()
    dp = DomainParticipant(domain)
    sub = Subscriber(dp, qos=Qos(Policy.Partition([partition])) if partition else qos.subscriber("rapid_agent_state"))
    config = DataReader(sub, Topic(dp, "rapid_agent_config", rapid.AgentConfig), qos=qos.reader("rapid_agent_config"))
    agent = DataReader(sub, Topic(dp, "rapid_agent_state", rapid.AgentState), qos=qos.reader("rapid_agent_state"))
    # (keep last 64, not the profile's 1: a loss of three streams sends three texts at once)
    def deep(topic: str) -> Qos:
        return Qos(*[p for p in qos.reader(topic) if p.__scope__ != "History"], Policy.History.KeepLast(64))
    text = DataReader(sub, Topic(dp, "rapid_textmessage", rapid.TextMessage), qos=deep("rapid_textmessage"))
    acks = DataReader(sub, Topic(dp, "rapid_ack", rapid.Ack), qos=deep("rapid_ack"))
    samples = [(t, DataReader(sub, Topic(dp, t, rapid.JointSample if t.startswith("rapid_joint_sample")
                                         else rapid.PositionSample), qos=qos.reader(t))) for t in sampled]
    keys: list[str] = []
    print(json.dumps({"ready": True}), flush=True)
    while True:
        for c in config.take(N=8):
            keys = [k.key for k in c.valueKeys]
        for s in agent.take(N=64):
            if keys:
                values = {}
                for k, v in zip(keys, s.values):
                    values[k] = getattr(v, "value", None)
                print(json.dumps({"agent": values}, default=str), flush=True)
        for a in acks.take(N=64):
            print(json.dumps({"ack": a.cmdId, "status": str(a.status), "completed": str(a.completedStatus),
                              "message": a.message}), flush=True)
        for topic, r in samples:
            for s in r.take(N=64):
                if topic.startswith("rapid_joint_sample"):
                    print(json.dumps({"joint": topic, "pos": list(s.anglePos)}), flush=True)
                else:
                    print(json.dumps({"position": topic, "xyz": list(s.pose.xyz)}), flush=True)
        for t in text.take(N=64):
            print(json.dumps({"text": t.message, "level": str(t.level)}), flush=True)
        time.sleep(0.02)


if __name__ == "__main__":
    main()
