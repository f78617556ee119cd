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


def _rows(header: str) -> list[list[str]]:
    """The rows of the docs/conformance.md table under `header` (a header line), as cells."""
    from tests.runtime.live import ROOT
    lines = (ROOT / "docs" / "conformance.md").read_text(encoding="utf-8").splitlines()
    start = lines.index(header) + 2
    rows = []
    for line in lines[start:]:
        if not line.startswith("| "):
            break
        rows.append([c.strip() for c in line.strip("|").split(" | ")])
    return rows


def test_docs_list_every_check_as_registered():
    from rapidgen.conform.model import all_checks
    want = [[c.id, c.level, c.title, c.rule] for c in all_checks().values()]
    assert _rows("| id | level | title | rule |") == want


def test_docs_list_every_broken_asset_with_its_check():
    """The table of broken assets is the registry of kinds: each with the check it fails
    alone (test_conformance.py runs them), '-' for a variant that must pass."""
    from tests.conformance.broken import KINDS
    got = {kind: check for check, kind, _what in _rows("| check | kind | what the asset gets wrong |")}
    assert got == {k: a or "-" for k, a in KINDS.items()}


def test_each_check_is_named_to_the_session_before_it_runs():
    """Accounting (CMD-16) names a command with the check that sent it: the runner tells the
    session which check runs (Session.begin) before calling it, not for one it skips."""
    seen = []

    class Session:
        def begin(self, check_id):
            seen.append(check_id)

    checks = [Check("X-01", REQUIRED, "a", "r", lambda s: seen.append("ran X-01")),
              Check("X-02", REQUIRED, "b", "r", _raise(Fail("x", "y"))),
              Check("X-03", REQUIRED, "c", "r", lambda s: None, needs=("X-02",))]
    run_checks(Session(), checks)
    assert seen == ["X-01", "ran X-01", "X-02"]
