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


def _queue(s):
    if not s.facts.has_type("Queue"):
        raise Unsupported("the asset has no Queue subsystem")
    _ready(s)


@check("QUE-01", REQUIRED, "QueueState is published, durable, with statusCode -1, 0 or 1",
       "rapid-protocol.md 5b: QueueState; RapidStateQos", needs=("CMD-01",))
def published(s):
    _queue(s)
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
    _queue(s)
    c = _harmless(s)
    ids = [s.client.send(c.subsystem, c.name, valid_args(c), source=s.source, action="QUEUE_APPEND") for _ in range(3)]
    s.memo["fifo"] = ids
    for cid in ids:
        s.client.wait_final(cid, s.timeout)
    acks = [a for a in s.client.acks if a.cmd_id in ids]
    finals = [a.cmd_id for a in acks if a.status == "ACK_COMPLETED"]
    expect(finals == ids, "COMPLETED in the order appended", f"{[ids.index(f) for f in finals]} of {len(ids)}")
    for k in range(1, len(ids)):  # k's EXECUTING comes after k-1's COMPLETED
        done = next(a.index for a in acks if a.cmd_id == ids[k - 1] and a.status == "ACK_COMPLETED")
        early = [a for a in acks if a.cmd_id == ids[k] and a.status == "ACK_EXECUTING" and a.index < done]
        expect(not early, f"command {k + 1} executing after command {k} completed", describe(early))
    for cid in ids:
        s.expect_ok(s.client.acks_of(cid), "an appended command")


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
       needs=("CMD-02",))
def delete(s):
    _queue(s)
    long = s.facts.long_running()
    if long is None:
        raise Unsupported("no long-running command (Mobility move) to hold the queue")
    cmd, args = long
    c = _harmless(s)
    first = s.client.send(cmd.subsystem, cmd.name, args, source=s.source, action="QUEUE_APPEND")
    # the victim is appended once the long command runs: DELETE is judged on a pending
    # command whatever order the queue takes waiting commands in (that is QUE-02's)
    s.client.wait_status(first, ("ACK_EXECUTING", "ACK_COMPLETED"), s.timeout)
    second = s.client.send(c.subsystem, c.name, valid_args(c), source=s.source, action="QUEUE_APPEND")
    time.sleep(0.3)
    d = s.run(c, action="QUEUE_DELETE", target=second)
    victim = s.client.wait_final(second, s.timeout)
    cancel = s.facts.command("Queue", "cancelAll")  # let the long command go
    if cancel is not None:
        s.run(cancel)
    s.client.wait_final(first, s.timeout)
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
