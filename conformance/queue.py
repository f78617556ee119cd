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
    acks = [a for a in s.client.acks if a.cmd_id in ids]
    finals = [a.cmd_id for a in acks if a.status == "ACK_COMPLETED"]
    expect(finals == ids, "COMPLETED in the order appended", f"{[ids.index(f) for f in finals]} of {len(ids)}")
    for k in range(1, len(ids)):  # k's EXECUTING comes after k-1's COMPLETED
        done = next(a.index for a in acks if a.cmd_id == ids[k - 1] and a.status == "ACK_COMPLETED")
        early = [a for a in acks if a.cmd_id == ids[k] and a.status == "ACK_EXECUTING" and a.index < done]
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
    s.wait_acks(first, ("ACK_EXECUTING", "ACK_COMPLETED"))
    # Evidence either way: the second starts (or completes), the first completes, or HOLD passes.
    s.wait_acks(second, ("ACK_EXECUTING", "ACK_COMPLETED"), timeout=HOLD)
    early, began = _overlap(s, first, second)
    if not any(a.status == "ACK_COMPLETED" for a in s.client.acks_of(first)):
        s.run(cancel)  # let the drive go (the second, pending, is canceled with it)
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
    long = s.long_running()  # Unsupported (why) when the runner may not send it
    if long is None:
        raise Unsupported("no long-running command (Mobility move) to hold the queue")
    cmd, args = long
    c = _harmless(s)
    first = s.client.send(cmd.subsystem, cmd.name, args, source=s.source, action="QUEUE_APPEND")
    # the victim is appended once the long command runs: DELETE is judged on a pending
    # command whatever order the queue takes waiting commands in (that is QUE-02's)
    s.wait_acks(first, ("ACK_EXECUTING", "ACK_COMPLETED"))
    second = s.client.send(c.subsystem, c.name, valid_args(c), source=s.source, action="QUEUE_APPEND")
    time.sleep(0.3)
    d = s.run(c, action="QUEUE_DELETE", target=second)
    victim = s.wait_acks(second)
    cancel = s.facts.command("Queue", "cancelAll")  # let the long command go
    if cancel is not None:
        s.run(cancel)
    s.wait_acks(first)
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


def _records(q):
    """SingleQueue's one (anonymous in the IDL) sequence member, whatever it is called."""
    for name in getattr(q, "__dataclass_fields__", {}):
        v = getattr(q, name)
        if isinstance(v, list):
            return v
    return []
