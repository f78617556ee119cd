"""A config republished by the user's code through the Rust bridge (docs/rust-backend.md,
"Republishing a config"), real processes on loopback: K10's generated bridge (the folder's
shared build) with a main.rs whose user code, once the bridge runs, publishes the position
config with another frame through `rapid_dds::configs::get()`, twice with the same content,
under --simulate. A Cyclone reader (Python) sees the start's config, then the republished one
with a larger serial (once: the second publish writes nothing and returns the same serial),
and position samples carrying the start serial, then the new one; the journal records it.

Domain 85 is shared (tests/field/test_restart.py's C++ bridge, on Fast DDS): every Cyclone
process here carries a discovery tag of this run's own."""
from __future__ import annotations

import json
import os
import queue
import re
import shutil
import subprocess
import sys
import threading
import time
from pathlib import Path

from tests.rust.conftest import cargo

ROOT = Path(__file__).resolve().parents[2]
DOMAIN = 85
PKG = ROOT / "generated" / "k10" / "python"
LOCAL = PKG / "rapid_k10red" / "qos_files" / "cyclonedds" / "local.xml"
FRAME = "republished"

# the user's code: a thread beside the bridge (main.rs of a copy of the generated bridge)
USER_MAIN = """fn main() {
    std::thread::spawn(|| {
        let configs = loop {
            if let Some(c) = rapid_dds::configs::get() {
                break c;
            }
            std::thread::sleep(std::time::Duration::from_millis(50));
        };
        std::thread::sleep(std::time::Duration::from_secs(2));
        let mut c = asset::config_rapid_position_config();
        c.frame_name = "%s".into();
        let bytes = rapid_k10red::cdr::serialize(&c, rapid_k10red::cdr::Endianness::Little).unwrap();
        let first = configs.publish("rapid_position_config", &bytes).unwrap();
        let again = configs.publish("rapid_position_config", &bytes).unwrap();
        println!("republished {first} {again}");
    });
""" % FRAME

WATCH = """
import json, sys, time
sys.path.insert(0, %r)
from cyclonedds.domain import DomainParticipant
from cyclonedds.sub import DataReader, Subscriber
from cyclonedds.topic import Topic
from rapid_k10red import rapid
from rapid_k10red.qos import RapidQos
qos = RapidQos()
dp = DomainParticipant(%d)
sub = Subscriber(dp, qos=qos.subscriber("rapid_position_config"))
config = DataReader(sub, Topic(dp, "rapid_position_config", rapid.PositionConfig), qos=qos.reader("rapid_position_config"))
sample = DataReader(sub, Topic(dp, "rapid_position_sample", rapid.PositionSample), qos=qos.reader("rapid_position_sample"))
print(json.dumps({"ready": True}), flush=True)
while True:
    for c in config.take(N=8):
        print(json.dumps({"config": c.hdr.serial, "frame": c.frameName}), flush=True)
    for s in sample.take(N=8):
        print(json.dumps({"sample": s.hdr.serial}), flush=True)
    time.sleep(0.02)
""" % (str(PKG), DOMAIN)


def _republishing_bridge(bridges: dict, out: Path) -> Path:
    """K10's generated bridge with USER_MAIN, its own crate (outside the shared workspace,
    its path dependencies the shared build's: only the bridge compiles again)."""
    ws = Path(bridges["ws"])
    src = ws / "generated" / "k10" / "rust" / "bridge"
    shutil.copytree(src, out, ignore=shutil.ignore_patterns("target"))
    toml = (out / "Cargo.toml").read_text(encoding="utf-8")
    toml = toml.replace('"rapid_k10red_bridge"', '"rapid_k10red_republish"').replace(
        '"rapid_k10red_cmd"', '"rapid_k10red_republish_cmd"')
    # (normalised, not resolved: the shared build's paths, through the workspace's symlinks)
    toml = re.sub(r'path = "(\.\.[^"]*)"', lambda m: f'path = "{os.path.normpath(src / m.group(1))}"', toml)
    toml += "\n[workspace]\n"
    (out / "Cargo.toml").write_text(toml, encoding="utf-8")
    main = (out / "src" / "main.rs").read_text(encoding="utf-8")
    assert main.count("fn main() {\n") == 1
    (out / "src" / "main.rs").write_text(main.replace("fn main() {\n", USER_MAIN), encoding="utf-8")
    shutil.copy(ws / "Cargo.lock", out / "Cargo.lock")
    env = dict(os.environ, CARGO_TARGET_DIR=str(bridges["target"]), CARGO_TERM_COLOR="never")
    res = subprocess.run([cargo(), "build", "--offline", "--bin", "rapid_k10red_republish"], cwd=out, env=env,
                         capture_output=True, text=True, timeout=1200, stdin=subprocess.DEVNULL)
    assert res.returncode == 0, res.stderr[-4000:]
    return Path(bridges["target"]) / "debug" / "rapid_k10red_republish"


class Lines:
    """A process's stdout lines, read by a thread."""

    def __init__(self, proc: subprocess.Popen) -> None:
        self.q: queue.Queue = queue.Queue()
        self.proc = proc
        threading.Thread(target=self._pump, daemon=True).start()

    def _pump(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self.q.put(line.rstrip("\n"))

    def until(self, pred, timeout: float, what: str) -> list[str]:
        seen, end = [], time.monotonic() + timeout
        while time.monotonic() < end:
            try:
                line = self.q.get(timeout=0.2)
            except queue.Empty:
                continue
            seen.append(line)
            if pred(line):
                return seen
        raise AssertionError(f"no {what} within {timeout} s; saw {seen[-20:]}")


def test_a_republished_config_gets_a_larger_serial_and_its_telemetry_follows(bridges, tmp_path):
    binary = _republishing_bridge(bridges, tmp_path / "bridge")
    tag = f"rapidgen-rust-republish-{os.getpid()}"
    env = dict(os.environ, CYCLONEDDS_URI=f"file://{LOCAL},<CycloneDDS><Domain id=\"any\"><Discovery><Tag>{tag}</Tag>"
                                          f"</Discovery></Domain></CycloneDDS>", PYTHONPATH=str(ROOT))
    journal = tmp_path / "journal"
    watch = subprocess.Popen([sys.executable, "-c", WATCH], env=env, stdout=subprocess.PIPE, text=True)
    log = (tmp_path / "bridge.log").open("w")
    bridge = subprocess.Popen([str(binary), "--simulate", "--domain", str(DOMAIN), "--journal", str(journal)],
                              env=env, stdout=subprocess.PIPE, stderr=log, text=True)
    try:
        watched = Lines(watch)
        watched.until(lambda s: "ready" in s, 30, "watcher")
        said = Lines(bridge)
        line = said.until(lambda s: s.startswith("republished"), 60, "republication")[-1]
        first, again = map(int, line.split()[1:])
        assert first == again  # the same content again: the same serial, nothing written
        events = [json.loads(s) for s in watched.until(
            lambda s: '"sample"' in s and json.loads(s)["sample"] == first, 30, "a sample with the new serial")]
        configs = [(e["config"], e["frame"]) for e in events if "config" in e]
        start = configs[0][0]
        assert configs[0][1] != FRAME and start < first, configs
        assert configs[1:] == [(first, FRAME)], configs  # once: the second publish wrote nothing
        samples = [e["sample"] for e in events if "sample" in e]
        assert set(samples) == {start, first} and samples == sorted(samples), samples
        # in the journal (synced before the config went out): a restart comes back above it
        recorded = "".join(f.read_text(encoding="utf-8", errors="replace") for f in journal.iterdir())
        assert re.search(r'"k": ?"s", ?"serial": ?%d\b' % first, recorded), recorded[-2000:]
    finally:
        for p in (bridge, watch):
            p.terminate()
        for p in (bridge, watch):
            try:
                p.wait(timeout=15)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
        log.close()
    assert bridge.returncode == 0, (tmp_path / "bridge.log").read_text(encoding="utf-8")[-2000:]
