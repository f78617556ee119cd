"""The ground side of the C++ bridge's restart tests (tests/cpp_runtime/test_restart.py), run
as its own process. The Python ground of tests/field/restart_ground.py, unchanged, drives the
Restarter asset's C++ bridge (tests/cpp_runtime/restarter/handlers.cpp: Worker/work appends
each cmdId it runs to $RESTART_EXECFILE) instead of the Python one.

    python -m tests.cpp_runtime.restart_ground kills BRIDGE PYDIR WORKDIR DOMAIN COMMANDS KILLS SEED
    python -m tests.cpp_runtime.restart_ground cross BRIDGE PYDIR WORKDIR DOMAIN   (DOMAIN and DOMAIN + 1)

kills: restart_ground.run's JSON document, plus "crashes" (bridge stderr lines of an abort,
a sanitizer or a signal other than the test's kills).
cross: a long queued command running and one waiting behind it when one runtime's bridge is
killed (SIGKILL); the other runtime's bridge is started on the same journal and answers them.
Both ways (C++ then Python, Python then C++); one JSON document with each way's final acks,
executions and journal log lines.
"""
from __future__ import annotations

import importlib
import json
import os
import subprocess
import sys
import threading
import time
from pathlib import Path

import tests.field.restart_ground as G
from tests.field.restart_asset import ASSET, PACKAGE, ROOT, env_for

CRASH_WORDS = ("terminate called", "Sanitizer", "Segmentation fault", "Aborted", "core dumped")


def cpp_env(pydir: Path, work: Path) -> dict:
    """The C++ bridge's environment: its built-in loopback profiles (no Fast DDS profile
    variables), the handler's execution file."""
    env = {k: v for k, v in env_for(pydir).items() if not k.startswith(("FASTDDS_", "FASTRTPS_"))}
    env["RESTART_EXECFILE"] = str(work / "executions")
    return env


def cpp_bridge_class(exe: str) -> type:
    class CppBridge(G.Bridge):
        def __init__(self, pydir: Path, work: Path, domain: int) -> None:
            super().__init__(pydir, work, domain)
            self.argv = [exe, "--domain", str(domain), "--journal", str(work / "journal")]
            self.env = cpp_env(pydir, work)
    return CppBridge


def kills(exe: str, pydir: Path, work: Path, domain: int, commands: int, n: int, seed: int) -> dict:
    G.Bridge = cpp_bridge_class(exe)  # run() and main()'s clean-up make their bridges from the module's name
    try:
        got = G.run(pydir, work, domain, commands, n, seed)
        got["crashes"] = [ln.rstrip() for b in G.Bridge.made for ln in b.logs if any(w in ln for w in CRASH_WORDS)]
        return got
    finally:
        G.Bridge.closing = True
        for b in G.Bridge.made:
            if b.proc is not None and b.proc.poll() is None:
                b.proc.kill()
                b.proc.wait()


# ---- cross: one runtime's journal read by the other ----------------------------------------------

class Proc:
    def __init__(self, argv: list[str], env: dict) -> None:
        self.proc = subprocess.Popen(argv, cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.logs: list[str] = []
        threading.Thread(target=lambda: self.logs.extend(self.proc.stderr or ()), daemon=True).start()
        line = self.proc.stdout.readline() if self.proc.stdout else ""
        if not line.startswith("bridge ready"):
            self.proc.kill()
            time.sleep(0.3)
            raise SystemExit(f"restart_ground: bridge did not start: {argv[0]} {line!r} {''.join(self.logs)[-2000:]}")
        threading.Thread(target=lambda: [None for _ in self.proc.stdout or ()], daemon=True).start()


def cross(exe: str, pydir: Path, work: Path, domain: int) -> dict:
    env = env_for(pydir)
    os.environ["CYCLONEDDS_URI"] = env["CYCLONEDDS_URI"]
    sys.path.insert(0, str(pydir))
    rapid = importlib.import_module(f"{PACKAGE}.rapid")
    qos = importlib.import_module(f"{PACKAGE}.qos").RapidQos()
    from rapid_runtime.commander import Commander

    def start(kind: str, folder: Path, domain: int) -> Proc:
        if kind == "cpp":
            return Proc([exe, "--domain", str(domain), "--journal", str(folder / "journal")], cpp_env(pydir, folder))
        return Proc([sys.executable, "-m", "tests.field.restart_bridge", str(pydir), str(folder / "executions"),
                     "--domain", str(domain), "--journal", str(folder / "journal")], env)

    out: dict = {}
    procs: list[Proc] = []
    try:
        # a domain each: the first way's commander lives on, and a Fast DDS reader that joins
        # late is sent what a Cyclone writer still holds (seen here: the C++ bridge started
        # second got the first way's two commands again)
        for (first, second), domain in ((("cpp", "py"), domain), (("py", "cpp"), domain + 1)):
            folder = work / f"{first}-then-{second}"
            folder.mkdir(parents=True)
            procs.append(start(first, folder, domain))
            c = Commander(rapid, qos, ASSET, "RapidGround", domain)
            if not c.wait_for_asset(G.READY):
                raise SystemExit("restart_ground: no bridge matched")
            long_id, next_id = f"{first}-long", f"{first}-next"
            c.send("Belt", "work", [("RAPID_INT", 8000)], action="QUEUE_APPEND", cmd_id=long_id)
            c.send("Belt", "work", [("RAPID_INT", 100)], action="QUEUE_APPEND", cmd_id=next_id)
            end = time.monotonic() + 30
            execs = folder / "executions"
            with c.cond:  # the long one running (its handler started), the other one queued behind it
                while not (any(a[0] == "ACK_QUEUED" for a in c.acks.get(next_id, ())) and execs.exists() and
                           long_id in execs.read_text().split()) and time.monotonic() < end:
                    c.cond.wait(0.05)
            procs[-1].proc.kill()
            procs[-1].proc.wait()
            procs.append(start(second, folder, domain))
            finals = {cid: c.wait_final(cid, 30) for cid in (long_id, next_id)}
            c.close()
            procs[-1].proc.terminate()
            code = procs[-1].proc.wait(20)
            time.sleep(0.3)  # the stderr pump's last lines
            out[f"{first}-then-{second}"] = {
                "finals": {cid: next((list(a) for a in acks if a[0] == "ACK_COMPLETED"), None)
                           for cid, acks in finals.items()},
                "runs": execs.read_text().split() if execs.exists() else [], "stop_code": code,
                "logs": [ln.rstrip() for p in procs[-2:] for ln in p.logs if "journal" in ln or "Traceback" in ln or
                         any(w in ln for w in CRASH_WORDS)]}
    finally:
        for p in procs:
            if p.proc.poll() is None:
                p.proc.kill()
                p.proc.wait()
    return out


def main(argv: list[str]) -> int:
    mode, exe, pydir, work = argv[0], argv[1], Path(argv[2]), Path(argv[3])
    if mode == "kills":
        domain, commands, n, seed = (int(a) for a in argv[4:8])
        print(json.dumps(kills(exe, pydir, work, domain, commands, n, seed)), flush=True)
    else:
        print(json.dumps(cross(exe, pydir, work, int(argv[4]))), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
