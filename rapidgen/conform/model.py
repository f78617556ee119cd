"""Checks and outcomes. A check function takes the Session and returns None (PASS) or a
note; it raises Fail(expected, seen) or Unsupported(why). A check whose `needs` did not
pass is BLOCKED (its own rule could not be judged), never run; a check that finds what it
would judge missing for a reason another check reports raises Blocked(why)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

REQUIRED, RECOMMENDED = "required", "recommended"
PASS, FAIL, UNSUPPORTED, BLOCKED, ERROR = "PASS", "FAIL", "UNSUPPORTED", "BLOCKED", "ERROR"


class Fail(Exception):
    def __init__(self, expected: str, seen: str) -> None:
        super().__init__(f"expected {expected}; seen {seen}")
        self.expected, self.seen = expected, seen


class Unsupported(Exception):
    """The check does not apply to this asset (no queue, no access control, ...)."""


class Blocked(Exception):
    """The check cannot judge its rule because of another check's finding (say which)."""


@dataclass(frozen=True)
class Check:
    id: str
    level: str
    title: str
    rule: str  # where the rule is written: rapid-protocol.md section, or the descriptor
    run: Callable = field(compare=False, repr=False)
    needs: tuple[str, ...] = ()
    late: bool = False  # judged at the end of the run (looks at everything the run saw)


@dataclass
class Result:
    check: Check
    outcome: str
    message: str = ""
    expected: str = ""
    seen: str = ""
    seconds: float = 0.0

    def as_dict(self) -> dict:
        c = self.check
        return {"id": c.id, "level": c.level, "title": c.title, "rule": c.rule, "outcome": self.outcome,
                "message": self.message, "expected": self.expected, "seen": self.seen,
                "seconds": round(self.seconds, 3)}


CHECKS: dict[str, Check] = {}


def check(id: str, level: str, title: str, rule: str, needs: tuple[str, ...] = (), late: bool = False):
    """Register a check (the suite's modules use this as a decorator)."""
    def register(fn):
        if id in CHECKS:
            raise ValueError(f"check {id} registered twice")
        CHECKS[id] = Check(id, level, title, rule, fn, tuple(needs), late)
        return fn
    return register


def expect(condition: bool, expected: str, seen) -> None:
    if not condition:
        raise Fail(expected, str(seen))


def all_checks() -> dict[str, Check]:
    import rapidgen.conform.suite  # noqa: F401  (registers the suite)
    return CHECKS
