"""Command-to-ack latency and throughput of the Python bridge, beside `ddsperf ping`.

    .venv/bin/python bench/command_latency.py [--latency 2000] [--flood 10000] [--domain 77]

Everything stays on loopback: the bridge and this process use the generated package's
"local" Cyclone transport (127.0.0.1, no multicast), and so does ddsperf (Debian
cyclonedds-tools), given the same file. Prints figures, never passes or fails on time;
exit 1 only when an ack was lost (or the bridge did not start).

  latency  N sequential Admin/noOp (BYPASS): time from write() to the COMPLETED ack read
           by this process (round trip through the bridge's intake, checks and ack writer)
  flood    N noOps written back to back, then waited for: commands/s and acks lost
"""
from __future__ import annotations

import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PYDIR = ROOT / "generated" / "k10" / "python"
PACKAGE = "rapid_k10red"
SOURCE = "RapidWorkbench"  # K10's allow-list lets it send everything
LOCAL = PYDIR / PACKAGE / "qos_files" / "cyclonedds" / "local.xml"


def percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(round(q / 100 * (len(ordered) - 1))))]


def start_bridge(domain: int, env: dict) -> subprocess.Popen:
    proc = subprocess.Popen([sys.executable, "-m", f"{PACKAGE}.bridge", "--simulate", "--domain", str(domain)],
                            cwd=PYDIR, env=env, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    line = proc.stdout.readline()
    if not line.startswith("bridge ready"):
        proc.kill()
        raise SystemExit(f"bench: the bridge did not start: {line!r}")
    return proc


def latency(c, n: int) -> list[float]:
    from rapid_runtime.acks import COMPLETED
    out = []
    for i in range(n):
        t0 = time.perf_counter()
        cid = c.send("Admin", "noOp", cmd_id=f"lat-{i}-{os.getpid()}")
        acks = c.wait_final(cid, 5)
        if acks and acks[-1][0] == COMPLETED:
            out.append((time.perf_counter() - t0) * 1000)
    return out


def flood(c, n: int, timeout: float) -> tuple[int, float]:
    """(acks COMPLETED received, seconds from the first write to the last COMPLETED)."""
    from rapid_runtime.acks import COMPLETED
    ids = [f"flood-{i}-{os.getpid()}" for i in range(n)]
    t0 = time.perf_counter()
    for cid in ids:
        c.send("Admin", "noOp", cmd_id=cid)
    end = time.monotonic() + timeout
    with c.cond:
        while True:
            done = sum(1 for cid in ids if any(a[0] == COMPLETED for a in c.acks.get(cid, ())))
            if done == n or time.monotonic() >= end:
                return done, time.perf_counter() - t0
            c.cond.wait(0.2)


def ddsperf(seconds: float, domain: int, env: dict) -> str:
    """`ddsperf ping` against `ddsperf pong` (both on the loopback config): its latency line."""
    exe = shutil.which("ddsperf")
    if exe is None:
        return "ddsperf not installed (apt: cyclonedds-tools)"
    pong = subprocess.Popen([exe, "-D", str(seconds + 3), "-i", str(domain), "pong"], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        res = subprocess.run([exe, "-D", str(seconds), "-i", str(domain), "ping"], env=env,
                             capture_output=True, text=True, timeout=seconds + 30)
    finally:
        pong.terminate()
        pong.wait(10)
    lines = [ln for ln in res.stdout.splitlines() if "mean" in ln and "%" in ln]
    return lines[-1].strip() if lines else f"no latency line (exit {res.returncode}): {res.stdout[-300:]!r}"


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--latency", type=int, default=2000, help="sequential commands timed (default 2000)")
    p.add_argument("--flood", type=int, default=10000, help="commands sent back to back (default 10000)")
    p.add_argument("--domain", type=int, default=77)
    p.add_argument("--ddsperf-seconds", type=float, default=5, help="0 skips ddsperf")
    args = p.parse_args()
    env = dict(os.environ, CYCLONEDDS_URI=f"file://{LOCAL}",
               PYTHONPATH=os.pathsep.join([str(PYDIR), str(ROOT / "runtime"), os.environ.get("PYTHONPATH", "")]))
    os.environ["CYCLONEDDS_URI"] = env["CYCLONEDDS_URI"]  # before DDS starts in this process
    sys.path[:0] = [str(PYDIR), str(ROOT / "runtime")]
    import importlib
    rapid = importlib.import_module(f"{PACKAGE}.rapid")
    qos = importlib.import_module(f"{PACKAGE}.qos").RapidQos()
    from rapid_runtime.commander import Commander

    if args.ddsperf_seconds > 0:
        print(f"ddsperf ping (Cyclone C, loopback, {args.ddsperf_seconds:g} s): "
              f"{ddsperf(args.ddsperf_seconds, args.domain + 1, env)}", flush=True)
    bridge = start_bridge(args.domain, env)
    try:
        c = Commander(rapid, qos, "K10Red", SOURCE, args.domain)
        if not c.wait_for_asset(20):
            raise SystemExit("bench: no bridge matched")
        if c.wait_final(c.send("AccessControl", "requestControl"), 10)[-1][1] != "ACK_COMPLETED_OK":
            raise SystemExit("bench: control not granted")
        latency(c, min(50, args.latency))  # warm-up
        ms = latency(c, args.latency)
        print(f"python bridge, command -> COMPLETED ack ({len(ms)} of {args.latency} sequential noOps): "
              f"p50 {percentile(ms, 50):.3f} ms, p99 {percentile(ms, 99):.3f} ms, "
              f"mean {statistics.fmean(ms):.3f} ms, {len(ms) / (sum(ms) / 1000):.0f} commands/s one at a time",
              flush=True)
        got, seconds = flood(c, args.flood, timeout=max(60.0, args.flood / 50))
        lost = args.flood - got
        print(f"flood: {args.flood} noOps written back to back, {got} COMPLETED acks received, {lost} lost, "
              f"{got / seconds:.0f} commands/s", flush=True)
        c.close()
    finally:
        bridge.terminate()
        bridge.wait(20)
    return 1 if lost else 0


if __name__ == "__main__":
    sys.exit(main())
