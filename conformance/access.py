"""Access control (rapid-protocol.md 5b), on assets with an AccessControl subsystem."""
from __future__ import annotations

from rapidgen.conform.model import REQUIRED, Blocked, Unsupported, check, expect

from .commands import _ready
from .dds import qos_mismatch

TOPIC = "rapid_accesscontrol_state"
INTRUDER = "RapidConformanceIntruder"


def _access(s):
    if not s.facts.has_type("AccessControl"):
        raise Unsupported("the asset has no AccessControl subsystem")
    _ready(s)


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
    _access(s)
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
    if s.controller(0.5) == s.source:
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


@check("ACC-04", REQUIRED, "grabControl takes control", "rapid-protocol.md 5b: grabControl always succeeds",
       needs=("ACC-02",))
def grab(s):
    _access(s)
    b = _other(s)
    g = s.facts.command("AccessControl", "grabControl")
    if g is not None and g.params:
        s.take_control(b)
    else:
        s.expect_ok(s.run(("AccessControl", "grabControl"), [], source=b), "grabControl")
    now = s.controller(2.0, want=b)
    expect(now == b, f"controller {b!r}", repr(now))


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
