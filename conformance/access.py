"""Access control (rapid-protocol.md 5b), on assets with an AccessControl subsystem."""
from __future__ import annotations

from rapidgen.conform.model import REQUIRED, Blocked, Unsupported, check, expect
from rapidgen.conform.session import OK, describe

from .commands import _ready
from .dds import qos_mismatch

TOPIC = "rapid_accesscontrol_state"
INTRUDER = "RapidConformanceIntruder"


def _access(s, answers: bool = True):
    if not s.facts.has_type("AccessControl"):
        raise Unsupported("the asset has no AccessControl subsystem")
    _ready(s, answers)


def _other(s, cmd=None):
    """A second source allowed cmd (default: grabControl), and that command."""
    cmd = cmd or s.facts.command("AccessControl", "grabControl")
    found = s.facts.refusable(s.source) if cmd is None else ((cmd, b) if (b := s.facts.other_source(cmd, s.source))
                                                               else None)
    if found is None:
        raise Unsupported("the allow-list names no second source allowed the same commands")
    return found[1]


@check("ACC-01", REQUIRED, "AccessControlState is published and durable", "rapid-protocol.md 5b; RapidStateQos",
       needs=("CMD-01",))
def published(s):
    _access(s, answers=False)  # judges the state alone
    eps = s.wait_endpoint("writer", TOPIC)
    if not eps:
        raise Blocked(f"no {TOPIC} writer (DDS-06)")
    bad = [w for ep in eps if (w := qos_mismatch(ep, "RapidStateQos"))]
    expect(not bad, "Reliable, TransientLocal, KeepLast", "; ".join(bad))
    expect(s.latest(TOPIC, timeout=3.0) is not None, "a state for a late-joining reader", "none")


@check("ACC-02", REQUIRED, "requestControl grants control when it is free",
       "rapid-protocol.md 5b (soraCore: granted; Astrobee: cookie, then grabControl)", needs=("ACC-01",))
def request(s):
    _access(s)
    if s.holder == s.source or s.controller(0.5) == s.source:
        s.run(("AccessControl", "releaseControl"), [])
    acks = s.take_control(s.source)
    now = s.controller(2.0, want=s.source)
    expect(now == s.source, f"controller {s.source!r}", f"{now!r} after {len(acks)} acks")


@check("ACC-03", REQUIRED, "A command from a source without control is refused",
       "rapid-protocol.md 5b: not the controller -> BAD_SYNTAX", needs=("ACC-02",))
def refused(s):
    _access(s)
    found = s.facts.refusable(s.source)
    if found is None:
        raise Unsupported("the allow-list names no second source allowed a harmless command")
    c, b = found
    s.expect_refused(s.run(c, source=b), f"{c.subsystem}/{c.name} from {b} (not the controller)")


@check("ACC-07", REQUIRED, "requestControl while another source holds control leaves control with it",
       "rapid-protocol.md 5b: soraCore queues the requester, Astrobee answers with a cookie; neither hands control over",
       needs=("ACC-02",))
def request_held(s):
    _access(s)
    request = s.facts.command("AccessControl", "requestControl")
    b = _other(s, request) if request is not None else None
    if b is None:
        raise Unsupported("no AccessControl/requestControl")
    s.ensure_control()
    before = s.controller(1.0, want=s.source)
    c = s.facts.harmless()  # the acks must say it too: a command of the holder's accepted before and after
    accepted = c is not None and _ok(s, s.run(c))
    try:
        acks = s.run(("AccessControl", "requestControl"), [], source=b)
        now = s.controller(0.5, want=b)  # a state handing control over comes with the answer, or soon after
        want = f"controller still {s.source!r} after {b}'s requestControl (queued, or a cookie)"
        expect(now != b, want, f"controller {now!r} (was {before!r}); requestControl answered {describe(acks)}")
        if accepted:
            probe = s.run(c)
            expect(_ok(s, probe), want, f"{c.subsystem}/{c.name} from {s.source}, accepted before, answered "
                                        f"{describe(probe)} after the request (AccessControlState names {now!r})")
    finally:  # b's request may have moved control whatever the state says: take it back
        s.holder = None
        try:
            s.ensure_control()
        except Blocked:  # answers that cannot be judged: the checks that need them say so
            pass


def _ok(s, acks) -> bool:
    f = s.final(acks)
    return f is not None and f.completed == OK


@check("ACC-04", REQUIRED, "grabControl takes control", "rapid-protocol.md 5b: grabControl always succeeds",
       needs=("ACC-02",))
def grab(s):
    _access(s)
    b = _other(s)
    g = s.facts.command("AccessControl", "grabControl")
    if g is not None and g.params:
        acks = s.take_control(b)
    else:
        acks = s.run(("AccessControl", "grabControl"), [], source=b)
        s.expect_ok(acks, "grabControl")
    now = s.controller(2.0, want=b)
    expect(now == b, f"controller {b!r} in AccessControlState once grabControl is answered",
           f"{now!r} after grabControl answered {describe(acks[-2:])}")


@check("ACC-05", REQUIRED, "releaseControl by a source without control is refused",
       "rapid-protocol.md 5b: release/transfer by a non-owner -> EXEC_FAILED", needs=("ACC-04",))
def release_other(s):
    _access(s)
    s.expect_refused(s.run(("AccessControl", "releaseControl"), []), "releaseControl by a non-owner")
    b = _other(s)
    s.expect_ok(s.run(("AccessControl", "releaseControl"), [], source=b), "releaseControl by the controller")
    s.ensure_control()


@check("ACC-06", REQUIRED, "stopAllMotion is accepted from any source",
       "rapid-protocol.md 5b: stopAllMotion is always allowed", needs=("ACC-01",))
def stop_all(s):
    _access(s)
    if s.facts.command("Mobility", "stopAllMotion") is None:
        raise Unsupported("no Mobility/stopAllMotion")
    s.expect_ok(s.run(("Mobility", "stopAllMotion"), [], source=INTRUDER), "stopAllMotion from a non-controller")
