"""The warning and critical thresholds of an agent value (the descriptor's
`warning: {below, above}`, `critical: {...}`), judged one way for every tool that shows a
level: the ROS 2 ground node's DiagnosticStatus and the monitor's colours.

A number below a level's `below` or above its `above` is at that level, critical judged
first; NaN is critical wherever a threshold is declared (a reading that is no number is
not a safe one); what is not a number (a string, a bool, a vector) is ok.
"""
from __future__ import annotations

from typing import Optional, Sequence

OK, WARNING, CRITICAL = "ok", "warning", "critical"

Bounds = Optional[Sequence[Optional[float]]]  # (below, above), either None; None: no threshold


def threshold_level(value: object, warning: Bounds, critical: Bounds) -> tuple[str, str]:
    """(ok | warning | critical, why: "above critical threshold 95", "" when ok)."""
    if not isinstance(value, (int, float)) or isinstance(value, bool):
        return OK, ""
    if value != value:  # NaN
        declared = [name for name, t in ((CRITICAL, critical), (WARNING, warning)) if t is not None and any(
            b is not None for b in t)]
        return (CRITICAL, "not a number") if declared else (OK, "")
    for name, t in ((CRITICAL, critical), (WARNING, warning)):
        if t is None:
            continue
        below, above = t
        if below is not None and value < below:
            return name, f"below {name} threshold {below:g}"
        if above is not None and value > above:
            return name, f"above {name} threshold {above:g}"
    return OK, ""
