"""Recording overhead: how many messages a second `rapidgen record` keeps up with before it
drops any, beside the rate K10's simulated bridge publishes.

    .venv/bin/python bench/record.py [--rates 1000,5000,10000,20000,0] [--seconds 3] [--domain 59]

Loopback only: every process uses K10's generated "local" Cyclone transport (127.0.0.1, no
multicast). Prints figures, never passes or fails on time.

  bridge   K10's simulated bridge (--sim-speed 1 and 20) recorded for --seconds: messages/s
           it publishes, all topics together
  steps    a publisher (this script, --publish) writes rapid::AgentState (K10's generated
           class, the rapid_agent_state profile QoS, 12 values like K10's) at each rate
           (0: as fast as it can) for --seconds while `rapidgen record` records; the
           recording is read back with the mcap library and its messages counted against
           those sent (kept = recorded / sent), with the recorder's CPU per message
  --bombs  no DDS traffic but replay's own participant (domain --domain): the hostile files of
           issue 34 (tests/record/bombs.py: a 29 KB file whose zstd chunk inflates to 900
           MiB, a 9 KB file of 3 million empty messages, the same as configs) given to
           `record --info`, `replay` and `monitor --replay`; each tool's exit status, peak
           RSS (its own rusage through a small measuring parent; the monitor's VmHWM once
           it serves) and wall time
"""
from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PYDIR = ROOT / "generated" / "k10" / "python"
PACKAGE = "rapid_k10red"
LOCAL = PYDIR / PACKAGE / "qos_files" / "cyclonedds" / "local.xml"
ENV = dict(os.environ, CYCLONEDDS_URI=f"file://{LOCAL}", PYTHONPATH=f"{PYDIR}{os.pathsep}{ROOT}")
RAPIDGEN = [sys.executable, "-m", "rapidgen"]


def publish(domain: int, rate: float, seconds: float, name: str = "K10Red") -> None:
    """Child mode: write AgentStates at `rate` (0: flat out) once a reader matched; print the count."""
    import importlib
    sys.path.insert(0, str(PYDIR))
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.topic import Topic
    rapid = importlib.import_module(f"{PACKAGE}.rapid")
    qos = importlib.import_module(f"{PACKAGE}.qos").RapidQos()
    dp = DomainParticipant(domain)
    writer = DataWriter(Publisher(dp, qos=qos.publisher()), Topic(dp, "rapid_agent_state", rapid.AgentState),
                        qos=qos.writer("rapid_agent_state"))
    end = time.monotonic() + 30
    while not writer.get_matched_subscriptions() and time.monotonic() < end:
        time.sleep(0.01)
    time.sleep(0.5)  # the recorder's reader matched on its side too
    sample = rapid.AgentState(hdr=rapid.Header(srcName=name, assetName="K10Red", serial=1),
                              values=[rapid.ParameterUnion(d=i * 0.5) for i in range(12)])
    sent = 0
    start = time.monotonic()
    stop = start + seconds
    while True:
        now = time.monotonic()
        if now >= stop:
            break
        if rate > 0:
            due = start + sent / rate
            if due > now:
                time.sleep(min(due - now, 0.01))
                continue
        sample.hdr.timeStamp = time.time_ns() // 1000
        writer.write(sample)
        sent += 1
    time.sleep(0.5)
    print(sent, time.monotonic() - start - 0.5, flush=True)


def cpu_seconds(pid: int) -> float:
    with open(f"/proc/{pid}/stat") as fh:
        fields = fh.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def start_recorder(out: Path, domain: int, *extra: str) -> subprocess.Popen:
    rec = subprocess.Popen([*RAPIDGEN, "record", "--domain", str(domain), "--partition", "K10Red", "-o", str(out),
                            "--quiet", *extra], cwd=ROOT, env=ENV, stderr=subprocess.PIPE, text=True)
    assert rec.stderr is not None
    line = rec.stderr.readline()
    if "recording domain" not in line:
        raise SystemExit(f"recorder did not start: {line}{rec.stderr.read()}")
    return rec


def stop_recorder(rec: subprocess.Popen) -> tuple[float, str]:
    cpu = cpu_seconds(rec.pid)
    rec.send_signal(signal.SIGINT)
    _, err = rec.communicate(timeout=120)
    return cpu, err


def count(path: Path) -> dict[str, int]:
    from mcap.reader import make_reader
    got: dict[str, int] = {}
    with open(path, "rb") as fh:
        for _s, ch, _m in make_reader(fh).iter_messages():
            got[ch.topic] = got.get(ch.topic, 0) + 1
    return got


def bridge_rate(domain: int, speed: int, seconds: float, tmp: Path) -> tuple[float, int]:
    out = tmp / f"bridge-{speed}.mcap"
    bridge = subprocess.Popen([sys.executable, "-m", f"{PACKAGE}.bridge", "--simulate", "--domain", str(domain),
                               "--sim-speed", str(speed)], cwd=PYDIR, env=ENV, stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, text=True)
    try:
        assert bridge.stdout is not None
        bridge.stdout.readline()  # bridge ready
        rec = start_recorder(out, domain)
        time.sleep(1.0)  # past the configs and start-up messages
        before = sum(count_live(out))
        time.sleep(seconds)
        stop_recorder(rec)
    finally:
        bridge.send_signal(signal.SIGTERM)
        bridge.wait(timeout=30)
    counts = count(out)
    return (sum(counts.values()) - before) / seconds, len(counts)


def count_live(path: Path):
    """Messages in the chunks written so far (the file is still open)."""
    from mcap.records import Message
    from mcap.stream_reader import StreamReader
    n = 0
    with open(path, "rb") as fh:
        try:
            for r in StreamReader(fh).records:
                n += isinstance(r, Message)
        except Exception:  # the end of what is written so far
            pass
    yield n


def bombs(domain: int) -> int:
    sys.path.insert(0, str(ROOT))
    from tests.record import bombs as B
    with tempfile.TemporaryDirectory(prefix="bench-bombs-") as tmpdir:
        tmp = Path(tmpdir)
        files = {"zstd bomb (cut)": tmp / "bomb.mcap", "zstd bomb (complete)": tmp / "bomb-complete.mcap",
                 "zstd bomb, size a lie": tmp / "bomb-lie.mcap", "3M empty messages": tmp / "empty.mcap",
                 "3M empty configs": tmp / "empty-cfg.mcap"}
        B.zstd_bomb(files["zstd bomb (cut)"])
        B.zstd_bomb(files["zstd bomb (complete)"], complete=True)
        B.zstd_bomb(files["zstd bomb, size a lie"], declared=4096)
        B.empty_messages(files["3M empty messages"], type_name="rapid::AgentState")
        B.empty_messages(files["3M empty configs"], type_name="rapid::AgentConfig", role="config", numbered=True)
        print(f"{'file':24} {'bytes':>8} {'tool':18} {'exit':>4} {'peak RSS':>9} {'wall':>7}  last line of stderr")
        for what, path in files.items():
            for tool in ("record --info", "replay", "monitor --replay"):
                if tool == "record --info":
                    args = [*RAPIDGEN, "record", "--info", str(path)]
                elif tool == "replay":
                    args = [*RAPIDGEN, "replay", str(path), "--domain", str(domain), "--rate", "1000",
                            "--linger", "0", "--quiet"]
                else:
                    args = [*RAPIDGEN, "monitor", "--replay", str(path), "--port", "0"]
                t = time.monotonic()
                if tool == "monitor --replay":
                    code, err, rss = _monitor(args)
                else:
                    code, _out, err, rss = B.run_measured(args, timeout=900, cwd=ROOT, env=ENV)
                last = (err.strip().splitlines() or [""])[-1][:90]
                print(f"{what:24} {path.stat().st_size:8d} {tool:18} {code:4d} {rss:6.0f} MiB {time.monotonic() - t:6.1f}s"
                      f"  {last}", flush=True)
    return 0


def _monitor(args: list[str]) -> tuple[int, str, float]:
    """(exit status, or 0 once it serves; stderr; peak RSS): stopped once its page serves."""
    from tests.record import bombs as B
    proc = subprocess.Popen(args, cwd=ROOT, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert proc.stdout is not None
    line = proc.stdout.readline()  # the page's address, or nothing when it exits
    rss = B.peak_rss_mib(proc.pid)
    if "http" in line:
        proc.send_signal(signal.SIGINT)
        try:
            proc.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.communicate()
        return 0, "serves: " + line.strip(), rss
    proc.communicate(timeout=900)
    # It exited before it served: once more under the measuring parent, for its own rusage.
    code, _out, err, rss = B.run_measured(args, timeout=900, cwd=ROOT, env=ENV)
    return code, err, rss


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rates", default="1000,5000,10000,20000,0", help="messages/s per step (0: flat out)")
    ap.add_argument("--seconds", type=float, default=3.0)
    ap.add_argument("--domain", type=int, default=59)
    ap.add_argument("--parallel", type=int, default=3, help="publishers flat out together in the last step (default 3)")
    ap.add_argument("--publish", nargs=2, type=float, metavar=("RATE", "SECONDS"), help=argparse.SUPPRESS)
    ap.add_argument("--name", default="K10Red", help=argparse.SUPPRESS)
    ap.add_argument("--bombs", action="store_true", help="the hostile files of issue 34 against each reading tool")
    args = ap.parse_args()
    if args.bombs:
        return bombs(args.domain)
    if args.publish:
        publish(args.domain, args.publish[0], args.publish[1], args.name)
        return 0
    with tempfile.TemporaryDirectory(prefix="bench-record-") as tmpdir:
        tmp = Path(tmpdir)
        for speed in (1, 20):
            rate, topics = bridge_rate(args.domain, speed, args.seconds, tmp)
            print(f"K10 simulated bridge, --sim-speed {speed}: {rate:.1f} messages/s on {topics} topics", flush=True)
        print(f"{'asked/s':>8} {'sent/s':>9} {'sent':>7} {'recorded':>9} {'kept':>7} {'recorder CPU/msg':>17}")
        steps = [(float(r), 1) for r in args.rates.split(",")] + ([(0.0, args.parallel)] if args.parallel > 1 else [])
        for rate, n in steps:
            out = tmp / f"step-{int(rate)}-{n}.mcap"
            rec = start_recorder(out, args.domain)
            time.sleep(0.5)
            cpu0 = cpu_seconds(rec.pid)  # after start-up (bindings generated, readers made)
            pubs = [subprocess.Popen([sys.executable, __file__, "--domain", str(args.domain), "--publish", str(rate),
                                      str(args.seconds), "--name", f"K10Red{i}"], cwd=ROOT, env=ENV,
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for i in range(n)]
            outs = [p.communicate(timeout=300) for p in pubs]
            cpu, _err = stop_recorder(rec)
            if any(p.returncode for p in pubs):
                print(f"publisher failed: {[o[1][-1000:] for o in outs]}")
                return 1
            sent = sum(int(o[0].split()[0]) for o in outs)
            took = max(float(o[0].split()[1]) for o in outs)
            recorded = count(out).get("rapid_agent_state", 0)
            asked = ("max" if rate == 0 else f"{rate:.0f}") + (f" x{n}" if n > 1 else "")
            per = f"{(cpu - cpu0) / recorded * 1e6:.1f} us" if recorded else "-"
            print(f"{asked:>8} {sent / took:9.0f} {sent:7d} {recorded:9d} {recorded / sent:7.1%} {per:>17}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
