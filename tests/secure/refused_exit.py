"""A `rapidgen conform` that DDS Security refuses, run in this process, then what of DDS is
left of it: `unshare -n python -m tests.secure.refused_exit ENCLAVE DOMAIN ASSET.yaml` (a
private network namespace: loopback only, brought up here).

Prints one JSON object, {"code": the command's exit code, "threads": the names of this
process's threads other than the main one}, and exits with the command's code. Threads left
after the command returned are Cyclone's: its participant was left to the garbage collector,
and a domain's threads that outlive the interpreter's finalization crashed the process at exit
(rapidgen/live/teardown.py)."""
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


def main() -> int:
    enclave, domain, asset = sys.argv[1:4]
    subprocess.run(["ip", "link", "set", "lo", "up"], check=True)
    from rapidgen.cli import main as rapidgen
    code = rapidgen(["conform", asset, "--domain", domain, "--timeout", "5", "--enclave", enclave])
    print(json.dumps({"code": code, "threads": _other_threads()}), flush=True)
    return code


if __name__ == "__main__":
    sys.exit(main())
