"""Driving a live K10 bridge with either ground-side program, the same words to both:
`rapidgen cmd` (Python, cyclonedds) or rapid_cmd (C++, Fast DDS: rapid_runtime_cpp_add_cmd
on K10's package). Both print one line per ack ("  QUEUED", "  COMPLETED OK  text"), so a
run's acks compare as text."""
from __future__ import annotations

import queue
import subprocess
import sys
import threading
import time
from pathlib import Path

from tests.runtime.live import ROOT, SEEDS, env_for, python_dir

SOURCE = "RapidWorkbench"  # K10's allow-list lets it send Mobility, PanCam, Queue, Admin/echo


class Running:
    """One ground-side program sending one command; its output lines as they come."""

    def __init__(self, argv: list[str], env: dict) -> None:
        self.proc = subprocess.Popen(argv, cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     text=True)
        self.lines: queue.Queue = queue.Queue()
        self.out: list[str] = []
        self.err: list[str] = []
        # stdout by one thread (wait_for reads its lines), stderr drained by another
        self._threads = [threading.Thread(target=self._pump, daemon=True),
                         threading.Thread(target=lambda: self.err.extend(self.proc.stderr), daemon=True)]
        for t in self._threads:
            t.start()

    def _pump(self) -> None:
        for line in self.proc.stdout:
            self.lines.put(line.rstrip("\n"))
        self.lines.put(None)

    def wait_for(self, text: str, timeout: float = 40) -> None:
        """Until an ack line starting with `text` came (QUEUED, EXECUTING)."""
        end = time.monotonic() + timeout
        while True:
            line = self.lines.get(timeout=max(0.1, end - time.monotonic()))
            if line is None:
                self.proc.wait(timeout=10)
                self._threads[1].join(timeout=5)
                raise AssertionError(f"ended before {text}: {self.out} {''.join(self.err)[-2000:]}")
            self.out.append(line)
            if line.strip().startswith(text):
                return

    def finish(self, timeout: float = 60) -> tuple[int, list[str]]:
        """(exit status, the ack lines: the header line dropped, DELETE's target lines kept)."""
        try:
            self.proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        while True:
            line = self.lines.get(timeout=10)
            if line is None:
                break
            self.out.append(line)
        return self.proc.returncode, [ln for ln in self.out if ln.startswith(("  ", "target "))]


class Driver:
    """Sends K10 commands on a domain with one of the two programs."""

    def __init__(self, kind: str, domain: int, cmd_program: Path | None = None) -> None:
        self.kind, self.domain, self.cmd_program = kind, domain, cmd_program

    def argv(self, words: tuple[str, ...], action: str, target: str, cmd_id: str, no_check: bool) -> list[str]:
        if self.kind == "python":
            head = [sys.executable, "-m", "rapidgen", "cmd", SEEDS["k10"]]  # the generated package: no generation per run
        else:
            head = [str(self.cmd_program)]
        extra = ["--action", action] + (["--target", target] if target else []) + (["--id", cmd_id] if cmd_id else [])
        return [*head, *words, "--domain", str(self.domain), "--source", SOURCE, "--timeout", "40", *extra,
                *(["--no-check"] if no_check else [])]

    def env(self) -> dict:
        env = env_for(python_dir("k10"), SEEDS["k10"])  # cyclonedds on K10's loopback-only transport
        return {k: v for k, v in env.items() if not k.startswith(("FASTDDS_", "FASTRTPS_"))}  # rapid_cmd: built-in rapid_local

    def start(self, *words: str, action: str = "BYPASS", target: str = "", cmd_id: str = "",
              no_check: bool = False) -> Running:
        return Running(self.argv(words, action, target, cmd_id, no_check), self.env())

    def send(self, *words: str, **kw) -> tuple[int, list[str]]:
        return self.start(*words, **kw).finish()


def scenario(d: Driver) -> dict[str, tuple[int, list[str]]]:
    """Valid, invalid, queued (APPEND, INSERT, REPLACE, DELETE) and cancelled commands;
    each command's exit status and ack lines. Each step waits for the ack that orders it."""
    got: dict[str, tuple[int, list[str]]] = {}
    got["requestControl"] = d.send("AccessControl", "requestControl")
    got["echo"] = d.send("Admin", "echo", "text=hello")
    got["out of range"] = d.send("PanCam", "pointCamera", "pan=9", no_check=True)
    got["not allowed"] = d.send("PanCam", "takePicture", "mode=sideways", no_check=True)
    drive = d.start("Mobility", "simpleMove", "frame=site", "xyt=40,0,0", action="APPEND", cmd_id="q-drive")
    drive.wait_for("EXECUTING")
    b = d.start("PanCam", "pointCamera", "pan=0.5", action="APPEND", cmd_id="q-b")
    b.wait_for("QUEUED")
    c = d.start("PanCam", "pointCamera", "pan=0.2", action="INSERT", target="q-b", cmd_id="q-c")
    c.wait_for("QUEUED")
    r = d.start("PanCam", "pointCamera", "pan=0.1", action="REPLACE", target="q-c", cmd_id="q-r")
    r.wait_for("QUEUED")
    got["REPLACE's target"] = c.finish()
    code, lines = d.send("PanCam", "pointCamera", "pan=0.5", action="DELETE", target="q-b", cmd_id="q-del")
    # after "target q-b:" its final ack; its QUEUED is shown or not as the durable history
    # reaches the new reader before or after it follows q-b (the whole of q-b is below)
    cut = lines.index("target q-b:") + 1 if "target q-b:" in lines else len(lines)
    got["DELETE"] = (code, lines[:cut] + [ln for ln in lines[cut:] if ln.startswith("  COMPLETED")])
    got["DELETE's target"] = b.finish()
    got["INSERT before a missing target"] = d.send("PanCam", "pointCamera", action="INSERT", target="q-none",
                                                   cmd_id="q-x")
    got["stopAllMotion"] = d.send("Mobility", "stopAllMotion")
    got["the cancelled drive"] = drive.finish()
    got["REPLACE"] = r.finish()
    got["cancelAll"] = d.send("Queue", "cancelAll")
    got["releaseControl"] = d.send("AccessControl", "releaseControl")
    got["without control"] = d.send("PanCam", "pointCamera", "pan=0.3")
    return got


def assert_refuses_bad_input(run, domain: int) -> None:
    """The ground-side programs' refusals before anything is sent (rapid_cmd, <crate>_cmd;
    no asset needed: the built-in tables are the dictionary): exit 2 for usage, 1 for a
    command the dictionary refuses, every name from the command line escaped. run(*args)
    runs the program on `domain`, where no asset is."""
    res = run("--help")
    assert res.returncode == 0 and "--action" in res.stdout
    res = run("Admin")
    assert res.returncode == 2 and "SUBSYSTEM and COMMAND are needed" in res.stderr
    res = run("Admin", "echo", "--action", "SIDEWAYS")
    assert res.returncode == 2 and "bad value for --action: SIDEWAYS" in res.stderr
    res = run("Nowhere\x1b[2J", "echo")
    assert res.returncode == 1 and "has no subsystem 'Nowhere\\x1b[2J'" in res.stderr and "\x1b" not in res.stderr
    res = run("PanCam", "pointCamera", "pan=abc", "zoom=2")
    assert res.returncode == 1 and "pan: 'abc' is not a number" in res.stderr
    assert "pointCamera has no parameter 'zoom'" in res.stderr
    res = run("PanCam", "pointCamera", "pan=9")
    assert res.returncode == 1 and "pan: 9 not in [-3.05, 3.05]" in res.stderr
    res = run("PanCam", "pointCamera", "--action", "INSERT")
    assert res.returncode == 1 and "QUEUE_INSERT needs a target cmdId" in res.stderr
    res = run("Admin", "echo", "text=hi")  # the dictionary's, but no asset on the domain
    assert res.returncode == 1 and f"no asset K10Red reads commands on domain {domain}" in res.stderr
