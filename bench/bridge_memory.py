"""Resident memory of the Python bridge under a long stream of commands.

    .venv/bin/python bench/bridge_memory.py [--commands 100000] [--domain 192] [--window N]

K10's bridge (runtime-answered Admin/noOp, no simulated telemetry) takes COMMANDS commands
from this process on loopback (the package's "local" Cyclone transport), at most 64
unanswered; its VmRSS and VmHWM are read from /proc as it goes (tests/runtime/memory_load.py).
Prints a line per tenth of the run and the growth after the command window filled (goal:
under 10 MB for 100,000 commands). Exit 1 only when commands went unanswered.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--commands", type=int, default=100_000)
    p.add_argument("--domain", type=int, default=192)
    p.add_argument("--window", type=int, default=None, help="the bridge's --command-window (default: its own, 4096)")
    args = p.parse_args()
    sys.path.insert(0, str(ROOT))
    from tests.runtime.memory_load import drive
    extra = [] if args.window is None else ["--command-window", str(args.window)]
    got = drive(args.domain, args.commands, max(1, args.commands // 10), extra)
    for n, rss, hwm in got["samples"]:
        print(f"{n:>8} commands: VmRSS {rss / 1024:6.1f} MiB, VmHWM {hwm / 1024:6.1f} MiB")
    samples = got["samples"]
    base = samples[min(2, len(samples) - 1)]  # past the window's filling (4096 commands by default)
    last = samples[-1]
    print(f"{got['answered']} of {args.commands} commands answered in {got['seconds']} s; "
          f"from {base[0]} to {last[0]} commands VmRSS grew {(last[1] - base[1]) / 1024:.1f} MiB, "
          f"VmHWM {(last[2] - base[2]) / 1024:.1f} MiB; in all since start VmRSS {(last[1] - samples[0][1]) / 1024:.1f} MiB")
    return 0 if got["answered"] == args.commands else 1


if __name__ == "__main__":
    sys.exit(main())
