"""Printing a Snapshot: aligned text tables (network text escaped: names on the wire are
untrusted), JSON for scripts, and the live terminal view (clear and redraw)."""
from __future__ import annotations

import json

from rapidgen.asset.describe import table
from rapidgen.textsafe import visible
from rapidgen.spy.collect import config_lines
from rapidgen.spy.model import Snapshot


def _rate(t) -> str:
    got = "-" if t.rate is None else f"{t.rate:.2f}"
    return got + (f" ({t.declared_rate:g})" if t.declared_rate else "")


def _partitions(p: dict) -> str:
    shown = ", ".join(repr(x) for x in p["partitions"][:8])
    more = len(p["partitions"]) - 8 + p.get("other_partitions", 0)
    return (shown + (f" (+{more} more)" if more > 0 else "")) or "-"


def text(snap: Snapshot) -> str:
    n_p, n_a = len(snap.participants), len(snap.assets)
    out = [f"rapidgen spy: domain {snap.domain}, {n_p} participant{'s' * (n_p != 1)}, "
           f"{n_a} partition{'s' * (n_a != 1)}, {snap.seconds:.1f} s watched", "", "Participants"]
    out += table(["participant", "process", "pid", "host", "partitions"],
                 [[p["key"][:17], p["process"] or "?", p["pid"] or "?", p["host"] or "?",
                   _partitions(p)] for p in snap.participants])
    for a in snap.assets:
        label = f"'{a.partition}'" if a.partition else "'' (the default partition)"
        out += ["", f"Asset {a.name} (partition {label}, {len(a.participants)} participant"
                f"{'s' * (len(a.participants) != 1)})"]
        rows = []
        for t in a.topics:
            prof = t.profile or "?"
            if t.expected_profile and t.profile != t.expected_profile:
                prof += f" (expected {t.expected_profile})"
            rows.append([t.topic, t.type_name + ("" if t.decodable else " (no bindings)"), t.role,
                         f"{len(t.writers)}/{len(t.readers)}", prof, _rate(t), str(t.samples)])
        out += table(["topic", "type", "role", "W/R", "QoS profile", "rate Hz (declared)", "samples"], rows)
        for t in a.topics:
            if t.role == "config" and t.latest:
                hdr = t.latest.get("hdr", {})
                out.append(f"  {t.topic} (serial {hdr.get('serial')}, from {hdr.get('srcName')!r}):")
                out += [f"    {line}" for line in config_lines(t.latest)]
    out += ["", "Findings" if snap.findings else "Findings: none"]
    out += [f"  {f.text()}" for f in snap.findings]
    if snap.limits:
        out += ["", "Limits reached (docs/spy.md)"]
        out += [f"  {line}" for line in snap.limits]
    return "\n".join(visible(line) for line in out) + "\n"


def as_json(snap: Snapshot) -> str:
    return json.dumps(snap.as_dict(), indent=2, ensure_ascii=True, allow_nan=False, default=str) + "\n"


CLEAR = "\x1b[H\x1b[2J"


def live_frame(snap: Snapshot) -> str:
    """One frame of the live view: home, clear, the text view, a footer."""
    return CLEAR + text(snap) + "\n(refreshing every second; Ctrl-C quits)\n"
