"""Stale telemetry in the C++ runtime (issue 39 item 1; docs/runtime.md "Stale telemetry"),
live: the Stale test asset generated for C++, its handlers replaced by
tests/cpp_runtime/stale/handlers.cpp (a position source that republishes its last pose at
10 Hz stamped with the time it was measured, as a bridge fed by another process does), its
bridge on loopback, Python readers (`rapidgen spy echo`, Cyclone DDS) watching. The source is
cut (the kill -9 of issue 39): the republished samples stop once older than the bound, one
TextMessage says so, the agent's stale_telemetry names the entry; resumed: "source back" once,
the key emptied, samples flow again. The rule itself, on a fake clock: test_freshness.cpp.
Domain 48."""
from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.cpp_runtime import build as B
from tests.cpp_runtime.test_handler_faults import cmd, tool_env

DOMAIN = 48
HANDLERS = Path(__file__).parent / "stale" / "handlers.cpp"
BOUND_MS, PERIOD_MS = 1000, 100  # the descriptor's stale_after_ms; the feeder's period
DESCRIPTOR = """\
version: 1
asset:
  name: Stale
  kind: rover
  description: a test asset whose position source dies (issue 39)
dds:
  domain: 48
idl:
  rapid: {rapid}
subsystem_types:
  - name: Feed
    description: the position source
    commands:
      - name: cut
        description: the source stops measuring
      - name: resume
        description: the source measures again
subsystems:
  - {{name: Admin}}
  - {{name: Source, type: Feed, description: the position source}}
telemetry:
  - kind: position
    frame: site
    rate: 10
    stale_after_ms: 1000
  - kind: agent
    values:
      - {{key: stale_telemetry, type: RAPID_STRING}}
  - kind: text
    categories: [system]
"""
SILENT = re.compile(r"^rapid_position_sample source silent for \d+\.\d s: samples stopped$")
BACK = "rapid_position_sample source back"

pytest.importorskip("cyclonedds")


@pytest.fixture(scope="module")
def stale(tmp_path_factory) -> tuple[Path, Path]:
    """(the Stale asset's C++ bridge, its descriptor): generated, handlers.cpp replaced, built
    against the session's runtime (a unity build at -O0), once per run."""
    def make() -> tuple[Path, Path]:
        runtime = B.runtime_dir(tmp_path_factory)
        base = B.base(tmp_path_factory) / "stale"
        base.mkdir()
        desc = base / "stale.yaml"
        desc.write_text(DESCRIPTOR.format(rapid=B.ROOT / "specs" / "rapid"))
        B.run([sys.executable, "-m", "rapidgen", "generate", str(desc), "--lang", "cpp", "-o", str(base / "out")])
        cpp = base / "out" / "cpp"
        shutil.copyfile(HANDLERS, cpp / "bridge" / "handlers.cpp")  # the user's file
        B.configure(cpp, base / "build", f"-Drapid_runtime_cpp_DIR={runtime}", "-DCMAKE_CXX_FLAGS_RELEASE=-O0",
                    "-DCMAKE_UNITY_BUILD=ON", "-DCMAKE_UNITY_BUILD_BATCH_SIZE=16")
        B.build(base / "build", "rapid_stale_bridge")
        return base / "build" / "rapid_stale_bridge", desc
    return B.once(tmp_path_factory, "stale-bridge", make)  # type: ignore[no-any-return]


class Echo:
    """`rapidgen spy echo TOPIC --json` in the background, its samples read from a file."""

    def __init__(self, desc: Path, topic: str, folder: Path) -> None:
        self.path = folder / f"{topic}.jsonl"
        self.out = open(self.path, "w")
        self.proc = subprocess.Popen([sys.executable, "-m", "rapidgen", "spy", "echo", topic, "--domain", str(DOMAIN),
                                      "--asset", str(desc), "--json"], cwd=B.ROOT, env=dict(tool_env(), PYTHONUNBUFFERED="1"), stdout=self.out,
                                     stderr=subprocess.PIPE, text=True, encoding="utf-8")

    def samples(self) -> list[dict]:
        complete = self.path.read_text(encoding="utf-8").split("\n")[:-1]  # (a line being written: not yet)
        return [json.loads(ln)["sample"] for ln in complete if ln.strip()]

    def until(self, what, timeout: float = 30):
        end = time.monotonic() + timeout
        while True:
            found = what(self.samples())
            if found:
                return found
            assert self.proc.poll() is None, self.proc.stderr.read()[-2000:]
            assert time.monotonic() < end, f"{self.path.name}: not seen in {timeout} s: {self.samples()[-5:]}"
            time.sleep(0.05)

    def close(self) -> None:
        if self.proc.poll() is None:
            self.proc.terminate()
            self.proc.communicate(timeout=30)
        self.out.close()


def _texts(samples: list[dict]) -> list[str]:
    return [s["message"] for s in samples]


def test_a_silent_source_stops_its_samples_and_is_said_once_then_back(stale, tmp_path):
    exe, desc = stale
    proc = subprocess.Popen([str(exe), "--domain", str(DOMAIN), "--seconds", "300"],
                            env=dict(B.dds_env(), RAPID_STATE_DIR=str(tmp_path / "state")), stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, encoding="utf-8", errors="replace")
    echoes = []
    try:
        first = proc.stdout.readline()
        assert first.startswith("bridge ready: asset Stale"), first + proc.stderr.read()[-3000:]
        pos, text, agent = (Echo(desc, t, tmp_path) for t in
                            ("rapid_position_sample", "rapid_textmessage", "rapid_agent_state"))
        echoes = [pos, text, agent]
        pos.until(lambda s: len(s) >= 5)

        res = cmd(desc, DOMAIN, "Source", "cut")
        assert res.returncode == 0 and "COMPLETED OK  source cut" in res.stdout, res.stdout + res.stderr
        said = text.until(lambda s: [m for m in s if SILENT.match(m["message"])])
        assert said[0]["category"] == "system", said
        agent.until(lambda s: [a for a in s if "rapid_position_sample" in json.dumps(a)])
        time.sleep(0.5)  # (a sample written as the silence was found has arrived)
        stopped = len(pos.samples())
        time.sleep(2 * BOUND_MS / 1000)  # the feeder still calls position() every 100 ms: refused
        during = pos.samples()
        assert len(during) == stopped, during[stopped:]
        frozen = during[-1]["hdr"]["timeStamp"]
        republished = [s for s in during if s["hdr"]["timeStamp"] == frozen]
        # the last measured pose, sent again while younger than the bound (at most one per period)
        assert 2 <= len(republished) <= BOUND_MS // PERIOD_MS + 1, len(republished)
        assert len({json.dumps(s["pose"]) for s in republished}) == 1

        res = cmd(desc, DOMAIN, "Source", "resume")
        assert res.returncode == 0 and "COMPLETED OK  source back" in res.stdout, res.stdout + res.stderr
        text.until(lambda s: BACK in _texts(s))
        fresh = pos.until(lambda s: [x for x in s if x["hdr"]["timeStamp"] > frozen])
        assert fresh
        last_agent = agent.until(lambda s: s if "rapid_position_sample" not in json.dumps(s[-1]) else None)[-1]
        assert "rapid_position_sample" not in json.dumps(last_agent)

        messages = _texts(text.samples())
        assert sum(bool(SILENT.match(m)) for m in messages) == 1 and messages.count(BACK) == 1, messages

        res = cmd(desc, DOMAIN, "Admin", "shutdown")
        assert res.returncode == 0, res.stdout + res.stderr
        out, err = proc.communicate(timeout=60)
        assert proc.returncode == 0 and out.strip() == "bridge stopped", (out, err[-3000:])
        logged = [ln for ln in err.splitlines() if "rapid_position_sample source" in ln]
        assert len(logged) == 2 and SILENT.match(logged[0].split("] ", 1)[1]) and logged[1].endswith(BACK), err
    finally:
        for e in echoes:
            e.close()
        if proc.poll() is None:
            proc.kill()
            proc.communicate()
