"""`--waivers FILE`: accepted changes, per rule and type, each with a reason.

    waivers:
      - rule: WIRE-MEMBER-02
        type: 'rapid::ext::Gps*'     # optional: fnmatch on the type (or `Type.member`)
        reason: no robot in the field uses Gps yet
"""
from __future__ import annotations

import fnmatch
from dataclasses import dataclass

from rapidgen.yamlread import load_yaml
from rapidgen.diagnostics import DiagnosticSink, SourceLoc, did_you_mean
from rapidgen.diff.rules import RULES, Finding
from rapidgen.diagnostics import display_path


@dataclass(frozen=True)
class Waiver:
    rule: str
    pattern: str | None
    reason: str
    loc: SourceLoc

    def covers(self, f: Finding) -> bool:
        if f.rule.id != self.rule:
            return False
        if self.pattern is None:
            return True
        s, p = f.subject, self.pattern
        return fnmatch.fnmatchcase(s, p) or s.startswith(p + ".") or s.startswith(p + "::")


def load_waivers(path: str, sink: DiagnosticSink) -> list[Waiver] | None:
    shown = display_path(path)
    doc = load_yaml(path, shown, sink)
    if doc is None:
        return None
    data = doc.data
    if not isinstance(data, dict) or set(data) != {"waivers"} or not isinstance(data["waivers"], list):
        sink.error("RG1804", "a waiver file is a mapping with one key, 'waivers', holding a list",
                   doc.loc(()), "waivers: [{rule: WIRE-MEMBER-02, type: 'rapid::X', reason: why}]")
        return None
    out: list[Waiver] = []
    for i, w in enumerate(data["waivers"]):
        at = doc.loc(("waivers", i))
        if not isinstance(w, dict) or not set(w) <= {"rule", "type", "reason"}:
            sink.error("RG1804", "a waiver is a mapping of 'rule', 'type' (optional) and 'reason'", at)
            continue
        rule_id, pattern, reason = w.get("rule"), w.get("type"), w.get("reason")
        if rule_id not in RULES:
            sink.error("RG1804", f"unknown rule id {rule_id!r}", doc.loc(("waivers", i, "rule")),
                       did_you_mean(str(rule_id), RULES) or "docs/diff.md lists every rule")
            continue
        if not isinstance(reason, str) or not reason.strip():
            sink.error("RG1804", "a waiver needs a 'reason'", at, "say why the change is acceptable")
            continue
        if pattern is not None and not isinstance(pattern, str):
            sink.error("RG1804", "'type' is a scoped name or pattern (text)", doc.loc(("waivers", i, "type")))
            continue
        out.append(Waiver(rule_id, pattern, reason, at))
    return None if sink.has_errors else out
