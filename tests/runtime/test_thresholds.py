"""rapid_runtime.thresholds: one rule for an agent value's warning and critical levels (the
ROS 2 ground node's DiagnosticStatus and the monitor's colours)."""
from __future__ import annotations

import math

import pytest

from rapid_runtime.thresholds import threshold_level

BATTERY = ((30, None), (15, None))  # warning, critical: (below, above)
VOLTAGE = ((44, 56), (40, 58))


@pytest.mark.parametrize("value,bounds,level,why", [
    (50, BATTERY, "ok", ""), (30, BATTERY, "ok", ""), (29.5, BATTERY, "warning", "below warning threshold 30"),
    (15, BATTERY, "warning", "below warning threshold 30"), (14.9, BATTERY, "critical", "below critical threshold 15"),
    (57, VOLTAGE, "warning", "above warning threshold 56"), (59, VOLTAGE, "critical", "above critical threshold 58"),
    (39, VOLTAGE, "critical", "below critical threshold 40"), (-math.inf, VOLTAGE, "critical",
                                                                "below critical threshold 40"),
    (math.nan, VOLTAGE, "critical", "not a number"), (math.nan, (None, None), "ok", ""),
    (math.nan, ((None, None), None), "ok", ""), (1e9, (None, None), "ok", ""),
    (True, VOLTAGE, "ok", ""), ("low", VOLTAGE, "ok", ""), ([0.0, 0.0, 0.0], VOLTAGE, "ok", ""),
])
def test_levels(value, bounds, level, why):
    assert threshold_level(value, *bounds) == (level, why)


def test_the_monitor_and_the_ground_node_judge_alike():
    """The ground node's DiagnosticStatus level (OK 0, WARN 1, ERROR 2) and the monitor's colour
    of the same values under the same thresholds."""
    from types import SimpleNamespace as NS

    from rapid_runtime.ros2.ground import Ground
    from rapidgen.monitor.hints import level_of

    hint = {"warning": {"below": 44, "above": 56}, "critical": {"below": 40, "above": 58}}
    values = [50.0, 57.0, 59.0, 39.0, 43.0, math.nan]
    g = Ground.__new__(Ground)
    g.tables = NS(name="Rover")
    g.DiagnosticArray = lambda: NS(header=NS(stamp=NS(sec=0, nanosec=0)), status=[])
    g.DiagnosticStatus = g.KeyValue = NS
    entry = {"values": [[f"v{i}", "RAPID_DOUBLE", "V", [44, 56], [40, 58]] for i in range(len(values))]}
    sample = NS(hdr=NS(timeStamp=0), values=[NS(value=v) for v in values])
    got = [status.level for status in g._agent(entry, sample).status]
    assert got == [bytes([{"ok": 0, "warning": 1, "critical": 2}[level_of(v, hint)]]) for v in values]
    assert got == [b"\x00", b"\x01", b"\x02", b"\x02", b"\x01", b"\x02"]
