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


def _one_source(s):
    """Checks that speak as a second source need an asset that takes cmdSrc on trust."""
    if s.secured_as:
        raise Unsupported(f"the runner joined a secured domain as {s.secured_as}, and a secured asset binds cmdSrc to "
                          "the writer's certificate (docs/secure.md): a second source needs its own enclave")


def _other(s, cmd=None):
    """A second source allowed cmd (default: grabControl), and that command."""
    _one_source(s)
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
    _one_source(s)
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


@check("ACC-08", REQUIRED, "Once control moved, the former controller's commands are refused",
       "rapid-protocol.md 5b: anyone who is not the controller gets BAD_SYNTAX \"RAPID access violation\"",
       needs=("ACC-03", "ACC-04"))
def former(s):
    """The runner holds control and its harmless command is accepted; a second source grabs
    control; the runner's same command must now be refused (the AccessControl subsystem
    alone is exempt, so ACC-05's releaseControl does not show this)."""
    _access(s)
    c = s.facts.harmless()
    if c is None:
        raise Unsupported("no command to send that moves nothing")
    b = _other(s)
    s.ensure_control()
    before = s.run(c)
    if not _ok(s, before):
        raise Blocked(f"{c.subsystem}/{c.name} from the controller {s.source} answered {describe(before)} (CMD-02)")
    try:
        s.grab_control(b)
        if s.holder != b:
            raise Blocked(f"grabControl by {b} was not answered OK (ACC-04)")
        s.expect_refused(s.run(c), f"{c.subsystem}/{c.name} from {s.source} once {b} took control from it "
                                   f"(5b: not the controller -> RAPID access violation)")
    finally:
        s.holder = None
        try:
            s.ensure_control()
        except Blocked:  # answers that cannot be judged: the checks that need them say so
            pass


@check("ACC-05", REQUIRED, "releaseControl by a source without control is refused",
       "rapid-protocol.md 5b: release/transfer by a non-owner -> EXEC_FAILED", needs=("ACC-04",))
def release_other(s):
    _access(s)
    b = _other(s)
    if s.holder != b:  # the second source holds control (ACC-04 left it so; ACC-08 took it back)
        s.grab_control(b)
        if s.holder != b:
            raise Blocked(f"grabControl by {b} was not answered OK (ACC-04)")
    s.expect_refused(s.run(("AccessControl", "releaseControl"), []), "releaseControl by a non-owner")
    s.expect_ok(s.run(("AccessControl", "releaseControl"), [], source=b), "releaseControl by the controller")
    s.ensure_control()


@check("ACC-06", REQUIRED, "stopAllMotion is accepted from any source",
       "rapid-protocol.md 5b: stopAllMotion is always allowed", needs=("ACC-01",))
def stop_all(s):
    _access(s)
    if s.facts.command("Mobility", "stopAllMotion") is None:
        raise Unsupported("no Mobility/stopAllMotion")
    _one_source(s)
    s.expect_ok(s.run(("Mobility", "stopAllMotion"), [], source=INTRUDER), "stopAllMotion from a non-controller")


@check("ACC-09", REQUIRED, "releaseControl by the controller is published: AccessControlState no longer names it",
       "rapid-protocol.md 5b: release passes control on (a requestor, or nobody); docs/runtime.md: "
       "AccessControlState published on every change", needs=("ACC-05",))
def release_published(s):
    _access(s)
    s.ensure_control()
    if s.controller(1.0, want=s.source) != s.source:
        raise Blocked(f"AccessControlState does not name the controller {s.source} (ACC-04)")
    acks = s.run(("AccessControl", "releaseControl"), [])
    try:
        if not _ok(s, acks):
            raise Blocked(f"releaseControl by the controller answered {describe(acks)} (ACC-05)")
        gone = s.wait_controller_not(s.source, 2.0)
        expect(gone, f"AccessControlState naming another controller than {s.source!r} (a requestor, or nobody) "
                     f"within 2 s of its releaseControl answered OK (published on every change)",
               f"still {s.controller(0.0)!r} after releaseControl answered {describe(acks)}")
    finally:
        try:
            s.ensure_control()
        except Blocked:
            pass


def _unprivileged(s):
    """(a source the allow-list lets take control, a harmless command it does not let it send),
    or None. Harmless: Admin/noOp or echo, else any command that is not motion, queue or
    access control."""
    from rapidgen.conform.asset import is_motion
    grab = s.facts.command("AccessControl", "grabControl") or s.facts.command("AccessControl", "requestControl")
    if s.facts.access is None or grab is None:
        return None
    cands = [c for c in (s.facts.command("Admin", "noOp"), s.facts.command("Admin", "echo")) if c is not None]
    cands += [c for c in s.facts.commands() if c.type not in ("AccessControl", "Queue", "Admin") and not is_motion(c)
              and c.type != "Mobility"]
    for rule in s.facts.access["rules"]:
        src = rule["source"]
        if src == s.source or not s.facts.allowed(src, grab):
            continue
        c = next((c for c in cands if not s.facts.allowed(src, c)), None)
        if c is not None:
            return src, c
    return None


@check("ACC-10", REQUIRED, "The allow-list holds for the controller: a command it does not allow is refused",
       "rapid-protocol.md 5 (seed 001: the command source checked against the sender's privileges); "
       "docs/runtime.md: the allow-list, then control", needs=("ACC-04",))
def privileges(s):
    """A source the descriptor's access_control lets take control, holding it, sends a
    harmless command the allow-list does not give it: refused (BAD_SYNTAX "RAPID access
    violation"), whoever holds control."""
    _access(s)
    _one_source(s)
    found = _unprivileged(s)
    if found is None:
        raise Unsupported("the allow-list refuses no source that may take control a harmless command")
    src, c = found
    try:
        s.grab_control(src)
        if s.holder != src:
            raise Blocked(f"grabControl by {src} was not answered OK (ACC-04)")
        s.expect_refused(s.run(c, source=src), f"{c.subsystem}/{c.name} from {src}, the controller, which the "
                                                f"allow-list does not let send it (RAPID access violation)")
    finally:
        s.holder = None
        try:
            s.ensure_control()
        except Blocked:
            pass
