"""The command queue (rapid-protocol.md 4 and 5b), on assets with a Queue subsystem."""
from __future__ import annotations

import time

from rapidgen.textsafe import visible
from rapidgen.conform.asset import valid_args
from rapidgen.conform.model import REQUIRED, Blocked, Unsupported, check, expect
from rapidgen.conform.session import describe

from .commands import _harmless, _ready
from .dds import qos_mismatch

TOPIC = "rapid_queue_state"
CODES = {-1, 0, 1}  # suspended, idle, active
RECORD = {"pending": {"Q_STATUS_INLINE", "Q_STATUS_PAUSED"}, "active": {"Q_STATUS_INPROCESS", "Q_STATUS_PAUSED"},
          "completed": {"Q_STATUS_SUCCEEDED", "Q_STATUS_FAILED", "Q_STATUS_CANCELED"}}


HOLD = 1.0  # s a long command runs while the command behind it must wait (QUE-02)
PROBE_AGAIN = 2.0  # s for the first ack of a command that should be answered at once
SETTLE = 1.0  # s after a command's final ack by which QueueState no longer lists it pending or active


def _queue(s, answers: bool = True):
    if not s.facts.has_type("Queue"):
        raise Unsupported("the asset has no Queue subsystem")
    _ready(s, answers)


@check("QUE-01", REQUIRED, "QueueState is published, durable, with statusCode -1, 0 or 1",
       "rapid-protocol.md 5b: QueueState; RapidStateQos", needs=("CMD-01",))
def published(s):
    _queue(s, answers=False)  # judges the state alone
    eps = s.wait_endpoint("writer", TOPIC)
    if not eps:
        raise Blocked(f"no {TOPIC} writer (DDS-06)")
    bad = [w for ep in eps if (w := qos_mismatch(ep, "RapidStateQos"))]
    expect(not bad, "Reliable, TransientLocal, KeepLast", "; ".join(bad))
    st = s.latest(TOPIC, timeout=3.0)
    expect(st is not None, "a QueueState for a late-joining reader", "none")
    expect(st.hdr.statusCode in CODES, "statusCode -1, 0 or 1", st.hdr.statusCode)


@check("QUE-02", REQUIRED, "Queued commands run one at a time, first in first out",
       "rapid-protocol.md 5b: the queue", needs=("CMD-02",))
def fifo(s):
    """Three instant commands appended at once complete in order, none EXECUTING before the
    one ahead of it COMPLETED; then, where the asset has a command that lasts (a drive), an
    instant command appended behind it must not execute while the drive runs (instant
    commands alone cannot show a queue that starts its commands together)."""
    _queue(s)
    c = _harmless(s)
    ids = [s.client.send(c.subsystem, c.name, valid_args(c), source=s.source, action="QUEUE_APPEND") for _ in range(3)]
    s.memo["fifo"] = ids
    for cid in ids:
        s.wait_acks(cid)
    for cid in ids:  # one lost: the order cannot be judged (CMD-16 names it)
        s.require_final(cid)
    # as the asset wrote them (one take hands a keyed topic's samples out instance by instance)
    acks = sorted((a for a in s.client.acks if a.cmd_id in ids), key=lambda a: (a.stamp, a.index))
    place = {id(a): n for n, a in enumerate(acks)}
    finals = [a.cmd_id for a in acks if a.status == "ACK_COMPLETED"]
    expect(finals == ids, "COMPLETED in the order appended", f"{[ids.index(f) for f in finals]} of {len(ids)}")
    for k in range(1, len(ids)):  # k's EXECUTING comes after k-1's COMPLETED
        done = next(place[id(a)] for a in acks if a.cmd_id == ids[k - 1] and a.status == "ACK_COMPLETED")
        early = [a for a in acks if a.cmd_id == ids[k] and a.status == "ACK_EXECUTING" and place[id(a)] < done]
        expect(not early, f"command {k + 1} executing after command {k} completed", describe(early))
    for cid in ids:
        s.expect_ok(s.client.acks_of(cid), "an appended command")
    return _one_at_a_time(s, c)


def _one_at_a_time(s, c) -> str | None:
    cancel = s.facts.command("Queue", "cancelAll")
    try:
        long = s.long_running()
    except Unsupported as u:  # a drive the runner may not send: FIFO judged, one at a time not
        return f"one at a time judged with instant commands only ({u})"
    if long is None or cancel is None:
        return "one at a time judged with instant commands only (no long-running command, or no Queue/cancelAll)"
    cmd, args = long
    t0 = time.monotonic()
    first = s.client.send(cmd.subsystem, cmd.name, args, source=s.source, action="QUEUE_APPEND")
    second = s.client.send(c.subsystem, c.name, valid_args(c), source=s.source, action="QUEUE_APPEND")
    try:
        _started(s, first)
        # Evidence either way: the second starts (or completes), the first completes, or HOLD passes.
        s.wait_acks(second, ("ACK_EXECUTING", "ACK_COMPLETED"), timeout=HOLD)
        early, began = _overlap(s, first, second)
    finally:
        _let_go(s, first)  # let the drive go (the second, pending, is canceled with it)
    if not early:  # the second's acks once both are final (a late EXECUTING would show here)
        for cid in (first, second):
            s.wait_acks(cid)
        early, began = _overlap(s, first, second)
    expect(not early, f"{c.subsystem}/{c.name}, appended behind {cmd.subsystem}/{cmd.name}, not executing before "
                      f"the drive COMPLETED",
           f"overlapping EXECUTING acks: {c.name} {early[0].status[4:]} at +{early[0].at - t0:.2f} s while "
           f"{cmd.name} was EXECUTING (since +{(began.at - t0) if began else 0:.2f} s) and not COMPLETED"
           if early else "")
    return None


def _started(s, drive: str) -> None:
    """Wait for the drive's EXECUTING (or COMPLETED); BLOCKED when it got no ack at all (lost:
    CMD-16's finding), as nothing can be judged behind a drive that never started."""
    s.wait_acks(drive, ("ACK_EXECUTING", "ACK_COMPLETED"))
    if not s.client.acks_of(drive):
        raise Blocked(s.silence(drive) + " (CMD-16)")


def _let_go(s, drive: str) -> None:
    """Queue/cancelAll unless the drive is answered COMPLETED: the runner never leaves a drive it
    sent running. Sent directly (a check BLOCKED by the asset's answers still stops its drive),
    and once more when the first cancelAll gets no ack at all."""
    cancel = s.facts.command("Queue", "cancelAll")
    if cancel is None or any(a.status == "ACK_COMPLETED" for a in s.client.acks_of(drive)):
        return
    for _ in range(2):
        cid = s.client.send(cancel.subsystem, cancel.name, [], source=s.source)
        try:
            s.wait_acks(cid, timeout=PROBE_AGAIN)
        except Blocked:  # acks the runner cannot tell apart: the cancel was sent all the same
            return
        if s.client.acks_of(cid):
            return


def _overlap(s, first: str, second: str):
    """(the second's EXECUTING or COMPLETED acks that came before the first's COMPLETED, the
    first's EXECUTING ack). A pending command canceled with the first is no overlap, nor
    anything after the second's own COMPLETED."""
    both = [a for a in s.client.acks if a.cmd_id in (first, second)]
    done = next((a.index for a in both if a.cmd_id == first and a.status == "ACK_COMPLETED"), None)
    began = next((a for a in both if a.cmd_id == first and a.status == "ACK_EXECUTING"), None)
    acks = [a for a in both if a.cmd_id == second]
    final = next((n for n, a in enumerate(acks) if a.status == "ACK_COMPLETED"), None)
    acks = acks if final is None else acks[:final + 1]  # what follows its COMPLETED is CMD-04's
    early = [a for a in acks if a.status in ("ACK_EXECUTING", "ACK_COMPLETED")
             and (done is None or a.index < done) and a.completed != "ACK_COMPLETED_CANCELED"]
    return early, began


@check("QUE-03", REQUIRED, "Queue actions with invalid targets are answered non-OK",
       "rapid-protocol.md 5b: BYPASS/APPEND with a target, INSERT/REPLACE/DELETE with none or an unknown one",
       needs=("CMD-01",))
def targets(s):
    _queue(s)
    c = _harmless(s)
    bad = []
    for action, target in (("QUEUE_APPEND", "some-target"), ("QUEUE_INSERT", ""), ("QUEUE_REPLACE", "no-such-id"),
                           ("QUEUE_DELETE", "no-such-id")):
        acks = s.run(c, action=action, target=target)
        f = s.final(acks)
        if f is None or f.completed in ("ACK_COMPLETED_OK", "ACK_COMPLETED_NOT"):
            bad.append(f"{action} target {target!r}: {describe(acks)}")
    expect(not bad, "BAD_SYNTAX or EXEC_FAILED", "; ".join(bad))


@check("QUE-04", REQUIRED, "DELETE cancels a pending command", "rapid-protocol.md 5b: DELETE of a pending command",
       needs=("CMD-02", "QUE-02"))
def delete(s):
    _queue(s)
    cmd, args, c = _held(s)
    first = s.client.send(cmd.subsystem, cmd.name, args, source=s.source, action="QUEUE_APPEND")
    second, d = "", []
    try:
        # the victim is appended once the long command runs: DELETE is judged on a pending
        # command whatever order the queue takes waiting commands in (that is QUE-02's)
        _started(s, first)
        second = s.client.send(c.subsystem, c.name, valid_args(c), source=s.source, action="QUEUE_APPEND")
        time.sleep(0.3)
        d = s.run(c, action="QUEUE_DELETE", target=second)
        if s.final(d).completed == "ACK_COMPLETED_OK":
            s.wait_acks(second)
    finally:
        _let_go(s, first)  # a DELETE refused: the victim, still pending, is canceled with the drive
    s.wait_acks(first)
    victim = s.wait_acks(second, timeout=PROBE_AGAIN)
    if not victim:  # never reached the queue (lost): the DELETE had no target to cancel
        raise Blocked(s.silence(second) + " (CMD-16): the DELETE cannot be judged")
    s.expect_ok(d, "the DELETE")
    f = s.final(victim)
    expect(f is not None and f.completed == "ACK_COMPLETED_CANCELED", "the deleted command COMPLETED/CANCELED",
           describe(victim))


@check("QUE-05", REQUIRED, "QueueState records carry the statuses of their lists",
       "rapid-protocol.md 5b: QUEUED -> INLINE, EXECUTING -> INPROCESS, completions -> SUCCEEDED/FAILED/CANCELED",
       needs=("QUE-01", "QUE-02"))
def records(s):
    _queue(s)
    states = [r.sample for r in s.client.samples(TOPIC)]
    bad, listed = [], set()
    for st in states:
        if st.hdr.statusCode not in CODES:
            bad.append(f"statusCode {st.hdr.statusCode}")
        for name, allowed in RECORD.items():
            for rec in _records(getattr(st, name)):
                listed.add(rec.cmd.cmdId)
                status = getattr(rec.trStatus, "name", str(rec.trStatus))
                if status not in allowed:
                    bad.append(f"{name} record {visible(rec.cmd.cmdId)}: {visible(status)}")
    missing = [cid for cid in s.memo.get("fifo", []) if cid not in listed]
    expect(not bad, "record statuses matching their list", "; ".join(sorted(set(bad))[:4]))
    expect(not missing, "the appended commands listed in QueueState", f"{len(missing)} never listed")


def _held(s):
    """(the long-running command, its arguments, the harmless command) of a check that holds
    the queue with a drive; Unsupported (why) when the runner may not send one."""
    long = s.long_running()
    if long is None:
        raise Unsupported("no long-running command (Mobility move) to hold the queue")
    return (*long, _harmless(s))


def _records(q):
    """SingleQueue's one (anonymous in the IDL) sequence member, whatever it is called."""
    for name in getattr(q, "__dataclass_fields__", {}):
        v = getattr(q, name)
        if isinstance(v, list):
            return v
    return []


RECORD_OF = {"ACK_COMPLETED_OK": "Q_STATUS_SUCCEEDED", "ACK_COMPLETED_BAD_SYNTAX": "Q_STATUS_FAILED",
             "ACK_COMPLETED_EXEC_FAILED": "Q_STATUS_FAILED", "ACK_COMPLETED_CANCELED": "Q_STATUS_CANCELED"}


def _listed(st) -> dict[str, tuple[str, str]]:
    """cmdId -> (list, record status) in one QueueState."""
    out = {}
    for name in ("completed", "active", "pending"):  # pending last: it wins for a cmdId listed twice
        for rec in _records(getattr(st, name)):
            out[rec.cmd.cmdId] = (name, getattr(rec.trStatus, "name", str(rec.trStatus)))
    return out


def _pending_order(s, ids: list[str], since: float) -> list[str] | None:
    """The order of ids in the latest QueueState received since `since` whose pending list
    holds them all (waiting SETTLE s for one); None when none did."""
    end = time.monotonic() + s.allow(SETTLE)
    while True:
        for r in reversed(s.client.samples(TOPIC)):
            if r.at < since:
                break
            pending = [rec.cmd.cmdId for rec in _records(r.sample.pending)]
            if all(i in pending for i in ids):
                return [i for i in pending if i in ids]
        if time.monotonic() > end:
            return None
        time.sleep(0.05)


@check("QUE-06", REQUIRED, "INSERT puts a command after its target; REPLACE puts it in its target's place",
       "rapid-protocol.md 4 and 5b: INSERT goes after targetCmdId; REPLACE cancels its target",
       needs=("QUE-02", "QUE-04"))
def positions(s):
    """Behind a running drive: A, B, E appended; C inserted after A; R replacing B. The pending
    order must be A, C, R, E (QueueState) and B CANCELED; the drive is then DELETEd and, where
    the queue carries on (it may suspend after a cancellation: soraCore), the four complete in
    that order."""
    _queue(s)
    cmd, args, c = _held(s)

    def send(action="QUEUE_APPEND", target=""):
        return s.client.send(c.subsystem, c.name, valid_args(c), source=s.source, action=action, target=target)
    drive = s.client.send(cmd.subsystem, cmd.name, args, source=s.source, action="QUEUE_APPEND")
    order = None
    try:
        _started(s, drive)
        a, b, e = send(), send(), send()
        since = time.monotonic()
        ins = send("QUEUE_INSERT", a)
        rep = send("QUEUE_REPLACE", b)
        want = [a, ins, rep, e]
        s.wait_acks(b, timeout=PROBE_AGAIN)  # REPLACE cancels it at once
        order = _pending_order(s, want, since)
        refused = [f"{n} {describe(s.client.acks_of(cid))}" for n, cid in (("INSERT", ins), ("REPLACE", rep))
                   if (f := s.final(s.client.acks_of(cid))) is not None and f.completed != "ACK_COMPLETED_OK"]
        expect(not refused, "INSERT after a pending command and REPLACE of one accepted", "; ".join(refused))
        s.client.send(c.subsystem, c.name, valid_args(c), source=s.source, action="QUEUE_DELETE", target=drive)
        end = time.monotonic() + s.allow(PROBE_AGAIN)  # the queue carries on once the drive is canceled (or waits)
        while time.monotonic() < end and any(s.final(s.client.acks_of(cid)) is None for cid in want):
            time.sleep(0.05)
    finally:
        _let_go(s, drive)  # cancels what still waits
    for cid in (*want, b):  # one that never reached the queue (lost): nothing to judge its place by
        if not s.wait_acks(cid, timeout=PROBE_AGAIN):
            raise Blocked(s.silence(cid) + " (CMD-16)")
    names = {a: "A", ins: "C (INSERT after A)", rep: "R (REPLACE B)", e: "E"}
    replaced = s.final(s.client.acks_of(b))
    done = [x for x in s.client.acks if x.cmd_id in want and x.status == "ACK_COMPLETED"
            and x.completed == "ACK_COMPLETED_OK"]
    ran = [x.cmd_id for x in sorted(done, key=lambda x: (x.stamp, x.index))]  # as the asset wrote them
    bad = []
    if replaced is None or replaced.completed != "ACK_COMPLETED_CANCELED":
        bad.append(f"B, replaced, answered {describe(s.client.acks_of(b))}")
    if order is not None and order != want:
        bad.append("QueueState pending " + ", ".join(names[i] for i in order))
    if len(ran) == len(want) and ran != want:
        bad.append("completed " + ", ".join(names[i] for i in ran))
    if order is None and len(ran) < len(want):
        raise Blocked("neither a QueueState listing the four pending nor their execution showed the order "
                      "(QUE-05, QUE-07)")
    expect(not bad, "pending and run as A, C (INSERT after A), R (REPLACE B), E; B CANCELED "
                    "(rapid-protocol.md 4: INSERT goes after targetCmdId; 5b: REPLACE cancels its target)",
           "; ".join(bad))
    return None if len(ran) == len(want) else "judged on QueueState (the queue did not run them after the drive)"


# Right after QUE-06 (its drive's completion is the last change the runner caused): this check
# sends nothing, so the state the asset publishes on that completion is the only one that can come.
@check("QUE-07", REQUIRED, "QueueState follows the acks: a finished command is no longer listed pending or active",
       "rapid-protocol.md 5b: QueueState on every change; Ack -> queue status (COMPLETED: a completed record)",
       needs=("QUE-01", "QUE-02"))
def follows(s):
    """For each queued command of the runner's with a final ack and no command of the runner's
    sent within SETTLE s after it (another change would republish the state for it): the
    latest QueueState received by then no longer lists it pending or active, and, where it
    lists it completed, with the status of its completion."""
    _queue(s)
    c = s.client
    with c.lock:
        queued = [cid for cid, cmd in c.sent.items() if getattr(cmd.cmdAction, "name", "") != "QUEUE_BYPASS"]
    with c.lock:
        sends = sorted(c.sent_at.values())
    finals = {cid: f for cid in queued if (f := s.final(c.acks_of(cid))) is not None
              and not any(f.at < at <= f.at + s.allow(SETTLE) for at in sends)}
    if not finals:
        raise Unsupported("no queued command was answered with a quiet second after it (QUE-02 judges the queue)")
    left = max(f.at for f in finals.values()) + s.allow(SETTLE) - time.monotonic()
    if left > 0:
        time.sleep(left)
    states = [(r.at, r.sample) for r in c.samples(TOPIC)]
    bad = []
    for cid, f in finals.items():
        by = f.at + s.allow(SETTLE)
        st = next(((at, x) for at, x in reversed(states) if at <= by), None)
        if st is None:
            continue
        where = _listed(st[1]).get(cid)
        if where is None:
            continue
        name, status = where
        if name in ("pending", "active"):
            bad.append(f"{visible(cid)[:60]!r} still listed {name} ({visible(status)}) {SETTLE:g} s after its final "
                       f"ack {describe([f])} (the latest QueueState came {f.at - st[0]:.2f} s before that ack)"
                       if st[0] < f.at else
                       f"{visible(cid)[:60]!r} listed {name} ({visible(status)}) in the QueueState of "
                       f"+{st[0] - f.at:.2f} s after its final ack {describe([f])}")
        elif RECORD_OF.get(f.completed, status) != status:
            bad.append(f"{visible(cid)[:60]!r} completed as {visible(status)} after {describe([f])}")
    expect(not bad, "QueueState republished when a command finishes: not pending or active after its final ack, "
                    "a completed record of its completion (rapid-protocol.md 5b)", "; ".join(bad[:3]))
    return f"{len(finals)} queued command(s) followed"
