"""The runner's outcomes without DDS: a check that raises Blocked is BLOCKED (not FAIL), and
so is a check that needs it; a required BLOCKED check fails the run."""
from __future__ import annotations

from rapidgen.conform.model import BLOCKED, FAIL, PASS, REQUIRED, Blocked, Check, Fail
from rapidgen.conform.runner import passed, run_checks


def _raise(exc):
    def run(_session):
        raise exc
    return run


def test_blocked_is_neither_pass_nor_fail():
    checks = [Check("X-01", REQUIRED, "writer", "r", _raise(Fail("a writer", "none"))),
              Check("X-02", REQUIRED, "state", "r", _raise(Blocked("no state writer (X-01)"))),
              Check("X-03", REQUIRED, "records", "r", lambda s: None, needs=("X-02",)),
              Check("X-04", REQUIRED, "other", "r", lambda s: None)]
    got = {r.check.id: r for r in run_checks(None, checks)}
    assert [got[c].outcome for c in ("X-01", "X-02", "X-03", "X-04")] == [FAIL, BLOCKED, BLOCKED, PASS]
    assert got["X-02"].message == "not judged: no state writer (X-01)"
    assert "X-02" in got["X-03"].message
    assert not passed(list(got.values())[1:])  # a required BLOCKED check alone fails the run
