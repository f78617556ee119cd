"""The generated Fast DDS profiles carry RAPID's keyed Ack topic on loopback.

An asset's ack writer on Fast DDS 2.9 (tests/cpp/src/ack_flood.cpp, K10's generated C++
types and XML) answers many more commands than Fast DDS's default of 10 instances, each
EXECUTING then COMPLETED at once, as an asset does. Readers as ground tools have them: a
volatile Cyclone reader matched before (rapidgen conform's and a commander's relaxed
reader), then late-joining durable readers on Cyclone (tests/cpp/py_acks.py) and on Fast
DDS. Every reader must get every command's COMPLETED ack. With the profiles before the fix
(no resourceLimitsQos, ASYNCHRONOUS writers) 40 of 60 writes failed, the late readers got
9 acks of 30 and the early volatile one 1 of 30 (docs/qos.md, "Fast DDS: resource limits
and publish mode").
"""
from __future__ import annotations

import os
import queue
import subprocess
import sys
import threading
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from tests.cpp.conftest import K10, ROOT

DOMAIN_FLOOD = 88
DOMAIN_LOAD = 90
XML = K10 / "qos" / "fastdds" / "rapid_qos_profiles.xml"
COMMANDS = 30  # per batch: three times Fast DDS's default instance limit
WAIT = 10.0  # seconds any one answer may take (a bound on waiting, never asserted on)
NS = {"f": "http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles"}


class Peer:
    """A line-driven helper process: ask() writes a command and returns its answer line."""

    def __init__(self, argv: list[str], env: dict) -> None:
        self.proc = subprocess.Popen(argv, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     text=True, env=env, start_new_session=True)
        self.lines: queue.Queue = queue.Queue()
        self.err: list[str] = []
        self._threads = [threading.Thread(target=self._pump, daemon=True),
                         threading.Thread(target=lambda: self.err.extend(self.proc.stderr), daemon=True)]
        for t in self._threads:
            t.start()

    def _pump(self) -> None:
        for line in self.proc.stdout:
            self.lines.put(line.strip())
        self.lines.put(None)

    def ask(self, command: str) -> str:
        self.proc.stdin.write(command + "\n")
        self.proc.stdin.flush()
        line = self.lines.get(timeout=3 * WAIT)
        assert line is not None, f"{command!r}: the helper ended; stderr: {''.join(self.err)[-3000:]}"
        return line

    def close(self) -> tuple[int, str]:
        """Exit status and stderr; the process is gone afterwards."""
        try:
            if self.proc.poll() is None:
                self.proc.stdin.write("quit\n")
                self.proc.stdin.close()
            self.proc.wait(timeout=30)
        except (OSError, subprocess.TimeoutExpired):
            self.proc.kill()
            self.proc.wait()
        for t in self._threads:
            t.join(timeout=5)
        return self.proc.returncode, "".join(self.err)


@pytest.fixture
def peers():
    started: list[Peer] = []

    def start(argv: list[str]) -> Peer:
        env = dict(os.environ, CYCLONEDDS_URI="file://" + str(K10 / "qos" / "cyclonedds" / "local.xml"),
                   PYTHONPATH=os.pathsep.join([str(K10 / "python"), str(ROOT)]))
        env.pop("FASTDDS_DEFAULT_PROFILES_FILE", None)
        started.append(Peer(argv, env))
        return started[-1]
    yield start
    for p in started:
        p.close()


def test_acks_of_many_commands_reach_early_and_late_readers(cpp_build, peers):
    flood = str(cpp_build / "ack_flood")
    asset = peers([flood, str(XML), str(DOMAIN_FLOOD)])
    ground_py = peers([sys.executable, str(ROOT / "tests" / "cpp" / "py_acks.py"), str(DOMAIN_FLOOD)])
    assert asset.ask("writer") == "writer"
    assert ground_py.ask("reader early volatile") == "reader early"
    assert asset.ask(f"matched 1 {WAIT}") == "matched 1"
    assert ground_py.ask(f"matched early 1 {WAIT}") == "matched 1"  # both ways: nothing sent before it

    assert asset.ask(f"write 0 {COMMANDS}") == f"wrote {2 * COMMANDS} failed 0"
    assert ground_py.ask(f"expect early 0 {COMMANDS} {WAIT}") == f"got early {COMMANDS} of {COMMANDS}"

    # late joiners: a durable reader gets every command's last ack from the writer's history
    ground_fast = peers([flood, str(XML), str(DOMAIN_FLOOD)])
    assert ground_py.ask("reader late durable") == "reader late"
    assert ground_fast.ask("reader late") == "reader late"
    assert asset.ask(f"matched 3 {WAIT}") == "matched 3"
    assert ground_py.ask(f"expect late 0 {COMMANDS} {WAIT}") == f"got late {COMMANDS} of {COMMANDS}"
    assert ground_fast.ask(f"expect late 0 {COMMANDS} {WAIT}") == f"got late {COMMANDS} of {COMMANDS}"

    # and the acks of later commands still reach every reader
    assert asset.ask(f"write {COMMANDS} {2 * COMMANDS}") == f"wrote {2 * COMMANDS} failed 0"
    for peer, name in ((ground_py, "early"), (ground_py, "late"), (ground_fast, "late")):
        assert peer.ask(f"expect {name} {COMMANDS} {2 * COMMANDS} {WAIT}") == f"got {name} {COMMANDS} of {COMMANDS}"

    for peer in (asset, ground_fast, ground_py):
        code, err = peer.close()
        assert code == 0 and err == "", err[-3000:]  # no Fast DDS warning or error, no traceback


@pytest.mark.parametrize("seed", ["athlete", "chariot", "eva-suit", "k10", "robonaut2", "xarm2"])
def test_every_generated_profile_file_loads_without_fastdds_complaints(cpp_build, peers, seed):
    """Fast DDS parses each seed's file (its warnings and errors go to stderr) and creates the
    ack writer and reader from it; the participant profile rapid_local is the seed's."""
    p = peers([str(cpp_build / "ack_flood"), str(ROOT / "generated" / seed / "qos" / "fastdds" /
                                                  "rapid_qos_profiles.xml"), str(DOMAIN_LOAD)])
    assert p.ask("writer") == "writer"
    assert p.ask("reader r") == "reader r"
    code, err = p.close()
    assert code == 0 and err == "", err[-3000:]


def test_a_broken_profile_file_is_reported_on_stderr(cpp_build, peers, tmp_path):
    """The check above can fail: a resource limit Fast DDS cannot parse."""
    broken = tmp_path / "broken.xml"
    broken.write_text(XML.read_text(encoding="utf-8").replace("<max_instances>0<", "<max_instances>none<", 1))
    p = peers([str(cpp_build / "ack_flood"), str(broken), str(DOMAIN_LOAD)])
    code, err = p.close()
    assert code == 3 and "max_instances" in err and "Error" in err


def _profiles(path: Path) -> list[tuple[str, str, ET.Element]]:
    root = ET.parse(path).getroot()
    return [(e.get("profile_name"), kind, e) for kind in ("data_writer", "data_reader")
            for e in root.iterfind(f"f:profiles/f:{kind}", NS)]


@pytest.mark.parametrize("seed", ["k10", "robonaut2"])
def test_every_endpoint_has_unlimited_instances_and_its_depth_per_instance(seed):
    every = _profiles(ROOT / "generated" / seed / "qos" / "fastdds" / "rapid_qos_profiles.xml")
    rows = [r for r in every if not r[0].startswith("RapidStream_")]  # setpoint streams: their own test
    assert len(rows) == 16  # 8 RAPID profiles, writer and reader
    for name, kind, e in rows:
        limits = {c.tag.split("}")[1]: int(c.text) for c in e.find("f:topic/f:resourceLimitsQos", NS)}
        history = e.find("f:topic/f:historyQos", NS)
        keep_last = history.find("f:kind", NS).text == "KEEP_LAST"
        per = int(history.find("f:depth", NS).text) if keep_last else 400
        assert limits == {"max_samples": 0, "max_instances": 0, "max_samples_per_instance": per}, (name, kind)
        mode = e.find("f:qos/f:publishMode/f:kind", NS)
        if kind == "data_writer":
            reliable = e.find("f:qos/f:reliability/f:kind", NS).text == "RELIABLE"
            assert mode.text == ("SYNCHRONOUS" if reliable else "ASYNCHRONOUS"), name
        else:
            assert mode is None
