"""Commands through K10's bridge on loopback while its resident memory is read from /proc:
what bench/bridge_memory.py prints and tests/runtime/test_bridge_memory.py asserts.

    python -m tests.runtime.memory_load DOMAIN COMMANDS [EVERY] [-- BRIDGE ARGS...]

Starts K10's bridge (its generated handler stubs: Admin/noOp is answered by the runtime, so
no simulated telemetry adds noise), takes control, sends COMMANDS Admin/noOp (BYPASS, each a
new cmdId, at most IN_FLIGHT unanswered) from this one process, and reads the bridge's
VmRSS and VmHWM every EVERY commands. Prints one JSON document: the samples
[[commands, rss_kib, hwm_kib], ...], the COMPLETED acks received, seconds.
"""
from __future__ import annotations

import importlib
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).parents[2]
PYDIR = ROOT / "generated" / "k10" / "python"
PACKAGE = "rapid_k10red"
SOURCE = "RapidWorkbench"  # K10's allow-list lets it send everything
IN_FLIGHT = 64
WAIT = 30.0


def status_kib(pid: int) -> tuple[int, int]:
    """(VmRSS, VmHWM) of a running process in KiB, (0, 0) once it is gone."""
    got = {"VmRSS:": 0, "VmHWM:": 0}
    try:
        with open(f"/proc/{pid}/status") as fh:
            for line in fh:
                key = line.split(None, 1)[0] if line.strip() else ""
                if key in got:
                    got[key] = int(line.split()[1])
    except OSError:
        pass
    return got["VmRSS:"], got["VmHWM:"]


def local_env() -> dict:
    local = PYDIR / PACKAGE / "qos_files" / "cyclonedds" / "local.xml"
    return dict(os.environ, CYCLONEDDS_URI=f"file://{local}", PYTHONDONTWRITEBYTECODE="1",
                PYTHONPATH=os.pathsep.join([str(PYDIR), str(ROOT / "runtime"), str(ROOT)]),
                RAPID_STATE_DIR=tempfile.mkdtemp(prefix="rapid-state-"))  # the bridge's journal: on, as by default


def drive(domain: int, commands: int, every: int, bridge_args: list[str]) -> dict:
    env = local_env()
    os.environ["CYCLONEDDS_URI"] = env["CYCLONEDDS_URI"]  # before DDS starts in this process
    sys.path[:0] = [str(PYDIR), str(ROOT / "runtime")]
    rapid = importlib.import_module(f"{PACKAGE}.rapid")
    qos = importlib.import_module(f"{PACKAGE}.qos").RapidQos()
    from rapid_runtime import messages as M
    from rapid_runtime.command import Cmd
    from rapid_runtime.dds import Node

    bridge = subprocess.Popen([sys.executable, "-m", f"{PACKAGE}.bridge", "--domain", str(domain), *bridge_args],
                              cwd=PYDIR, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        line = bridge.stdout.readline() if bridge.stdout else ""
        if not line.startswith("bridge ready"):
            raise SystemExit(f"memory_load: the bridge did not start: {line!r} {bridge.stderr.read()[-2000:]}")
        node = Node(rapid, qos, domain)
        writer = node.writer("rapid_command", rapid.Command)
        acks = node.reader("rapid_ack", rapid.Ack, keep_all=True)
        end = time.monotonic() + WAIT
        while not (writer.get_matched_subscriptions() and acks.get_matched_publications()):
            if time.monotonic() > end:
                raise SystemExit("memory_load: no bridge matched")
            time.sleep(0.02)
        done: set[str] = set()

        def send(cid: str, sub: str, name: str) -> None:
            writer.write(M.command_out(rapid, Cmd(cid, SOURCE, sub, name, (), src_name=SOURCE, asset_name="K10Red")))

        def collect(timeout: float) -> bool:
            """Take the acks there are; False when none came within timeout."""
            deadline = time.monotonic() + timeout
            while True:
                got = acks.take(N=256)
                for a in got:
                    if isinstance(a, rapid.Ack) and a.status == rapid.AckStatus.ACK_COMPLETED:
                        done.add(a.cmdId)
                if got:
                    return True
                if time.monotonic() > deadline:
                    return False
                time.sleep(0.0005)

        send("control", "AccessControl", "requestControl")
        end = time.monotonic() + WAIT
        while "control" not in done and time.monotonic() < end:
            collect(0.1)
        samples = [[0, *status_kib(bridge.pid)]]
        t0 = time.monotonic()
        sent = answered = 0
        while answered < commands:
            while sent < commands and sent - answered < IN_FLIGHT:
                send(f"m{sent}", "Admin", "noOp")
                sent += 1
            if not collect(WAIT):
                break  # nothing came for WAIT seconds: report what there is
            # count only this run's commands (control is in `done` too)
            answered = len(done) - 1
            if answered // every > samples[-1][0] // every or answered >= commands:
                samples.append([answered, *status_kib(bridge.pid)])
        seconds = time.monotonic() - t0
        alive = bridge.poll() is None
        return {"samples": samples, "answered": answered, "seconds": round(seconds, 1), "alive": alive}
    finally:
        if bridge.poll() is None:
            bridge.terminate()
        try:
            bridge.wait(20)
        except subprocess.TimeoutExpired:
            bridge.kill()
            bridge.wait()


def main(argv: list[str]) -> int:
    extra: list[str] = []
    if "--" in argv:
        argv, extra = argv[:argv.index("--")], argv[argv.index("--") + 1:]
    domain, commands = int(argv[0]), int(argv[1])
    every = int(argv[2]) if len(argv) > 2 else max(1, commands // 20)
    print(json.dumps(drive(domain, commands, every, extra)), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
