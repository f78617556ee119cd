"""A live rapidgen tool run in this process on a secured domain, then what of DDS is left of
it: `unshare -n python -m tests.secure.refused_exit TOOL ENCLAVE DOMAIN ASSET.yaml` (a private
network namespace: loopback only, brought up here). TOOL: conform, cmd (AccessControl
requestControl as RapidWorkbench), spy (the overview, 2 s, beside a granted `rapidgen cmd`
in another process: peer()) or spy-echo (rapid_position_sample, 1 s); the first two are what
DDS Security refuses to a watch-only or audit-only enclave.

Prints one JSON object, {"code": the command's exit code, "threads": the names of this
process's threads other than the main one}, and exits with the command's code. Threads left
after the command returned are Cyclone's: its participant was left to the garbage collector,
and a domain's threads that outlive the interpreter's finalization crashed the process at exit
(runtime/rapid_runtime/teardown.py)."""
from __future__ import annotations

import json
import os
import subprocess
import sys


def _other_threads() -> list[str]:
    pid = os.getpid()
    names = []
    for tid in sorted(os.listdir("/proc/self/task"), key=int):
        if int(tid) != pid:
            with open(f"/proc/self/task/{tid}/comm", encoding="utf-8") as fh:
                names.append(fh.read().strip())
    return names


def argv(tool: str, enclave: str, domain: str, asset: str) -> list[str]:
    common = ["--domain", domain, "--enclave", enclave]
    if tool == "conform":
        return ["conform", asset, "--timeout", "5", *common]
    if tool == "cmd":  # no asset runs here: a granted enclave waits 1 s and finds none
        return ["cmd", asset, "AccessControl", "requestControl", "--source", "RapidWorkbench", "--timeout", "1",
                "--discover", "0.5", *common]
    if tool == "spy":
        return ["spy", "--asset", asset, "--seconds", "2", "--once", "--json", *common]
    if tool == "spy-echo":
        return ["spy", "echo", "rapid_position_sample", "--asset", asset, "--seconds", "1", "--json", *common]
    raise SystemExit(f"unknown tool {tool!r}")


def peer(enclaves: str, domain: str, asset: str) -> subprocess.Popen:
    """A granted `rapidgen cmd` in another process, waiting for an asset that never comes: its
    command writer and ack reader are what the spy opens readers for (a participant with
    readers of its own is what the collector left undeleted). Returned once its writer
    exists: it says so (no CommandConfig) after making it."""
    proc = subprocess.Popen([sys.executable, "-m", "rapidgen", "cmd", asset, "AccessControl", "requestControl",
                             "--source", "RapidWorkbench", "--domain", domain, "--timeout", "60", "--discover",
                             "0.01", "--enclave", os.path.join(enclaves, "RapidWorkbench")],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    assert proc.stderr is not None
    line = proc.stderr.readline()
    if "no CommandConfig" not in line:
        proc.kill()
        raise SystemExit(f"the peer did not start: {line}{proc.stderr.read()}")
    return proc


def main() -> int:
    tool, enclave, domain, asset = sys.argv[1:5]
    subprocess.run(["ip", "link", "set", "lo", "up"], check=True)
    other = peer(os.path.dirname(os.path.normpath(enclave)), domain, asset) if tool == "spy" else None
    from rapidgen.cli import main as rapidgen
    try:
        code = rapidgen(argv(tool, enclave, domain, asset))
    finally:
        if other is not None:
            other.kill()
            other.wait()
    sys.stdout.flush()
    print(json.dumps({"code": code, "threads": _other_threads()}), flush=True)
    return code


if __name__ == "__main__":
    sys.exit(main())
