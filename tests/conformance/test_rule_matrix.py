"""The rule matrix of docs/conformance.md (issue 37), without DDS: every rule listed has a
check that exercises it or says why none can, every check it names exists, and every check
of the suite appears in it."""
from __future__ import annotations

import re

from tests.runtime.live import ROOT

HEADER = "| rule | what (where written) | positive | negative | not from the wire |"
CHECK_ID = re.compile(r"^[A-Z]{3,4}-\d\d$")
RULE_ID = re.compile(r"^(R\d*b?|RT|D)\.[a-z0-9-]+$")


def _matrix() -> list[list[str]]:
    lines = (ROOT / "docs" / "conformance.md").read_text(encoding="utf-8").splitlines()
    start = lines.index(HEADER) + 2
    rows = []
    for line in lines[start:]:
        if not line.startswith("| "):
            break
        cells = [c.strip() for c in line.strip().strip("|").split(" | ")]
        assert len(cells) == 5, line
        rows.append(cells)
    return rows


def _ids(cell: str) -> list[str]:
    return [] if cell in ("", "-") else [c.strip() for c in cell.split(",")]


def test_every_rule_has_a_check_or_a_reason():
    rows = _matrix()
    assert len(rows) >= 60, len(rows)
    names = [r[0] for r in rows]
    assert len(set(names)) == len(names), [n for n in names if names.count(n) > 1]
    for rule, what, positive, negative, why in rows:
        assert RULE_ID.match(rule), rule
        assert what and ":" in what, (rule, "say where the rule is written")
        assert _ids(positive) or _ids(negative) or why, (rule, "no check and no reason")


def test_matrix_names_only_checks_of_the_suite():
    from rapidgen.conform.model import all_checks
    suite = set(all_checks())
    named = {c for r in _matrix() for c in _ids(r[2]) + _ids(r[3])}
    assert all(CHECK_ID.match(c) for c in named), sorted(c for c in named if not CHECK_ID.match(c))
    assert named <= suite, sorted(named - suite)


def test_every_check_appears_in_the_matrix():
    from rapidgen.conform.model import all_checks
    named = {c for r in _matrix() for c in _ids(r[2]) + _ids(r[3])}
    assert set(all_checks()) <= named, sorted(set(all_checks()) - named)


def test_sections_5_and_5b_and_the_runtime_choices_are_there():
    """Each source the issue names has rules in the matrix (a section dropped is a hole)."""
    rows = _matrix()
    for prefix in ("R5.", "R5b.", "RT."):
        assert sum(r[0].startswith(prefix) for r in rows) >= 10, prefix
