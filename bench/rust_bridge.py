"""Command-to-ack latency, a flood and memory of K10's generated Rust bridge (rapid_dds on
Cyclone, through cyclors) beside K10's generated C++ bridge (Fast DDS) in the same run, both
driven by the same client (the C++ runtime's rapid_cmd), and `ddsperf ping` beside them.

    .venv/bin/python bench/rust_bridge.py [--latency 2000] [--flood 10000] [--rss 100000]
                                          [--build /tmp/rapidgen-bench-rust] [--domain 97]

Builds once in --build (kept: later runs are incremental), Release: what bench/cpp_bridge.py
builds (the C++ runtime, K10's C++ bridge and rapid_cmd), and K10's Rust bridge generated
(`rapidgen generate --lang rust`) into a one-crate Cargo workspace, `cargo build --release`
from rapid_dds's Cargo.lock. Everything stays on loopback: rapid_cmd and the C++ bridge use
the built-in rapid_local profile, the Rust bridge its built-in `local` transport
(CYCLONEDDS_URI unset), ddsperf ../shared/dds-local/cyclonedds-loopback.xml. Prints figures,
never passes or fails on time; exit 1 when an ack was lost.

  latency  N sequential Admin/echo (BYPASS, from the controller) to each bridge, in blocks
           that take turns (a busy moment of the machine hits both): write() to the final
           COMPLETED ack read by rapid_cmd; p50/p99/max, the Rust bridge's p50 over the C++
           bridge's (issue 38's goal: within 1.5x), with the bridges' CPU a command;
           `--no-journal` (the protocol path), then once more with the restart journal on
  flood    N echoes written back to back to the Rust bridge (rapid_cmd --flood): final acks,
           acks lost, what its door said
  rss      the Rust bridge's VmRSS after every tenth of N commands (256 in flight): flat?
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from datetime import datetime, timezone
from pathlib import Path

from cpp_bridge import (build as build_cpp, cpu_and_switches, ddsperf, echoes, flood_and_memory, git_head, run,
                        stop, take_control)

ROOT = Path(__file__).resolve().parents[1]
RUST = ROOT / "runtime" / "rust"
WORKSPACE = """[workspace]
resolver = "2"
members = ["generated/k10/rust/bridge"]
exclude = ["runtime", "generated/rapid"]
"""


def build_rust(out: Path) -> Path:
    """K10's Rust bridge, Release, built in out/rust (incremental)."""
    ws = out / "rust"
    if not ws.exists():
        (ws / "generated").mkdir(parents=True)
        (ws / "runtime").symlink_to(ROOT / "runtime")  # (the generated crates' paths to runtime/rust resolve)
        (ws / "generated" / "rapid").symlink_to(ROOT / "generated" / "rapid")
        (ws / "Cargo.toml").write_text(WORKSPACE, encoding="utf-8")
    run([sys.executable, "-m", "rapidgen", "generate", str(ROOT / "specs" / "assets" / "k10.yaml"), "--lang", "rust",
         "-o", str(ws / "generated" / "k10")], cwd=ROOT)
    shutil.copy(RUST / "rapid_dds" / "Cargo.lock", ws / "Cargo.lock")
    cargo = shutil.which("cargo") or str(Path.home() / ".cargo" / "bin" / "cargo")
    env = dict(os.environ, CARGO_TARGET_DIR=str(out / "rust-target"), CARGO_TERM_COLOR="never")
    if "LIBCLANG_PATH" not in env:
        for lib in sorted(Path("/usr/lib").glob("llvm-*/lib/libclang.so*"), reverse=True):
            env["LIBCLANG_PATH"] = str(lib.parent)
            break
    run([cargo, "build", "--release"], cwd=ws, env=env, timeout=3600)
    manifest = (ws / "generated" / "k10" / "rust" / "bridge" / "Cargo.toml").read_text(encoding="utf-8")
    name = next(json.loads(ln.split("=", 1)[1]) for ln in manifest.splitlines() if ln.startswith("name = "))
    return out / "rust-target" / "release" / name


def start(exe: Path, domain: int, env: dict, extra: list[str], tmp: Path, name: str) -> tuple[subprocess.Popen, Path]:
    """A bridge, ready (its first line says so); its stderr in a file (the door's lines)."""
    log = tmp / f"{name}.err"
    with log.open("w") as err:
        proc = subprocess.Popen([str(exe), "--domain", str(domain), *extra], env=env, stdout=subprocess.PIPE,
                                stderr=err, text=True)
    line = proc.stdout.readline()
    if "ready" not in line:
        stop(proc, name)
        raise SystemExit(f"bench: {name} did not start ({line!r}): {log.read_text()[-2000:]}")
    return proc, log


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--latency", type=int, default=2000, help="sequential commands timed per bridge (default 2000)")
    p.add_argument("--block", type=int, default=250, help="commands a bridge gets before the other's turn")
    p.add_argument("--flood", type=int, default=10000, help="commands sent back to back (default 10000)")
    p.add_argument("--rss", type=int, default=100000, help="commands for the memory figure (default 100000; 0: none)")
    p.add_argument("--build", type=Path, default=Path("/tmp/rapidgen-bench-rust"))
    p.add_argument("--domain", type=int, default=97, help="the bridges' DDS domain, one at a time (default 97)")
    p.add_argument("--ddsperf-domain", type=int, help="ddsperf's (default: --domain + 1)")
    p.add_argument("--ddsperf-seconds", type=float, default=5, help="0 skips ddsperf")
    p.add_argument("--json", type=Path, help="also write the figures there")
    args = p.parse_args()
    out: dict = {"load_start": os.getloadavg()}
    cpp_bridge, cmd, _ = build_cpp(args.build)
    rust_bridge = build_rust(args.build)
    # rapid_cmd and the C++ bridge: the built-in rapid_local profile; the Rust bridge: its built-in `local`
    env = {k: v for k, v in os.environ.items() if not k.startswith(("FASTDDS_", "FASTRTPS_")) and k != "CYCLONEDDS_URI"}
    print(f"commit {git_head()}, {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC", flush=True)
    print("load average at the start: " + " ".join(f"{x:.2f}" for x in os.getloadavg()), flush=True)

    def client(*extra: str) -> dict:
        return echoes(cmd, args.domain, env, *extra)

    perf = None
    if args.ddsperf_seconds > 0:
        perf = ddsperf(args.ddsperf_seconds, args.domain + 1 if args.ddsperf_domain is None else args.ddsperf_domain)
        print(f"ddsperf ping (Cyclone C, loopback, {args.ddsperf_seconds:g} s): {perf}", flush=True)
    out["ddsperf"] = perf
    bridges = {"C++": cpp_bridge, "Rust": rust_bridge}
    lost = 0
    with tempfile.TemporaryDirectory(prefix="rapidgen-bench-rust-") as tmp_name:
        tmp = Path(tmp_name)
        for label, flags in (("--no-journal", ["--no-journal"]), ("journal on", None)):
            # blocks taking turns: each block a fresh bridge process would cost a start, so
            # each bridge runs once, its blocks timed apart and pooled
            samples: dict[str, list[dict]] = {name: [] for name in bridges}
            cpu: dict[str, float] = {name: 0.0 for name in bridges}
            left = args.latency
            while left > 0:
                n = min(args.block, left)
                for name, exe in bridges.items():
                    extra = flags if flags is not None else ["--journal", str(tmp / f"journal-{name}")]
                    proc, _ = start(exe, args.domain, env, extra, tmp, f"{name}-{label}")
                    try:
                        take_control(cmd, args.domain, env)
                        client("--repeat", "20")  # warm-up
                        c0, _ = cpu_and_switches(proc.pid)
                        samples[name].append(client("--repeat", str(n)))
                        cpu[name] += cpu_and_switches(proc.pid)[0] - c0
                    finally:
                        stop(proc, f"the {name} bridge")
                left -= n
            got = {}
            for name, runs in samples.items():
                answered = sum(r["answered"] for r in runs)
                lost += sum(r["count"] - r["answered"] for r in runs)
                # (pooled medians of the blocks: rapid_cmd reports each block's percentiles)
                got[name] = {"p50_us": statistics.median(r["p50_us"] for r in runs),
                             "p99_us": max(r["p99_us"] for r in runs), "max_us": max(r["max_us"] for r in runs),
                             "answered": answered, "cpu_us": cpu[name] / max(1, answered) * 1e6}
                g = got[name]
                print(f"{name} bridge, {label}: command -> COMPLETED ack ({answered} sequential echoes, rapid_cmd, "
                      f"{len(runs)} blocks): p50 {g['p50_us']:.0f} us (median of the blocks'), p99 {g['p99_us']:.0f} "
                      f"us (the worst block's), max {g['max_us']:.0f} us; the bridge's CPU {g['cpu_us']:.0f} us a "
                      "command", flush=True)
            ratio = got["Rust"]["p50_us"] / got["C++"]["p50_us"]
            print(f"  Rust over C++, p50 ({label}): {ratio:.2f}x (goal: within 1.5x)"
                  + (f"; ddsperf's p50 {perf['50%']:.0f} us" if isinstance(perf, dict) and "50%" in perf else ""),
                  flush=True)
            out[label] = got
        proc, log = start(rust_bridge, args.domain, env, ["--no-journal"], tmp, "Rust-flood")
        try:
            take_control(cmd, args.domain, env)
            out["flood"], out["rss_kib"], flood_lost = flood_and_memory(client, log, proc.pid, args.flood, args.rss,
                                                                        "Rust bridge")
            lost += flood_lost
        finally:
            stop(proc, "the Rust bridge")
    print("load average at the end: " + " ".join(f"{x:.2f}" for x in os.getloadavg()), flush=True)
    if args.json:
        out["load_end"] = os.getloadavg()
        args.json.write_text(json.dumps(out))
    return 1 if lost else 0


if __name__ == "__main__":
    sys.exit(main())
