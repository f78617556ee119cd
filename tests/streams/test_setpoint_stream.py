"""Setpoint streams end to end, real processes on loopback (domain 140): X-Arm-2's generated
C++ bridge writes its hand pose stream at 500 Hz, Robonaut 2's generated C++ bridge reads
it (specs/assets/*.yaml `streams:`), a Cyclone DDS process watches R2's AgentState and
TextMessage. Each bridge's handlers.cpp carries a few lines of test code (code.py).

- samples arrive in R2's typed callback (Streams::handPose) with the writer's values;
- the writer frozen (SIGSTOP): R2's deadline (10 ms) passes, the declared action runs
  (on_loss stop), a TextMessage says so, AgentState's handPoseStream is "lost" and
  handPoseMissed counts; the callback gets nothing more;
- the writer resumed (SIGCONT): "recovered", AgentState "active", samples again;
- a rover with Mobility reading the same stream (tests/streams/rover.yaml): its loss runs
  Mobility/stopAllMotion through its command manager (acks from the asset itself).
"""
from __future__ import annotations

import json
import os
import queue
import re
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from tests.runtime.live import BridgeProcess
from tests.streams import code, harness

ROOT = Path(__file__).resolve().parents[2]
DOMAIN = 140
R2 = ROOT / "specs" / "assets" / "robonaut2.yaml"
XARM2 = ROOT / "specs" / "assets" / "xarm2.yaml"
ROVER = Path(__file__).resolve().parent / "rover.yaml"
STATE = re.compile(r"^stream handPose (\w+) after (\d+) samples, last x (-?\d+)")


# Its own build of the runtime and three bridges costs ~2-4 min on these 2 cores, which the
# default run cannot afford; RAPIDGEN_STREAMS_E2E=1 (or the full field campaign) runs it.
pytestmark = pytest.mark.skipif(not (os.environ.get("RAPIDGEN_STREAMS_E2E") or os.environ.get("RAPIDGEN_FIELD_FULL")),
                                reason="RAPIDGEN_STREAMS_E2E=1: setpoint streams end to end (its own C++ build, 2-4 min)")


@pytest.fixture(scope="module")
def bridges() -> dict[str, Path]:
    missing = harness.toolchain_missing()
    if missing:
        pytest.fail(missing)
    return harness.build({R2: code.R2, XARM2: code.XARM2, ROVER: code.R2}, quick=True)


class Watcher:
    """tests/streams/watch.py on R2's partition: AgentState values and TextMessages."""

    def __init__(self, domain: int, partition: str = "") -> None:
        pydir = harness.workdir() / "py-robonaut2"
        harness.run([sys.executable, "-m", "rapidgen", "generate", R2, "--lang", "python", "-o", pydir])
        pkg = pydir / "python"
        local = pkg / "rapid_robonaut2" / "qos_files" / "cyclonedds" / "local.xml"
        env = dict(os.environ, CYCLONEDDS_URI=f"file://{local}", PYTHONPATH=f"{ROOT}")
        self.proc = subprocess.Popen([sys.executable, "-m", "tests.streams.watch", str(pkg), "rapid_robonaut2",
                                      str(domain), *([partition] if partition else [])], cwd=ROOT, env=env,
                                     stdout=subprocess.PIPE, text=True)
        self.events: queue.Queue = queue.Queue()
        threading.Thread(target=self._pump, daemon=True).start()
        assert "ready" in self.next(30)

    def _pump(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self.events.put(json.loads(line))

    def next(self, timeout: float) -> dict:
        return self.events.get(timeout=timeout)  # type: ignore[no-any-return]

    def until(self, pred, timeout: float, what: str) -> dict:
        end = time.monotonic() + timeout
        seen = []
        while time.monotonic() < end:
            try:
                e = self.next(max(0.01, end - time.monotonic()))
            except queue.Empty:
                break
            seen.append(e)
            if pred(e):
                return e
        raise AssertionError(f"no {what} within {timeout} s; saw the last {seen[-5:]}")

    def stop(self) -> None:
        self.proc.kill()
        self.proc.wait()


def state_line(bridge: BridgeProcess, timeout: float) -> re.Match:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        line = bridge.lines.get(timeout=max(0.01, end - time.monotonic()))
        assert line is not None, f"R2's bridge ended: {''.join(bridge.err)[-2000:]}"
        m = STATE.match(line)
        if m:
            return m
    raise AssertionError("no stream state line from R2's bridge")


def agent_is(state: str):
    return lambda e: "agent" in e and e["agent"].get("handPoseStream") == state


def test_stream_arrives_is_lost_and_recovers(bridges):
    env = harness.dds_env()
    r2 = BridgeProcess.of_command([str(bridges["robonaut2"]), "--domain", str(DOMAIN), "--seconds", "90"], ROOT, env)
    rover = BridgeProcess.of_command([str(bridges["rover"]), "--domain", str(DOMAIN), "--seconds", "90"], ROOT, env)
    watcher = rover_watch = writer = None
    try:
        r2.wait_ready()
        rover.wait_ready()
        watcher = Watcher(DOMAIN)
        rover_watch = Watcher(DOMAIN, "StreamRover")
        watcher.until(agent_is("waiting"), 15, "AgentState 'waiting' before any writer")
        writer = BridgeProcess.of_command([str(bridges["xarm2"]), "--domain", str(DOMAIN), "--seconds", "90"],
                                          ROOT, env)
        writer.wait_ready()

        active = state_line(r2, 20)
        assert active.group(1) == "active" and int(active.group(2)) >= 1  # the typed callback ran
        watcher.until(agent_is("active"), 10, "AgentState 'active'")
        assert state_line(rover, 20).group(1) == "active"  # both readers matched and reading
        time.sleep(0.5)

        os.kill(writer.proc.pid, signal.SIGSTOP)  # the writer freezes mid-stream
        lost = state_line(r2, 10)
        assert lost.group(1) == "lost"
        n_lost, x_lost = int(lost.group(2)), int(lost.group(3))
        assert n_lost >= 10 and x_lost >= n_lost  # the writer's samples went through the callback
        text = watcher.until(lambda e: "text" in e and "lost" in e["text"], 10, "a TextMessage saying lost")
        assert "handPose" in text["text"] and "motion stopped" in text["text"] and "WARN" in text["level"]
        agent = watcher.until(agent_is("lost"), 10, "AgentState 'lost'")
        assert agent["agent"]["handPoseMissed"] >= 1
        stop = rover_watch.until(lambda e: "ack" in e and e["ack"].startswith("stream-handPose-stop-")
                                 and "COMPLETED" in e["status"], 10, "the rover's stopAllMotion acks")
        assert "not implemented" in stop["message"]  # the runtime ran it; the stub handler answered
        assert state_line(rover, 10).group(1) == "lost"

        os.kill(writer.proc.pid, signal.SIGCONT)
        back = state_line(r2, 10)
        assert back.group(1) == "active" and int(back.group(2)) > n_lost and int(back.group(3)) > x_lost
        watcher.until(lambda e: "text" in e and "recovered" in e["text"], 10, "a TextMessage saying recovered")
        watcher.until(agent_is("active"), 10, "AgentState 'active' again")
    finally:
        if writer is not None:
            os.kill(writer.proc.pid, signal.SIGCONT)
            writer.stop()
        for w in (watcher, rover_watch):
            if w is not None:
                w.stop()
        rover.stop()
        r2.stop()
