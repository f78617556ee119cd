"""The ground side of the field tests, a process in the ground namespace (CYCLONEDDS_URI
names the site's Cyclone file). Prints one JSON document on its last line.

  python -m tests.field.ground drive PACKAGE DOMAIN ROUNDS [--wave W] [--speed X] [--targets N]
      requestControl, then ROUNDS rounds of every queue action, W rounds sent at once behind
      a drive that holds the queue until each is answered once (then deleted); each round: b=APPEND, c=INSERT after b,
      d=APPEND then e=REPLACE d, f=APPEND then g=DELETE f, h=BYPASS (K10Native). Waits for every final
      ack; reports every command's acks and the seconds from send to its COMPLETED.
  python -m tests.field.ground sequential PACKAGE DOMAIN COUNT
      COUNT instant BYPASS commands, each sent once the one before is answered (latency).
  python -m tests.field.ground outage PACKAGE DOMAIN [--long N] [--hold S] [--during M]
      a queue of long commands; the test cuts the link while it runs (see outage()).
  python -m tests.field.ground late PACKAGE DOMAIN IDS.json
      a late joiner: the durable acks of the listed cmdIds, every config, the QueueState."""
from __future__ import annotations

import argparse
import importlib
import json
import os
import sys
import time

from rapid_runtime import messages as M
from rapid_runtime.acks import COMPLETED
from rapid_runtime.commander import Commander
from rapid_runtime.dds import Node, type_class, use_transport
from rapid_runtime.tables import Tables

WAIT = 600.0  # s: a bound for a broken run; the tests judge what arrived, not when
SILENT = 15.0  # s without any ack of the first command: it was lost at first contact (> 5 s + 2 lunar round trips)


def load(package: str):
    rapid = importlib.import_module(f"{package}.rapid")
    tables = Tables(importlib.import_module(f"{package}.asset_tables"))
    qos = importlib.import_module(f"{package}.qos").RapidQos()
    use_transport(qos, None)  # the site's file (CYCLONEDDS_URI)
    return rapid, tables, qos


class TimedCommander(Commander):
    """A Commander that also notes when each command's COMPLETED arrived."""

    def __init__(self, *a) -> None:
        self.sent_at: dict[str, float] = {}
        self.done_at: dict[str, float] = {}
        super().__init__(*a)

    def _on_ack(self, sample) -> None:
        cmd_id, status = M.ack_fields(sample)[:2]
        if status == COMPLETED:
            self.done_at.setdefault(cmd_id, time.monotonic())
        super()._on_ack(sample)

    def timed_send(self, *a, **kw) -> str:
        t = time.monotonic()
        cid = self.send(*a, **kw)
        self.sent_at[cid] = t
        return cid

    def first_contact(self, *a, **kw) -> str:
        """The first command, sent again with the same cmdId while no ack at all answers it:
        a command can be lost at first contact, before the asset's reader knows our writer
        (docs/runtime.md, "The ground's part"; rapidgen cmd does the same)."""
        cid = self.timed_send(*a, **kw)
        for _ in range(3):
            with self.cond:
                if self.cond.wait_for(lambda: self.acks.get(cid), SILENT):
                    return cid
            print(f"ground: no ack of {cid} within {SILENT:g} s: sending it again", file=sys.stderr, flush=True)
            self.send(*a, cmd_id=cid, **kw)
        return cid

    def wait_final(self, ids, timeout: float) -> bool:
        end = time.monotonic() + timeout
        with self.cond:
            while True:
                if all(any(a[0] == COMPLETED for a in self.acks.get(i, ())) for i in ids):
                    return True
                left = end - time.monotonic()
                if left <= 0:
                    return False
                self.cond.wait(left)


def _point(tables, pan: float):
    entry = tables.command("PanCam", "pointCamera")
    return [(p.type, pan if p.name == "pan" else float(p.default or 0.0)) for p in entry.params]


def _move(x: float):
    return [("RAPID_STRING", "site"), ("RAPID_VEC3d", [x, 0.0, 0.0])]


def drive(args) -> dict:
    rapid, tables, qos = load(args.package)
    c = TimedCommander(rapid, qos, tables.name, args.source, args.domain)
    if not c.wait_for_asset(WAIT):
        return {"error": "no asset"}
    cid = c.first_contact("AccessControl", "requestControl", [])
    c.wait_final([cid], WAIT)
    rounds, holds, releases, targets = [], [], [], []
    for start in range(0, args.rounds, args.wave):
        # Each wave queues behind a drive (the hold) that runs until every command of the
        # wave has been answered once: the targets of INSERT, REPLACE and DELETE are still
        # pending when those arrive, whatever the link delayed. Then a DELETE ends the drive.
        hold = c.timed_send("Mobility", "simpleMove", _move(300.0 * args.speed), action="QUEUE_APPEND")
        holds.append(hold)
        wave = []
        if start == 0 and args.targets:  # pending commands for other tools to act on
            targets = [{k: c.timed_send("PanCam", "pointCamera", _point(tables, 0.2), action="QUEUE_APPEND")
                        for k in ("insert", "replace", "delete")} for _ in range(args.targets)]
            wave.extend(t for group in targets for t in group.values())
        for i in range(start, min(start + args.wave, args.rounds)):
            pan = 0.1 + (i % 20) * 0.05
            r = {}
            r["b"] = c.timed_send("PanCam", "pointCamera", _point(tables, pan), action="QUEUE_APPEND")
            r["c"] = c.timed_send("PanCam", "pointCamera", _point(tables, -pan), action="QUEUE_INSERT", target=r["b"])
            r["d"] = c.timed_send("PanCam", "pointCamera", _point(tables, pan), action="QUEUE_APPEND")
            r["e"] = c.timed_send("PanCam", "pointCamera", _point(tables, pan), action="QUEUE_REPLACE", target=r["d"])
            r["f"] = c.timed_send("PanCam", "pointCamera", _point(tables, pan), action="QUEUE_APPEND")
            r["g"] = c.timed_send("Admin", "noOp", [], action="QUEUE_DELETE", target=r["f"])
            # beside the queue, on a subsystem of its own and not abortable: a BYPASS preempts
            # an abortable command running on its subsystem (rapid-protocol.md 5b)
            r["h"] = c.timed_send("K10Native", "nativeCommand", [("RAPID_STRING", f"round {i}")],
                                  action="QUEUE_BYPASS")
            rounds.append(r)
            wave.extend(r.values())
        with c.cond:
            c.cond.wait_for(lambda: all(c.acks.get(x) for x in [hold, *wave]), WAIT)
        if start == 0 and args.targets:  # the other tools act on the targets, then the queue goes on
            print(json.dumps({"gate": hold, "targets": targets}), flush=True)
            sys.stdin.readline()
        releases.append(c.timed_send("Admin", "noOp", [], action="QUEUE_DELETE", target=hold))
        c.wait_final([hold, releases[-1], *wave], WAIT)
    with c.cond:
        acks = {k: list(v) for k, v in c.acks.items()}
    out = {"rounds": rounds, "holds": holds, "releases": releases, "control": cid, "acks": acks,
           "gate": holds[0] if args.targets else None, "targets": targets,
           "latency": {k: c.done_at[k] - c.sent_at[k] for k in c.sent_at if k in c.done_at}}
    c.close()
    return out


def sequential(args) -> dict:
    """COUNT BYPASS commands one at a time (K10Native, instant): each sent once the one
    before is answered; seconds from send to its COMPLETED, and every ack."""
    rapid, tables, qos = load(args.package)
    c = TimedCommander(rapid, qos, tables.name, args.source, args.domain)
    if not c.wait_for_asset(WAIT):
        return {"error": "no asset"}
    control = c.first_contact("AccessControl", "requestControl", [])
    c.wait_final([control], WAIT)
    ids = []
    for i in range(args.count):
        ids.append(c.timed_send("K10Native", "nativeCommand", [("RAPID_STRING", f"seq {i}")]))
        c.wait_final(ids[-1:], WAIT)
    with c.cond:
        acks = {k: list(v) for k, v in c.acks.items() if k in ids}
    c.close()
    return {"ids": ids, "acks": acks, "latency": [c.done_at[k] - c.sent_at[k] for k in ids if k in c.done_at]}


def outage(args) -> dict:
    """LONG drives of HOLD s each and instant commands between them, all appended; once
    the first drive executes, prints "executing" and waits for a line on stdin (the test
    cuts the link), then appends DURING more commands (sent into the outage) and waits
    for every final ack."""
    rapid, tables, qos = load(args.package)
    c = TimedCommander(rapid, qos, tables.name, args.source, args.domain)
    if not c.wait_for_asset(WAIT):
        return {"error": "no asset"}
    control = c.first_contact("AccessControl", "requestControl", [])
    c.wait_final([control], WAIT)
    before, x = [], 0.0
    for i in range(args.long):
        x = args.hold * 0.5 * args.speed if x == 0.0 else 0.0
        before.append(c.timed_send("Mobility", "simpleMove", _move(x), action="QUEUE_APPEND"))
        before.append(c.timed_send("PanCam", "pointCamera", _point(tables, 0.1 * (i % 5)), action="QUEUE_APPEND"))
    with c.cond:
        c.cond.wait_for(lambda: any(a[0] == "ACK_EXECUTING" for a in c.acks.get(before[0], ())), WAIT)
    print("executing", flush=True)
    sys.stdin.readline()
    t_cut = time.monotonic()
    during = [c.timed_send("PanCam", "pointCamera", _point(tables, 0.05 * i), action="QUEUE_APPEND")
              for i in range(args.during)]
    c.wait_final(before + during, WAIT)
    with c.cond:
        acks = {k: list(v) for k, v in c.acks.items()}
    c.close()
    return {"before": before, "during": during, "acks": acks,
            "done_after_cut": {k: c.done_at[k] - t_cut for k in before + during if k in c.done_at}}


def late(args) -> dict:
    rapid, tables, qos = load(args.package)
    with open(args.ids, encoding="utf-8") as fh:
        ids = set(json.load(fh))
    node = Node(rapid, qos, args.domain)
    acks_reader = node.reader("rapid_ack", rapid.Ack)
    configs = {t: node.reader(t, type_class(rapid, ty)) for t, (ty, _v) in tables.configs.items()}
    queue = node.reader("rapid_queue_state", rapid.QueueState)
    final: dict[str, list] = {}
    got_configs: dict[str, int] = {}
    state = None
    end = time.monotonic() + WAIT
    # until each listed command's COMPLETED: a writer may keep more than the last ack per
    # command (the C++ bridge keeps 8), which arrive over a lossy link in any number of takes
    done: set[str] = set()
    while time.monotonic() < end and not (ids <= done and len(got_configs) == len(configs) and state):
        for s in acks_reader.take(N=4096):
            cmd_id, status, completed, message = M.ack_fields(s)
            if cmd_id in ids:
                final.setdefault(cmd_id, []).append([status, completed, message])
                if status == COMPLETED:
                    done.add(cmd_id)
        for topic, r in configs.items():
            for s in r.take(N=16):
                got_configs[topic] = s.hdr.serial
        for s in queue.take(N=16):
            state = {part: [[rec.cmd.cmdId, str(rec.trStatus).split(".")[-1]] for rec in getattr(s, part).records]
                     for part in ("pending", "active", "completed")}
        time.sleep(0.05)
    return {"acks": final, "configs": got_configs, "config_topics": sorted(configs), "queue": state,
            "ack_writers_blocking": _blocking(acks_reader)}


def _blocking(reader) -> list:
    """The max_blocking_time (s) of each writer matched to reader, as discovery announced it:
    shows which QoS profile a remote writer was made with (docs/qos.md, Fast DDS's @link
    profiles set it from the link's rtt)."""
    from cyclonedds.qos import Policy
    out = []
    for h in reader.get_matched_publications():
        try:
            rel = reader.get_matched_publication_data(h).qos[Policy.Reliability]
        except Exception:  # left meanwhile, or announced without it
            continue
        out.append(getattr(rel, "max_blocking_time", 0) / 1e9)
    return out


def main() -> int:
    ap = argparse.ArgumentParser()
    sub = ap.add_subparsers(dest="what", required=True)
    d = sub.add_parser("drive")
    d.add_argument("package")
    d.add_argument("domain", type=int)
    d.add_argument("rounds", type=int)
    d.add_argument("--wave", type=int, default=10)
    d.add_argument("--speed", type=float, default=1.0, help="the bridge's simulation speed")
    d.add_argument("--targets", type=int, default=0,
                   help="in the first wave, also queue N x 3 targets, print their ids and the wave's drive (JSON) and "
                        "wait for a line on stdin (other tools INSERT after, REPLACE and DELETE them) before deleting it")
    d.add_argument("--source", default="RapidWorkbench")  # K10's allow-list lets it send everything
    q = sub.add_parser("sequential")
    q.add_argument("package")
    q.add_argument("domain", type=int)
    q.add_argument("count", type=int)
    q.add_argument("--source", default="RapidWorkbench")
    o = sub.add_parser("outage")
    o.add_argument("package")
    o.add_argument("domain", type=int)
    o.add_argument("--long", type=int, default=4, help="drives queued")
    o.add_argument("--hold", type=float, default=4.0, help="seconds each drive lasts")
    o.add_argument("--speed", type=float, default=1.0)
    o.add_argument("--during", type=int, default=3, help="commands sent while the link is down")
    o.add_argument("--source", default="RapidWorkbench")
    late_p = sub.add_parser("late")
    late_p.add_argument("package")
    late_p.add_argument("domain", type=int)
    late_p.add_argument("ids")
    args = ap.parse_args()
    out = {"drive": drive, "sequential": sequential, "outage": outage, "late": late}[args.what](args)
    print(json.dumps(out), flush=True)
    os._exit(0)  # DDS threads need not be joined: the answer is printed


if __name__ == "__main__":
    sys.exit(main())
