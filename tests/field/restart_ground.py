"""The ground side of the restart test, run as its own process: a command stream into the
Restarter bridge while the bridge is killed (SIGKILL) at random moments and started again.

    python -m tests.field.restart_ground PYDIR WORKDIR DOMAIN COMMANDS KILLS SEED

- Commands: Belt/work through the queue (APPEND), Side/work beside it (BYPASS), Admin/noOp;
  work of 20-150 ms, one sent every 5-40 ms, each with a new cmdId.
- Kills: after KILLS randomly chosen commands, a random 0-60 ms later: SIGKILL, then the
  bridge is started again on the same journal. Before the second restart a torn record
  (what a power cut leaves of a write that was never synced) and a garbage line are
  appended to the journal: the bridge must report it, set it aside and go on.
- Then the ground does what a ground tool must do across a restart: a command with no final
  ack after a while is sent again with the same cmdId (a command still in the old
  process's DDS reader when it died is gone; the journal makes the retry safe: a known
  cmdId is never run twice).
- A late-joining ack reader (a new participant) reads the ack history at the end.
Prints one JSON document: sent ids and kinds, each final ack (sender's and late joiner's),
the execution counts from the handler's file, the bridge logs about the journal.
"""
from __future__ import annotations

import collections
import importlib
import json
import os
import random
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

from tests.field.restart_asset import ASSET, PACKAGE, env_for

SOURCE = "RapidGround"
READY = 30.0
RETRY_AFTER = 2.0  # seconds without a final ack before a command is sent again
SETTLE = 90.0  # the whole retry phase at most


class Bridge:
    closing = False  # set when the ground ends: a bridge still starting is killed at once
    made: list["Bridge"] = []

    def __init__(self, pydir: Path, work: Path, domain: int) -> None:
        Bridge.made.append(self)
        self.argv = [sys.executable, "-m", "tests.field.restart_bridge", str(pydir), str(work / "executions"),
                     "--domain", str(domain), "--journal", str(work / "journal")]
        self.env = env_for(pydir)
        self.logs: list[str] = []
        self.starts = 0
        self.proc: subprocess.Popen | None = None

    def start(self) -> None:
        self.proc = subprocess.Popen(self.argv, cwd=Path(__file__).parents[2], env=self.env, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True)
        proc = self.proc
        if Bridge.closing:
            proc.kill()
        threading.Thread(target=lambda: self.logs.extend(proc.stderr or ()), daemon=True).start()
        line = proc.stdout.readline() if proc.stdout else ""
        if not line.startswith("bridge ready"):
            proc.kill()
            time.sleep(0.5)
            raise SystemExit(f"restart_ground: bridge did not start: {line!r} {''.join(self.logs)[-2000:]}")
        threading.Thread(target=lambda: [None for _ in proc.stdout or ()], daemon=True).start()
        self.starts += 1

    def kill(self) -> None:
        assert self.proc is not None
        self.proc.send_signal(signal.SIGKILL)
        self.proc.wait()

    def stop(self) -> int:
        assert self.proc is not None
        self.proc.terminate()
        try:
            return self.proc.wait(20)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            return self.proc.wait()


def damage(journal_dir: Path) -> str:
    """Append a torn record and a garbage line to the journal file (a power cut mid-write, a
    damaged block); the name of the file."""
    files = sorted(journal_dir.glob("*.journal"))
    assert files, f"no journal in {journal_dir}"
    with open(files[0], "ab") as fh:
        fh.write(b"0badc0de {\"k\":\"x\",\"id\":\"garbage\x00\xff\"}\n")
        fh.write(b"1234abcd {\"k\":\"q\",\"id\":\"torn-")
    return files[0].name


def run(pydir: Path, work: Path, domain: int, commands: int, kills: int, seed: int) -> dict:
    env = env_for(pydir)
    os.environ["CYCLONEDDS_URI"] = env["CYCLONEDDS_URI"]
    sys.path.insert(0, str(pydir))
    rapid = importlib.import_module(f"{PACKAGE}.rapid")
    qos = importlib.import_module(f"{PACKAGE}.qos").RapidQos()
    from rapid_runtime.commander import Commander

    rng = random.Random(seed)
    bridge = Bridge(pydir, work, domain)
    bridge.start()
    c = Commander(rapid, qos, ASSET, SOURCE, domain)
    if not c.wait_for_asset(READY):
        raise SystemExit("restart_ground: no bridge matched")
    kill_after = set(rng.sample(range(commands), min(kills, commands)))
    plan: dict[str, tuple] = {}
    last_sent: dict[str, float] = {}
    damaged = ""
    restarting: threading.Thread | None = None
    write_timeouts = 0

    def send(cid: str) -> None:
        """Send (again); a write DDS refuses counts as not sent: the retry phase sends it later.
        (A reliable writer blocks, then times out, while a killed bridge's reader is still
        matched and its history is full of samples that reader never acknowledged.)"""
        nonlocal write_timeouts
        sub, name, args, action = plan[cid]
        last_sent[cid] = time.monotonic()
        try:
            c.send(sub, name, args, action=action, cmd_id=cid)
        except Exception:  # cyclonedds' DDSException (timeout)
            write_timeouts += 1
    for i in range(commands):
        r = rng.random()
        ms = rng.randint(20, 150)
        if r < 0.6:
            kind = ("Belt", "work", [("RAPID_INT", ms)], "QUEUE_APPEND")
        elif r < 0.85:
            kind = ("Side", "work", [("RAPID_INT", ms)], "QUEUE_BYPASS")
        else:
            kind = ("Admin", "noOp", [], "QUEUE_BYPASS")
        cid = f"r{seed}-{i}"
        plan[cid] = kind
        send(cid)
        time.sleep(rng.uniform(0.005, 0.04))
        if i in kill_after:
            time.sleep(rng.uniform(0, 0.06))
            if restarting is not None:
                restarting.join()  # the last restart is done before the next kill
            bridge.kill()
            if bridge.starts == 2:  # the second restart meets a damaged journal
                damaged = damage(work / "journal")
            restarting = threading.Thread(target=bridge.start, daemon=True)
            restarting.start()  # commands go on being sent while the bridge is down
    if restarting is not None:
        restarting.join()

    # retries: a command without a final ack is sent again, same cmdId, until all are final
    def final(cid: str) -> tuple | None:
        return next((a for a in c.acks.get(cid, ()) if a[0] == "ACK_COMPLETED"), None)

    retried: collections.Counter[str] = collections.Counter()
    end = time.monotonic() + SETTLE
    while time.monotonic() < end:
        with c.cond:
            missing = [cid for cid in plan if final(cid) is None]
        if not missing:
            break
        now = time.monotonic()
        for cid in missing:
            if now - last_sent[cid] > RETRY_AFTER:
                send(cid)
                retried[cid] += 1
        time.sleep(0.2)
    with c.cond:
        finals = {cid: final(cid) for cid in plan}
    c.close()

    # a late joiner: a new participant whose ack reader reads the history
    late = Commander(rapid, qos, ASSET, "LateGround", domain, follow=plan)  # followed before any history arrives
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline:
        with late.cond:
            if all(any(a[0] == "ACK_COMPLETED" for a in late.acks.get(cid, ())) for cid in plan):
                break
        time.sleep(0.1)
    with late.cond:
        late_finals = {cid: next((a for a in late.acks.get(cid, ()) if a[0] == "ACK_COMPLETED"), None) for cid in plan}
    late.close()
    code = bridge.stop()
    time.sleep(0.3)  # the stderr pump's last lines
    runs = collections.Counter(Path(work / "executions").read_text().split()) if (work / "executions").exists() \
        else collections.Counter()
    return {"plan": {cid: [k[0], k[1], k[3]] for cid, k in plan.items()}, "finals": finals, "late": late_finals,
            "runs": dict(runs), "retried": dict(retried), "write_timeouts": write_timeouts, "starts": bridge.starts, "stop_code": code,
            "damaged": damaged, "aside": sorted(p.name for p in (work / "journal").glob("*.damaged-*")),
            "journal_logs": [ln.rstrip() for ln in bridge.logs if "journal" in ln or "Traceback" in ln],
            "tracebacks": sum("Traceback" in ln for ln in bridge.logs)}


def main(argv: list[str]) -> int:
    pydir, work = Path(argv[0]), Path(argv[1])
    domain, commands, kills, seed = (int(a) for a in argv[2:6])
    try:
        print(json.dumps(run(pydir, work, domain, commands, kills, seed)), flush=True)
    finally:  # never leave a bridge behind: it would answer the next run's commands on this domain
        Bridge.closing = True
        for b in Bridge.made:
            if b.proc is not None and b.proc.poll() is None:
                b.proc.kill()
                b.proc.wait()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
