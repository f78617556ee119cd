"""A rogue participant on an asset's domain, for the live hostile-data tier: it joins the
asset's partition and writes any RAPID topic with any bytes (what DDS lets anyone on the
domain do without DDS Security). Runs as its own process, like a real stranger:

    python -m tests.hostile.rogue MODE PYDIR PACKAGE DOMAIN [SECONDS] [ARG]

Prints "rogue ready" once its writers exist (discovery is left to the caller: sleep or
wait for matches), then "rogue done N" after it has written N samples. Modes are in MODES.
Library use (in another test's own rogue process): Rogue(...).raw(topic, bytes).
"""
from __future__ import annotations

import importlib
import os
import random
import sys
import time

# Escape sequences a rogue puts in every text field it controls: OSC 0 (terminal title),
# OSC 52 (clipboard), CSI 2J (clear screen), BEL, a C1 CSI, a bidi override.
EVIL = "\x1b]0;pwned\x07\x1b]52;c;cHduZWQ=\x07\x1b[2J\x9b31m\u202e"
EVIL_SHORT = "\x1b]0;x\x07\x9b2J\x1b[2J"  # for String32 fields


class Rogue:
    def __init__(self, pydir: str, package: str, domain: int, partition: str | None = None) -> None:
        sys.path.insert(0, pydir)
        from cyclonedds.domain import DomainParticipant
        from cyclonedds.pub import Publisher
        from cyclonedds.qos import Policy, Qos

        self.rapid = importlib.import_module(f"{package}.rapid")
        self.qos = importlib.import_module(f"{package}.qos").RapidQos()
        self.tables = importlib.import_module(f"{package}.asset_tables")
        self.asset = self.tables.ASSET["name"]
        self.partition = partition or self.tables.ASSET["partition"]
        self.dp = DomainParticipant(domain)
        self.pub = Publisher(self.dp, qos=Qos(Policy.Partition([self.partition])))
        self._writers: dict = {}

    def writer(self, topic: str, cls):
        from cyclonedds.pub import DataWriter
        from cyclonedds.topic import Topic

        if topic not in self._writers:
            self._writers[topic] = DataWriter(self.pub, Topic(self.dp, topic, cls), qos=self.qos.writer(topic))
        return self._writers[topic]

    def raw(self, topic: str, cls, data: bytes, strict: bool = True) -> bool:
        """Write `data` as a sample of `topic`, whatever it holds (CDR header included).
        Cyclone's own writer refuses bytes it cannot take a key from (BAD_PARAMETER; its
        readers drop those in the C layer alike): False then, or an error when strict."""
        from cyclonedds._clayer import ddspy_write
        data = data.ljust((len(data) + 3) & ~3, b"\0")
        ret = ddspy_write(self.writer(topic, cls)._ref, data)
        if ret < 0 and strict:
            raise RuntimeError(f"write on {topic}: {ret}")
        return ret >= 0

    def header(self, src: str = "Rogue", serial: int = 0):
        return self.rapid.Header(srcName=src, assetName=self.asset, timeStamp=time.time_ns() // 1000,
                                 statusCode=0, serial=serial)

    def command(self, cmd_id: str, name: str = "noOp", subsystem: str = "Admin", src: str = "Rogue",
                action: str = "QUEUE_BYPASS", target: str = ""):
        r = self.rapid
        return r.Command(hdr=self.header(src), cmdName=name, cmdId=cmd_id, cmdSrc=src, subsysName=subsystem,
                         arguments=[], cmdAction=r.QueueAction[action], targetCmdId=target)

    def bad_utf8_command(self, n: int) -> bytes:
        """A Command whose cmdId holds \\xff bytes (Cyclone's C layer passes them through)."""
        marker = f"RG{n:06d}"
        data = self.command(marker).serialize()
        return data.replace(marker.encode(), b"\xff\xfe" + marker.encode()[2:], 1)

    def ack(self, cmd_id: str, message: str = "", status: str = "ACK_COMPLETED",
            completed: str = "ACK_COMPLETED_OK", src: str | None = None):
        r = self.rapid
        return r.Ack(hdr=self.header(src or self.asset), cmdId=cmd_id, status=r.AckStatus[status],
                     completedStatus=r.AckCompletedStatus[completed], message=message)


def mutate(data: bytes, rng: random.Random) -> bytes:
    """One random mutation of a valid encoding: flipped bytes, a cut, garbage appended, a
    length field made huge, or random bytes behind a valid CDR header."""
    b = bytearray(data)
    kind = rng.randrange(5)
    if kind == 0:
        for _ in range(rng.randint(1, 8)):
            b[rng.randrange(4, len(b))] = rng.randrange(256)
    elif kind == 1:
        del b[rng.randrange(4, len(b)):]
    elif kind == 2:
        b += rng.randbytes(rng.randint(1, 64))
    elif kind == 3:
        at = rng.randrange(4, max(5, len(b) - 4)) & ~3
        b[at:at + 4] = rng.choice([b"\xff\xff\xff\x7f", b"\x00\x00\x00\x80", b"\xff\xff\xff\xff"])
    else:
        b = bytearray(data[:4]) + rng.randbytes(rng.randint(0, 256))
    return bytes(b)


# ---- modes -----------------------------------------------------------------------------------

def bad_command(r: Rogue, seconds: float, arg: str) -> int:
    """`arg` Commands (default 1) whose cmdId is invalid UTF-8."""
    n = int(arg or 1)
    for i in range(n):
        r.raw("rapid_command", r.rapid.Command, r.bad_utf8_command(i))
    return n


def fuzz(r: Rogue, seconds: float, arg: str) -> int:
    """`arg` (default 2000) random and mutated samples on every topic the bridge reads
    (rapid_command), seeded (RAPIDGEN_FUZZ_SEED) so a failure can be replayed."""
    n = int(arg or 2000)
    rng = random.Random(int(os.environ.get("RAPIDGEN_FUZZ_SEED", "19")))
    good = [r.command(f"fz-{i}", src=rng.choice(["Rogue", EVIL_SHORT]), action=rng.choice(
        ["QUEUE_BYPASS", "QUEUE_APPEND", "QUEUE_DELETE"])).serialize() for i in range(16)]
    written = 0
    for i in range(n):
        written += r.raw("rapid_command", r.rapid.Command, mutate(rng.choice(good), rng), strict=False)
        if i % 200 == 199:
            time.sleep(0.05)  # let a reliable reader keep up: this is a fuzz, not a flood
    print(f"rogue wrote {written} (Cyclone's writer refused {n - written} it could not key)", flush=True)
    return n


def evil_acks(r: Rogue, seconds: float, arg: str) -> int:
    """Acks for cmdId `arg` whose message and cmdId carry terminal escapes, for `seconds`."""
    end, n = time.monotonic() + seconds, 0
    w = r.writer("rapid_ack", r.rapid.Ack)
    while time.monotonic() < end:
        w.write(r.ack(arg, message=EVIL + "done", status="ACK_EXECUTING", completed="ACK_COMPLETED_NOT"))
        w.write(r.ack(arg + EVIL, message=EVIL))
        n += 2
        time.sleep(0.05)
    return n


def storm(r: Rogue, seconds: float, arg: str) -> int:
    """APPEND/DELETE/REPLACE as fast as the writer goes, for `seconds` (a flood of commands
    that each need an answer; the rogue holds no control)."""
    w = r.writer("rapid_command", r.rapid.Command)
    end, n = time.monotonic() + seconds, 0
    actions = ("QUEUE_APPEND", "QUEUE_DELETE", "QUEUE_REPLACE")
    from cyclonedds.core import DDSException
    while time.monotonic() < end:
        a = actions[n % 3]
        try:
            w.write(r.command(f"st-{n}", name="noOp", action=a, target="" if a == "QUEUE_APPEND" else f"st-{n - 1}"))
        except DDSException:  # held back: the reader's cache is full (what the bridge wants)
            continue
        n += 1
    return n


def bad_config(r: Rogue, seconds: float, arg: str) -> int:
    """A durable CommandConfig for the asset whose srcName is invalid UTF-8, kept on the
    network for `seconds` (a late reader gets it at once)."""
    from rapid_runtime import messages as M
    c = r.tables.CONFIGS["rapid_command_config"]
    type_name, value = c["type"], c["value"]
    data = M.config(r.rapid, type_name, value, r.header("Rogue")).serialize()
    r.raw("rapid_command_config", r.rapid.CommandConfig, data.replace(b"Rogue", b"\xff\xfegue", 1))
    time.sleep(seconds)
    return 1


def ack_flood(r: Rogue, seconds: float, arg: str) -> int:
    """Acks for cmdIds nobody sent, as fast as the writer goes, for `seconds`."""
    w = r.writer("rapid_ack", r.rapid.Ack)
    end, n = time.monotonic() + seconds, 0
    while time.monotonic() < end:
        w.write(r.ack(f"nobody-{n}-".ljust(63, "x"), message="y" * 100))
        n += 1
    return n


MODES = {"bad-config": bad_config, "ack-flood": ack_flood, "storm": storm, "bad-command": bad_command, "fuzz": fuzz, "evil-acks": evil_acks}


def main(argv: list[str]) -> int:
    mode, pydir, package, domain = argv[0], argv[1], argv[2], int(argv[3])
    seconds = float(argv[4]) if len(argv) > 4 else 5.0
    arg = argv[5] if len(argv) > 5 else ""
    r = Rogue(pydir, package, domain)
    print("rogue ready", flush=True)
    time.sleep(float(os.environ.get("ROGUE_DISCOVERY_S", "1.5")))  # the asset's readers match us
    n = MODES[mode](r, seconds, arg)
    print(f"rogue done {n}", flush=True)
    time.sleep(float(os.environ.get("ROGUE_LINGER_S", "1.0")))  # reliable samples reach their readers
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
