"""Both bridges beside their own floors, in one run: the Python bridge beside a bare
cyclonedds-python pong (bench/command_latency.py), the C++ bridge beside bare Fast DDS's
echo shape (bench/cpp_bridge.py), both beside ddsperf; then one table.

    .venv/bin/python bench/bridges.py [--latency 2000] [--cpp-latency 10000] [--flood 10000]
                                      [--profile] [--build /tmp/rapidgen-bench-cpp]

Runs the two scripts one after the other (their own output streams through) with --json,
and prints their figures side by side with the goals of issue 40: Python bridge, journal
on, p50 <= 1.3x its floor and >= 5000 commands/s with a window in flight; C++ bridge p50
<= 1.2x bare Fast DDS's echo shape (2 acks, main thread waits), journal on <= 1.5x, max
< 5 ms over --cpp-latency sequential commands. Domains: the Python part 57, 60, 61; the C++
part 63 (bridge), 61 (ddsperf), 60 (Fast DDS floor), one after the other. Load averages
beside: the machine may be shared.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent


def cell(p50, p99, mx, unit="us") -> str:
    f = (lambda v: f"{v:.0f}") if unit == "us" else (lambda v: f"{v:.3f}")
    return f"{f(p50)} / {f(p99)} / {f(mx)} {unit}"


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--latency", type=int, default=2000, help="the Python part's sequential commands per target")
    p.add_argument("--cpp-latency", type=int, default=10000, help="the C++ part's sequential commands")
    p.add_argument("--flood", type=int, default=10000)
    p.add_argument("--throughput", type=int, default=10000)
    p.add_argument("--profile", action="store_true", help="the Python bridge's stages too")
    p.add_argument("--build", default="/tmp/rapidgen-bench-cpp")
    args = p.parse_args()
    rc = 0
    with tempfile.TemporaryDirectory(prefix="rapidgen-bench-both-") as tmp:
        py, cpp = Path(tmp) / "py.json", Path(tmp) / "cpp.json"
        rc |= subprocess.run([sys.executable, str(HERE / "command_latency.py"), "--latency", str(args.latency),
                              "--throughput", str(args.throughput), "--flood", str(args.flood), "--json", str(py),
                              *(["--profile"] if args.profile else [])]).returncode
        rc |= subprocess.run([sys.executable, str(HERE / "cpp_bridge.py"), "--latency", str(args.cpp_latency),
                              "--flood", str(args.flood), "--rss", "0", "--domain", "63", "--ddsperf-domain", "61",
                              "--floor-domain", "60", "--build", args.build, "--json", str(cpp)]).returncode
        a = json.loads(py.read_text()) if py.exists() else {}
        b = json.loads(cpp.read_text()) if cpp.exists() else {}
    print("\n== both bridges beside their floors (p50 / p99 / max) ==")
    loads = [x for d in (a, b) for k in ("load_start", "load_end") for x in [d.get(k)] if x]
    print("load average (1 min) over the runs: " + ", ".join(f"{x[0]:.2f}" for x in loads))
    for name, d in (("Python part", a), ("C++ part", b)):
        perf = d.get("ddsperf")
        if isinstance(perf, dict) and "50%" in perf:
            print(f"  ddsperf ping (Cyclone C), {name}'s run: {cell(perf['50%'], perf['99%'], perf['max'])}")
        elif perf:
            print(f"  ddsperf: {perf}")
    lat = a.get("latency", {})
    floor = lat.get("floor (bare cyclonedds-python pong)")
    for name, f in lat.items():
        ratio = f"{f['p50_ms'] / floor['p50_ms']:.2f}x the floor" if floor else ""
        goal = "  (goal <= 1.3x)" if "journal on" in name else ""
        print(f"  {name:<38} {cell(f['p50_ms'], f['p99_ms'], f['max_ms'], 'ms'):>28}  {ratio}{goal}")
    for name, t in a.get("throughput", {}).items():
        print(f"  {name:<38} {t['per_s']:8.0f} commands/s with {t['window']} in flight"
              + ("  (goal >= 5000/s)" if "journal on" in name else ""))
    fl = a.get("flood")
    if fl:
        print(f"  flood of {fl['count']} to the Python bridge: {fl['final']} answered, {fl['busy']} of them "
              f"'bridge busy' from the door, {fl['count'] - fl['final']} "
              + ("dropped unanswered by the door" if fl.get("door_dropped") else "lost"))
    echo = b.get("floors", {}).get("2 main")
    if isinstance(echo, dict):
        print(f"  {'bare Fast DDS, echo shape (2 acks)':<38} {cell(echo['p50_us'], echo['p99_us'], echo['max_us']):>28}")
    for key, goal in (("bridge", "1.2x"), ("journal", "1.5x")):
        f = b.get(key)
        if isinstance(f, dict):
            ratio = f"{f['p50_us'] / echo['p50_us']:.2f}x the floor" if isinstance(echo, dict) else ""
            label = "C++ bridge, --no-journal" if key == "bridge" else "C++ bridge, journal on"
            print(f"  {label:<38} {cell(f['p50_us'], f['p99_us'], f['max_us']):>28}  {ratio}  (goal <= {goal}"
                  + (", max < 5 ms" if key == "bridge" else "") + f"; {f['answered']} of {f['count']})")
    fl = b.get("flood")
    if fl:
        print(f"  flood of {fl['sent']} to the C++ bridge: {fl['final']} final ({fl['ok']} OK), {fl['lost']} lost")
    return rc


if __name__ == "__main__":
    sys.exit(main())
