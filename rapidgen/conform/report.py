"""Reports of a run: one progress line per check, the summary table, JUnit XML (one
testcase per check; UNSUPPORTED and BLOCKED are skipped, FAIL a failure, ERROR an
error) and JSON."""
from __future__ import annotations

import json
import xml.etree.ElementTree as ET

from rapidgen.conform.model import BLOCKED, ERROR, FAIL, PASS, UNSUPPORTED, Result

MARK = {PASS: "pass", FAIL: "FAIL", UNSUPPORTED: "n/a ", BLOCKED: "blkd", ERROR: "ERR "}


def progress_line(r: Result, index: int, total: int) -> str:
    c = r.check
    text = f"[{index:>2}/{total}] {MARK[r.outcome]} {c.id:<7} {c.title}"
    if r.message:
        text += f"\n              {r.message}"
    return text


def table(results: list[Result], asset: str, seconds: float) -> str:
    rows = [("check", "level", "outcome", "title")]
    rows += [(r.check.id, r.check.level, r.outcome, r.check.title) for r in results]
    w = [max(len(row[i]) for row in rows) for i in range(3)]
    lines = [f"{a:<{w[0]}}  {b:<{w[1]}}  {c:<{w[2]}}  {d}" for a, b, c, d in rows]
    lines.insert(1, "-" * (sum(w) + 6 + max(len(r[3]) for r in rows)))
    counts = {k: sum(r.outcome == k for r in results) for k in (PASS, FAIL, ERROR, UNSUPPORTED, BLOCKED)}
    req_bad = [r.check.id for r in results if r.check.level == "required" and r.outcome in (FAIL, ERROR, BLOCKED)]
    lines.append("")
    lines.append(f"{asset}: {len(results)} checks, " + ", ".join(f"{v} {k.lower()}" for k, v in counts.items() if v)
                 + f" in {seconds:.1f} s; " + ("every required check passed" if not req_bad
                                              else f"required checks not passed: {', '.join(req_bad)}"))
    return "\n".join(lines)


def junit(results: list[Result], asset: str, seconds: float) -> bytes:
    suite = ET.Element("testsuite", name=f"rapidgen conform {asset}", tests=str(len(results)),
                       failures=str(sum(r.outcome == FAIL for r in results)),
                       errors=str(sum(r.outcome == ERROR for r in results)),
                       skipped=str(sum(r.outcome in (UNSUPPORTED, BLOCKED) for r in results)),
                       time=f"{seconds:.3f}")
    for r in results:
        c = r.check
        case = ET.SubElement(suite, "testcase", classname=f"conformance.{c.id.split('-')[0]}",
                             name=f"{c.id} {c.title}", time=f"{r.seconds:.3f}")
        props = ET.SubElement(case, "properties")
        for k, v in (("level", c.level), ("rule", c.rule)):
            ET.SubElement(props, "property", name=k, value=v)
        if r.outcome == FAIL:
            ET.SubElement(case, "failure", message=r.message, type=c.level).text = \
                f"expected: {r.expected}\nseen: {r.seen}\nrule: {c.rule}"
        elif r.outcome == ERROR:
            ET.SubElement(case, "error", message=r.message, type="error")
        elif r.outcome in (UNSUPPORTED, BLOCKED):
            ET.SubElement(case, "skipped", message=f"{r.outcome}: {r.message}")
    root = ET.Element("testsuites")
    root.append(suite)
    ET.indent(root)
    return ET.tostring(root, encoding="utf-8", xml_declaration=True) + b"\n"


def as_json(results: list[Result], asset: str, seconds: float, ok: bool, domain: int) -> str:
    return json.dumps({"asset": asset, "domain": domain, "seconds": round(seconds, 3), "passed": ok,
                       "checks": [r.as_dict() for r in results]}, indent=2) + "\n"
