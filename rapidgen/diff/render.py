"""Findings as compiler-like text (the default) or JSON (`--json`)."""
from __future__ import annotations

import json

from rapidgen.diagnostics import SourceLoc, escaped
from rapidgen.diff.rules import CATEGORIES, Finding


def _loc(loc: SourceLoc | None) -> str:
    return escaped(str(loc)) if loc is not None else "(absent)"


def counts(findings: list[Finding]) -> dict[str, int]:
    return {c: sum(1 for f in findings if f.rule.category == c) for c in CATEGORIES}


def text(findings: list[Finding], waived: int) -> str:
    lines = []
    for f in findings:
        head = f.new if f.new is not None else f.old
        lines.append(f"{_loc(head)}: {f.rule.category.lower()}[{f.rule.id}]: {escaped(f.message)}")
        if f.old is not None:
            lines.append(f"  {_loc(f.old)}: note: in OLD")
        if f.new is not None and head is not f.new:
            lines.append(f"  {_loc(f.new)}: note: in NEW")
        lines.append(f"  = {f.rule.title}: {f.rule.why}")
    c = counts(findings)
    summary = ", ".join(f"{c[k]} {k}" for k in CATEGORIES)
    lines.append(f"rapidgen diff: {summary} change{'s' * (len(findings) != 1)}"
                 + (f" ({waived} waived)" if waived else ""))
    return "\n".join(lines) + "\n"


def _jloc(loc: SourceLoc | None) -> dict | None:
    return None if loc is None else {"file": loc.file, "line": loc.line, "col": loc.col}


def as_json(findings: list[Finding], waived: int) -> str:
    doc = {
        "findings": [{"rule": f.rule.id, "category": f.rule.category, "title": f.rule.title,
                      "subject": f.subject, "message": f.message, "old": _jloc(f.old), "new": _jloc(f.new),
                      "explanation": f.rule.why} for f in findings],
        "counts": counts(findings),
        "waived": waived,
    }
    return json.dumps(doc, indent=2, ensure_ascii=False) + "\n"
