"""One secured scenario, run inside a private network namespace (`unshare -n python -m
tests.secure.scenario SPEC.json`): loopback only, so DDS never leaves this host and a raw
socket on `lo` sees every packet of the run.

SPEC: {"bridge": [argv...], "bridge_env": {...}, "ready_s": 20,
       "cases": {name: {"argv": [...], "env": {...}}},     run together, after the bridge is ready
       "watch": {"argv": [...], "env": {...}} | null,       run after the cases
       "capture": bool}
Prints one JSON object: the bridge's exit status and output, each case's and the watcher's,
and with capture the bytes seen on lo (hex) and the packet count."""
from __future__ import annotations

import json
import os
import select
import signal
import socket
import subprocess
import sys
import threading
import time

ETH_P_ALL = 0x0003


def _capture(stop: threading.Event, out: list[bytes]) -> threading.Thread:
    sock = socket.socket(socket.AF_PACKET, socket.SOCK_RAW, socket.htons(ETH_P_ALL))
    sock.bind(("lo", 0))
    sock.settimeout(0.2)

    def run() -> None:
        while not stop.is_set():
            try:
                out.append(sock.recv(70000))
            except TimeoutError:
                continue
        sock.close()
    t = threading.Thread(target=run, daemon=True)
    t.start()
    return t


def _env(extra: dict) -> dict:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("FASTDDS_", "FASTRTPS_", "RAPID_SECURITY_"))}
    env.update(extra)
    return env


def _result(p: subprocess.Popen, out: str, err: str) -> dict:
    # the log's first lines (a stream's first state) and its last (the summary): a loaded
    # machine's lost/recovered lines in between once pushed the first out of a plain tail
    if len(err) > 6000:
        err = err[:2000] + "\n[...]\n" + err[-4000:]
    return {"rc": p.returncode, "stdout": out, "stderr": err}


def main() -> int:
    spec = json.loads(open(sys.argv[1], encoding="utf-8").read())
    subprocess.run(["ip", "link", "set", "lo", "up"], check=True)
    packets: list[bytes] = []
    stop = threading.Event()
    cap = _capture(stop, packets) if spec.get("capture") else None
    result: dict = {"cases": {}}
    bridge = subprocess.Popen(spec["bridge"], env=_env(spec.get("bridge_env", {})), stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True)
    assert bridge.stdout is not None
    ready, seen = False, ""
    deadline = time.monotonic() + spec.get("ready_s", 20)
    while time.monotonic() < deadline and bridge.poll() is None:
        if select.select([bridge.stdout], [], [], 0.2)[0]:
            line = bridge.stdout.readline()
            seen += line
            if line.startswith("bridge ready"):
                ready = True
                break
    result["bridge_ready"] = ready
    if ready:
        procs = {name: subprocess.Popen(c["argv"], env=_env(c.get("env", {})), stdout=subprocess.PIPE,
                                        stderr=subprocess.PIPE, text=True) for name, c in spec["cases"].items()}
        for name, p in procs.items():
            out, err = p.communicate(timeout=120)
            result["cases"][name] = _result(p, out, err)
        w = spec.get("watch")
        if w:
            p = subprocess.Popen(w["argv"], env=_env(w.get("env", {})), stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, text=True)
            out, err = p.communicate(timeout=120)
            result["watch"] = _result(p, out, err)
    if bridge.poll() is None:
        bridge.send_signal(signal.SIGTERM)
    try:
        out, err = bridge.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        bridge.kill()
        out, err = bridge.communicate()
    result["bridge"] = _result(bridge, seen + out, err)
    if cap is not None:
        stop.set()
        cap.join(timeout=5)
        result["packets"] = len(packets)
        result["wire"] = b"".join(packets).hex()
    json.dump(result, sys.stdout)
    return 0


if __name__ == "__main__":
    sys.exit(main())
