"""Reports of a run: one progress line per check, the summary table, JUnit XML (one
testcase per check; UNSUPPORTED and BLOCKED are skipped, FAIL a failure, ERROR an
error) and JSON; each with the run's notes: the participant judged as the asset, the
strangers in its partition (never judged) and what was dropped.

Messages carry text from the wire (cmdIds, ack messages, names): every one reaches the
terminal and the reports through visible(), so no control character (ESC, BEL, C1) is ever
written raw; XML then gets only characters XML 1.0 allows."""
from __future__ import annotations

import json
import xml.etree.ElementTree as ET

from rapidgen.textsafe import visible
from rapidgen.conform.model import BLOCKED, ERROR, FAIL, PASS, UNSUPPORTED, Result

MARK = {PASS: "pass", FAIL: "FAIL", UNSUPPORTED: "n/a ", BLOCKED: "blkd", ERROR: "ERR "}


def progress_line(r: Result, index: int, total: int) -> str:
    c = r.check
    text = f"[{index:>2}/{total}] {MARK[r.outcome]} {c.id:<7} {c.title}"
    if r.message:
        text += f"\n              {visible(r.message)}"
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
    lines.append(f"{visible(asset)}: {len(results)} checks, "
                 + ", ".join(f"{v} {k.lower()}" for k, v in counts.items() if v)
                 + f" in {seconds:.1f} s; " + ("every required check passed" if not req_bad
                                              else f"required checks not passed: {', '.join(req_bad)}"))
    return "\n".join(lines)


def visible_all(value):
    """value (plain data: dicts, lists, strings, numbers) with every string made visible."""
    if isinstance(value, str):
        return visible(value)
    if isinstance(value, dict):
        return {visible_all(k): visible_all(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [visible_all(v) for v in value]
    return value


def notes_text(notes: dict | None) -> str:
    """The notes as text lines (empty when there is nothing to say beyond the asset)."""
    if not notes:
        return ""
    notes = visible_all(notes)
    lines = [f"judged: {p}" for p in notes["asset_participants"]]
    if notes.get("identification"):
        lines.append(f"  ({notes['identification']})")
    if notes.get("control"):
        lines.append(notes["control"])
    if notes["strangers"]:
        lines.append("strangers in the asset's partition (not the asset: their samples are not judged):")
        for s in notes["strangers"]:
            lines.append(f"  participant {s['participant']}: {len(s['endpoints'])} endpoint(s)")
            for topic, t in s["samples"].items():
                lines.append(f"    {topic}: {t['count']} sample(s), {_size(t['bytes'])} ignored"
                             + (f" ({t['not_decoded']} too large to decode)" if t["not_decoded"] else ""))
            if s["acks_for_runner"]:
                lines.append(f"    {s['acks_for_runner']} of its acks carried cmdIds the runner sent (not the asset's)")
        if notes.get("more_strangers"):
            lines.append(f"  and {notes['more_strangers']} more participant(s)")
    if notes["dropped"]:
        lines.append("dropped:")
        lines += [f"  {d}" for d in notes["dropped"]]
    return "\n".join(lines)


def _size(n: int) -> str:
    return f"{n / (1 << 20):.1f} MiB" if n >= 1 << 20 else f"{n / 1024:.1f} KiB" if n >= 1024 else f"{n} B"


def junit(results: list[Result], asset: str, seconds: float, notes: dict | None = None) -> bytes:
    suite = ET.Element("testsuite", name=visible(f"rapidgen conform {asset}"), tests=str(len(results)),
                       failures=str(sum(r.outcome == FAIL for r in results)),
                       errors=str(sum(r.outcome == ERROR for r in results)),
                       skipped=str(sum(r.outcome in (UNSUPPORTED, BLOCKED) for r in results)),
                       time=f"{seconds:.3f}")
    if notes:
        notes = visible_all(notes)
        props = ET.SubElement(suite, "properties")
        for p in notes["asset_participants"]:
            ET.SubElement(props, "property", name="asset_participant", value=p)
        if notes.get("control"):
            ET.SubElement(props, "property", name="control", value=notes["control"])
        for s in notes["strangers"]:
            counts = ", ".join(f"{t} {v['count']}" for t, v in s["samples"].items())
            ET.SubElement(props, "property", name="stranger",
                          value=s["participant"] + (f": samples ignored: {counts}" if counts else ""))
        for d in notes["dropped"]:
            ET.SubElement(props, "property", name="dropped", value=d)
    for r in results:
        c = r.check
        case = ET.SubElement(suite, "testcase", classname=f"conformance.{c.id.split('-')[0]}",
                             name=f"{c.id} {c.title}", time=f"{r.seconds:.3f}")
        props = ET.SubElement(case, "properties")
        for k, v in (("level", c.level), ("rule", c.rule)):
            ET.SubElement(props, "property", name=k, value=v)
        if r.outcome == FAIL:
            ET.SubElement(case, "failure", message=visible(r.message), type=c.level).text = \
                f"expected: {visible(r.expected)}\nseen: {visible(r.seen)}\nrule: {c.rule}"
        elif r.outcome == ERROR:
            ET.SubElement(case, "error", message=visible(r.message), type="error")
        elif r.outcome in (UNSUPPORTED, BLOCKED):
            ET.SubElement(case, "skipped", message=visible(f"{r.outcome}: {r.message}"))
    text = notes_text(notes)
    if text:
        ET.SubElement(suite, "system-out").text = text + "\n"
    root = ET.Element("testsuites")
    root.append(suite)
    ET.indent(root)
    return ET.tostring(root, encoding="utf-8", xml_declaration=True) + b"\n"


def as_json(results: list[Result], asset: str, seconds: float, ok: bool, domain: int,
            notes: dict | None = None) -> str:
    checks = []
    for r in results:
        d = r.as_dict()
        for k in ("message", "expected", "seen"):
            d[k] = visible(d[k])
        checks.append(d)
    out = {"asset": visible(asset), "domain": domain, "seconds": round(seconds, 3), "passed": ok, "checks": checks}
    if notes is not None:
        out.update(visible_all(notes))
    return json.dumps(out, indent=2, allow_nan=False) + "\n"
