"""Command-to-ack latency, throughput, a flood and memory of K10's generated C++ bridge
(Fast DDS), driven by the runtime's C++ client (rapid_cmd), beside `ddsperf ping` in the
same run.

    .venv/bin/python bench/cpp_bridge.py [--latency 2000] [--flood 10000] [--rss 100000]
                                         [--build /tmp/rapidgen-bench-cpp] [--domain 93]
                                         [--ddsperf-domain D] [--floor-domain D]

Builds what it needs once in --build (kept: later runs are incremental): the runtime, K10's
generated package with its bridge and rapid_cmd (rapid_runtime_cpp_add_cmd), and
bench/fastdds_ping (a bare Fast DDS round trip), Release.
Everything stays on loopback: the bridge and rapid_cmd use the built-in rapid_local
profile (127.0.0.1 only), ddsperf ../shared/dds-local/cyclonedds-loopback.xml (or
CYCLONEDDS_URI). Prints figures, never passes or fails on time; exit 1 when an ack was lost.

  ddsperf    `ddsperf ping` against `ddsperf pong` (Cyclone C): the floor of a round trip
  Fast DDS   bench/fastdds_ping: the same N sequential round trips on bare Fast DDS 2.9
             (K10's Command and Ack types, the runtime's Node and the bridge's built-in
             rapid_local profile, the endpoints set up as rapid_cmd's and the bridge's), no
             runtime above it: pong answers on its receive thread. Three shapes: 1 ack, the
             ping's main thread waiting (rapid_cmd's shape); 2 acks (EXECUTING, COMPLETED:
             an echo's), main thread; 1 ack, the ping's listener writing the next command
             (ddsperf's shape, no wake-up). The floor Fast DDS itself sets under the bridge
  latency    N sequential Admin/echo (BYPASS, from the controller): write() to the final
             COMPLETED ack read by rapid_cmd; p50/p99 and commands/s one at a time; with
             the bridge's CPU time and context switches per command (all its threads)
  flood      N echoes written back to back (rapid_cmd --flood), then waited for: acks lost,
             and what the bridge's intake door said (it sheds past 256 waiting per writer,
             drops past 4096 busy answers: a bridge that falls behind loses acks by design)
  rss        the bridge's VmRSS after every tenth of N commands (256 in flight): flat?

The goal lines run the bridge with --no-journal (the protocol path; a bridge without the
option is run as it is, and said so); then one more latency run with its restart journal
on (a temporary folder), labelled as such.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from datetime import datetime, timezone
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def git_head() -> str:
    res = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    dirty = subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "--", "runtime/cpp", "bench"],
                           capture_output=True, text=True).stdout.strip()
    return res.stdout.strip() + (" (runtime/cpp or bench modified)" if dirty else "")
LOOPBACK = ROOT.parent / "shared" / "dds-local" / "cyclonedds-loopback.xml"
SOURCE = "RapidWorkbench"  # K10's allow-list lets it send Admin/echo and AccessControl
ECHO = ["Admin", "echo", "text=bench"]


def run(cmd: list[str], **kw) -> subprocess.CompletedProcess:
    res = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if res.returncode != 0:
        raise SystemExit(f"bench: {' '.join(cmd)} failed:\n{res.stdout[-2000:]}\n{res.stderr[-3000:]}")
    return res


def build(out: Path) -> tuple[Path, Path, Path]:
    """(bridge, rapid_cmd) of K10 and fastdds_ping, built in `out` (incremental)."""
    gen = out / "gen" / "k10"
    run([sys.executable, "-m", "rapidgen", "generate", str(ROOT / "specs" / "assets" / "k10.yaml"), "--lang", "cpp",
         "-o", str(gen)], cwd=ROOT)
    jobs = str(max(1, min(4, os.cpu_count() or 1)))
    run(["cmake", "-S", str(ROOT / "runtime" / "cpp"), "-B", str(out / "runtime"), "-DCMAKE_BUILD_TYPE=Release"])
    run(["cmake", "--build", str(out / "runtime"), "-j", jobs])
    cpp = gen / "cpp"
    run(["cmake", "-S", str(ROOT / "tests" / "cpp_runtime" / "seeds"), "-B", str(out / "bridges"),
         "-DCMAKE_BUILD_TYPE=Release", f"-Drapid_runtime_cpp_DIR={out / 'runtime'}", f"-DSEED_DIRS={cpp}",
         f"-DPLAIN_DIR={cpp}"])
    run(["cmake", "--build", str(out / "bridges"), "-j", jobs, "--target", "rapid_k10red_bridge", "--target",
         "rapid_k10red_cmd"])
    run(["cmake", "-S", str(ROOT / "bench" / "fastdds_ping"), "-B", str(out / "fastdds_ping"),
         "-DCMAKE_BUILD_TYPE=Release", f"-Drapid_runtime_cpp_DIR={out / 'runtime'}",
         f"-Drapid_k10red_DIR={out / 'bridges' / 'k10'}", f"-DK10_BRIDGE_DIR={cpp / 'bridge'}"])
    run(["cmake", "--build", str(out / "fastdds_ping"), "-j", jobs])
    return (out / "bridges" / "k10" / "rapid_k10red_bridge", out / "bridges" / "rapid_k10red_cmd",
            out / "fastdds_ping" / "fastdds_ping")


def fastdds_floor(exe: Path, domain: int, count: int, acks: int, wait: str, env: dict) -> dict | str:
    """bench/fastdds_ping: `count` sequential round trips on bare Fast DDS (its JSON figures)."""
    pong = subprocess.Popen([str(exe), "pong", "--domain", str(domain), "--acks", str(acks)], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        if not pong.stdout.readline().startswith("pong ready"):
            return f"fastdds_ping pong did not start: {pong.stderr.read()[-500:]!r}"
        res = subprocess.run([str(exe), "ping", "--domain", str(domain), "--count", str(count), "--wait", wait],
                             env=env, capture_output=True, text=True, timeout=600)
    finally:
        stop(pong, "fastdds_ping pong")
    lines = [ln for ln in res.stdout.splitlines() if ln.startswith("{")]
    if not lines:
        return f"fastdds_ping ping said (exit {res.returncode}): {res.stdout[-300:]!r} {res.stderr[-500:]!r}"
    return json.loads(lines[-1])


def ddsperf(seconds: float, domain: int) -> dict | str:
    """`ddsperf ping` against `ddsperf pong` on loopback: its last latency figures (us)."""
    exe = shutil.which("ddsperf")
    if exe is None:
        return "ddsperf not installed (apt: cyclonedds-tools)"
    env = dict(os.environ)
    env.setdefault("CYCLONEDDS_URI", f"file://{LOOPBACK}")
    pong = subprocess.Popen([exe, "-D", str(seconds + 3), "-i", str(domain), "pong"], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        res = subprocess.run([exe, "-D", str(seconds), "-i", str(domain), "ping"], env=env, capture_output=True,
                             text=True, timeout=seconds + 30)
    finally:
        pong.terminate()
        pong.wait(10)
    lines = [ln for ln in res.stdout.splitlines() if "mean" in ln and "%" in ln]
    if not lines:
        return f"no latency line (exit {res.returncode}): {res.stdout[-300:]!r}"
    figures = dict(re.findall(r"(mean|min|50%|90%|99%|max)\s+([\d.]+)us", lines[-1]))
    return {k: float(v) for k, v in figures.items()} or lines[-1].strip()


def rss_kib(pid: int) -> int:
    text = Path(f"/proc/{pid}/status").read_text()
    return int(re.search(r"VmRSS:\s+(\d+) kB", text).group(1))


def cpu_and_switches(pid: int) -> tuple[float, int]:
    """(CPU seconds, context switches) of all the process's threads so far."""
    ticks = os.sysconf("SC_CLK_TCK")
    cpu, switches = 0.0, 0
    for task in Path(f"/proc/{pid}/task").iterdir():
        try:
            fields = (task / "stat").read_text().rsplit(")", 1)[1].split()
            cpu += (int(fields[11]) + int(fields[12])) / ticks  # utime, stime
            status = (task / "status").read_text()
        except OSError:  # (a thread that ended meanwhile)
            continue
        switches += sum(int(n) for n in re.findall(r"ctxt_switches:\s+(\d+)", status))
    return cpu, switches


def start_bridge(exe: Path, domain: int, env: dict, extra: list[str], tmp: str):
    """The bridge, ready; its stderr goes to a file in tmp (the door's log lines)."""
    log = Path(tmp) / f"bridge-{len(list(Path(tmp).glob('bridge-*')))}.err"
    with log.open("w") as err:
        bridge = subprocess.Popen([str(exe), "--domain", str(domain), *extra], env=env, stdout=subprocess.PIPE,
                                  stderr=err, text=True)
    if not bridge.stdout.readline().startswith("bridge ready"):
        stop(bridge)
        raise SystemExit(f"bench: the bridge did not start: {log.read_text()[-2000:]}")
    return bridge, log


def echoes(cmd: Path, domain: int, env: dict, *extra: str) -> dict:
    """rapid_cmd sending Admin/echo as `extra` says (--repeat N, --flood N): its JSON figures."""
    res = subprocess.run([str(cmd), *ECHO, "--domain", str(domain), "--source", SOURCE, "--timeout", "120", *extra],
                         capture_output=True, text=True, env=env, timeout=3600)
    lines = [ln for ln in res.stdout.splitlines() if ln.startswith("{")]
    if not lines:
        raise SystemExit(f"bench: rapid_cmd said {res.stdout[-1000:]} {res.stderr[-2000:]}")
    return json.loads(lines[-1])


def take_control(cmd: Path, domain: int, env: dict) -> None:
    granted = subprocess.run([str(cmd), "AccessControl", "requestControl", "--domain", str(domain), "--source", SOURCE],
                             capture_output=True, text=True, env=env, timeout=120)
    if granted.returncode != 0:
        raise SystemExit(f"bench: control not granted: {granted.stdout} {granted.stderr}")


def stop(proc: subprocess.Popen, name: str = "the bridge") -> None:
    proc.terminate()
    try:
        proc.wait(30)
    except subprocess.TimeoutExpired:  # (said, and not left running to skew the next run)
        print(f"bench: {name} did not stop within 30 s of SIGTERM; killed", flush=True)
        proc.kill()
        proc.wait()


def door_said(log: Path) -> str:
    """The intake door's lines (a writer shed or dropped), shortened."""
    lines = [ln.split("] ", 1)[-1] for ln in log.read_text(errors="replace").splitlines() if "floods" in ln]
    return "; ".join(ln[:160] for ln in lines)


def flood_and_memory(client, log: Path, pid: int, flood: int, rss: int, name: str) -> tuple[dict, list[int], int]:
    """`flood` commands back to back, then `rss` more in tenths (256 in flight), the bridge's
    VmRSS after each: (the flood's figures, [RSS before, after each tenth] in KiB, acks lost),
    printed as it goes. `client(*args)` runs rapid_cmd and returns its JSON line."""
    fl = client("--flood", str(flood))
    lost = fl["lost"]
    door = door_said(log)
    print(f"{name} flood: {fl['sent']} echoes written back to back, {fl['final']} final acks ({fl['ok']} OK), "
          f"{fl['lost']} lost, {fl['per_s']:.0f} commands/s" + (f"; the door: {door}" if door else ""), flush=True)
    step = max(1, rss // 10)
    figures = [rss_kib(pid)]
    for _ in range(10 if rss else 0):
        lost += client("--flood", str(step), "--window", "256")["lost"]
        figures.append(rss_kib(pid))
    if len(figures) > 1:
        print(f"RSS of the {name}: {figures[0] / 1024:.1f} MiB before; after "
              + ", ".join(f"{(i + 1) * step}: {k / 1024:.1f}" for i, k in enumerate(figures[1:])) + " MiB "
              f"({(figures[-1] - figures[1]) / 1024:+.1f} MiB from the first tenth to the last)", flush=True)
    return fl, figures, lost


def columns(perf, floors: dict, bridge: dict) -> str:
    """The round trips side by side (p50 / p99 us) and the bridge's p50 over each floor's."""
    heads = ["ddsperf (Cyclone C)", "Fast DDS 1 ack, main", "Fast DDS 2 acks, main", "Fast DDS 1 ack, listener",
             "C++ bridge"]
    cells = [perf.get("50%"), perf.get("99%")] if isinstance(perf, dict) else [None, None]
    cells = [tuple(cells)]
    for key in ((1, "main"), (2, "main"), (1, "listener")):
        f = floors.get(key)
        cells.append((f["p50_us"], f["p99_us"]) if isinstance(f, dict) else (None, None))
    cells.append((bridge["p50_us"], bridge["p99_us"]))
    show = lambda c: "-" if c[0] is None else f"{c[0]:.0f} / {c[1]:.0f}"
    ratio = lambda c: "-" if not c[0] else f"{bridge['p50_us'] / c[0]:.1f}x"
    width = max(len(h) for h in heads) + 2
    lines = ["round trip, p50 / p99 us, and the bridge's p50 over each (load " +
             " ".join(f"{x:.2f}" for x in os.getloadavg()) + "):"]
    for h, c in zip(heads, cells):
        lines.append(f"  {h:<{width}}{show(c):>14}  {ratio(c):>6}")
    return "\n".join(lines)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--latency", type=int, default=2000, help="sequential commands timed (default 2000)")
    p.add_argument("--flood", type=int, default=10000, help="commands sent back to back (default 10000)")
    p.add_argument("--rss", type=int, default=100000, help="commands for the memory figure (default 100000; 0: none)")
    p.add_argument("--build", type=Path, default=Path("/tmp/rapidgen-bench-cpp"))
    p.add_argument("--domain", type=int, default=93, help="the bridge's DDS domain (default 93)")
    p.add_argument("--ddsperf-domain", type=int, help="ddsperf's (default: --domain + 1)")
    p.add_argument("--floor-domain", type=int, help="fastdds_ping's (default: --domain + 2)")
    p.add_argument("--ddsperf-seconds", type=float, default=5, help="0 skips ddsperf")
    p.add_argument("--json", type=Path, help="also write the figures there (bench/bridges.py reads them)")
    args = p.parse_args()
    out: dict = {"load_start": os.getloadavg()}
    bridge_exe, cmd, ping_exe = build(args.build)
    env = {k: v for k, v in os.environ.items() if not k.startswith(("FASTDDS_", "FASTRTPS_"))}  # built-in rapid_local
    print(f"commit {git_head()}, {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC", flush=True)

    def client(*extra: str) -> dict:
        return echoes(cmd, args.domain, env, *extra)

    print("load average at the start: " + " ".join(f"{x:.2f}" for x in os.getloadavg()), flush=True)
    if args.ddsperf_seconds > 0:
        perf = ddsperf(args.ddsperf_seconds,
                       args.domain + 1 if args.ddsperf_domain is None else args.ddsperf_domain)
        print(f"ddsperf ping (Cyclone C, loopback, {args.ddsperf_seconds:g} s): {perf}", flush=True)
    else:
        perf = None
    out["ddsperf"] = perf
    floors = {}
    for acks, wait, what in ((1, "main", "1 ack, main thread waits (rapid_cmd's shape)"),
                             (2, "main", "2 acks (an echo's), main thread waits"),
                             (1, "listener", "1 ack, the listener sends the next (ddsperf's shape)")):
        got = fastdds_floor(ping_exe, args.domain + 2 if args.floor_domain is None else args.floor_domain,
                            args.latency, acks, wait, env)
        floors[(acks, wait)] = got
        if isinstance(got, dict):
            print(f"bare Fast DDS round trip, {what}: p50 {got['p50_us']:.0f} us, p99 {got['p99_us']:.0f} us, "
                  f"max {got['max_us']:.0f} us ({got['answered']} of {got['count']}), {got['per_s']:.0f}/s",
                  flush=True)
        else:
            print(f"bare Fast DDS round trip, {what}: {got}", flush=True)
    usage = subprocess.run([str(bridge_exe), "--help"], capture_output=True, text=True, env=env, timeout=60)
    has_journal = "--no-journal" in usage.stdout + usage.stderr
    if not has_journal:
        print("note: this bridge has no --no-journal option: run as it is", flush=True)
    lost = 0
    with tempfile.TemporaryDirectory(prefix="rapidgen-bench-cpp-") as tmp:
        bridge, log = start_bridge(bridge_exe, args.domain, env, ["--no-journal"] if has_journal else [], tmp)
        try:
            take_control(cmd, args.domain, env)
            client("--repeat", "50")  # warm-up
            cpu0, sw0 = cpu_and_switches(bridge.pid)
            lat = client("--repeat", str(args.latency))
            cpu1, sw1 = cpu_and_switches(bridge.pid)
            out["floors"] = {f"{acks} {wait}": f for (acks, wait), f in floors.items()}
            out["bridge"] = lat
            per = max(1, lat["answered"])
            ratio = f", {lat['p50_us'] / perf['50%']:.1f}x ddsperf's p50" \
                if isinstance(perf, dict) and "50%" in perf else ""
            for (acks, wait), floor in floors.items():
                if isinstance(floor, dict) and floor["p50_us"] > 0:
                    ratio += f", {lat['p50_us'] / floor['p50_us']:.1f}x bare Fast DDS's ({acks} ack, {wait})"
            print(f"C++ bridge{' (--no-journal)' if has_journal else ''}, command -> COMPLETED ack "
                  f"({lat['answered']} of {lat['count']} sequential echoes, rapid_cmd): p50 {lat['p50_us']:.0f} us, "
                  f"p99 {lat['p99_us']:.0f} us, max {lat['max_us']:.0f} us{ratio}; {lat['per_s']:.0f} commands/s "
                  f"one at a time; the bridge spent {(cpu1 - cpu0) / per * 1e6:.0f} us of CPU and "
                  f"{(sw1 - sw0) / per:.1f} context switches a command", flush=True)
            print(columns(perf, floors, lat), flush=True)
            fl, _, flood_lost = flood_and_memory(client, log, bridge.pid, args.flood, args.rss, "bridge")
            out["flood"] = fl
            lost += flood_lost
        finally:
            stop(bridge)
        if has_journal:  # the same path with the restart journal on: what a default bridge costs
            bridge, _ = start_bridge(bridge_exe, args.domain, env, ["--journal", str(Path(tmp) / "journal")], tmp)
            try:
                take_control(cmd, args.domain, env)
                client("--repeat", "50")
                lat = client("--repeat", str(args.latency))
                out["journal"] = lat
                print(f"C++ bridge, journal on: command -> COMPLETED ack ({lat['answered']} of {lat['count']}): "
                      f"p50 {lat['p50_us']:.0f} us, p99 {lat['p99_us']:.0f} us, max {lat['max_us']:.0f} us; "
                      f"{lat['per_s']:.0f} commands/s one at a time", flush=True)
            finally:
                stop(bridge)
    print("load average at the end: " + " ".join(f"{x:.2f}" for x in os.getloadavg()), flush=True)
    if args.json:
        out["load_end"] = os.getloadavg()
        args.json.write_text(json.dumps(out))
    return 1 if lost else 0


if __name__ == "__main__":
    sys.exit(main())
