"""`rapidgen conform` is safe to point at a real robot (issue 39): without the descriptor's
conformance section and without --allow-motion it sends nothing that moves the asset (the
checks that would are UNSUPPORTED, saying why, and the run still passes); with the section
it sends exactly the arguments the section names; and after the run control is where it was
before: with nobody, or handed back to the operator who held it. A second participant
(tests/conformance/watch.py) reads every command on the wire and the AccessControlState.

DDS domains 91 and 92 (no other test uses them), loopback only (tests/runtime/live.env_for)."""
from __future__ import annotations

import json
import queue
import re
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from tests.conformance.harness import RAPIDGEN, BridgeProcess, outcomes
from tests.runtime.live import ROOT, SEEDS, env_for, python_dir

pytest.importorskip("cyclonedds")
ASSET = "k10"
PYDIR, PACKAGE = python_dir(ASSET), SEEDS[ASSET]
REASON = "sends Mobility/simpleMove: allow it in the descriptor's conformance section or with --allow-motion"
CHECKS = "CMD-,QUE-,ACC-"  # the ones that send commands (DDS, CFG, TEL only read)
NOBODY = ("", "No Controller")


def _descriptor(tmp: Path, section: bool) -> Path:
    """specs/assets/k10.yaml (without its conformance section unless `section`), its IDL paths
    made absolute."""
    text = (ROOT / "specs/assets/k10.yaml").read_text()
    if not section:
        text = re.sub(r"\n# What `rapidgen conform` may send.*", "\n", text, flags=re.S)
        assert "conformance:" not in text
    text = text.replace("rapid: ../rapid", f"rapid: {ROOT / 'specs/rapid'}")
    text = text.replace("files: [idl/ArcGps.idl]", f"files: [{ROOT / 'specs/assets/idl/ArcGps.idl'}]")
    path = tmp / f"k10-{'section' if section else 'no-motion'}.yaml"
    path.write_text(text)
    return path


class Watch:
    def __init__(self, domain: int, operator: str = "") -> None:
        argv = [sys.executable, "-m", "tests.conformance.watch", str(PYDIR), PACKAGE, str(domain)]
        self.proc = subprocess.Popen(argv + ([operator] if operator else []), cwd=ROOT, env=env_for(PYDIR, PACKAGE),
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.lines: queue.Queue = queue.Queue()
        threading.Thread(target=lambda: [self.lines.put(x) for x in self.proc.stdout] + [self.lines.put(None)],
                         daemon=True).start()
        first = self.lines.get(timeout=60)
        assert first == "watch ready\n", (first, self.proc.stderr.read() if first is None else "")

    def finish(self) -> tuple[list[dict], str | None]:
        """(every command seen, the controller after the run)."""
        self.proc.stdin.close()
        self.proc.wait(timeout=60)
        got = []
        while (line := self.lines.get(timeout=10)) is not None:
            got.append(json.loads(line))
        assert got and "controller" in got[-1], got[-3:]
        return got[:-1], got[-1]["controller"]


def _conform(descriptor: Path, domain: int, out: Path, *extra: str) -> dict:
    report = out / f"run-{domain}-{len(list(out.iterdir()))}.json"
    res = subprocess.run([*RAPIDGEN, "conform", str(descriptor), "--domain", str(domain), "--only", CHECKS,
                          "--json", str(report), *extra], cwd=ROOT, env=env_for(PYDIR, PACKAGE),
                         capture_output=True, text=True, timeout=300)
    assert report.exists(), res.stderr[-3000:]
    return {"code": res.returncode, "stdout": res.stdout, "report": json.loads(report.read_text())}


@pytest.fixture(scope="module")
def bridge_91():
    bridge = BridgeProcess(PYDIR, PACKAGE, 91)
    try:
        bridge.wait_ready()
        yield 91
    finally:
        bridge.stop()


@pytest.fixture(scope="module")
def bridge_92():
    bridge = BridgeProcess(PYDIR, PACKAGE, 92)
    try:
        bridge.wait_ready()
        yield 92
    finally:
        bridge.stop()


def _moves(commands: list[dict]) -> list[dict]:
    return [c for c in commands if c["subsystem"] == "Mobility" and c["name"] != "stopAllMotion"]


def test_without_leave_nothing_moves_and_control_is_released(bridge_91, tmp_path):
    watch = Watch(bridge_91)
    run = _conform(_descriptor(tmp_path, section=False), bridge_91, tmp_path)
    commands, controller = watch.finish()
    checks = {c["id"]: c for c in run["report"]["checks"]}
    assert checks["QUE-04"]["outcome"] == "UNSUPPORTED" and checks["QUE-04"]["message"] == REASON, checks["QUE-04"]
    # QUE-02 judges FIFO with instant commands and says why it did not judge one at a time with a drive
    assert checks["QUE-02"]["outcome"] == "PASS" and REASON in checks["QUE-02"]["message"], checks["QUE-02"]
    assert run["code"] == 0, run["stdout"][-3000:]
    assert not [o for o in outcomes(run["report"]).values() if o in ("FAIL", "ERROR", "BLOCKED")], run["stdout"]
    assert "motion: none" in run["stdout"]
    assert len(commands) > 20, commands  # the watch saw the run's commands ...
    assert _moves(commands) == [], _moves(commands)  # ... and none that moves the rover
    assert controller in NOBODY, controller  # nobody held control before: nobody after
    assert "RapidConformance" not in str(controller)
    assert run["report"]["control"].startswith("control: nobody holds it, as before the run"), run["report"]["control"]


def test_the_section_arguments_are_sent_and_control_goes_back_to_the_operator(bridge_92, tmp_path):
    # the simulated K10 lets RapidWorkbench (the runner's source: the one allowed everything) and
    # MultiCenterCockpit command: the operator at the cockpit holds control when the run starts
    watch = Watch(bridge_92, operator="MultiCenterCockpit")
    run = _conform(ROOT / "specs/assets/k10.yaml", bridge_92, tmp_path)
    commands, controller = watch.finish()
    got = outcomes(run["report"])
    assert got["QUE-04"] == "PASS" and got["QUE-02"] == "PASS", run["stdout"][-3000:]
    assert run["code"] == 0
    moves = _moves(commands)
    assert moves, commands
    # exactly the descriptor's: Mobility/simpleMove(frame site, xyt 500, 0, 0); nothing else moves
    assert {(c["name"], c["args"][0], tuple(c["args"][1])) for c in moves} == {("simpleMove", "site", (500.0, 0, 0))}
    assert controller == "MultiCenterCockpit", (controller, run["report"]["control"])
    text = run["report"]["control"]
    assert text.startswith("control: 'MultiCenterCockpit' holds it, as before the run (transferControl from "
                           "RapidWorkbench to MultiCenterCockpit"), text
    transfers = [c for c in commands if c["name"] == "transferControl"]
    assert transfers and transfers[-1]["src"] == "RapidWorkbench" and transfers[-1]["args"] == ["MultiCenterCockpit"]


def test_allow_motion_sends_the_runners_long_drive(bridge_91, tmp_path):
    watch = Watch(bridge_91)
    run = _conform(_descriptor(tmp_path, section=False), bridge_91, tmp_path, "--allow-motion")
    commands, controller = watch.finish()
    assert outcomes(run["report"])["QUE-04"] == "PASS", run["stdout"][-3000:]
    assert {(c["name"], tuple(c["args"][1])) for c in _moves(commands)} == {("simpleMove", (1000.0, 0, 0))}
    assert controller in NOBODY, controller
