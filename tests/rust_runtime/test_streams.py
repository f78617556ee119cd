"""Setpoint streams in the Rust runtime (docs/realtime.md "In the Rust runtime"), real
processes on loopback: tests/streams/rig.yaml's Rust bridge (one input stream per loss
action, from the folder's shared build: build.RIG) under --simulate, tests/streams/pilot.py
(Cyclone DDS, Python) writing its three streams in partition RigPilot, tests/streams/watch.py
reading the rig's AgentState, TextMessages, acks, body position, mast pose and arm joints. One
run, in order:

- setpoints move the simulated robot (body toward x = 2, arm toward (2, -2, 0.5), mast toward
  z = 1); a missed deadline (the writers paused, alive, early): each stream lost in its
  action's words, stopAllMotion for drive only, the state and missed keys in AgentState; stop
  halts the body short of its setpoint, hold and none let the arm and the mast reach theirs;
  resumed: recovered;
- non-finite samples: drive's writer sends NaN rotations around a new target x = -1: dropped,
  reported once, the stream lost for want of a finite sample (stop: stopAllMotion, the body
  halts and does not turn back), the other streams active; a finite sample recovers it;
- a killed writer: lost on the deadline, then "its writer is gone" (LIVELINESS, 600 ms lease);
- the bridge's summary per stream at SIGTERM, exit status 0.

And the seeds' hand pose, Rust to Rust (domain 84, tagged as well): X-Arm 2's output stream
under --simulate read by Robonaut 2's bridge, lost with its writer frozen, recovered.

Domain 82 is shared (tests/cpp_client/test_broken.py's range 73-82), so every process here
carries a Cyclone discovery tag of this run's own: participants with another tag or none
ignore them and are ignored."""
from __future__ import annotations

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

from tests.rust_runtime.build import OLD_HANDLERS, RIG
from tests.streams.test_setpoint_stream import RIG as RIG_YAML
from tests.streams.test_setpoint_stream import Watcher, latest, python_package, texts_until

ROOT = Path(__file__).resolve().parents[2]
DOMAIN = 82
SEED_DOMAIN = 84  # shared with tests/field/test_restart.py: tagged too
R2_LOCAL = ROOT / "generated" / "robonaut2" / "python" / "rapid_robonaut2" / "qos_files" / "cyclonedds" / "local.xml"
ACTIONS = {"drive": "motion stopped", "arm": "holding the last setpoint", "mast": "no action"}
BODY, MAST, ARM = "rapid_position_sample", "rapid_position_sample-mastHead", "rapid_joint_sample"


def _env(py: Path) -> tuple[Path, str, dict]:
    pkg, name, env = python_package(RIG_YAML, py)
    tag = f"rapidgen-rust-streams-{os.getpid()}"
    env["CYCLONEDDS_URI"] += f',<CycloneDDS><Domain id="any"><Discovery><Tag>{tag}</Tag></Discovery></Domain></CycloneDDS>'
    return pkg, name, env


class TaggedWatcher(Watcher):
    """watch.py on the package's own partition (its `topics` printed too), with a tag in env."""

    def __init__(self, pkg: Path, name: str, env: dict, domain: int = DOMAIN,
                 topics: tuple[str, ...] = (BODY, MAST, ARM)) -> None:
        self.proc = subprocess.Popen([sys.executable, "-m", "tests.streams.watch", str(pkg), name, str(domain), "",
                                      *topics], cwd=ROOT, env=env, stdout=subprocess.PIPE, text=True)
        self.events = queue.Queue()
        self.history = []
        threading.Thread(target=self._pump, daemon=True).start()
        assert "ready" in self.next(30)


def says(text: str, action: str) -> bool:
    """The loss text ends with its action's words (cut like every TextMessage at 127 bytes,
    as the C++ runtime's: a long count can cut the action's last letters)."""
    tail = text.rsplit("): ", 1)[-1]
    return tail == action or (len(text.encode()) == 127 and len(tail) >= 4 and action.startswith(tail))


def pools(err: str) -> dict[str, list[int]]:
    """Each stream's serialized samples as the bridge logs them at stop (rapid_dds pooled.rs):
    made, reused, freed past the pool, the pool's size, held."""
    return {m.group(1): [int(x) for x in m.groups()[1:]] for m in re.finditer(
        r"stream (\w+): serialized samples: (\d+) made, (\d+) reused, (\d+) freed past the pool of (\d+), (\d+) held", err)}


def agent_all(state: str):
    return lambda e: "agent" in e and all(e["agent"].get(f"{n}Stream") == state for n in ACTIONS)


def latest_events(watcher: Watcher, seconds: float) -> list[dict]:
    """Every event seen within the next `seconds`."""
    out = []
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        try:
            out.append(watcher.next(max(0.01, end - time.monotonic())))
        except queue.Empty:
            break
    return out


def body_x(watcher: Watcher, seconds: float) -> float:
    return latest(watcher, seconds)[BODY][0]


def test_loss_actions_non_finite_and_summary(bridges, tmp_path):
    pkg, name, env = _env(tmp_path / "py")
    rig = subprocess.Popen([str(bridges[RIG]), "--simulate", "--domain", str(DOMAIN), "--no-journal"], cwd=ROOT,
                           env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    watcher = pilot = None
    try:
        assert rig.stdout is not None
        ready = rig.stdout.readline()
        assert "ready on domain 82 (simulated)" in ready, ready + (rig.stderr.read() if rig.poll() is not None else "")
        watcher = TaggedWatcher(pkg, name, env)
        watcher.until(agent_all("waiting"), 15, "AgentState: every stream waiting before any writer")
        pilot = subprocess.Popen([sys.executable, "-m", "tests.streams.pilot", str(pkg), name, str(DOMAIN)], cwd=ROOT,
                                 env=env, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        assert pilot.stdin is not None and pilot.stdout is not None
        assert "ready" in pilot.stdout.readline()

        def send(command: str) -> None:
            pilot.stdin.write(command + "\n")
            pilot.stdin.flush()

        # each stream's TextMessage and the AgentState showing them all active come in either
        # order (streams turning active in different reporting rounds on a busy machine): both at once
        actives: dict[str, dict] = {}
        state_seen = [False]

        def all_active(e: dict) -> bool:
            for n in ACTIONS:
                if n not in actives and e.get("text", "").startswith(f"stream {n}") and "active" in e["text"]:
                    actives[n] = e
            state_seen[0] = state_seen[0] or agent_all("active")(e)
            return state_seen[0] and len(actives) == len(ACTIONS)
        watcher.until(all_active, 15, "AgentState: every stream active, and a TextMessage per stream saying so")
        # the setpoints move the simulated robot: body toward x = 2, arm toward (2, -2, 0.5), mast toward z = 1
        watcher.until(lambda e: e.get("joint") == "rapid_joint_sample" and e["pos"][0] > 0.05, 10, "the arm moving")

        # a missed deadline, the writers alive (paused early: the arm and the mast still on their way)
        send("pause drive arm mast")
        lost = texts_until(watcher, {n: "lost (no sample within its 200 ms deadline" for n in ACTIONS}, 10,
                           "a TextMessage per stream saying lost on its deadline")
        for n, action in ACTIONS.items():
            assert says(lost[n]["text"], action) and "WARN" in lost[n]["level"], lost[n]
        stop = watcher.seen_or_until(lambda e: e.get("ack") == "stream-drive-stop-1" and "COMPLETED" in e["status"],
                                     10, "Mobility/stopAllMotion run for drive")
        assert "OK" in stop["completed"] and "stopped" in stop["message"]  # the simulated handler answered
        agent = watcher.until(agent_all("lost"), 10, "AgentState: every stream lost")
        assert all(agent["agent"][f"{n}Missed"] >= 1 for n in ACTIONS), agent
        before = latest(watcher, 0.5)
        after = latest(watcher, 3.0)  # stop: the body stays; hold and none: arm and mast go on to their setpoints
        x0, x1 = before[BODY][0], after[BODY][0]
        assert 0 < x1 < 1.99 and abs(x1 - x0) < 1e-6, (x0, x1)
        assert after[ARM] == pytest.approx([2.0, -2.0, 0.5], abs=1e-3), (before, after)  # (halted, it stays short)
        assert after[MAST][2] == pytest.approx(1.0, abs=1e-3), after
        send("resume drive arm mast")
        texts_until(watcher, {n: "recovered" for n in ACTIONS}, 10, "a TextMessage per stream saying recovered")
        watcher.until(agent_all("active"), 10, "AgentState: every stream active again")

        # NaN and Inf: never handed on (the body would turn back toward x = -1), lost on the deadline
        send("nan drive")
        dropped = texts_until(watcher, {"drive": "samples with NaN or Inf dropped"}, 10, "drive's NaN reported")["drive"]
        assert "WARN" in dropped["level"] and dropped["text"].endswith("lost without a finite one in 200 ms")
        lost = texts_until(watcher, {"drive": "lost (no finite sample within its 200 ms deadline"}, 10,
                           "drive lost for want of a finite sample")["drive"]
        assert says(lost["text"], "motion stopped") and "WARN" in lost["level"], lost
        watcher.seen_or_until(lambda e: e.get("ack") == "stream-drive-stop-2" and "COMPLETED" in e["status"], 10,
                              "stopAllMotion for drive again")
        agent = watcher.until(lambda e: "agent" in e and e["agent"].get("driveStream") == "lost", 10, "drive lost")
        assert agent["agent"]["driveMissed"] >= 2
        assert (agent["agent"]["armStream"], agent["agent"]["mastStream"]) == ("active", "active")
        x0, x1 = body_x(watcher, 0.5), body_x(watcher, 1.5)
        assert abs(x1 - x0) < 1e-6, (x0, x1)  # not turning back toward x = -1, and halted (stop)
        texts = [e["text"] for e in watcher.history if "text" in e and e["text"].startswith("stream drive: samples")]
        assert len(texts) == 1, texts  # once for the run of them, not once per sample
        send("finite drive")
        texts_until(watcher, {"drive": "recovered"}, 10, "drive recovered")
        watcher.until(lambda e: e.get("position") == BODY and e["xyz"][0] > x1 + 0.02, 10, "the body moving again")

        # the writer killed: the deadline goes first, then the 600 ms lease
        pilot.kill()
        pilot.wait()
        texts_until(watcher, {n: "lost (no sample within" for n in ACTIONS}, 10, "every stream lost on its deadline")
        gone = texts_until(watcher, {n: "its writer is gone (no liveliness within 600 ms)" for n in ACTIONS}, 10,
                           "a TextMessage per stream saying its writer is gone")
        assert all("WARN" in g["level"] for g in gone.values())
        watcher.until(agent_all("lost"), 10, "AgentState: every stream lost again")
        acks = {e["ack"] for e in watcher.history if "ack" in e}
        assert acks >= {"stream-drive-stop-1", "stream-drive-stop-2", "stream-drive-stop-3"}, acks
        assert all(a.startswith("stream-drive-stop-") for a in acks), acks  # hold and none send nothing

        rig.terminate()
        _, err = rig.communicate(timeout=20)
        assert rig.returncode == 0, err[-2000:]
        summary = {m.group(1): [int(x) for x in m.groups()[1:]] for m in re.finditer(
            r"stream (\w+): (\d+) samples, (\d+) deadlines missed, (\d+) losses, (\d+) non-finite dropped", err)}
        assert set(summary) == set(ACTIONS), err[-2000:]
        assert summary["drive"][2] >= 3 and summary["drive"][3] >= 5, summary  # NaN, pause, kill; the NaN run
        assert summary["arm"][3] == 0 and summary["mast"][2] >= 2, summary
        # Cyclone's serialized samples came from each topic's free list (a keep-last-1 reader
        # has a few alive at once, whatever the count), and every one came back when the
        # reader went (the writers are gone by now)
        pooled = pools(err)
        assert set(pooled) == set(ACTIONS), err[-2000:]
        for name, (made, reused, freed, size, held) in pooled.items():
            samples, non_finite = summary[name][0], summary[name][3]
            assert made <= size and made + reused >= samples + non_finite >= 100, (name, pooled[name], summary[name])
            assert freed == 0 and held == 0 and size == 8, (name, pooled[name])
        assert "panicked" not in err, err[-2000:]
    finally:
        if pilot is not None and pilot.poll() is None:
            pilot.kill()
            pilot.wait()
        if watcher is not None:
            watcher.stop()
        if rig.poll() is None:
            rig.kill()
            rig.wait()


def test_generated_stream_glue(bridges):
    """The rig's generated glue: trait Streams with a default body per input stream, and its
    fresh handlers.rs handing its callbacks over (with_streams). The folder's build compiled
    Robonaut 2's committed handlers.rs, which predates its stream's glue (a bare HandlerSet):
    a handlers.rs written before a stream was declared still compiles."""
    gen = bridges["ws"] / "generated" / RIG / "rust" / "bridge" / "src"
    dispatch = (gen / "dispatch.rs").read_text(encoding="utf-8")
    for method, t in (("drive", "PositionSample"), ("arm", "JointSample"), ("mast", "PositionSample")):
        assert re.search(rf"fn {method}\(&self, sample: &rapid_streamrig::rapid::{t}\) \{{\n\s+let _ = sample;", dispatch)
    handlers = (gen / "handlers.rs").read_text(encoding="utf-8")
    assert ".with_streams(SetpointStreams)" in handlers and "pub fn make_handlers() -> Dispatch" in handlers
    built = (bridges["ws"] / OLD_HANDLERS).read_text(encoding="utf-8")
    assert built == (ROOT / OLD_HANDLERS).read_text(encoding="utf-8")
    assert "pub fn make_handlers() -> HandlerSet" in built and "with_streams" not in built
    assert "fn hand_pose(&self" in (bridges["ws"] / OLD_HANDLERS).with_name("dispatch.rs").read_text(encoding="utf-8")


def test_seed_streams_x_arm_2_simulated_drives_robonaut_2(bridges, tmp_path):
    """The seeds' hand pose, Rust to Rust: X-Arm 2's bridge under --simulate writes its output
    stream handPose (500 Hz, from the kept sample), Robonaut 2's bridge without --simulate
    (its committed handlers.rs: no callbacks, samples counted and watched) reads it in
    partition XArm2: active, lost with the writer frozen (SIGSTOP: no sample within 10 ms,
    on_loss stop), recovered (SIGCONT), in AgentState and TextMessages. Domain 84, tagged."""
    env = dict(os.environ, CYCLONEDDS_URI=f"file://{R2_LOCAL},<CycloneDDS><Domain id=\"any\"><Discovery>"
               f"<Tag>rapidgen-rust-seed-streams-{os.getpid()}</Tag></Discovery></Domain></CycloneDDS>")
    r2 = subprocess.Popen([str(bridges["robonaut2"]), "--domain", str(SEED_DOMAIN), "--no-journal"], cwd=ROOT,
                          env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    writer = watcher = None
    try:
        assert r2.stdout is not None and "ready" in r2.stdout.readline()
        watcher = TaggedWatcher(R2_LOCAL.parents[3], "rapid_robonaut2", env, SEED_DOMAIN, ())
        agent = lambda state: lambda e: "agent" in e and e["agent"].get("handPoseStream") == state  # noqa: E731
        watcher.until(agent("waiting"), 15, "AgentState 'waiting' before any writer")
        writer = subprocess.Popen([str(bridges["xarm2"]), "--simulate", "--domain", str(SEED_DOMAIN), "--no-journal"],
                                  cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=(tmp_path / "xarm2.err").open("w"),
                                  text=True)
        assert writer.stdout is not None and "ready" in writer.stdout.readline()
        watcher.until(agent("active"), 15, "AgentState 'active': the simulated X-Arm 2's hand pose arrives")
        # ("recovered" when a loaded machine made the 10 ms deadline pass before the reporter looked)
        watcher.seen_or_until(lambda e: "text" in e and re.search(r"handPose (active|recovered)", e["text"]), 10,
                              "a TextMessage saying active")
        os.kill(writer.pid, signal.SIGSTOP)
        text = watcher.until(lambda e: "text" in e and "handPose lost" in e["text"], 10, "a TextMessage saying lost")
        assert says(text["text"], "motion stopped") and "WARN" in text["level"], text
        lost = watcher.until(agent("lost"), 10, "AgentState 'lost'")
        assert lost["agent"]["handPoseMissed"] >= 1
        # (a loaded machine may miss the 10 ms deadline before the freeze; frozen, it stays lost)
        frozen = latest_events(watcher, 1.5)
        assert not any("text" in e and "recovered" in e["text"] for e in frozen), frozen
        assert [e for e in frozen if "agent" in e][-1]["agent"]["handPoseStream"] == "lost", frozen
        os.kill(writer.pid, signal.SIGCONT)
        watcher.until(lambda e: "text" in e and "handPose recovered" in e["text"], 10, "a TextMessage saying recovered")
        watcher.until(agent("active"), 10, "AgentState 'active' again")
        r2.terminate()
        _, err = r2.communicate(timeout=20)
        assert r2.returncode == 0, err[-2000:]
        m = re.search(r"stream handPose: (\d+) samples, (\d+) deadlines missed, (\d+) losses", err)
        assert m and int(m.group(1)) >= 1 and int(m.group(3)) >= 1, err[-2000:]
        # both sides' serialized samples from their topic's free list
        read = pools(err)["handPose"]
        assert read[0] <= read[3] and read[0] + read[1] >= int(m.group(1)), read
        writer.terminate()
        assert writer.wait(timeout=20) == 0
        wrote = pools((tmp_path / "xarm2.err").read_text(encoding="utf-8"))["handPose"]
        assert wrote[0] <= wrote[3] and wrote[0] + wrote[1] >= int(m.group(1)) and wrote[2] == 0, wrote
    finally:
        if writer is not None and writer.poll() is None:
            os.kill(writer.pid, signal.SIGCONT)
            writer.kill()
            writer.wait()
        if watcher is not None:
            watcher.stop()
        if r2.poll() is None:
            r2.kill()
            r2.wait()
