"""Findings as compiler-like text (the default), JSON (`--json`) or GitHub Actions
annotations (`--format github`)."""
from __future__ import annotations

import json
import re

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
    lines.append(_summary(findings, waived))
    return "\n".join(lines) + "\n"


def _summary(findings: list[Finding], waived: int) -> str:
    c = counts(findings)
    summary = ", ".join(f"{c[k]} {k}" for k in CATEGORIES)
    return (f"rapidgen diff: {summary} change{'s' * (len(findings) != 1)}"
            + (f" ({waived} waived)" if waived else ""))


def _jfile(name: str) -> str:
    """A file name whose bytes are not UTF-8 (os.fsdecode's lone surrogates) as `\\xNN`
    text: stdout cannot encode a lone surrogate."""
    try:
        return name.encode("utf-8", "surrogateescape").decode("utf-8", "backslashreplace")
    except UnicodeEncodeError:
        return escaped(name)


def _jloc(loc: SourceLoc | None) -> dict | None:
    return None if loc is None else {"file": _jfile(loc.file), "line": loc.line, "col": loc.col}


# json.dumps escapes C0 controls; these it leaves raw with ensure_ascii=False (DEL, the C1
# controls a terminal may obey, the line separators JavaScript rejects, any lone surrogate
# left): escaped too
_RAW = re.compile("[\x7f-\x9f\u2028\u2029\ud800-\udfff]")


def as_json(findings: list[Finding], waived: int) -> str:
    doc = {
        "findings": [{"rule": f.rule.id, "category": f.rule.category, "title": f.rule.title,
                      "subject": f.subject, "message": f.message, "old": _jloc(f.old), "new": _jloc(f.new),
                      "explanation": f.rule.why} for f in findings],
        "counts": counts(findings),
        "waived": waived,
    }
    out = json.dumps(doc, indent=2, ensure_ascii=False)
    return _RAW.sub(lambda m: f"\\u{ord(m.group()):04x}", out) + "\n"


def github(findings: list[Finding], waived: int, fail_on: set[str], rev: str | None) -> str:
    """One annotation per finding (error when its category is in --fail-on, else warning)
    at its NEW location; a finding only OLD has (a removal) names the file without a line
    (the line is OLD's), then the text summary line."""
    from rapidgen.github_annotations import command

    lines = []
    for f in findings:
        level = "error" if f.rule.category in fail_on else "warning"
        title = f"{f.rule.category.lower()}[{f.rule.id}]: {f.rule.title}"
        message = f"{f.message} ({f.rule.why})"
        if f.new is not None:
            lines.append(command(level, message, f.new, title))
        elif f.old is not None:
            old = f.old
            if rev is not None and old.file.startswith(f"{rev}:"):
                old = old._replace(file=old.file[len(rev) + 1:])
            lines.append(command(level, f"{message}; in OLD at {f.old}", old, title, with_line=False))
        else:
            lines.append(command(level, message, None, title))
    lines.append(_summary(findings, waived))
    return "\n".join(lines) + "\n"
