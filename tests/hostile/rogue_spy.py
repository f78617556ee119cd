"""A rogue participant for `rapidgen spy`'s live hostile-data tests (tests/hostile/test_live_spy.py),
built on tests/hostile/rogue.py's Rogue; runs as its own process:

    python -m tests.hostile.rogue_spy MODE PYDIR PACKAGE DOMAIN [SECONDS] [ARG]

Prints "rogue ready GUID" (its participant's) once it is up, "rogue written N" after its
first samples are written (durable ones stay on the network for late joiners), then keeps
going until SECONDS are over (the test kills it when it no longer needs it).

Modes:
- bad-config: a durable CommandConfig (the rogue's own instance) whose subsystem name is
  invalid UTF-8, a durable config with terminal escapes in every text field, then every
  0.2 s an AgentState with invalid UTF-8 and one holding +Inf, -Inf and NaN.
- big-config: a CommandConfig at its IDL bounds (64 subsystem types of 100 commands of 16
  parameters, every string at its bound: ~5 MB), republished at 10 Hz; ARG "vary" changes
  its serial each time (the bytes differ: nothing can be reused).
- partitions: one participant in ARG (default 4000) partitions (one named with terminal
  escapes), a durable config and a state in all of them, rewritten every second.
"""
from __future__ import annotations

import os
import sys
import time

from tests.hostile.rogue import EVIL, Rogue

SHORT_EVIL = "\x1b]0;pw\x07\x1b[2J\x9b\u202e"  # for String32 fields (EVIL is longer than 32 bytes)


def _bad_utf8(data: bytes, marker: str) -> bytes:
    """`data` with the first occurrence of `marker` starting with \\xff\\xfe (same length)."""
    at = data.index(marker.encode())
    return data[:at] + b"\xff\xfe" + data[at + 2:]


def full_command_config(r: Rogue, serial: int = 1, src: str = "Rogue"):
    """A CommandConfig at its IDL bounds: every sequence full, every string at its bound."""
    rapid = r.rapid
    param = [rapid.KeyTypePair(key=f"p{k}".ljust(32, "p"), type=rapid.DataType.RAPID_STRING) for k in range(16)]
    types = [rapid.SubsystemType(name=f"T{i:02d}".ljust(32, "t"), commands=[
        rapid.CommandDef(name=f"c{i}_{j}".ljust(64, "c"), abortable=True, suspendable=True, parameters=param)
        for j in range(100)]) for i in range(64)]
    subs = [rapid.Subsystem(name=f"S{i}".ljust(32, "s"), subsystemTypeName=f"T{i % 64:02d}".ljust(32, "t"))
            for i in range(128)]
    return rapid.CommandConfig(hdr=r.header(src, serial), availableSubsystemTypes=types, availableSubsystems=subs)


def small_config(r: Rogue, src: str, subsystem: str, serial: int = 7):
    rapid = r.rapid
    cmd = rapid.CommandDef(name=f"poke{EVIL}", abortable=False, suspendable=False,
                           parameters=[rapid.KeyTypePair(key=f"k{SHORT_EVIL}", type=rapid.DataType.RAPID_INT)])
    return rapid.CommandConfig(hdr=r.header(src, serial),
                               availableSubsystemTypes=[rapid.SubsystemType(name=f"Evil{SHORT_EVIL}", commands=[cmd])],
                               availableSubsystems=[rapid.Subsystem(name=subsystem,
                                                                    subsystemTypeName=f"Evil{SHORT_EVIL}")])


def agent_state(r: Rogue, marker: str, values: tuple[float, ...] = ()):
    rapid = r.rapid
    return rapid.AgentState(hdr=r.header(marker), values=[rapid.ParameterUnion(d=v) for v in values])


def bad_config(r: Rogue, seconds: float, arg: str) -> int:
    rapid = r.rapid
    bad = _bad_utf8(small_config(r, "RogueBad", "RGBADNAME").serialize(), "RGBADNAME")
    r.raw("rapid_command_config", rapid.CommandConfig, bad)
    good = small_config(r, f"Rogue{SHORT_EVIL}", f"sub{SHORT_EVIL}")
    r.writer("rapid_command_config", rapid.CommandConfig).write(good)
    print("rogue written 2", flush=True)
    n, end = 2, time.monotonic() + seconds
    state = _bad_utf8(agent_state(r, "RGSTATE").serialize(), "RGSTATE")
    odd = agent_state(r, "RogueInf", (float("inf"), float("-inf"), float("nan")))
    while time.monotonic() < end:
        r.raw("rapid_agent_state", rapid.AgentState, state)
        r.writer("rapid_agent_state", rapid.AgentState).write(odd)
        n += 2
        time.sleep(0.2)
    return n


def big_config(r: Rogue, seconds: float, arg: str) -> int:
    rapid = r.rapid
    cfg = full_command_config(r)
    data = cfg.serialize()
    print(f"rogue config {len(data)} bytes", flush=True)
    n, end = 0, time.monotonic() + seconds
    while time.monotonic() < end:
        if arg == "vary" and n:
            cfg.hdr.serial = n + 1
            data = cfg.serialize()
        r.raw("rapid_command_config", rapid.CommandConfig, data)
        n += 1
        if n == 1:
            print("rogue written 1", flush=True)
        time.sleep(0.1)
    return n


def partitions(r: Rogue, seconds: float, arg: str) -> int:
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.qos import Policy, Qos
    from cyclonedds.topic import Topic
    rapid = r.rapid
    count = int(arg or 4000)
    names = [f"Evil{EVIL}"] + [f"RG{i:05d}" for i in range(count - 1)]
    pub = Publisher(r.dp, qos=Qos(Policy.Partition(names)))
    cfg_w = DataWriter(pub, Topic(r.dp, "rapid_command_config", rapid.CommandConfig),
                       qos=r.qos.writer("rapid_command_config"))
    state_w = DataWriter(pub, Topic(r.dp, "rapid_agent_state", rapid.AgentState), qos=r.qos.writer("rapid_agent_state"))
    n, end = 0, time.monotonic() + seconds
    while time.monotonic() < end:
        cfg_w.write(small_config(r, "RogueMany", "Many", serial=n))
        state_w.write(agent_state(r, "RogueMany"))
        n += 2
        if n == 2:
            print("rogue written 2", flush=True)
        time.sleep(1.0)
    return n


MODES = {"bad-config": bad_config, "big-config": big_config, "partitions": partitions}


def main(argv: list[str]) -> int:
    mode, pydir, package, domain = argv[0], argv[1], argv[2], int(argv[3])
    seconds = float(argv[4]) if len(argv) > 4 else 30.0
    arg = argv[5] if len(argv) > 5 else ""
    r = Rogue(pydir, package, domain)
    print(f"rogue ready {r.dp.guid}", flush=True)
    time.sleep(float(os.environ.get("ROGUE_DISCOVERY_S", "0.5")))
    n = MODES[mode](r, seconds, arg)
    print(f"rogue done {n}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
