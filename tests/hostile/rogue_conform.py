"""Rogue modes aimed at `rapidgen conform` (tests/hostile/test_live_conform.py): a second
participant in the asset's partition, next to a healthy bridge, writing what the runner
reads (acks, configs, telemetry, states). Built on tests/hostile/rogue.py's Rogue:

    python -m tests.hostile.rogue_conform MODE PYDIR PACKAGE DOMAIN [SECONDS] [ARG]

Prints "rogue ready" once its participant exists, "rogue writing" once discovery had its time,
runs MODE for SECONDS (or until terminated) and prints "rogue done N" (N samples written).
Modes:
  bad-samples  undecodable samples (invalid UTF-8 in a string) on every topic conform reads:
               durable configs once, acks, telemetry and states every 0.2 s
  strangers    well-formed samples that would fail the asset if they were its own: acks for
               every command the runner sends (EXECUTING with a 128-byte message, a
               COMPLETED/EXEC_FAILED, an EXECUTING after it) and for cmdIds nobody sent, configs
               that differ from the descriptor, telemetry with wrong serials and misaligned
               values, states with a bad status code, writers in another partition and with
               another durability; every text field holds terminal escapes
  big-config   a CommandConfig at its full IDL bounds (5.0 MB), rewritten ARG times a
               second (default 10)
"""
from __future__ import annotations

import os
import sys
import time

from tests.hostile.rogue import EVIL, Rogue

SHORT_EVIL = "\x1b]0;pwned\x07\x1b[2J\x9b31m\u202e"  # fits a String32 (22 bytes)


def fit(text: str, nbytes: int) -> str:
    """`text` cut to at most nbytes UTF-8 bytes (whole characters)."""
    return text.encode()[:nbytes].decode("utf-8", "ignore")


def spoil(data: bytes, marker: str) -> bytes:
    """The encoding with `marker`'s first two bytes replaced by \\xff\\xfe (invalid UTF-8,
    same length: every length field stays right)."""
    m = marker.encode()
    assert m in data, marker
    return data.replace(m, b"\xff\xfe" + m[2:], 1)


class ConformRogue(Rogue):
    def __init__(self, pydir: str, package: str, domain: int) -> None:
        super().__init__(pydir, package, domain)
        self.configs = dict(self.tables.CONFIGS)
        self.written = 0

    def put(self, topic: str, sample) -> None:
        self.writer(topic, type(sample)).write(sample)
        self.written += 1

    def put_raw(self, topic: str, cls, data: bytes) -> None:
        self.raw(topic, cls, data)
        self.written += 1

    # ---- samples of each kind -------------------------------------------------------------
    def hdr(self, src: str, serial: int = 0, status: int = 0):
        r = self.rapid
        return r.Header(srcName=src, assetName=self.asset, timeStamp=time.time_ns() // 1000, statusCode=status,
                        serial=serial)

    def config(self, topic: str, src: str, serial: int):
        r, type_name = self.rapid, self.configs[topic]["type"]
        h = self.hdr(src, serial)
        if type_name == "rapid::CommandConfig":
            t = r.SubsystemType(name=fit(SHORT_EVIL, 31), commands=[r.CommandDef(name=fit(EVIL, 63))])
            return r.CommandConfig(hdr=h, availableSubsystemTypes=[t],
                                   availableSubsystems=[r.Subsystem(name=fit(SHORT_EVIL, 31), subsystemTypeName="x")])
        if type_name == "rapid::AgentConfig":
            return r.AgentConfig(hdr=h, agentTags=["rogue"], topics=[fit(EVIL, 127)], valueKeys=[])
        if type_name == "rapid::PositionConfig":
            return r.PositionConfig(hdr=h, frameName=fit(EVIL, 127), valueKeys=[])
        if type_name == "rapid::JointConfig":
            return r.JointConfig(hdr=h, jointGroupName=fit(EVIL, 31), jointDefinitions=[])
        raise KeyError(type_name)

    def telemetry(self, topic: str, src: str, serial: int):
        r = self.rapid
        union = r.ParameterUnion(discriminator=r.DataType.RAPID_STRING, value=fit(EVIL, 127))
        if topic == "rapid_position_sample":
            return r.PositionSample(hdr=self.hdr(src, serial), values=[union] * 3)
        if topic == "rapid_agent_state":
            return r.AgentState(hdr=self.hdr(src, serial), values=[union] * 5)
        raise KeyError(topic)

    def access_state(self, src: str):
        return self.rapid.AccessControlState(hdr=self.hdr(src), controller=fit(SHORT_EVIL, 31),
                                             requestors=[fit(SHORT_EVIL, 31)])

    def queue_state(self, src: str):
        r = self.rapid
        rec = r.CommandRecord(cmd=self.command(fit(EVIL, 63), src=fit(SHORT_EVIL, 31)))
        return r.QueueState(hdr=self.hdr(src, status=7), pending=r.SingleQueue(records=[rec]))

    def answer(self, cmd_id: str) -> None:
        """Acks for a command the runner sent: what a confused or hostile commander writes."""
        r, long = self.rapid, fit(EVIL + "x" * 128, 128)
        for status, done, msg in (("ACK_EXECUTING", "ACK_COMPLETED_NOT", long),
                                  ("ACK_COMPLETED", "ACK_COMPLETED_EXEC_FAILED", EVIL),
                                  ("ACK_EXECUTING", "ACK_COMPLETED_NOT", long)):
            a = r.Ack(hdr=r.Header(srcName=fit(SHORT_EVIL, 31), assetName=fit(SHORT_EVIL, 31),
                                   timeStamp=time.time_ns() // 1000), cmdId=cmd_id,
                      status=r.AckStatus[status], completedStatus=r.AckCompletedStatus[done], message=msg)
            self.put("rapid_ack", a)


# ---- modes ------------------------------------------------------------------------------------

def bad_samples(r: ConformRogue, until: float, arg: str) -> None:
    marker = "RGBAD1"
    for topic in r.configs:
        cfg = r.config(topic, marker, 1)
        r.put_raw(topic, type(cfg), spoil(cfg.serialize(), marker))
    n = 0
    while time.monotonic() < until:
        n += 1
        m = f"RB{n:04d}"
        r.put_raw("rapid_ack", r.rapid.Ack, spoil(r.ack(m).serialize(), m))
        for topic in ("rapid_position_sample", "rapid_agent_state"):
            s = r.telemetry(topic, m, 1)
            r.put_raw(topic, type(s), spoil(s.serialize(), m))
        s = r.access_state(m)
        r.put_raw("rapid_accesscontrol_state", type(s), spoil(s.serialize(), m))
        s = r.queue_state(m)
        r.put_raw("rapid_queue_state", type(s), spoil(s.serialize(), m))
        time.sleep(0.2)


def strangers(r: ConformRogue, until: float, arg: str) -> None:
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.qos import Policy, Qos
    from cyclonedds.sub import DataReader, Subscriber
    from cyclonedds.topic import Topic

    src = fit(SHORT_EVIL, 31)
    for topic in r.configs:
        r.put(topic, r.config(topic, src, 0))
    # the same topics elsewhere: a writer in another partition (DDS-05), and a volatile config
    # writer in the partition (an incompatible QoS for the runner's durable config reader: DDS-03)
    elsewhere = Publisher(r.dp, qos=Qos(Policy.Partition([fit(SHORT_EVIL, 31)])))
    other = DataWriter(elsewhere, Topic(r.dp, "rapid_agent_state", r.rapid.AgentState),
                       qos=r.qos.writer("rapid_agent_state"))
    volatile_topic = next(iter(r.configs))
    cfg = r.config(volatile_topic, src, 0)
    volatile = DataWriter(r.pub, Topic(r.dp, volatile_topic, type(cfg)),
                          qos=r.qos.writer(volatile_topic) + Qos(Policy.Durability.Volatile))
    sub = Subscriber(r.dp, qos=Qos(Policy.Partition([r.partition])))
    commands = DataReader(sub, Topic(r.dp, "rapid_command", r.rapid.Command), qos=r.qos.reader("rapid_command"))
    r.put("rapid_accesscontrol_state", r.access_state(src))
    r.put("rapid_queue_state", r.queue_state(src))
    n = 0
    while time.monotonic() < until:
        n += 1
        for c in commands.take(N=64):
            if hasattr(c, "cmdId"):
                r.answer(c.cmdId)
        if n % 4 == 0:  # 5 Hz: telemetry and acks nobody asked for
            for topic in ("rapid_position_sample", "rapid_agent_state"):
                r.put(topic, r.telemetry(topic, src, n))
            r.put("rapid_ack", r.ack(fit(EVIL, 63), message=fit(EVIL * 4, 128), src=src))
            other.write(r.telemetry("rapid_agent_state", src, n))
            volatile.write(cfg)
            r.written += 2
        time.sleep(0.05)


def big_config(r: ConformRogue, until: float, arg: str) -> None:
    """Every sequence and string of a CommandConfig at its bound, written `arg` Hz."""
    rate = float(arg or 10)
    rt = r.rapid
    params = [rt.KeyTypePair(key="p" * 32, type=rt.DataType.RAPID_STRING) for _ in range(16)]
    cmds = [rt.CommandDef(name="c" * 64, parameters=params) for _ in range(100)]
    types_ = [rt.SubsystemType(name="t" * 32, commands=cmds) for _ in range(64)]
    cfg = rt.CommandConfig(hdr=r.hdr("Rogue", 1), availableSubsystemTypes=types_,
                           availableSubsystems=[rt.Subsystem(name="s" * 32, subsystemTypeName="t" * 32)
                                                for _ in range(128)])
    data = cfg.serialize()
    print(f"rogue config {len(data)} bytes", flush=True)
    while time.monotonic() < until:
        t0 = time.monotonic()
        r.put_raw("rapid_command_config", rt.CommandConfig, data)
        time.sleep(max(0.0, 1.0 / rate - (time.monotonic() - t0)))


MODES = {"bad-samples": bad_samples, "strangers": strangers, "big-config": big_config}


def main(argv: list[str]) -> int:
    import signal
    mode, pydir, package, domain = argv[0], argv[1], argv[2], int(argv[3])
    seconds = float(argv[4]) if len(argv) > 4 else 60.0
    arg = argv[5] if len(argv) > 5 else ""
    def terminate(*_):
        raise KeyboardInterrupt
    signal.signal(signal.SIGTERM, terminate)
    r = ConformRogue(pydir, package, domain)
    print("rogue ready", flush=True)
    try:
        time.sleep(float(os.environ.get("ROGUE_DISCOVERY_S", "1.0")))
        print("rogue writing", flush=True)
        MODES[mode](r, time.monotonic() + seconds, arg)
    except KeyboardInterrupt:
        pass
    print(f"rogue done {r.written}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
