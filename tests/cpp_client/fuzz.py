"""Malformed and random Commands over DDS, for the C++ bridge's command intake:

    python -m tests.cpp_client.fuzz DOMAIN COUNT SEED

writes COUNT samples on rapid_command in K10's partition through cyclonedds, as raw CDR
(the Command type's writer, bytes given as they are: ddspy_write), each a valid command
of a few shapes (built-ins, queued moves, camera commands with arguments, access control)
mutated one of several ways: bytes flipped, a length or a discriminator set wild,
truncated, extended, or replaced by random bytes. A sample the reference codec
(rapidgen.cdr, the contract the C++ codec keeps) decodes to a command for K10 with a new,
non-empty cmdId is well formed: it must be answered (at least one ack: the intake never
stays silent on one). Then Admin/echo must still complete OK. Prints one JSON line:
{written, well_formed, answered, unanswered: [first few cmdIds], refused_by_writer, alive}."""
from __future__ import annotations

import json
import random
import struct
import sys
import time

from rapidgen.cdr import CdrError, Codec
from rapidgen.diagnostics import DiagnosticSink
from rapidgen.vectors import load_model
from tests.runtime.live import ROOT

ASSET, SOURCE = "K10Red", "RapidWorkbench"


def shapes(rapid, M, Cmd) -> list:
    """Valid commands of several shapes: each a function of the cmdId giving its CDR."""
    def enc(sub, name, args=(), action="QUEUE_BYPASS", target="", src=SOURCE):
        def make(cmd_id: str) -> bytes:
            cmd = Cmd(cmd_id=cmd_id, cmd_src=src, subsystem=sub, name=name, args=tuple(args), action=action,
                      target=target, src_name=src, asset_name=ASSET)
            return M.command_out(rapid, cmd).serialize()
        return make
    return [
        enc("Admin", "echo", [("RAPID_STRING", "fuzz")]),
        enc("PanCam", "pointCamera", [("RAPID_FLOAT", 0.5), ("RAPID_FLOAT", -0.2)]),
        enc("PanCam", "pointCamera", [("RAPID_FLOAT", 0.1), ("RAPID_FLOAT", 0.0)], action="QUEUE_APPEND"),
        enc("Mobility", "simpleMove", [("RAPID_STRING", "site"), ("RAPID_VEC3d", [0.5, 0.0, 0.0])],
            action="QUEUE_INSERT", target="head"),
        enc("PanCam", "takePicture", [("RAPID_STRING", "stereo"), ("RAPID_FLOAT", 10.0)], action="QUEUE_REPLACE",
            target="nothing"),
        enc("Queue", "cancelAll"),
        enc("AccessControl", "requestControl", src="Fuzzer"),
        enc("PanCam", "takePanorama", [("RAPID_FLOAT", -1.0), ("RAPID_FLOAT", 1.0), ("RAPID_FLOAT", 0.0),
                                       ("RAPID_INT", 8), ("RAPID_BOOL", True), ("RAPID_LONGLONG", 2 ** 40),
                                       ("RAPID_DOUBLE", 1.5), ("RAPID_MAT33f", [1.0] * 9)]),
    ]


def mutate(rng: random.Random, data: bytes) -> bytes:
    b = bytearray(data)
    how = rng.randrange(7)
    if how == 0:  # a few bytes flipped after the encapsulation header
        for _ in range(rng.randint(1, 4)):
            b[rng.randrange(4, len(b))] ^= 1 << rng.randrange(8)
    elif how == 1:  # a 4-byte field set wild (a length, a discriminator, an enum)
        at = rng.randrange(4, max(5, len(b) - 4)) & ~3
        b[at:at + 4] = struct.pack("<I", rng.choice([0, 1, 7, 8, 9, 127, 128, 255, 0x7FFFFFFF, 0xFFFFFFFF,
                                                     rng.getrandbits(32)]))
    elif how == 2:  # truncated
        del b[rng.randrange(4, len(b)):]
    elif how == 3:  # random bytes appended
        b += bytes(rng.getrandbits(8) for _ in range(rng.randint(1, 64)))
    elif how == 4:  # random bytes, the encapsulation header kept
        b = bytearray(b[:4] + bytes(rng.getrandbits(8) for _ in range(rng.randint(0, 300))))
    elif how == 5:  # a run of bytes set to one value
        at = rng.randrange(4, len(b))
        b[at:at + rng.randint(1, 16)] = bytes([rng.choice([0, 0xFF, 0x80, 0x7F])]) * 16
    # how == 6: unchanged (a valid command among the noise)
    return bytes(b)


def main(domain: int, count: int, seed: int) -> dict:
    from cyclonedds._clayer import ddspy_write

    from rapid_runtime import messages as M
    from rapid_runtime.command import Cmd
    from rapid_runtime.commander import Commander
    from rapidgen.live.bindings import import_bindings

    asset = import_bindings("rapid_k10red")
    sink = DiagnosticSink()
    codec = Codec(load_model([str(ROOT / "specs" / "assets" / "k10.yaml")], [], sink))
    commander = Commander(asset.rapid, asset.qos_module.RapidQos(), ASSET, SOURCE, domain)
    out = {"written": 0, "well_formed": 0, "answered": 0, "unanswered": [], "refused_by_writer": 0, "alive": False}
    try:
        if not commander.wait_for_asset(60):
            raise SystemExit("no bridge")
        granted = commander.wait_final(commander.send("AccessControl", "requestControl"), 30)
        assert granted and granted[-1][1] == "ACK_COMPLETED_OK", granted
        rng = random.Random(seed)
        made = shapes(asset.rapid, M, Cmd)
        expected, seen = [], set()
        for i in range(count):
            data = mutate(rng, rng.choice(made)(f"fz{seed}-{i}"))
            data += b"\x00" * (-len(data) % 4)  # (cyclonedds sends whole 4-byte words)
            try:
                value = codec.decode("rapid::Command", data)
            except (CdrError, ValueError, UnicodeDecodeError):
                value = None
            if value is not None and value["hdr"]["assetName"] == ASSET and value["cmdId"] \
                    and value["cmdId"] not in seen:
                seen.add(value["cmdId"])
                commander.follow(value["cmdId"])
                expected.append(value["cmdId"])
            if ddspy_write(commander.writer._ref, data) < 0:
                out["refused_by_writer"] += 1  # (cyclonedds would not take it: never sent)
                if expected and value is not None and expected[-1] == value["cmdId"]:
                    expected.pop()
            else:
                out["written"] += 1
            if i % 64 == 63:
                time.sleep(0.01)  # (the writer's history, not the bridge, is what this spares)
        out["well_formed"] = len(expected)
        end = time.monotonic() + 60
        with commander.cond:
            while time.monotonic() < end and any(not commander.acks.get(c) for c in expected):
                commander.cond.wait(0.2)
            missing = [c for c in expected if not commander.acks.get(c)]
        out["answered"] = len(expected) - len(missing)
        out["unanswered"] = missing[:10]
        acks = commander.wait_final(commander.send("Admin", "echo", [("RAPID_STRING", "still here")]), 30)
        out["alive"] = bool(acks) and acks[-1] == ("ACK_COMPLETED", "ACK_COMPLETED_OK", "still here")
    finally:
        commander.close()
    return out


if __name__ == "__main__":
    print(json.dumps(main(int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]))), flush=True)
