"""A 1 kHz JointSample setpoint stream (64 joints) looped back through a consuming bridge
(issue 21's must-show): two generated C++ bridges on loopback, Pilot64 writing its output
stream `setpoints` at 1 kHz, Arm64 reading it as an input stream (bench/setpoint/*.yaml),
each with a few lines of bench code in its handlers.cpp (bench/setpoint/code.py) and a
per-thread heap allocation counter linked in (bench/setpoint/alloc_count.cpp).

    python bench/setpoint_stream.py [--samples 10000] [--domain 96]

Prints, after a warm-up of 1000 samples:
  period jitter    |arrival interval - 1 ms| at the reader: p50, p99, max
  writer wake-up   how late clock_nanosleep returned at the writer: p50, p99, max
  latency          write (hdr.timeStamp, us) to the typed callback (CLOCK_REALTIME): p50, p99
  missed deadlines the reader's DEADLINE (3 ms) misses the runtime counted
  allocations      heap allocations per sample on the reader's receive thread (reception,
                   take into the reused sample, callback) and on the writer's thread (fill,
                   stamp, serialize, send)
  samples lost     serials (hdr.serial) the reader never saw
Not a test: figures depend on the machine's load (bench/README.md).
"""
from __future__ import annotations

import argparse
import os
import re
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from bench.setpoint import code  # noqa: E402
from tests.runtime.live import BridgeProcess  # noqa: E402
from tests.streams import harness  # noqa: E402

HERE = ROOT / "bench" / "setpoint"
WARMUP = 1000
PERIOD_NS = 1_000_000
DEADLINE_NS = 3_000_000


def pct(xs: list[float], p: float) -> float:
    s = sorted(xs)
    return s[min(len(s) - 1, int(round(p / 100 * (len(s) - 1))))]


def read(path: Path) -> tuple[int, list[list[int]]]:
    lines = path.read_text().splitlines()
    rt = int(lines[0].split()[1])
    return rt, [[int(x) for x in line.split()] for line in lines[1:]]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--samples", type=int, default=10000)
    ap.add_argument("--domain", type=int, default=96)
    args = ap.parse_args()
    missing = harness.toolchain_missing()
    if missing:
        print(missing, file=sys.stderr)
        return 1
    t0 = time.monotonic()
    progs = harness.build({HERE / "arm.yaml": code.ARM, HERE / "pilot.yaml": code.PILOT},
                          alloc_count=HERE / "alloc_count.cpp")
    print(f"built in {time.monotonic() - t0:.0f} s", file=sys.stderr)
    out = Path(tempfile.mkdtemp(prefix="setpoint-"))
    env = dict(harness.dds_env(), SETPOINT_SAMPLES=str(args.samples), SETPOINT_READER_OUT=str(out / "reader"),
               SETPOINT_WRITER_OUT=str(out / "writer"))
    limit = str(args.samples / 1000 + 60)
    reader = BridgeProcess.of_command([str(progs["arm"]), "--domain", str(args.domain), "--seconds", limit], ROOT, env)
    reader.wait_ready()
    writer = BridgeProcess.of_command([str(progs["pilot"]), "--domain", str(args.domain), "--seconds", limit],
                                      ROOT, env)
    writer.wait_ready()
    time.sleep((args.samples + WARMUP + 500) / 1000)
    log = reader.stop()  # the reader first: no deadline is missed because the writer stopped
    writer.stop()
    rt_r, rec = read(out / "reader")
    rt_w, wrec = read(out / "writer")
    steady = rec[WARMUP:WARMUP + args.samples]
    if len(steady) < args.samples // 2:
        print(f"only {len(rec)} samples arrived", file=sys.stderr)
        return 1
    jitter = [abs((b[0] - a[0]) - PERIOD_NS) / 1000 for a, b in zip(steady, steady[1:])]
    latency = [(r[1] - r[2] * 1000) / 1000 for r in steady]
    allocs = steady[-1][3] - steady[0][3]
    lost = (steady[-1][4] - steady[0][4] + 1) - len(steady)  # serials the reader never saw
    first, last = steady[0][4], steady[-1][4]
    wsteady = [w for w in wrec if first <= w[4] <= last]
    wake = [(w[0] - w[1]) / 1000 for w in wsteady]
    wallocs = wsteady[-1][3] - wsteady[0][3]
    gaps = sum(int((b[0] - a[0]) // DEADLINE_NS) for a, b in zip(steady, steady[1:]))
    missed = [int(m.group(1)) for m in re.finditer(r"stream setpoints: \d+ samples, (\d+) deadlines missed", log)]
    n = len(steady)
    print(f"1 kHz JointSample setpoint stream, 64 joints (anglePos, angleVel, torque), loopback, "
          f"{n} samples after {WARMUP} of warm-up; SCHED_FIFO granted: reader {bool(rt_r > 0)}, writer {bool(rt_w > 0)}")
    print(f"  period jitter at the reader  p50 {pct(jitter, 50):.1f} us  p99 {pct(jitter, 99):.1f} us  "
          f"max {max(jitter):.1f} us")
    print(f"  writer wake-up lateness      p50 {pct(wake, 50):.1f} us  p99 {pct(wake, 99):.1f} us  max {max(wake):.1f} us")
    print(f"  end-to-end latency           p50 {pct(latency, 50):.1f} us  p99 {pct(latency, 99):.1f} us  "
          f"max {max(latency):.1f} us  (hdr.timeStamp has 1 us resolution)")
    print(f"  samples lost                 {lost} of {last - first + 1} written in the window")
    print(f"  missed deadlines (3 ms)      {gaps} in the window (gaps of 3 ms or more); the runtime counted "
          f"{missed[-1] if missed else '?'} in the whole run, start-up included")
    print(f"  heap allocations per sample  reader receive thread {allocs / n:.3f} ({allocs} in {n}), "
          f"writer thread {wallocs / len(wsteady):.3f} ({wallocs} in {len(wsteady)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
