"""`validate` warns (RG1508) of every advertised command the ROS 2 bridge would answer
EXEC_FAILED "... has no ROS 2 mapping": located at the command (a custom type's) or at the
subsystem entry (a standard type's, whose commands the descriptor does not spell out). The
commands the runtime answers itself (Admin echo/noOp/shutdown, Queue/cancelAll, access
control, Mobility/stopAllMotion) are not named."""
from __future__ import annotations

from pathlib import Path

from rapidgen.asset.load import load_asset
from rapidgen.diagnostics import DiagnosticSink, Severity
from rapidgen.ros2 import msgdefs

ROOT = Path(__file__).resolve().parents[2]
DESCRIPTOR = f"""\
version: 1
asset: {{name: Rover, kind: rover}}
idl: {{rapid: {ROOT / 'specs/rapid'}}}
subsystem_types:
  - name: Dock
    commands:
      - name: dock
      - name: undock
subsystems:
  - {{name: Admin}}
  - {{name: Mobility}}
  - {{name: AccessControl}}
  - {{name: Dock1, type: Dock}}
telemetry:
  - {{kind: position, frame: site}}
ros2:
  telemetry:
    - {{topic: /odom, type: nav_msgs/msg/Odometry, feeds: position}}
  commands:
    - command: Dock1/dock
      call: {{service: /dock, type: std_srvs/srv/Trigger}}
"""


def _warnings(tmp_path: Path, text: str):
    path = tmp_path / "rover.yaml"
    path.write_text(text)
    msgdefs.lookup.cache_clear()
    sink = DiagnosticSink()
    assert load_asset(str(path), sink) is not None
    msgdefs.lookup.cache_clear()
    assert not sink.has_errors, [str(d) for d in sink.diagnostics]
    return [d for d in sink.diagnostics if d.code == "RG1508"]


def _line(text: str, words: str) -> int:
    return next(n for n, line in enumerate(text.splitlines(), 1) if words in line)


def test_every_unmapped_command_is_named_where_it_is_advertised(tmp_path):
    got = _warnings(tmp_path, DESCRIPTOR)
    named = {d.message.split()[1]: d for d in got}
    # simpleMove, move and move6DOF: the bridge answers them EXEC_FAILED; stopAllMotion it answers itself
    assert sorted(named) == ["Dock1/undock", "Mobility/move", "Mobility/move6DOF", "Mobility/simpleMove"], named
    assert all(d.severity is Severity.WARNING for d in got)
    assert named["Dock1/undock"].loc.line == _line(DESCRIPTOR, "- name: undock")
    assert named["Mobility/simpleMove"].loc.line == _line(DESCRIPTOR, "{name: Mobility}")
    assert "EXEC_FAILED" in named["Dock1/undock"].message
    assert "ros2.commands" in named["Dock1/undock"].hint and "Dock1/undock" in named["Dock1/undock"].hint


def test_mapping_the_command_silences_it(tmp_path):
    text = DESCRIPTOR.replace("  - {name: Mobility}\n", "") + \
        "    - command: Dock1/undock\n      call: {service: /undock, type: std_srvs/srv/Trigger}\n"
    assert _warnings(tmp_path, text) == []


def test_no_warning_without_a_ros2_section(tmp_path):
    assert _warnings(tmp_path, DESCRIPTOR.split("ros2:")[0]) == []
