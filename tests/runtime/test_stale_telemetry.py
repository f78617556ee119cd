"""Stale telemetry in the runtime (TelemetryPublisher, telemetry.Freshness; docs/runtime.md,
"Stale telemetry"), without a network: K10's generated classes and tables (its agent entry
given a stale_telemetry key), a node that records what would be written, a clock the test
moves. A sample's stamp is its source's time; a sample older than its entry's bound is not
written; a source silent past the bound is said once (log, TextMessage, AgentState), and
again when it is back."""
from __future__ import annotations

import copy
import importlib
import importlib.util
import subprocess
import sys
import threading
from types import SimpleNamespace

import pytest

from rapid_runtime.bridge import TelemetryPublisher
from rapid_runtime.configs import Serials
from rapid_runtime.telemetry import STALE_KEY, stale_after_ms
from tests.runtime.live import ROOT, SEEDS, python_dir
from tests.runtime.tables_of import tables

T0 = 1_800_000_000.0  # s since the epoch: the test's clock starts here


@pytest.fixture(scope="module")
def rapid():
    path = str(python_dir("k10"))
    sys.path.insert(0, path)
    try:
        return importlib.import_module(f"{SEEDS['k10']}.rapid")
    finally:
        sys.path.remove(path)


class Node:
    def __init__(self) -> None:
        self.written: list[tuple[str, object]] = []

    def writer(self, topic, cls, keep_last=None):
        node = self

        class Writer:
            def write(self, sample):
                node.written.append((topic, cls.deserialize(sample.serialize())))
        return Writer()


class Clock:
    def __init__(self) -> None:
        self.now = T0

    def __call__(self) -> float:
        return self.now


@pytest.fixture
def tel(rapid):
    telemetry = copy.deepcopy(tables("k10").telemetry)
    agent = next(t for t in telemetry if t["kind"] == "agent")
    agent["values"].append({"name": STALE_KEY, "type": "RAPID_STRING", "unit": "", "has_default": False})
    lines: list[str] = []
    bridge = SimpleNamespace(tables=SimpleNamespace(telemetry=telemetry), rapid=rapid, name="K10Red",
                             serials=Serials(1_700_000_000), node=Node(), log=lines.append,
                             stopped=threading.Event())
    bridge.stopped.set()  # no watcher thread: the test calls check() itself
    t = TelemetryPublisher(bridge)
    t.freshness.clock = Clock()
    t.lines = lines
    return t


def us(seconds: float) -> int:
    return int(seconds * 1e6)


def texts(tel) -> list[str]:
    return [s.message for topic, s in tel.b.node.written if topic == "rapid_textmessage"]


def stale_values(tel) -> list[str]:
    """The stale_telemetry value of each AgentState written."""
    out = []
    for topic, s in tel.b.node.written:
        if topic == "rapid_agent_state":
            out.append(s.values[-1].value)
    return out


def positions(tel) -> list[int]:
    return [s.hdr.timeStamp for topic, s in tel.b.node.written if topic == "rapid_position_sample"]


def test_the_bound_is_declared_or_three_periods_with_a_floor():
    assert stale_after_ms({"rate": 10, "stale_after_ms": 250}) == 250
    assert stale_after_ms({"rate": 1}) == 3000  # 3 periods
    assert stale_after_ms({"rate": 0.5}) == 6000
    assert stale_after_ms({"rate": 10}) == 1000  # 300 ms, floored
    assert stale_after_ms({"rate": None}) is None  # on change: not watched
    assert stale_after_ms({"rate": None, "stale_after_ms": 2000}) == 2000


def test_a_sample_keeps_its_source_stamp_until_the_bound(tel):
    clock = tel.freshness.clock
    assert tel.position([1, 2, 3], stamp=us(T0))
    clock.now = T0 + 2.5  # K10's position is 1 Hz: bound 3 s
    assert tel.position([1, 2, 3], stamp=us(T0))  # republished, still current: its source's stamp
    assert positions(tel) == [us(T0), us(T0)]
    clock.now = T0 + 3.5
    assert tel.position([1, 2, 3], stamp=us(T0)) is False
    assert positions(tel) == [us(T0), us(T0)]


def test_a_silent_source_is_said_once_and_its_return_too(tel):
    clock = tel.freshness.clock
    tel.agent_state({"batteryCharge": 80.0}, stamp=us(T0))
    tel.position([1, 2, 3], stamp=us(T0))
    clock.now = T0 + 0.5
    tel.agent_state({"batteryCharge": 79.0}, stamp=us(clock.now))
    tel.check()
    assert texts(tel) == [] and stale_values(tel) == ["", ""]
    clock.now = T0 + 3.2
    tel.agent_state({"batteryCharge": 78.0}, stamp=us(clock.now))
    assert tel.position([1, 2, 3], stamp=us(T0)) is False
    tel.check()
    assert texts(tel) == ["rapid_position_sample source silent for 3.2 s: samples stopped"]
    # the AgentState saying so carries the agent's last values and the silent entry's name
    (_, last), = [w for w in tel.b.node.written if w[0] == "rapid_agent_state"][-1:]
    assert last.values[0].value == pytest.approx(78.0)
    assert stale_values(tel)[-1] == "rapid_position_sample"
    for step in (3.5, 4, 10):  # said once
        clock.now = T0 + step
        tel.agent_state({"batteryCharge": 77.0}, stamp=us(clock.now))
        tel.check()
    assert len(texts(tel)) == 1
    assert stale_values(tel)[-1] == "rapid_position_sample"
    assert any("source silent" in line for line in tel.lines)
    # back: a current sample goes out and says so
    assert tel.position([4, 5, 6], stamp=us(clock.now))
    assert texts(tel)[1:] == ["rapid_position_sample source back"]
    assert stale_values(tel)[-1] == ""
    assert positions(tel)[-1] == us(clock.now)


def test_an_entry_without_a_bound_is_never_refused(tel):
    tel.freshness.clock.now = T0 + 3600
    assert tel.image(b"\x00" * 16, mime="image/x-raw", width=4, height=4, index=0, stamp=us(T0))  # on change
    tel.check()
    assert texts(tel) == []


def test_the_agent_entry_itself_going_silent(tel):
    clock = tel.freshness.clock
    tel.agent_state({"batteryCharge": 80.0}, stamp=us(T0))  # 4 Hz: bound 1 s (the floor)
    clock.now = T0 + 1.5
    tel.check()
    assert texts(tel) == ["rapid_agent_state source silent for 1.5 s: samples stopped"]
    assert stale_values(tel) == ["", "rapid_agent_state"]


# ---- the descriptor's bound ---------------------------------------------------------------------
DESCRIPTOR = """version: 1
asset: {{name: Bound, kind: rover, description: stale_after_ms}}
subsystems: [{{name: Admin}}]
telemetry:
  - {{kind: position, frame: odom, rate: 10{position}}}
  - {{kind: agent, rate: 2, values: [{{key: battery, type: RAPID_FLOAT}}]}}
  - {{kind: text{text}}}
"""


def _generate(tmp_path, position: str = "", text: str = "") -> subprocess.CompletedProcess:
    path = tmp_path / "bound.yaml"
    path.write_text(DESCRIPTOR.format(position=position, text=text))
    return subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(path), "--lang", "python", "-o",
                           str(tmp_path / "gen")], cwd=ROOT, capture_output=True, text=True)


def test_a_declared_bound_reaches_the_tables_and_only_there(tmp_path):
    res = _generate(tmp_path, position=", stale_after_ms: 250")
    assert res.returncode == 0, res.stdout + res.stderr
    spec = importlib.util.spec_from_file_location("bound_tables", tmp_path / "gen/python/rapid_bound/asset_tables.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    position, agent, text = module.TELEMETRY
    assert position["stale_after_ms"] == 250 and stale_after_ms(position) == 250
    assert "stale_after_ms" not in agent and stale_after_ms(agent) == 1500  # derived: 3 periods of 2 Hz
    assert stale_after_ms(text) is None


@pytest.mark.parametrize("position, text", [(", stale_after_ms: 0", ""), (", stale_after_ms: -5", ""),
                                            (", stale_after_ms: soon", ""), ("", ", stale_after_ms: 1000")])
def test_a_bound_that_is_no_bound_is_refused(tmp_path, position, text):
    res = _generate(tmp_path, position, text)
    assert res.returncode != 0 and "stale_after_ms" in res.stdout + res.stderr, res.stdout + res.stderr
