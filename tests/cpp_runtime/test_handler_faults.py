"""Handlers on a bad day in the C++ runtime (issue 42; runtime/cpp/README.md "The handler
contract"): the GoogleTest suite of fault-injecting handlers (test_handler_faults.cpp) plain
and under ASan/UBSan, then the same faults live: the Faulty test asset generated for C++, its
user-owned handlers replaced by tests/cpp_runtime/faulty/handlers.cpp, its bridge on
loopback, a Python ground tool (`rapidgen cmd`, Cyclone DDS) commanding it.

Live: a helper thread's progress after its BYPASS handler returned (no crash, the bridge
answers on); a handler that ignores DELETE (the DELETE's answer says so, the target's own
final ack at the bound, the next APPEND runs, the cmdId sent again gets its stored final
ack); invalid UTF-8 and a NUL in a handler's answer and TextMessage (the tools decode U+FFFD); Admin shutdown
and SIGTERM with handlers that never return (every command answered, exit 0 within the
shutdown bound, the journal closed clean). Domains 93 and 94 (50-55 are
tests/runtime/test_simulate_telemetry.py's)."""
from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.cpp_runtime import build as B

LIVE_DOMAIN, SIGTERM_DOMAIN = 93, 94
DOMAINS = (LIVE_DOMAIN, SIGTERM_DOMAIN)
HANDLERS = Path(__file__).parent / "faulty" / "handlers.cpp"
STOP_MS, SHUTDOWN_MS = 500, 1500
ACK_WAIT_S = 2.0  # Bridge::stop waits up to 2 s for the last acks to be acknowledged
EXIT_BOUND_S = 3 * (SHUTDOWN_MS / 1000 + ACK_WAIT_S)  # the shutdown bound with 3x slack
DESCRIPTOR = """\
version: 1
asset:
  name: Faulty
  kind: rover
  description: a test asset whose handlers misbehave (issue 42)
dds:
  domain: 93
idl:
  rapid: {rapid}
subsystem_types:
  - name: Worker
    description: handlers on a bad day
    commands:
      - name: helper
        description: returns at once; a thread of its own reports progress after
      - name: stubborn
        description: ignores cancel until told to return
        abortable: true
      - name: quick
        description: answers at once
      - name: badText
        description: answers with invalid UTF-8 and a NUL
subsystems:
  - {{name: Admin}}
  - {{name: Queue}}
  - {{name: Belt, type: Worker, description: the queue's}}
telemetry:
  - kind: text
    categories: [faults]
"""
FFFD = "\ufffd"


def test_fault_suite_passes(runtime_build):
    res = subprocess.run([str(runtime_build / "faults"), "--gtest_brief=1"], capture_output=True, text=True,
                         timeout=300)
    assert res.returncode == 0, res.stdout[-6000:] + res.stderr[-3000:]
    ran = re.search(r"\[==========\] (\d+) tests", res.stdout)
    assert ran and int(ran.group(1)) >= 10, res.stdout[-2000:]


def test_fault_suite_is_clean_under_address_and_undefined_behaviour_sanitizers(faults_under_sanitizers):
    env = dict(os.environ, ASAN_OPTIONS="detect_leaks=1:abort_on_error=0", UBSAN_OPTIONS="print_stacktrace=1")
    res = subprocess.run([str(faults_under_sanitizers), "--gtest_brief=1"], capture_output=True, text=True,
                         timeout=600, env=env)
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr[-6000:]
    assert "Sanitizer" not in res.stderr and "runtime error" not in res.stderr, res.stderr[-6000:]


def test_fault_suite_is_clean_under_thread_sanitizer(logic_under_tsan):
    """The stop bound's watchdog, helper threads calling a context, the manager going while
    one does: no data race."""
    res = subprocess.run([str(logic_under_tsan.parent / "faults"), "--gtest_brief=1"], capture_output=True,
                         text=True, timeout=600, env=dict(os.environ, TSAN_OPTIONS="halt_on_error=1"))
    assert res.returncode == 0 and "ThreadSanitizer" not in res.stderr, res.stdout[-3000:] + res.stderr[-6000:]


# ---- live: the Faulty asset's C++ bridge, a Python ground tool --------------------------------------

@pytest.fixture(scope="module")
def faulty(tmp_path_factory) -> tuple[Path, Path]:
    """(the Faulty asset's C++ bridge, its descriptor): generated, handlers.cpp replaced, built
    against the session's runtime (a unity build at -O0), once per run."""
    def make() -> tuple[Path, Path]:
        runtime = B.runtime_dir(tmp_path_factory)
        base = B.base(tmp_path_factory) / "faulty"
        base.mkdir()
        desc = base / "faulty.yaml"
        desc.write_text(DESCRIPTOR.format(rapid=B.ROOT / "specs" / "rapid"))
        B.run([sys.executable, "-m", "rapidgen", "generate", str(desc), "--lang", "cpp", "-o", str(base / "out")])
        cpp = base / "out" / "cpp"
        shutil.copyfile(HANDLERS, cpp / "bridge" / "handlers.cpp")  # the user's file
        B.configure(cpp, base / "build", f"-Drapid_runtime_cpp_DIR={runtime}", "-DCMAKE_CXX_FLAGS_RELEASE=-O0",
                    "-DCMAKE_UNITY_BUILD=ON", "-DCMAKE_UNITY_BUILD_BATCH_SIZE=16")
        B.build(base / "build", "rapid_faulty_bridge")
        return base / "build" / "rapid_faulty_bridge", desc
    return B.once(tmp_path_factory, "faulty-bridge", make)  # type: ignore[no-any-return]


class Bridge:
    """The Faulty bridge as a process of its own group, its marker folder and journal."""

    def __init__(self, exe: Path, folder: Path, domain: int) -> None:
        self.marks = folder / "marks"
        self.marks.mkdir()
        self.state = folder / "state"
        env = dict(B.dds_env(), RAPID_STATE_DIR=str(self.state), FAULTY_DIR=str(self.marks))
        self.proc = subprocess.Popen([str(exe), "--domain", str(domain), "--stop-timeout", str(STOP_MS),
                                      "--shutdown-timeout", str(SHUTDOWN_MS)], env=env, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True, encoding="utf-8", errors="replace",
                                     start_new_session=True)
        assert self.proc.stdout is not None
        first = self.proc.stdout.readline()
        assert first.startswith("bridge ready: asset Faulty"), first + self.proc.stderr.read()[-3000:]
        self.out = first
        self.err = ""

    def wait_mark(self, name: str, timeout: float = 30) -> None:
        end = time.monotonic() + timeout
        while not (self.marks / name).exists():
            assert self.proc.poll() is None, f"bridge exited {self.proc.returncode} waiting for {name}"
            assert time.monotonic() < end, f"{name} never written"
            time.sleep(0.02)

    def ended(self, timeout: float) -> int:
        """The exit code once it ended (timeout: a failure); its stdout and stderr read."""
        try:
            out, err = self.proc.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            self.kill()
            raise AssertionError(f"the bridge did not end within {timeout} s")
        self.out += out
        self.err += err
        return self.proc.returncode

    def kill(self) -> None:
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGKILL)
            self.proc.communicate()


def tool_env() -> dict:
    return {k: v for k, v in B.dds_env().items() if k != "CYCLONEDDS_URI"}  # the tools' local (loopback) profile


def cmd(desc: Path, domain: int, *args: str, background: bool = False):
    """`rapidgen cmd` on the descriptor's dictionary (its stdout: the acks as the tool decodes them)."""
    argv = [sys.executable, "-m", "rapidgen", "cmd", str(desc), "--domain", str(domain), "--from-descriptor",
            "--timeout", "30", *args]
    env = tool_env()
    if background:
        return subprocess.Popen(argv, cwd=B.ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True, encoding="utf-8")
    return subprocess.run(argv, cwd=B.ROOT, env=env, capture_output=True, text=True, encoding="utf-8", timeout=90)


def test_live_handler_faults_leave_the_bridge_answering_honestly(faulty, tmp_path):
    exe, desc = faulty
    bridge = Bridge(exe, tmp_path, LIVE_DOMAIN)
    try:
        # a helper thread reports progress after its BYPASS handler returned: nothing, no crash
        res = cmd(desc, LIVE_DOMAIN, "Belt", "helper", "--id", "h1")
        assert res.returncode == 0 and "COMPLETED OK  helper started" in res.stdout, res.stdout + res.stderr
        bridge.wait_mark("helper-h1")  # (both late progress calls made)
        res = cmd(desc, LIVE_DOMAIN, "Belt", "quick")
        assert res.returncode == 0 and "COMPLETED OK  quick" in res.stdout, res.stdout + res.stderr
        assert bridge.proc.poll() is None

        # invalid UTF-8 and a NUL from the handler, in its answer and in a TextMessage it
        # publishes: a final ack the Python tool decodes, a TextMessage `rapidgen spy` decodes
        # (the handler publishes one per run: sent again until the new reader has matched)
        spy = subprocess.Popen([sys.executable, "-m", "rapidgen", "spy", "echo", "rapid_textmessage", "--domain",
                                str(LIVE_DOMAIN), "--asset", str(desc), "--json", "--count", "1"], cwd=B.ROOT,
                               env=tool_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               encoding="utf-8")
        try:
            for _ in range(20):
                res = cmd(desc, LIVE_DOMAIN, "Belt", "badText")
                assert res.returncode == 0, res.stdout + res.stderr
                assert f"COMPLETED OK  bad {FFFD}{FFFD} text {FFFD} nul[{FFFD}] end" in res.stdout, res.stdout
                try:
                    spy.wait(timeout=1)
                    break
                except subprocess.TimeoutExpired:
                    pass
            said, err = spy.communicate(timeout=30)
        finally:
            if spy.poll() is None:
                spy.kill()
                spy.communicate()
        assert spy.returncode == 0 and said.strip(), said + err
        text = json.loads(said.splitlines()[0])["sample"]
        assert (text["category"], text["message"]) == (f"faults{FFFD}", f"bad {FFFD}{FFFD} text {FFFD} nul[{FFFD}] end")

        # a handler that ignores DELETE: said so; its final ack at the bound; the queue goes on
        res = cmd(desc, LIVE_DOMAIN, "Belt", "stubborn", "--action", "APPEND", "--id", "s1", "--no-wait")
        assert "QUEUED" in res.stdout, res.stdout + res.stderr
        bridge.wait_mark("started-s1")
        res = cmd(desc, LIVE_DOMAIN, "Admin", "noOp", "--action", "DELETE", "--target", "s1")
        assert "COMPLETED OK  s1 cancel requested; handler has not stopped yet" in res.stdout, res.stdout
        res = cmd(desc, LIVE_DOMAIN, "Belt", "quick", "--action", "APPEND", "--id", "q1")
        assert res.returncode == 0 and "COMPLETED OK  quick" in res.stdout, res.stdout + res.stderr
        # s1 sent again (a fresh tool): nothing runs; its stored final ack
        res = cmd(desc, LIVE_DOMAIN, "Belt", "stubborn", "--action", "APPEND", "--id", "s1")
        assert "COMPLETED EXEC_FAILED  handler did not stop" in res.stdout, res.stdout + res.stderr
        assert sorted(p.name for p in bridge.marks.iterdir()) == ["helper-h1", "started-s1"]

        # Admin shutdown with s1's handler still running: answered, and the process ends
        res = cmd(desc, LIVE_DOMAIN, "Admin", "shutdown")
        assert "COMPLETED OK  shutting down" in res.stdout, res.stdout + res.stderr
        assert bridge.ended(EXIT_BOUND_S + 30) == 0, bridge.err[-3000:]  # (+30: the tool's own exit)
        assert "bridge stopped (1 handler(s) still running)" in bridge.out, bridge.out
        logs = bridge.err
        assert logs.count("'s1' (Belt/stubborn): handler did not stop within 500 ms") == 1, logs
        assert "must stop it in hardware" in logs and "Traceback" not in logs, logs
    finally:
        bridge.kill()


def journal_entries(bridge: Bridge, domain: int) -> list[dict]:
    path = bridge.state / f"Faulty-domain{domain}.journal"
    if not path.exists():
        return []
    return [json.loads(line.split(" ", 1)[1]) for line in path.read_text().splitlines() if " " in line]


def test_sigterm_ends_the_bridge_within_its_bound_with_every_command_answered(faulty, tmp_path):
    exe, desc = faulty
    bridge = Bridge(exe, tmp_path, SIGTERM_DOMAIN)
    tools = []
    try:
        tools.append(cmd(desc, SIGTERM_DOMAIN, "Belt", "stubborn", "--action", "APPEND", "--id", "s2",
                         background=True))
        bridge.wait_mark("started-s2")
        tools.append(cmd(desc, SIGTERM_DOMAIN, "Belt", "quick", "--action", "APPEND", "--id", "s3", background=True))
        end = time.monotonic() + 60  # s3 queued behind s2 (journaled before its QUEUED ack)
        while not any(e.get("k") == "q" and e.get("id") == "s3" for e in journal_entries(bridge, SIGTERM_DOMAIN)):
            assert time.monotonic() < end, "s3 never queued"
            time.sleep(0.02)
        bridge.proc.send_signal(signal.SIGTERM)
        start = time.monotonic()
        code = bridge.ended(60)
        took = time.monotonic() - start
        assert code == 0, bridge.err[-3000:]
        assert took < EXIT_BOUND_S, f"{took:.1f} s after SIGTERM (shutdown bound {SHUTDOWN_MS} ms)"
        assert "bridge stopped (1 handler(s) still running)" in bridge.out, bridge.out
        assert "'s2' (Belt/stubborn): handler did not stop within the shutdown bound" in bridge.err, bridge.err
        # each tool got its command's final ack, decoded
        out2, err2 = tools[0].communicate(timeout=60)
        assert "COMPLETED EXEC_FAILED  handler did not stop" in out2, out2 + err2
        out3, err3 = tools[1].communicate(timeout=60)
        assert "COMPLETED CANCELED  asset shutting down" in out3, out3 + err3
        # and journaled: both finished, the journal closed clean (a restart answers nothing again)
        entries = journal_entries(bridge, SIGTERM_DOMAIN)
        finals = {e["id"]: (e["c"], e["m"]) for e in entries if e.get("k") == "c"}
        assert finals == {"s2": ("ACK_COMPLETED_EXEC_FAILED", "handler did not stop"),
                          "s3": ("ACK_COMPLETED_CANCELED", "asset shutting down")}, entries
        assert entries[-1] == {"k": "stop"}, entries
    finally:
        for p in tools:
            if p.poll() is None:
                p.kill()
                p.communicate()
        bridge.kill()
