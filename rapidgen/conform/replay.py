"""The protocol specification's cases (runtime/spec) replayed live against the asset under
test: the same rules every runtime replays offline, judged from the wire (SPEC-01).

A case is replayed when it can be, here:
- it is live (rapidgen.protocol_cases: no step the runner cannot perform over DDS, such as
  releasing a handler, a restart or the door's refusal; its handlers only answer), sends no
  Admin/shutdown, and moves nothing the run may not move (docs/conformance.md);
- the asset agrees with the case's seed on everything the case uses: each command exists
  with the same parameter types, each source has the same rights, both have (or lack) a
  Queue and an AccessControl subsystem.

What is compared: each cmdId's outcome (no ack where the case expects none; else the
completion of its first final ack: the acks before it, a repeat's final ack again and the
texts vary between implementations, and CMD-03/CMD-04 judge the sequence), the last
QueueState (code, pending and active cmdIds) and AccessControlState (controller,
requestors). What only the runtime itself shows (handler calls, retired acks,
its log, its own pending list) is not. cmdIds get a prefix of this run's, so a case can be
replayed again against the same asset.
"""
from __future__ import annotations

import os
import time

from rapidgen.conform.asset import is_motion
from rapidgen.conform.model import Fail
from rapidgen.textsafe import visible

QUEUE_TOPIC = "rapid_queue_state"
ACCESS_TOPIC = "rapid_accesscontrol_state"
UNSEEN = ("calls", "retired", "log", "no_log", "pending", "order", "stopped")  # expectations the wire does not show
MAX_RELEASES = 20  # releaseControl rounds to free control before a case (each passes it on)
QUIET = 0.5  # s a command the case expects unanswered is watched for an ack


def applicable(case: dict, seed_tables, facts, motion_ok, speaks_as: str | None = None) -> str | None:
    """Why the case cannot be replayed against this asset (None: it can). speaks_as: the one
    source a runner on a secured domain may send as (its enclave's)."""
    if not case["live"]:
        return "offline only"
    if seed_tables.has_type("Queue") != facts.has_type("Queue") or \
            seed_tables.has_type("AccessControl") != facts.has_type("AccessControl"):
        return "the asset's Queue/AccessControl subsystems differ from the case's seed"
    for s in case["steps"]:
        if s["op"] != "send":
            continue
        if speaks_as and s["src"] != speaks_as:
            return f"sends as {s['src']}: on a secured domain the runner speaks only as {speaks_as}"
        if (s["subsystem"], s["name"]) == ("Admin", "shutdown"):
            return "shuts the asset down"
        entry = seed_tables.command(s["subsystem"], s["name"])
        if entry is None:
            continue  # a command the seed does not know: the case expects a refusal, any asset's
        cmd = next((c for c in facts.commands() if c.subsystem == s["subsystem"] and c.name == s["name"]), None)
        if cmd is None or [p["type"] for p in cmd.params] != [p.type for p in entry.params]:
            return f"{s['subsystem']}/{s['name']} differs from the seed's"
        if is_motion(cmd) and not motion_ok(cmd):
            return f"sends {s['subsystem']}/{s['name']}, which moves the asset"
        if facts.allowed(s["src"], cmd) != _seed_allows(seed_tables, s["src"], s["subsystem"], s["name"]):
            return f"{s['src']}'s rights differ from the seed's"
    return None


def _seed_allows(tables, source: str, subsystem: str, name: str) -> bool:
    """The seed's allow-list read as AssetFacts.allowed reads the asset's (the runner's own
    reading, not the runtime's: it judges the runtimes)."""
    if tables.access is None:
        return True
    rule = next((r for r in tables.access.rules if r.source == source), None)
    if rule is None:
        return tables.access.default == "allow"
    return any(a in ("*", f"{subsystem}/*", f"{subsystem}/{name}") for a in rule.allow)


class Replay:
    """One case against the live asset through the conformance session."""

    def __init__(self, s, case: dict, seed_name: str, prefix: str) -> None:
        self.s, self.case, self.seed_name, self.prefix = s, case, seed_name, prefix
        self.started = time.monotonic()
        self.sent: set[str] = set()

    def live_id(self, cid: str) -> str:
        return f"{self.prefix}{cid}" if cid and cid != "head" else cid

    def case_id(self, live: str) -> str:
        return live[len(self.prefix):] if live.startswith(self.prefix) else live

    def where(self, i: int) -> str:
        return f"{self.case['file']}:{self.case['line']} {self.case['name']!r}, step {i + 1}"

    def run(self) -> None:
        for i, step in enumerate(self.case["steps"]):
            op = step["op"]
            if op == "send":
                asset = self.s.asset if step["asset"] == self.seed_name else step["asset"]
                live = self.live_id(step["id"])
                if asset != self.s.asset:  # another asset's: no answer is owed (CMD-16)
                    self.s.unanswerable.add(live)
                if live in self.sent:  # sent again on purpose: its final ack again is no finding (CMD-04)
                    self.s.memo.setdefault("repeats", set()).add(live)
                self.sent.add(live)
                self.s.client.send(step["subsystem"], step["name"], [(a["type"], a["value"]) for a in step["args"]],
                                   source=step["src"], action=step["action"], target=self.live_id(step["target"]),
                                   cmd_id=self.live_id(step["id"]), asset=asset)
            elif op == "acks":
                self.acks(i, step)
            elif op == "queue":
                self.state(i, QUEUE_TOPIC, step, self.queue_seen)
            elif op == "control":
                self.state(i, ACCESS_TOPIC, step, self.control_seen)
            elif op in UNSEEN:
                continue
            else:  # (applicable() let no other step through)
                raise Fail(f"{self.where(i)}: a step the runner can perform", op)

    def _acks(self, cid: str) -> list:
        return [a for a in self.s.client.acks_of(self.live_id(cid)) if a.at >= self.started]

    def acks(self, i: int, step: dict) -> None:
        """Live, a cmdId's outcome is judged, not its whole sequence: the acks before the final
        one and a repeat's final ack differ between implementations (Astrobee sends no
        QUEUED; soraCore drops a repeated cmdId) and CMD-03/CMD-04 judge them. So: a command
        the case expects unanswered gets no ack (within a short look), one it expects to end
        ends with the completion the case says (its first COMPLETED), and one still in flight
        is not judged yet."""
        want = [(a["status"], a["completion"]) for a in step["acks"]]
        finals = [c for st, c in want if st == "COMPLETED"]

        def seen() -> list:
            return self._acks(step["id"])

        if not want:
            time.sleep(self.s.allow(QUIET))
            got = seen()
            if got:
                raise Fail(f"{self.where(i)}: no ack for {step['id']}", _shown(got))
            return
        if not finals:
            return
        if not self._wait(lambda: any(a.status == "ACK_COMPLETED" for a in seen())):
            raise Fail(f"{self.where(i)}: {step['id']} ends COMPLETED {finals[0] or ''}".rstrip(), _shown(seen()) or
                       "no final ack")
        first = next(a for a in seen() if a.status == "ACK_COMPLETED")
        got = first.completed.removeprefix("ACK_COMPLETED_")
        if finals[0] is not None and got != finals[0]:
            raise Fail(f"{self.where(i)}: {step['id']} ends COMPLETED {finals[0]}", _shown(seen()))

    def queue_seen(self, st) -> dict:
        return {"code": st.hdr.statusCode,
                "pending": [self.case_id(r.cmd.cmdId) for r in _records(st.pending)],
                "active": [self.case_id(r.cmd.cmdId) for r in _records(st.active)]}

    def control_seen(self, st) -> dict:
        return {"controller": st.controller, "requestors": list(st.requestors)}

    def state(self, i: int, topic: str, step: dict, view) -> None:
        want = {k: v for k, v in step.items() if k != "op"}

        def now() -> dict | None:
            st = self.s.latest(topic)
            return None if st is None else view(st)

        def ok() -> bool:
            got = now()
            return got is not None and all(got.get(k) == v for k, v in want.items())
        if not self._wait(ok):
            raise Fail(f"{self.where(i)}: {topic} {want}", str(now()))

    def _wait(self, ok) -> bool:
        end = time.monotonic() + self.s.timeout
        c = self.s.client
        with c.lock:
            while not ok():
                left = end - time.monotonic()
                if left <= 0:
                    return False
                c.lock.wait(min(left, 0.1))
        return True


def _shown(acks) -> str:
    return ", ".join(f"{a.status.removeprefix('ACK_')} {a.completed.removeprefix('ACK_COMPLETED_')}" for a in acks)


def _records(q) -> list:
    """SingleQueue's one sequence member (anonymous in the IDL), whatever it is called."""
    for name in getattr(q, "__dataclass_fields__", {}):
        v = getattr(q, name)
        if isinstance(v, list):
            return v
    return []


def free_control(s, sources: set[str]) -> bool:
    """Nobody holds control (True), releasing it from whichever of `sources` holds it; False
    when someone else does."""
    if not s.facts.has_type("AccessControl"):
        return True
    for _ in range(MAX_RELEASES):
        st = s.latest(ACCESS_TOPIC, timeout=2.0)
        holder = "" if st is None else st.controller
        if holder == "":
            s.holder = None
            return True
        if holder not in sources:
            return False
        s.run(("AccessControl", "releaseControl"), [], source=holder, final=False)
        s.controller(2.0, want="" if not (st and st.requestors) else None)
    return False


def cases_and_seeds():
    """(every case, seed -> its tables), or None where runtime/spec is not there (an
    installed wheel: the cases and the seeds' tables live in a rapidgen checkout)."""
    from rapidgen.protocol_cases import CASES, ROOT, SEEDS, load_cases, seed_tables
    folder, package = SEEDS["k10"]
    if not CASES.is_dir() or not (ROOT / "generated" / folder / "python" / package).is_dir():
        return None
    return load_cases(), seed_tables


def run_prefix() -> str:
    return f"spec-{os.getpid()}-{time.time_ns() // 1_000_000 % 10_000_000}-"


def describe_skip(case: dict, why: str) -> str:
    return f"{case['file']}:{case['line']} {visible(case['name'])[:60]}: {why}"
