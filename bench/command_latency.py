"""Command-to-ack latency and throughput of the Python bridge, beside its floor (a bare
cyclonedds-python pong answering with the same acks) and `ddsperf ping`, in one run.

    .venv/bin/python bench/command_latency.py [--latency 2000] [--window 200] [--throughput 10000]
                                              [--flood 10000] [--profile] [--cprofile]

Everything stays on loopback: every process uses the generated package's "local" Cyclone
transport (127.0.0.1, no multicast), ddsperf too. Domains (default): the bridge with its
journal 57, the floor 60, ddsperf then the bridge --no-journal 61 (--domain D alone: D, D+1,
D+2). Prints figures, never passes or fails on time; exit 1 only when an ack was lost (or
something did not start); the flood's acks the door says it dropped (past its 4096 busy
answers, by design) are counted apart, not as lost.

  ddsperf     `ddsperf ping` against `ddsperf pong` (Cyclone C, Debian cyclonedds-tools; the
              cyclonedds wheel ships no ddsperf binary, only a UI that wraps one)
  floor       bench/python_pong.py: bare cyclonedds-python, K10's types, the bridge's topics
              and QoS, answering each command EXECUTING then COMPLETED/OK on one thread
  bridges     K10's bridge (--simulate), with its restart journal (a temporary folder on
              this machine's disk: one fdatasync per batch) and with --no-journal
  latency     N sequential Admin/noOp (BYPASS), from rapid_runtime.commander.Commander (the
              client `rapidgen cmd` uses): write() to the COMPLETED ack read. The three
              targets take turns in blocks of --block, so a busy moment of the machine hits
              all of them. The client's own share: its send() and the wake from the ack's
              arrival on its reader thread to wait_final's return, and its CPU a command
  throughput  N noOps with at most --window in flight (below the door's 256 a writer):
              commands/s from the first write to the last COMPLETED
  flood       N noOps written back to back: what the door answered ("bridge busy" past 256
              waiting from one writer), counted apart from the OK ones, and acks lost
  --profile   then a bridge with timestamps at each stage (bench/profiled_bridge.py):
              where a command's time goes; --cprofile adds cProfile's own-time table
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
import threading
import time
from datetime import datetime, timezone
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PYDIR = ROOT / "generated" / "k10" / "python"
PACKAGE = "rapid_k10red"
SOURCE = "RapidWorkbench"  # K10's allow-list lets it send everything
LOCAL = PYDIR / PACKAGE / "qos_files" / "cyclonedds" / "local.xml"
BUSY = "bridge busy"  # the door's answer (rapid_runtime/intake.py)


def percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(round(q / 100 * (len(ordered) - 1))))]


def load() -> str:
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def git_head() -> str:
    res = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    dirty = subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "--", "runtime/rapid_runtime", "bench"],
                           capture_output=True, text=True).stdout.strip()
    return res.stdout.strip() + (" (runtime or bench modified)" if dirty else "")


class Server:
    """A process that answers commands: the bridge or the floor; ready once it says so."""

    def __init__(self, name: str, argv: list[str], env: dict, ready: str) -> None:
        self.name = name
        self.err = tempfile.TemporaryFile(mode="w+")
        self.proc = subprocess.Popen(argv, cwd=PYDIR, env=env, stdout=subprocess.PIPE, stderr=self.err, text=True)
        line = self.proc.stdout.readline()
        if not line.startswith(ready):
            self.stop()
            self.err.seek(0)
            raise SystemExit(f"bench: {name} did not start: {line!r} {self.err.read()[-2000:]}")

    def stop(self) -> None:
        self.proc.terminate()
        try:
            self.proc.wait(30)
        except subprocess.TimeoutExpired:
            print(f"bench: {self.name} did not stop within 30 s of SIGTERM; killed", flush=True)
            self.proc.kill()
            self.proc.wait()

    def log(self) -> str:
        self.err.seek(0)
        return self.err.read()


def timed_commander(rapid, qos, domain: int):
    """The Commander, noting when each COMPLETED ack reached its reader thread (the client's
    wake is measured from there) and counting finals and the door's answers."""
    from rapid_runtime.acks import COMPLETED
    from rapid_runtime.commander import Commander

    class Timed(Commander):
        def __init__(self, *a, **kw) -> None:
            self.arrived: dict[str, int] = {}
            self.finals = self.busy = 0
            self.last_final = 0.0  # perf_counter() of the last COMPLETED
            super().__init__(*a, **kw)

        def _on_ack(self, sample) -> None:
            super()._on_ack(sample)
            if sample.status.name == COMPLETED and sample.cmdId not in self.arrived:
                self.arrived[sample.cmdId] = time.perf_counter_ns()
                with self.cond:
                    self.finals += 1
                    self.last_final = time.perf_counter()
                    if BUSY in sample.message:
                        self.busy += 1
                    self.cond.notify_all()

    c = Timed(rapid, qos, "K10Red", SOURCE, domain)
    if not c.wait_for_asset(20):
        raise SystemExit(f"bench: nothing answers on domain {domain}")
    return c


class Figures:
    def __init__(self) -> None:
        self.ms: list[float] = []
        self.send_us: list[float] = []
        self.wake_us: list[float] = []
        self.cpu = 0.0


def latency(c, n: int, fig: Figures | None, tag: str) -> None:
    from rapid_runtime.acks import COMPLETED
    for i in range(n):
        cpu0 = time.process_time()
        t0 = time.perf_counter_ns()
        cid = c.send("Admin", "noOp", cmd_id=f"{tag}-{i}-{os.getpid()}-{t0}")
        t1 = time.perf_counter_ns()
        acks = c.wait_final(cid, 5)
        t2 = time.perf_counter_ns()
        if fig is not None and acks and acks[-1][0] == COMPLETED:
            fig.ms.append((t2 - t0) / 1e6)
            fig.send_us.append((t1 - t0) / 1e3)
            fig.wake_us.append((t2 - c.arrived.get(cid, t2)) / 1e3)
            fig.cpu += time.process_time() - cpu0


def windowed(c, n: int, window: int, tag: str, timeout: float = 120) -> tuple[int, int, float]:
    """n noOps, at most `window` in flight: (finals, door's busy answers, seconds)."""
    base_f, base_b = c.finals, c.busy
    end = time.monotonic() + timeout
    t0 = time.perf_counter()
    sent = 0
    while sent < n:
        with c.cond:
            while sent - (c.finals - base_f) >= window and time.monotonic() < end:
                c.cond.wait(0.5)
        if time.monotonic() >= end:
            break
        c.send("Admin", "noOp", cmd_id=f"{tag}-{sent}-{os.getpid()}")
        sent += 1
    with c.cond:
        while c.finals - base_f < sent and time.monotonic() < end:
            c.cond.wait(0.5)
        got = c.finals - base_f
        return got, c.busy - base_b, (c.last_final if got else time.perf_counter()) - t0  # to the last answer


def ddsperf(seconds: float, domain: int, env: dict) -> dict | str:
    """`ddsperf ping` against `ddsperf pong` (both on the loopback config): its figures (us)."""
    import re
    exe = shutil.which("ddsperf")
    if exe is None:
        return "ddsperf not installed (apt: cyclonedds-tools; the cyclonedds wheel has none)"
    pong = subprocess.Popen([exe, "-D", str(seconds + 3), "-i", str(domain), "pong"], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        res = subprocess.run([exe, "-D", str(seconds), "-i", str(domain), "ping"], env=env,
                             capture_output=True, text=True, timeout=seconds + 30)
    finally:
        pong.terminate()
        pong.wait(10)
    lines = [ln for ln in res.stdout.splitlines() if "mean" in ln and "%" in ln]
    if not lines:
        return f"no latency line (exit {res.returncode}): {res.stdout[-300:]!r}"
    return {k: float(v) for k, v in re.findall(r"(mean|min|50%|90%|99%|max)\s+([\d.]+)us", lines[-1])}


def profile_report(path: Path, client_arrived: dict[str, int]) -> None:
    doc = json.loads(path.read_text())
    stamps, syncs = doc["stamps"], sorted(doc["syncs"])
    import bisect
    starts = [s[0] for s in syncs]
    rows: dict[str, list[float]] = {}

    def put(what: str, a: int | None, b: int | None) -> None:
        if a is not None and b is not None:
            rows.setdefault(what, []).append((b - a) / 1e3)
    for cid, s in stamps.items():
        if "ack1c" not in s or "take0" not in s:
            continue
        put("client write -> bridge's take() (DDS in, reader thread's wake)", s.get("sent"), s["take0"])
        put("take(): raw take and decode (a batch)", s["take0"], s["take1"])
        put("sample -> Cmd, to the door", s["take1"], s.get("offered"))
        put("door -> receive() (inline, or the intake thread's wake)", s.get("offered"), s.get("recv0"))
        put("receive(): checks, noOp, journal records written", s.get("recv0"), s.get("recv1"))
        i = bisect.bisect_left(starts, s.get("recv1", 0))
        sync = syncs[i] if i < len(syncs) and syncs[i][1] <= s.get("ack0x", 0) else None
        if sync is not None:
            put("journal fdatasync (one per batch)", sync[0], sync[1])
        put("receive() returned -> EXECUTING write begins (sync, flush)", s.get("recv1"), s.get("ack0x"))
        put("EXECUTING ack write (make Ack, DDS write)", s.get("ack0x"), s.get("ack1x"))
        put("COMPLETED ack write", s.get("ack0c"), s.get("ack1c"))
        put("in the bridge: take() called -> COMPLETED written", s["take0"], s["ack1c"])
        put("COMPLETED written -> client's reader has it (DDS out, wake)", s["ack1c"],
            client_arrived.get(cid) if client_arrived.get(cid) else None)
    print("where the time goes (profiled bridge, journal on; medians and p90 over "
          f"{len(rows.get('take(): raw take and decode (a batch)', []))} commands, us):", flush=True)
    for what, v in rows.items():
        print(f"  {what:<64} p50 {percentile(v, 50):7.1f}   p90 {percentile(v, 90):7.1f}", flush=True)
    if doc.get("cprofile"):
        print("cProfile, all threads, by own time (s own, s cumulative, calls, function):", flush=True)
        for own, cum, calls, where in doc["cprofile"][:25]:
            print(f"  {own:8.3f} {cum:8.3f} {calls:8d}  {where}", flush=True)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--latency", type=int, default=2000, help="sequential commands timed, per target (default 2000)")
    p.add_argument("--block", type=int, default=200, help="commands per turn while the targets alternate")
    p.add_argument("--throughput", type=int, default=10000, help="commands with a window in flight (default 10000)")
    p.add_argument("--window", type=int, default=200, help="commands in flight for the throughput (default 200)")
    p.add_argument("--flood", type=int, default=10000, help="commands back to back, bridge with journal (0: none)")
    p.add_argument("--domain", type=int, help="the bridge with its journal (default 57)")
    p.add_argument("--floor-domain", type=int, help="the bare pong (default 60; with --domain D: D+1)")
    p.add_argument("--ddsperf-domain", type=int,
                   help="ddsperf, then the bridge --no-journal (default 61; with --domain D: D+2)")
    p.add_argument("--ddsperf-seconds", type=float, default=5, help="0 skips ddsperf")
    p.add_argument("--profile", action="store_true", help="then where a command's time goes in the bridge")
    p.add_argument("--cprofile", action="store_true", help="with --profile: cProfile's table too")
    p.add_argument("--json", type=Path, help="also write the figures there (bench/bridges.py reads them)")
    args = p.parse_args()
    out: dict = {"load_start": os.getloadavg()}
    if args.domain is None:
        args.domain, floor_d, second_d = 57, 60, 61
    else:
        floor_d, second_d = args.domain + 1, args.domain + 2
    args.floor_domain = floor_d if args.floor_domain is None else args.floor_domain
    args.ddsperf_domain = second_d if args.ddsperf_domain is None else args.ddsperf_domain
    env = dict(os.environ, CYCLONEDDS_URI=f"file://{LOCAL}",
               PYTHONPATH=os.pathsep.join([str(PYDIR), str(ROOT / "runtime"), os.environ.get("PYTHONPATH", "")]))
    os.environ["CYCLONEDDS_URI"] = env["CYCLONEDDS_URI"]  # before DDS starts in this process
    sys.path[:0] = [str(PYDIR), str(ROOT / "runtime")]
    import importlib
    rapid = importlib.import_module(f"{PACKAGE}.rapid")
    qos = importlib.import_module(f"{PACKAGE}.qos").RapidQos()
    print(f"commit {git_head()}, {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC; load average {load()}", flush=True)

    perf = None
    if args.ddsperf_seconds > 0:
        perf = ddsperf(args.ddsperf_seconds, args.ddsperf_domain, env)
        print(f"ddsperf ping (Cyclone C, loopback, {args.ddsperf_seconds:g} s): "
              + (f"p50 {perf['50%']:.1f} us, p99 {perf['99%']:.1f} us, max {perf['max']:.0f} us"
                 if isinstance(perf, dict) and "50%" in perf else str(perf)), flush=True)
    out["ddsperf"] = perf
    bridge = [sys.executable, "-m", f"{PACKAGE}.bridge", "--simulate"]
    lost = 0
    with tempfile.TemporaryDirectory(prefix="rapidgen-bench-py-") as tmp:
        servers = {
            "floor (bare cyclonedds-python pong)": Server(
                "the floor", [sys.executable, str(ROOT / "bench" / "python_pong.py"), "--domain",
                              str(args.floor_domain)], env, "pong ready"),
            "Python bridge, journal on": Server(
                "the bridge", [*bridge, "--domain", str(args.domain), "--journal", str(Path(tmp) / "j")], env,
                "bridge ready"),
            "Python bridge, --no-journal": Server(
                "the bridge --no-journal", [*bridge, "--domain", str(args.ddsperf_domain), "--no-journal"], env,
                "bridge ready"),
        }
        domains = [args.floor_domain, args.domain, args.ddsperf_domain]
        try:
            clients = {name: timed_commander(rapid, qos, d) for name, d in zip(servers, domains)}
            for name, c in clients.items():
                if "bridge" in name and c.wait_final(c.send("AccessControl", "requestControl"), 10)[-1][1] \
                        != "ACK_COMPLETED_OK":
                    raise SystemExit("bench: control not granted")
                latency(c, 50, None, "warm")
            figs = {name: Figures() for name in clients}
            done = 0
            while done < args.latency:  # the targets take turns
                step = min(args.block, args.latency - done)
                for name, c in clients.items():
                    latency(c, step, figs[name], "lat")
                done += step
            floor = percentile(figs["floor (bare cyclonedds-python pong)"].ms, 50)
            out["latency"] = {name: {"p50_ms": percentile(f.ms, 50), "p99_ms": percentile(f.ms, 99),
                                     "max_ms": max(f.ms), "answered": len(f.ms), "count": args.latency,
                                     "client_send_us": percentile(f.send_us, 50),
                                     "client_wake_us": percentile(f.wake_us, 50),
                                     "client_cpu_us": f.cpu / len(f.ms) * 1e6}
                              for name, f in figs.items() if f.ms}
            print(f"\nsequential noOps, {args.latency} each, in turns of {args.block} (load {load()}):", flush=True)
            print("  answered: " + "; ".join(f"{name} ({len(f.ms)} of {args.latency} sequential noOps)"
                                          for name, f in figs.items()), flush=True)
            print(f"  {'':<38}{'p50 ms':>8}{'p99 ms':>8}{'max ms':>8}{'/floor':>8}{'one at a time':>15}", flush=True)
            for name, f in figs.items():
                if not f.ms:
                    print(f"  {name:<38} no answers", flush=True)
                    continue
                print(f"  {name:<38}{percentile(f.ms, 50):8.3f}{percentile(f.ms, 99):8.3f}{max(f.ms):8.2f}"
                      f"{percentile(f.ms, 50) / floor:7.2f}x{len(f.ms) / (sum(f.ms) / 1000):11.0f}/s", flush=True)
            if isinstance(perf, dict) and "50%" in perf:
                print(f"  (ddsperf p50 {perf['50%'] / 1000:.3f} ms: the floor is "
                      f"{floor * 1000 / perf['50%']:.0f}x it)", flush=True)
            print("the client's own share (p50 us: its send(); COMPLETED on its reader thread -> wait_final "
                  "returned; its CPU a command):", flush=True)
            for name, f in figs.items():
                if f.ms:
                    print(f"  {name:<38} send {percentile(f.send_us, 50):5.0f}, wake {percentile(f.wake_us, 50):5.0f}, "
                          f"CPU {f.cpu / len(f.ms) * 1e6:5.0f}", flush=True)
            if args.throughput:
                print(f"\nthroughput: {args.throughput} noOps, at most {args.window} in flight (load {load()}):",
                      flush=True)
                for name, c in clients.items():
                    got, busy, secs = windowed(c, args.throughput, args.window, "thr")
                    lost += args.throughput - got
                    out.setdefault("throughput", {})[name] = {"per_s": got / secs, "final": got, "busy": busy,
                                                              "count": args.throughput, "window": args.window}
                    print(f"  {name:<38}{got / secs:8.0f} commands/s; {got} of {args.throughput} final"
                          + (f" ({busy} 'bridge busy' from the door)" if busy else "")
                          + (f", {args.throughput - got} lost" if got < args.throughput else ""), flush=True)
            if args.flood:
                name = "Python bridge, journal on"
                c = clients[name]
                got, busy, secs = windowed(c, args.flood, args.flood, "flood", timeout=max(60.0, args.flood / 50))
                door = [ln.split("] ", 1)[-1][:140] for ln in servers[name].log().splitlines() if "floods" in ln]
                dropped = any("dropping" in ln for ln in door)  # by design: past its 4096 busy answers
                if not dropped:
                    lost += args.flood - got
                out["flood"] = {"count": args.flood, "final": got, "busy": busy, "per_s": got / secs,
                                "door_dropped": dropped}
                print(f"\nflood: {args.flood} noOps back to back to the {name}: {got} COMPLETED acks received, "
                      f"{args.flood - got} " + ("dropped unanswered by the door (past 4096 busy answers)"
                                                  if dropped else "lost") + f"; {got - busy} OK, "
                      f"{busy} answered 'bridge busy' by the door (past 256 waiting); "
                      f"{got / secs:.0f} answers/s, {(got - busy) / secs:.0f} OK/s"
                      + (f"; the door said: {'; '.join(door)}" if door else ""), flush=True)
            for c in clients.values():
                c.close()
        finally:
            for s in servers.values():
                s.stop()
        if args.profile:
            stamps = Path(tmp) / "profile.json"
            argv = [sys.executable, str(ROOT / "bench" / "profiled_bridge.py"), str(stamps),
                    *(["--cprofile"] if args.cprofile else []), "--", "--simulate", "--domain", str(args.domain),
                    "--journal", str(Path(tmp) / "jp")]
            s = Server("the profiled bridge", argv, env, "bridge ready")
            try:
                c = timed_commander(rapid, qos, args.domain)
                c.wait_final(c.send("AccessControl", "requestControl"), 10)
                latency(c, 50, None, "warm")
                f = Figures()
                latency(c, args.latency, f, "prof")
                c.close()
            finally:
                s.stop()
            print(f"\nprofiled bridge (journal on; the probes cost a little): p50 {percentile(f.ms, 50):.3f} ms "
                  f"over {len(f.ms)} sequential noOps", flush=True)
            profile_report(stamps, c.arrived)
    print(f"load average at the end: {load()}", flush=True)
    if args.json:
        out["load_end"] = os.getloadavg()
        args.json.write_text(json.dumps(out))
    return 1 if lost else 0


if __name__ == "__main__":
    sys.exit(main())
