"""Commands and acks (rapid-protocol.md 5 and 5b). Where soraCore and Astrobee differ
(QUEUED or not, dropping other assets' commands and repeated cmdIds), both pass."""
from __future__ import annotations

import os
import time
from typing import Any

from rapidgen.textsafe import visible
from rapidgen.conform.asset import is_motion, valid_args, wrong_type
from rapidgen.conform.model import RECOMMENDED, REQUIRED, Blocked, Unsupported, check, expect
from rapidgen.conform.session import COMPLETED, GRACE, describe

from .dds import qos_mismatch

QUIET = 1.0  # s without an ack that shows a command was ignored (plus the link's round trips: s.pause)
NEXT = {  # ack status -> statuses that may follow it for one cmdId (5b, both implementations)
    None: {"ACK_QUEUED", "ACK_EXECUTING", "ACK_COMPLETED"},
    "ACK_QUEUED": {"ACK_EXECUTING", "ACK_COMPLETED", "ACK_REQUEUED"},
    "ACK_EXECUTING": {"ACK_EXECUTING", "ACK_REQUEUED", "ACK_COMPLETED"},
    "ACK_REQUEUED": {"ACK_QUEUED", "ACK_EXECUTING", "ACK_COMPLETED", "ACK_REQUEUED"},
}


def _ready(s, answers: bool = True):
    """The command path matched (and control taken, where the asset has access control).
    answers: BLOCKED when an earlier command showed its answers cannot be judged (the
    checks that do not wait for answers pass False)."""
    s.needs_commands()
    if "ready" not in s.memo:
        s.memo["ready"] = s.wait_command_match(s.timeout)
        if s.memo["ready"]:
            try:
                s.ensure_control()
            except Blocked:  # acks the runner cannot tell apart: Session.answers() says so from now on
                pass
    expect(s.memo["ready"], "the asset's command reader and ack writer matched", "no match")
    if answers:
        s.answers()


def _harmless(s):
    c = s.facts.harmless()
    if c is None:
        raise Unsupported("no command to send that moves nothing")
    return c


@check("CMD-01", REQUIRED, "The asset reads rapid_command and writes rapid_ack in its partition",
       "rapid-protocol.md 4 and 5b (the Ack topic is plain rapid_ack)")
def endpoints(s):
    s.needs_commands()
    r, w = s.wait_endpoint("reader", "rapid_command"), s.wait_endpoint("writer", "rapid_ack")
    expect(bool(r and w), "a rapid_command reader and a rapid_ack writer",
           f"{len(r)} command reader(s), {len(w)} ack writer(s)")
    _ready(s, answers=False)


@check("CMD-02", REQUIRED, "A valid command is answered COMPLETED/OK", "rapid-protocol.md 5", needs=("CMD-01",))
def valid(s):
    _ready(s)
    c = _harmless(s)
    acks = s.run(c, final=False)  # its silence is this check's own finding (not CMD-16's)
    s.memo["valid"] = acks[0].cmd_id if acks else None
    if s.final(acks) is None:
        s.owned.update(cid for cid, origin in s.client.origin.items() if origin == "CMD-02")
    if not acks:  # the checks after this that wait for an answer would each wait out the timeout
        s.memo.setdefault("answers", f"a valid command ({c.subsystem}/{c.name}) got no ack within "
                                     f"{s.timeout:g} s (CMD-02)")
    s.expect_ok(acks, f"{c.subsystem}/{c.name}")


def _refused(s, what, sub, name, args):
    _ready(s)
    s.expect_refused(s.run((sub, name), args), what)


@check("CMD-05", REQUIRED, "An unknown subsystem is answered non-OK", "rapid-protocol.md 5 and 5b: BAD_SYNTAX",
       needs=("CMD-01",))
def unknown_subsystem(s):
    c = _harmless(s)
    _refused(s, "an unknown subsystem", "NoSuchSubsystem", c.name, valid_args(c))


@check("CMD-06", REQUIRED, "An unknown command name is answered non-OK", "rapid-protocol.md 5: find the CommandDef",
       needs=("CMD-01",))
def unknown_command(s):
    c = _harmless(s)
    _refused(s, "an unknown command", c.subsystem, "noSuchCommand", [])


def _with_params(s):
    c = s.with_params()  # a motion command only with --allow-motion: its arguments here are wrong or odd
    if c is None:
        raise Unsupported("no command takes arguments")
    return c


@check("CMD-07", REQUIRED, "A wrong argument count is answered non-OK",
       "rapid-protocol.md 5: argument count must equal the parameter count", needs=("CMD-01",))
def wrong_count(s):
    c = _with_params(s)
    _refused(s, "one argument too many", c.subsystem, c.name, valid_args(c) + [("RAPID_INT", 1)])


@check("CMD-08", REQUIRED, "A wrong argument type is answered non-OK",
       "rapid-protocol.md 5: each discriminator must equal the parameter's DataType", needs=("CMD-01",))
def wrong_types(s):
    c = _with_params(s)
    args = valid_args(c)
    args[0] = wrong_type(args[0][0])
    _refused(s, f"a {args[0][0]} for a {c.params[0]['type']}", c.subsystem, c.name, args)


@check("CMD-09", RECOMMENDED, "A command addressed to another asset is ignored",
       "rapid-protocol.md 5 (5b: Astrobee relies on the partition instead)", needs=("CMD-01",))
def other_asset(s):
    _ready(s)
    c = _harmless(s)
    since = time.monotonic()
    cid = s.client.send(c.subsystem, c.name, valid_args(c), source=s.source, asset=s.asset + "Other")
    s.unanswerable.add(cid)  # not to be answered: no final ack is owed (CMD-16)
    s.pause(QUIET)
    s.silent_since(since)
    acks = s.client.acks_of(cid)
    expect(not acks, f"no ack within {QUIET:g} s", describe(acks))


@check("CMD-10", RECOMMENDED, "A repeated cmdId is not run again", "rapid-protocol.md 5 (5b: Astrobee does not check)",
       needs=("CMD-02",))
def repeated(s):
    cid = s.memo.get("valid")
    c = _harmless(s)
    s.memo["repeated"] = cid  # its acks are CMD-10's to judge, not CMD-03's or CMD-04's
    before = len(s.client.acks_of(cid))
    since = time.monotonic()
    s.client.send(c.subsystem, c.name, valid_args(c), source=s.source, cmd_id=cid)
    s.pause(QUIET)
    s.silent_since(since)
    after = s.client.acks_of(cid)
    # Not run again. The asset may answer a resent, already answered cmdId with its stored final
    # ack (same status, completion and message: the runtimes do, issue 42); nothing else.
    first = s.final(after[:before])
    again = [a for a in after[before:]
             if first is None or (a.status, a.completed, a.message) != (first.status, first.completed, first.message)]
    expect(not again, "no new ack for the repeated cmdId but its stored final ack", describe(again))


@check("CMD-13", REQUIRED, "Acks are durable: a late-joining ack reader gets a command's acks",
       "rapid-protocol.md 6: Ack -> RapidReliableDurableQos", needs=("CMD-02",))
def late_acks(s):
    bad = [w for ep in s.endpoints("writer", "rapid_ack") if (w := qos_mismatch(ep, "RapidReliableDurableQos"))]
    expect(not bad, "ack writer Reliable, TransientLocal, KeepLast", "; ".join(bad))
    cid = s.memo.get("valid")
    reader = s.client.guard(s.client.profile_reader("rapid_ack", "rapid::Ack"), "rapid_ack")  # the asset's acks only
    s.client.extra_guards.append(reader)
    end = time.monotonic() + s.allow(3.0, trips=4)  # a new reader: found, asked, history sent, a loss repaired
    seen = 0
    found = False
    while time.monotonic() < end and not found:
        got: list[Any] = reader.take_all(1024)  # rapid::Ack samples (not kept: a flood must not grow this)
        seen += len(got)
        found = any(a.cmdId == cid for a in got)
        time.sleep(0.05)
    expect(found, f"the acks of {cid} for a reader created after it was answered", f"{seen} acks, none of it")


NUMERIC = ("RAPID_FLOAT", "RAPID_DOUBLE", "RAPID_INT", "RAPID_LONGLONG")
WIDTH = {"RAPID_INT": 2**31, "RAPID_LONGLONG": 2**63}  # a probe must still fit its union member
NOT_ALLOWED = "conformance-not-allowed"


def _outside(p: dict) -> list[tuple[str, object]]:
    """(which limit, a value past it) for parameter p: above its maximum, below its minimum,
    not among its allowed values (a string, or a number inside its range), each where the
    descriptor declares it."""
    out: list[tuple[str, object]] = []
    t, lo, hi, allowed = p["type"], p.get("min"), p.get("max"), p.get("allowed") or []
    if t in NUMERIC:
        integer = t in WIDTH
        for which, end, sign in (("above its maximum", hi, 1), ("below its minimum", lo, -1)):
            if end is None:
                continue
            value = end + sign if integer else float(end) + sign * max(1.0, abs(float(end)))
            if not integer or -WIDTH[t] <= value < WIDTH[t]:
                out.append((f"{which} {end:g}", value))
        if allowed:
            top = (hi if hi is not None else max(allowed) + 1)
            value = next((v for v in (max(allowed) + 1, min(allowed) - 1, top)
                          if v not in allowed and (lo is None or v >= lo) and (hi is None or v <= hi)), None)
            if value is not None:
                out.append((f"not among its allowed values {'|'.join(map(str, allowed))}",
                            int(value) if integer else float(value)))
    elif t == "RAPID_STRING" and allowed:
        value = next(v for v in (NOT_ALLOWED, NOT_ALLOWED + "-2") if v not in allowed)
        out.append((f"not among its allowed values {'|'.join(map(str, allowed))}", value))
    return out


@check("CMD-15", RECOMMENDED, "A value outside its declared range or allowed values is answered non-OK",
       "descriptor: parameter range and allowed values", needs=("CMD-01",))
def out_of_range(s):
    """One probe per kind of limit the descriptor declares (above a maximum, below a minimum,
    a value not allowed), each on the first parameter that declares it; never a motion
    command without leave."""
    refused, probes, kinds = None, [], set()
    for c in s.facts.commands():
        limited = [(i, p, which, v) for i, p in enumerate(c.params) for which, v in _outside(p)]
        if is_motion(c) and not s.allow_motion:  # refused by a good asset, a drive by a bad one
            if refused is None and limited:
                refused = s.refusal(c)
            continue
        for i, p, which, v in limited:
            kind = which.split(" its ")[0]
            if kind not in kinds:
                kinds.add(kind)
                probes.append((c, i, p, which, v))
    if not probes:
        raise Unsupported(refused or "no parameter declares a range or allowed values")
    _ready(s)
    bad = []
    for c, i, p, which, v in probes:
        args = valid_args(c)
        args[i] = (p["type"], v)
        acks = s.run(c, args)
        f = s.final(acks)
        if f.completed in ("ACK_COMPLETED_OK", "ACK_COMPLETED_NOT"):
            bad.append(f"{c.subsystem}/{c.name} {p['name']}={v!r} ({which}) answered {describe(acks)}")
    expect(not bad, "a value outside its parameter's declared range or allowed values answered BAD_SYNTAX or "
                    "EXEC_FAILED (descriptor: range, allowed)", "; ".join(bad))
    return f"{len(probes)} probe(s): " + ", ".join(f"{c.name} {p['name']} {which.split(' its ')[0]}"
                                                 for c, _i, p, which, _v in probes)


@check("CMD-11", REQUIRED, "Ack messages are at most 127 bytes", "rapid-protocol.md 5 and 5b: Ack.message String128",
       needs=("CMD-01",), late=True)
def ack_length(s):
    echo = s.facts.command("Admin", "echo")
    if echo is not None and echo.params:
        s.run(echo, [("RAPID_STRING", "x" * 127)], final=False)  # judged: the messages; an answer missing is CMD-16's
    s.run((s.facts.commands()[0].subsystem, "n" * 63), [], final=False)
    long = [f"{visible(a.cmd_id)}: {len(a.message.encode())} bytes" for a in s.client.acks
            if len(a.message.encode()) > 127]
    expect(not long, "every Ack.message within 127 bytes", "; ".join(long[:3]))


@check("CMD-03", REQUIRED, "Each cmdId's acks follow QUEUED -> EXECUTING -> COMPLETED (either implementation)",
       "rapid-protocol.md 5b: ack sequences; completedStatus NOT until COMPLETED", needs=("CMD-02",), late=True)
def sequence(s):
    bad = []
    for cid in _judged(s):
        prev = None
        for a in s.client.acks_of(cid):
            if prev == "ACK_COMPLETED":
                break  # CMD-04's finding
            if a.status not in NEXT[prev]:
                bad.append(f"{cid}: {describe(s.client.acks_of(cid))}")
                break
            final = a.status == "ACK_COMPLETED"
            if final == (a.completed == "ACK_COMPLETED_NOT") and not (a.status == "ACK_REQUEUED"):
                bad.append(f"{cid}: {a.status} with {a.completed}")
                break
            prev = a.status
    expect(not bad, "(QUEUED) (EXECUTING|REQUEUED)* COMPLETED per cmdId", "; ".join(bad[:3]))


@check("CMD-04", REQUIRED, "Nothing follows a cmdId's final COMPLETED ack", "rapid-protocol.md 5b",
       needs=("CMD-02",), late=True)
def after_final(s):
    s.pause(0.5)
    bad = []
    for cid in _judged(s):
        acks = s.client.acks_of(cid)
        i = next((n for n, a in enumerate(acks) if a.status == "ACK_COMPLETED"), None)
        if i is not None and len(acks) > i + 1:
            bad.append(f"{cid}: {describe(acks)}")
    expect(not bad, "no ack after COMPLETED", "; ".join(bad[:3]))


@check("CMD-12", REQUIRED, "Acks carry the cmdId of a command sent and the asset's name",
       "rapid-protocol.md 5 and 5b: correlate acks by cmdId alone", needs=("CMD-01",), late=True)
def ack_ids(s):
    """Two findings: acks of the runner's cmdIds naming another asset, and acks for cmdIds
    nobody sent (not the runner, no commander seen on rapid_command) while commands of the
    runner's went unanswered: the asset does not answer with the cmdIds it was sent. The
    checks that wait for answers are then BLOCKED (Session.wait_acks), not failed one
    timeout after another."""
    if not s.awaited:  # nothing was sent yet (--only CMD-12): one command to answer
        _ready(s, answers=False)
        try:
            s.run(_harmless(s), final=False)
        except Blocked:
            pass
    c = s.client
    with c.lock:
        acks, sent = list(c.acks), dict(c.sent_at)
    nobody = c.unsent()
    unanswered = [cid for cid in s.awaited if not any(a.cmd_id == cid and a.status == COMPLETED for a in acks)]
    bad = []
    if nobody and unanswered:
        first: dict[str, float] = {}
        for a in nobody:
            first.setdefault(a.cmd_id, a.at)
        seen = [f"{visible(i)[:60]!r} at +{t - s.started:.1f} s (sent: {visible(_closest(i, sent))[:60]!r})"
                for i, t in list(first.items())[:3]]
        bad.append(f"acks for {len(first)} cmdId(s) nobody sent: " + ", ".join(seen)
                   + f"; {len(unanswered)} of the {len(s.awaited)} commands awaited got no COMPLETED ack")
    named = [f"{visible(a.cmd_id)!r} assetName={visible(a.asset)!r}" for a in acks
             if a.cmd_id in sent and a.asset != s.asset]
    if named:
        bad.append("; ".join(list(dict.fromkeys(named))[:3]))
    expect(not bad, f"acks carrying the cmdIds sent and assetName {s.asset!r}", "; ".join(bad))
    if nobody:
        return (f"acks for cmdIds nobody seen sent ({len({a.cmd_id for a in nobody})}), while every command of "
                f"the runner's was answered: another commander's, sent before the run? (not judged)")


def _closest(cmd_id: str, sent: dict[str, float]) -> str:
    """The cmdId sent that cmd_id most resembles (longest common prefix; of equals, the latest)."""
    if not sent:
        return ""
    return max(sent, key=lambda x: (len(os.path.commonprefix([x, cmd_id])), sent[x]))


def _judged(s) -> list[str]:
    """The runner's cmdIds but those it sent again on purpose (CMD-10's, SPEC-01's repeats):
    a repeat's final ack written again is no ack after COMPLETED."""
    again = {s.memo.get("repeated"), *s.memo.get("repeats", ())}
    return [c for c in list(s.client.sent) if c not in again]


# Last of all: an asset that crashes on it must not take the other checks with it.
PROBE_AGAIN = 2.0  # s without any ack for the probe before a second one tells a lost probe from a stopped asset


@check("CMD-14", REQUIRED, "Malformed commands do not stop the asset", "rapid-protocol.md 5: commands cannot be dropped",
       needs=("CMD-02",), late=True)
def survives(s):
    """Ten malformed commands, then the harmless command must still be answered OK. A probe
    with no ack at all gets a second one: one command lost (CMD-16's finding) is not an asset
    that stopped. Every command of the burst is looked at: one without a final ack is named
    (CMD-16 judges it, with the full timeout)."""
    c = _harmless(s)
    s.ensure_control()  # an access-control fault earlier in the run may have left control elsewhere
    p = s.with_params() if s.facts.with_params(motion=s.allow_motion) else c
    odd: list[dict[str, Any]] = [  # keyword arguments of send()
        dict(args=[("RAPID_DOUBLE", float("nan"))] * 16), dict(args=[("RAPID_STRING", "\x01\x7f\u00e9" * 30)]),
        dict(args=[(t, v) for t, v in valid_args(p)], cmd_id=""), dict(args=[("RAPID_MAT33f", [float("inf")] * 9)]),
        dict(args=[(t, v) for t, v in valid_args(p)], action="QUEUE_INSERT", target="\u00e9" * 31)]
    burst = []
    for kw in odd:
        burst.append(s.client.send(p.subsystem, p.name, source=s.source, **kw))
        burst.append(s.client.send("\u00e9" * 15, "\x01x" * 31, source=s.source, **kw))
    time.sleep(0.3)
    s.answers()
    args = valid_args(c)
    probes = [s.client.send(c.subsystem, c.name, args, source=s.source)]
    acks = s.wait_acks(probes[0], timeout=PROBE_AGAIN)
    if not acks:
        probes.append(s.client.send(c.subsystem, c.name, args, source=s.source))
        s.wait_acks(probes[-1])
    answered = next((got for cid in probes if s.final(got := s.client.acks_of(cid)) is not None), None)
    what = f"{c.subsystem}/{c.name} after {len(burst)} malformed commands"
    if answered is None:
        s.owned.update(burst + probes)  # this check's finding: the asset stopped answering
        s.expect_ok(s.client.acks_of(probes[-1]), what + f" ({len(probes)} sent, none answered)")
    s.expect_ok(answered, what)
    due = [cid for cid in dict.fromkeys(burst) if s.accountable(cid)]
    end = time.monotonic() + s.allow(GRACE)  # the burst came before the probe: its answers too
    while time.monotonic() < end and any(s.final(s.client.acks_of(cid)) is None for cid in due):
        time.sleep(0.05)
    unanswered = [cid for cid in due if s.final(s.client.acks_of(cid)) is None]
    lost = [cid for cid in probes if s.final(s.client.acks_of(cid)) is None]
    if unanswered or lost:
        return (f"{len(unanswered)} of the {len(due)} malformed commands answered nothing yet"
                + (f", {len(lost)} probe(s) unanswered" if lost else "") + " (CMD-16 judges)")
    return None


ACCOUNT = "rapid-protocol.md 5: commands cannot be dropped"


# After CMD-14 (the last commands of the run): each command is judged once its time is up.
@check("CMD-16", REQUIRED, "Every command sent is answered with a final COMPLETED ack",
       f"{ACCOUNT}; 5b: every command gets a final COMPLETED (dropped silently only: another asset's, a repeated "
       f"cmdId, a queued action without a queue)", needs=("CMD-14",), late=True)
def accounted(s):
    """Every command the checks sent, followed to its final ack (--timeout s after it was
    sent, at most): one without is named with the check that sent it. Those checks were
    BLOCKED (they could not judge their rule); this is the finding."""
    _ready(s)
    c = s.client
    due = [cid for cid in list(c.sent) if s.accountable(cid)]

    def missing() -> list[str]:
        return [cid for cid in due if not any(a.cmd_id == cid and a.status == COMPLETED for a in c.acks)]
    left = missing()
    while left:
        last = max(c.sent_at[cid] for cid in left) + s.timeout
        if time.monotonic() >= last:
            break
        time.sleep(0.05)
        left = missing()
    listed = [s.silence(cid) for cid in left[:4]] + ([f"and {len(left) - 4} more"] if len(left) > 4 else [])
    expect(not left, f"a final COMPLETED ack for each of the {len(due)} commands sent, within {s.timeout:g} s "
                     f"({ACCOUNT})", f"{len(left)} unanswered: " + "; ".join(listed))
    return f"{len(due)} commands, each answered"
