"""docs/diff.md lists every rule exactly as the registry says it; the README shows CI use."""
from __future__ import annotations

import os
import re

from rapidgen.diff.rules import CATEGORIES, RULES
from tests.diff.conftest import REPO

ROW = re.compile(r"^\| ((?:WIRE|SRC|PROTO)-[A-Z]+-\d\d) \| (\w+) \| (.*?) \| (.*) \|$", re.M)


def test_doc_table_matches_the_registry():
    with open(os.path.join(REPO, "docs", "diff.md"), encoding="utf-8") as f:
        rows = ROW.findall(f.read())
    assert [r[0] for r in rows] == list(RULES)  # each once, in registry order
    for rid, category, title, why in rows:
        r = RULES[rid]
        assert (category, title, why) == (r.category, r.title, r.why), rid


def test_registry_is_well_formed():
    assert len(RULES) >= 30
    prefix = {"WIRE": "WIRE-", "PROTOCOL": "PROTO-", "SOURCE": "SRC-"}
    for r in RULES.values():
        assert r.category in CATEGORIES and r.id.startswith(prefix[r.category])
        assert r.title and r.why and "|" not in r.why + r.title


def test_readme_documents_ci_use():
    with open(os.path.join(REPO, "README.md"), encoding="utf-8") as f:
        text = f.read()
    assert "rapidgen diff specs/rapid specs/rapid" in text
    assert "rapidgen diff --against" in text and "--fail-on WIRE,PROTOCOL" in text
