"""Commands across the lunar link (issue 23): command-to-final-ack time in round trips and
the retransmissions the relay counted, with the site's Cyclone file tuned for the link
(rtt 2.6, lease 120: docs/qos.md) and, for comparison, as shipped (Cyclone's defaults).

    .venv/bin/python bench/field_link.py [--count 50] [--rounds 20] [--only tuned|shipped]
                                         [--full] [--cpp BRIDGE]

--full: the issue's campaign, 200 sequential commands and 200 rounds (200 commands of every
queue action). --cpp BRIDGE: K10's generated C++ bridge (Fast DDS) instead of the Python
one, with the site library's Fast DDS file (tuned: rtt/lease, docs/qos.md; shipped: none);
"executed twice" then counts commands with more than one EXECUTING ack (no handler log).

Needs root (network namespaces, TUN devices: tests/field/link.py). Two runs, one link
each, side by side: K10's simulated bridge in the asset namespace; in the ground namespace
COUNT instant BYPASS commands one after another (latency), then ROUNDS rounds of every
queue action sent in waves (traffic). Prints figures; never passes or fails. docs/field.md
says what they mean."""
from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import threading
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tests.field.link import LUNAR, Link, rtt  # noqa: E402
from tests.field.site import site_config, site_env, site_fastdds, site_library  # noqa: E402
from tests.runtime.live import SEEDS, BridgeProcess  # noqa: E402

PACKAGE, DOMAIN, SPEED = SEEDS["k10"], 7, 4.0


def _ground(link: Link, config: Path, *args: str) -> dict:
    res = link.run("ground", [sys.executable, "-m", "tests.field.ground", *args], cwd=ROOT, env=site_env(config),
                   capture_output=True, text=True, timeout=3600)
    if res.returncode != 0:
        raise RuntimeError(res.stderr[-2000:])
    return json.loads(res.stdout.splitlines()[-1])


def _delta(after: dict, before: dict) -> dict:
    return {d: {k: after[d][k] - before[d][k] for k in after[d]} for d in ("up", "down")}


def _bridge(link: Link, folder: Path, name: str, config: Path, cpp: str | None) -> BridgeProcess:
    if cpp is None:
        env = dict(site_env(config), FIELD_EXEC_LOG=str(folder / "exec.log"), FIELD_SIM_SPEED=str(SPEED))
        return BridgeProcess.of_command(link.argv("asset", [sys.executable, "-m", "tests.field.counting_bridge",
                                                            PACKAGE, "--domain", str(DOMAIN), "--journal",
                                                            str(folder / "journal")]), ROOT, env)
    tuned = name == "tuned"
    profiles = site_fastdds(folder, rtt=rtt(LUNAR) if tuned else None, lease=120.0 if tuned else None)
    env = {k: v for k, v in os.environ.items() if not k.startswith(("FASTDDS_", "FASTRTPS_"))}
    return BridgeProcess.of_command(link.argv("asset", [cpp, "--simulate", "--sim-speed", str(SPEED), "--domain",
                                                        str(DOMAIN), "--transport", "wan", "--qos", str(profiles),
                                                        "--journal", str(folder / "journal")]), ROOT, env)


def _twice(folder: Path, cpp: str | None, *acks: dict) -> int:
    if cpp is None:
        runs = [line.split()[1] for line in (folder / "exec.log").read_text().splitlines()]
        return len(runs) - len(set(runs))
    return sum(1 for a in acks for seq in a.values() if sum(1 for x in seq if x[0] == "ACK_EXECUTING") > 1)


def campaign(name: str, count: int, rounds: int, out: dict, cpp: str | None = None) -> None:
    with tempfile.TemporaryDirectory(prefix=f"field-{name}-") as tmp, Link(LUNAR, seed=11) as link:
        folder = Path(tmp)
        config = site_library(folder, rtt=rtt(LUNAR), lease=120.0) if name == "tuned" else site_config(folder)
        bridge = _bridge(link, folder, name, config, cpp)
        link.children.append(bridge.proc)
        try:
            bridge.wait_ready(60)
            s0 = link.stats()
            seq = _ground(link, config, "sequential", PACKAGE, str(DOMAIN), str(count))
            s1 = link.stats()
            drive = _ground(link, config, "drive", PACKAGE, str(DOMAIN), str(rounds), "--wave", "10",
                            "--speed", str(SPEED))
            s2 = link.stats()
        finally:
            bridge.stop()
        finals = [a for acks in drive["acks"].values() for a in acks if a[0] == "ACK_COMPLETED"]
        out[name] = {"latency": seq["latency"], "seq": _delta(s1, s0), "drive": _delta(s2, s1),
                     "drive_commands": len(drive["acks"]), "drive_finals": len(finals),
                     "twice": _twice(folder, cpp, seq["acks"], drive["acks"]),
                     "queued_latency": list(drive["latency"].values())}


def pct(values: list[float], q: float) -> float:
    v = sorted(values)
    return v[min(len(v) - 1, int(q * len(v)))]


def report(out: dict, count: int, rounds: int, cpp: str | None = None) -> None:
    trip = rtt(LUNAR)
    print("bridge: " + ("K10's C++ bridge (Fast DDS 2.9, the site's wan profiles)" if cpp else
                        "K10's Python bridge (Cyclone DDS)") + "; ground: Python/Cyclone")
    print(f"lunar link: 1.3 s each way, 20 ms jitter, 5% loss each way (round trip {trip:g} s); "
          f"{count} sequential BYPASS commands, then {rounds} rounds of every queue action (7 commands each)\n")
    print("| site file | commands | p50 ack (round trips) | p99 | max | DATA sent | of which resent | packets lost "
          "| executed twice |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, r in out.items():
        lat = [x / trip for x in r["latency"]]
        both = {k: r["seq"]["up"][k] + r["seq"]["down"][k] + r["drive"]["up"][k] + r["drive"]["down"][k]
                for k in ("rtps_data", "retransmitted", "lost")}
        print(f"| {name} | {len(lat)} + {r['drive_commands']} | {statistics.median(lat):.2f} | {pct(lat, 0.99):.2f} "
              f"| {max(lat):.2f} | {both['rtps_data']} | {both['retransmitted']} "
              f"({both['retransmitted'] / max(1, both['rtps_data']):.0%}) | {both['lost']} | {r['twice']} |")
    for name, r in out.items():
        q = [x / trip for x in r["queued_latency"]]
        print(f"\n{name}: queue-action rounds, send to final ack (all {len(q)} commands, queue waits included): "
              f"p50 {statistics.median(q):.2f}, p99 {pct(q, 0.99):.2f} round trips; "
              f"{r['drive_finals']} final acks for {r['drive_commands']} commands")
        for phase in ("seq", "drive"):
            for d in ("up", "down"):
                c = r[phase][d]
                print(f"  {phase:5} {d:4}: {c['received']} packets, {c['lost']} lost, {c['rtps_data']} DATA, "
                      f"{c['retransmitted']} resent")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--count", type=int, default=50, help="sequential BYPASS commands (latency)")
    ap.add_argument("--rounds", type=int, default=20, help="rounds of every queue action (traffic)")
    ap.add_argument("--only", choices=("tuned", "shipped"))
    ap.add_argument("--full", action="store_true",
                    help="the issue's campaign: 200 sequential commands, 200 rounds (overrides --count, --rounds)")
    ap.add_argument("--cpp", metavar="BRIDGE", help="K10's C++ bridge (the built rapid_k10red_bridge) as the asset")
    args = ap.parse_args()
    if args.full:
        args.count, args.rounds = 200, 200
    if args.cpp and not os.access(args.cpp, os.X_OK):
        ap.error(f"--cpp {args.cpp}: not an executable (build K10's C++ bridge: runtime/cpp/README.md)")
    out: dict = {}
    names = [args.only] if args.only else ["tuned", "shipped"]
    errors: list[str] = []

    def run(name: str) -> None:
        try:
            campaign(name, args.count, args.rounds, out, args.cpp)
        except Exception as exc:  # printed below; the other campaign still reports
            errors.append(f"{name}: {exc}")

    threads = [threading.Thread(target=run, args=(n,)) for n in names]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    if out:
        report({n: out[n] for n in names if n in out}, args.count, args.rounds, args.cpp)
    for e in errors:
        print(f"failed: {e}", file=sys.stderr)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
