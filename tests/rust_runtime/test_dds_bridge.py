"""Every seed's generated Rust bridge (`rapidgen generate <seed> --lang rust`: bridge/ beside
the types, on runtime/rust's rapid_runtime and rapid_dds, Cyclone DDS's C library through
cyclors) run with --simulate is judged by `rapidgen conform` over DDS on loopback (the
bridge's built-in `local` transport): every applicable check passes, telemetry included.

The six seeds are generated into one temporary Cargo workspace (runtime/ and the RAPID set's
crate linked into it, so the bridges' paths to runtime/rust resolve as in generated/) and
built by one `cargo build` (offline when it can) in the session's target folder, starting
from rapid_dds's Cargo.lock: cyclors and the runtime build once for all. A debug build, as cyclors
builds Cyclone DDS 0.11 from C sources (cmake, bindgen on libclang) and its Debug build type
costs about a quarter less CPU than Release (docs/rust-backend.md)."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml

from tests.runtime.live import SEEDS as LIVE_SEEDS
from tests.runtime.live import BridgeProcess, python_dir
from tests.rust_runtime.build import HOSTILE, SEEDS, descriptor as _descriptor

ROOT = Path(__file__).resolve().parents[2]
DOMAIN = 72


def _conform(bridges: dict[str, Path], seed: str, tmp_path: Path) -> dict[str, dict]:
    binary, ws = bridges[seed], bridges["ws"]
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}  # the bridge's own `local`
    bridge = BridgeProcess.of_command([str(binary), "--simulate", "--domain", str(DOMAIN)], ROOT, env)
    try:
        line = bridge.lines.get(timeout=30)
        assert line and "ready" in line, f"{line!r} {bridge.err[-20:]}"
        report = tmp_path / f"conform-{seed}.json"
        local = (ws if seed == HOSTILE else ROOT) / "generated" / seed / "qos" / "cyclonedds" / "local.xml"
        start = time.monotonic()
        res = subprocess.run([sys.executable, "-m", "rapidgen", "conform", str(_descriptor(ws, seed)),
                              "--domain", str(DOMAIN), "--json", str(report)],
                             cwd=ROOT, env=dict(os.environ, CYCLONEDDS_URI=f"file://{local}"), capture_output=True,
                             text=True, timeout=600)
        print(f"conform against the Rust bridge of {seed}: {time.monotonic() - start:.1f} s")
        assert report.exists(), res.stdout[-3000:] + res.stderr[-3000:]
        return {c["id"]: c for c in json.loads(report.read_text())["checks"]}
    finally:
        bridge.stop()


@pytest.mark.parametrize("seed", (*SEEDS, HOSTILE))
def test_conform_judges_the_generated_rust_bridge(bridges, seed, tmp_path):
    checks = _conform(bridges, seed, tmp_path)
    status = {cid: c["outcome"] for cid, c in checks.items()}
    print(f"{seed}: " + ", ".join(f"{cid} {st}" for cid, st in status.items()))
    assert len(status) >= 54 and status.get("TEL-01") == "PASS" and status.get("DDS-06") == "PASS", status
    failed = {cid: f"{st}: {checks[cid].get('message') or ''}"[:300] for cid, st in status.items()
              if st not in ("PASS", "UNSUPPORTED")}
    assert not failed, failed
    if seed in ("k10", HOSTILE):  # the seed with every kind of check: commands, queue, access control, images, extension
        assert all(status.get(f"TEL-0{i}") == "PASS" for i in range(1, 9)), status
        assert any(c.startswith("QUE-") and st == "PASS" for c, st in status.items()), status


# ---- K10's bridge beyond conform ---------------------------------------------------------------

def _run(binary: Path, *args: str) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}
    return subprocess.run([str(binary), *args], capture_output=True, text=True, timeout=60, env=env)


def test_bridge_options(bridges):
    res = _run(bridges["k10"], "--help")
    assert res.returncode == 0 and "--simulate" in res.stdout and "--transport local|lan|wan" in res.stdout
    res = _run(bridges["k10"], "--domian", "3")
    assert res.returncode == 2 and 'unknown argument "--domian"' in res.stderr and "usage:" in res.stderr
    res = _run(bridges["k10"], "--domain", "-1")
    assert res.returncode == 2 and "not a domain id" in res.stderr
    res = _run(bridges["k10"], "--transport", "nosuch")
    assert res.returncode == 2 and "one of local, lan, wan" in res.stderr
    res = _run(bridges["k10"], "--command-window", "0")
    assert res.returncode == 2 and "at least 1" in res.stderr


def _cmd(*args: str) -> subprocess.CompletedProcess:
    local = ROOT / "generated" / "k10" / "qos" / "cyclonedds" / "local.xml"
    return subprocess.run([sys.executable, "-m", "rapidgen", "cmd", str(ROOT / "specs" / "assets" / "k10.yaml"),
                           *args, "--domain", str(DOMAIN), "--source", "RapidWorkbench", "--timeout", "20"],
                          cwd=ROOT, env=dict(os.environ, CYCLONEDDS_URI=f"file://{local}"), capture_output=True,
                          text=True, timeout=120)


def test_generated_bridge_without_simulate_runs_the_stub_handlers(bridges):
    """Without --simulate the bridge runs handlers.rs as generated (its arguments unpacked by
    dispatch.rs): the runtime answers its own commands, every other one COMPLETED/EXEC_FAILED
    "not implemented"; Admin/shutdown stops it cleanly."""
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}
    bridge = BridgeProcess.of_command([str(bridges["k10"]), "--domain", str(DOMAIN)], ROOT, env)
    try:
        line = bridge.lines.get(timeout=30)
        assert line and line.strip() == f"K10Red ready on domain {DOMAIN}", f"{line!r} {bridge.err[-20:]}"
        res = _cmd("AccessControl", "requestControl")
        assert res.returncode == 0 and "COMPLETED OK  control granted to RapidWorkbench" in res.stdout, res
        res = _cmd("PanCam", "pointCamera", "pan=0.5")
        assert res.returncode == 1 and res.stdout.splitlines()[1:] == [
            "  EXECUTING", "  COMPLETED EXEC_FAILED  not implemented"], res.stdout + res.stderr
        res = _cmd("Admin", "echo", "text=hello")
        assert res.returncode == 0 and "COMPLETED OK  hello" in res.stdout, res.stdout + res.stderr
        res = _cmd("Admin", "shutdown")
        assert res.returncode == 0, res.stdout + res.stderr
        line = bridge.lines.get(timeout=30)
        assert line and line.strip() == "bridge stopped", f"{line!r} {bridge.err[-20:]}"
    finally:
        bridge.stop()


def test_a_late_joiner_gets_every_commands_final_ack(bridges):
    """Acks are one instance per command (keyed.rs: the blob type given Ack's key), the last 8
    of each kept: a reader joining after 100 commands gets the final ack of each. With one
    instance for all (cyclors' blob type as it is) it got those of the last 64 only."""
    n = 100
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}
    bridge = BridgeProcess.of_command([str(bridges["k10"]), "--simulate", "--domain", str(DOMAIN)], ROOT, env)
    pydir = ROOT / "generated" / "k10" / "python"
    local = ROOT / "generated" / "k10" / "qos" / "cyclonedds" / "local.xml"
    try:
        line = bridge.lines.get(timeout=30)
        assert line and "ready" in line, f"{line!r} {bridge.err[-20:]}"
        res = subprocess.run([sys.executable, "-m", "tests.rust_runtime.ground", "late-acks", str(pydir), "rapid_k10red",
                              str(DOMAIN), str(n)], cwd=ROOT, capture_output=True, text=True, timeout=240,
                             env=dict(os.environ, CYCLONEDDS_URI=f"file://{local}",
                                      PYTHONPATH=f"{pydir}{os.pathsep}{ROOT}"))
        assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-4000:]
        got = json.loads(res.stdout.splitlines()[-1])
    finally:
        bridge.stop()
    last = got["last"]
    assert len(last) == n
    missing = [cid for cid, ack in last.items() if not (ack or "").startswith("ACK_COMPLETED ")]
    assert not missing, f"{len(missing)} of {n} commands' final acks not seen by the late joiner: {missing[:3]}"


def test_a_restart_answers_from_the_journal(bridges, tmp_path):
    """The restart journal (docs/runtime.md, "Restarts"), in the Rust bridge: killed (SIGKILL)
    with a drive running and a noOp queued behind it, started again on the same journal, it
    answers both as the other runtimes do, a repeat of a command finished before the kill
    gets its final ack again without running, the configs come back with a larger serial,
    and SIGTERM stops it cleanly (exit 0, the journal closed)."""
    pydir = ROOT / "generated" / "k10" / "python"
    local = ROOT / "generated" / "k10" / "qos" / "cyclonedds" / "local.xml"
    argv = [str(bridges["k10"]), "--simulate", "--domain", str(DOMAIN), "--journal", str(tmp_path / "journal")]
    res = subprocess.run([sys.executable, "-m", "tests.rust_runtime.ground", "restart", str(pydir), "rapid_k10red",
                          str(DOMAIN), json.dumps(argv)], cwd=ROOT, capture_output=True, text=True, timeout=240,
                         env=dict(os.environ, CYCLONEDDS_URI=f"file://{local}", PYTHONPATH=f"{pydir}{os.pathsep}{ROOT}"))
    assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-4000:]
    got = json.loads(res.stdout.splitlines()[-1])
    assert got["at_kill"]["drive"][-1][0] == "ACK_EXECUTING" and got["at_kill"]["behind"][-1][0] == "ACK_QUEUED", got
    assert got["after"]["drive"][-1] == ["ACK_COMPLETED", "ACK_COMPLETED_EXEC_FAILED",
                                         "asset restarted while it ran; outcome unknown"], got["after"]
    assert got["after"]["behind"][-1] == ["ACK_COMPLETED", "ACK_COMPLETED_CANCELED",
                                          "asset restarted before it ran"], got["after"]
    before, repeat = got["before_repeat"], got["repeat"]
    assert [a[0] for a in repeat[len(before):]] == ["ACK_COMPLETED"] and repeat[-1][1] == "ACK_COMPLETED_OK", repeat
    assert sum(a[0] == "ACK_EXECUTING" for a in repeat) == 1, repeat  # ran once, before the kill
    first, second = got["serials"]
    assert first is not None and second is not None and second > first, got["serials"]
    assert got["stop_code"] == 0, got["log"]
    journal = next((tmp_path / "journal").glob("*.journal"))
    assert '"k":"stop"' in journal.read_text().splitlines()[-1], journal.read_text()[-500:]


def test_seven_robots_on_one_domain_three_of_them_rust_are_seen_by_spy(bridges):
    """Seven robots on one domain (issue 38): four Python bridges (ATHLETE, Chariot, EVA suit,
    Robonaut2) and three Rust ones (K10, X-Arm-2 and K10 with hostile names in its own
    partition), all simulated; `rapidgen spy` with their descriptors sees every asset, each
    with its configs, and no finding."""
    python = ("athlete", "chariot", "eva-suit", "robonaut2")
    rust = ("k10", "xarm2", HOSTILE)
    ws = bridges["ws"]
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}  # the Rust bridges' own `local`
    running: list[BridgeProcess] = []
    try:
        for seed in python:
            running.append(BridgeProcess(python_dir(seed), LIVE_SEEDS[seed], DOMAIN))
        for seed in rust:
            running.append(BridgeProcess.of_command([str(bridges[seed]), "--simulate", "--domain", str(DOMAIN)], ROOT, env))
        for bridge in running:
            line = bridge.lines.get(timeout=30)
            assert line and "ready" in line, f"{line!r} {bridge.err[-20:]}"
        local = ROOT / "generated" / "k10" / "qos" / "cyclonedds" / "local.xml"
        assets = [a for seed in (*python, *rust) for a in ("--asset", str(_descriptor(ws, seed)))]
        res = subprocess.run([sys.executable, "-m", "rapidgen", "spy", "--once", "--json", "--domain", str(DOMAIN),
                              "--seconds", "5", *assets], cwd=ROOT, capture_output=True, text=True, timeout=120,
                             env=dict(os.environ, CYCLONEDDS_URI=f"file://{local}"))
        assert res.returncode == 0, res.stderr[-3000:]
        snap = json.loads(res.stdout)
    finally:
        for bridge in running:
            bridge.stop()
    assert snap["findings"] == [], snap["findings"]
    seen = {a["name"]: a for a in snap["assets"]}
    want = {"ATHLETE", "Chariot", "EvaSuitA", "Robonaut2", "K10Red", "XArm2", "Hostile_1"}
    assert want <= set(seen), sorted(seen)
    for name in want:
        roles = {t["role"] for t in seen[name]["topics"]}
        assert "config" in roles, (name, roles)


def test_regeneration_leaves_handlers_rs_byte_identical(tmp_path):
    """handlers.rs is the user's: written once, never touched by regeneration, also when the
    descriptor changes (dispatch.rs changes with it); deleting it brings fresh stubs."""
    k10 = ROOT / "specs" / "assets" / "k10.yaml"

    def generate(descriptor: Path) -> None:
        res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(descriptor), "--lang", "rust", "-o",
                              str(tmp_path / "out")], cwd=ROOT, capture_output=True, text=True, timeout=120)
        assert res.returncode == 0, res.stderr

    generate(k10)
    handlers = tmp_path / "out" / "rust" / "bridge" / "src" / "handlers.rs"
    stub = handlers.read_bytes()
    assert stub.count(b"Outcome::NotImplemented") == 9  # every command the runtime does not answer
    assert b"do not edit" not in stub
    generate(k10)
    assert handlers.read_bytes() == stub
    mine = stub.replace(b"Outcome::NotImplemented", b'Outcome::Ok("mine".into())', 1) + b"// my notes\n"
    handlers.write_bytes(mine)
    changed = yaml.safe_load(k10.read_text(encoding="utf-8"))
    changed["idl"] = {k: str((k10.parent / v).resolve()) if isinstance(v, str) else [str((k10.parent / x).resolve())
                      for x in v] for k, v in changed["idl"].items()}
    changed["subsystem_types"][0]["commands"].append({"name": "wipeLens", "description": "clean the optics"})
    (tmp_path / "k10b.yaml").write_text(yaml.safe_dump(changed), encoding="utf-8")
    dispatch = tmp_path / "out" / "rust" / "bridge" / "src" / "dispatch.rs"
    before = dispatch.read_text(encoding="utf-8")
    generate(tmp_path / "k10b.yaml")
    assert handlers.read_bytes() == mine
    assert "fn wipe_lens(&self, ctx: &Context) -> Outcome;" in dispatch.read_text(encoding="utf-8")
    assert "wipe_lens" not in before
    handlers.unlink()
    generate(tmp_path / "k10b.yaml")
    assert b"fn wipe_lens(" in handlers.read_bytes()


def test_old_ack_writer_generations_are_deleted(bridges):
    """Commands are dealt to ack writer generations of max(256, window / 4) commands; a
    generation no longer current goes once its commands are retired (Cyclone keeps memory
    for every instance a writer wrote, until the writer goes). With a command window of 16,
    after 700 commands four writers were made (three generations and the next, made early)
    and two live: the current one and the next."""
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}
    bridge = BridgeProcess.of_command([str(bridges["k10"]), "--simulate", "--domain", str(DOMAIN),
                                       "--command-window", "16"], ROOT, env)
    pydir = ROOT / "generated" / "k10" / "python"
    local = ROOT / "generated" / "k10" / "qos" / "cyclonedds" / "local.xml"
    try:
        line = bridge.lines.get(timeout=30)
        assert line and "ready" in line, f"{line!r} {bridge.err[-20:]}"
        res = subprocess.run([sys.executable, "-m", "tests.rust_runtime.ground", "ack-writers", str(pydir),
                              "rapid_k10red", str(DOMAIN), "700"], cwd=ROOT, capture_output=True, text=True,
                             timeout=240, env=dict(os.environ, CYCLONEDDS_URI=f"file://{local}",
                                                   PYTHONPATH=f"{pydir}{os.pathsep}{ROOT}"))
        assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-4000:]
        got = json.loads(res.stdout.splitlines()[-1])
    finally:
        bridge.stop()
    assert got == {"answered": 700, "ack_writers": 2}, got


@pytest.mark.parametrize("seed, package, topic, want", [
    ("k10", "rapid_k10red", "rapid_imagesensor_sample-hazCam", ["image/png", [640, 480], [640, 480, 1]]),
    ("chariot", "rapid_chariot", "rapid_imagesensor_sample", ["image/jpeg", [1024, 768], [1024, 768, 1]]),
])
def test_simulated_pictures_decode_whole(bridges, seed, package, topic, want):
    """A simulated camera's picture (rapid_dds images.rs: PNG with stored deflate, DC-only
    baseline JPEG) is of the declared MIME type and size and decodes to its last block
    (the Python runtime's test decoders)."""
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}
    bridge = BridgeProcess.of_command([str(bridges[seed]), "--simulate", "--domain", str(DOMAIN)], ROOT, env)
    pydir = ROOT / "generated" / seed / "python"
    local = ROOT / "generated" / seed / "qos" / "cyclonedds" / "local.xml"
    try:
        line = bridge.lines.get(timeout=30)
        assert line and "ready" in line, f"{line!r} {bridge.err[-20:]}"
        res = subprocess.run([sys.executable, "-m", "tests.rust_runtime.ground", "picture", str(pydir), package,
                              str(DOMAIN), topic], cwd=ROOT, capture_output=True, text=True, timeout=120,
                             env=dict(os.environ, CYCLONEDDS_URI=f"file://{local}",
                                      PYTHONPATH=f"{pydir}{os.pathsep}{ROOT}"))
        assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-4000:]
        got = json.loads(res.stdout.splitlines()[-1])
    finally:
        bridge.stop()
    assert [got.get("mime"), got.get("meta"), got.get("picture")] == want, got


def test_hostile_descriptor_names_are_valid_rust(bridges):
    """The hostile descriptor's bridge (it compiled without a warning and passes conform
    above): every name a usable, distinct Rust name."""
    dispatch = (bridges["ws"] / "generated" / HOSTILE / "rust" / "bridge" / "src" / "dispatch.rs").read_text(
        encoding="utf-8")
    assert "fn delete(&self, ctx: &Context, ctx_: &str, this: f32, my_arg: i32, my_arg_: i64, arg_9lives: [f64; 3], " \
           "ber: [f32; 9], assert: bool) -> Outcome;" in dispatch
    assert "fn class_handler(&self, ctx: &Context) -> Outcome;" in dispatch
    assert "fn class_handler_(&self, ctx: &Context) -> Outcome;" in dispatch  # distinct names
    assert "pub trait ClassHandler: Send + Sync {" in dispatch and "pub trait ClassHandlerHandler: Send + Sync {" in dispatch
    assert "fn do_it(&self, ctx: &Context, std: &str, rapid_runtime: f64) -> Outcome;" in dispatch
    assert '("class", "do-it") => self.class.do_it(ctx, arg!(ctx, 0, String), arg!(ctx, 1, Double)),' in dispatch


def test_a_simulated_drive_moves_the_reported_position(bridges):
    """--simulate: Mobility/simpleMove drives the body (bridge::Simulated, 0.5 m/s) and the
    position samples report it: the pose's xyz and the odometer value key."""
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}
    bridge = BridgeProcess.of_command([str(bridges["k10"]), "--simulate", "--domain", str(DOMAIN)], ROOT, env)
    pydir = ROOT / "generated" / "k10" / "python"
    local = ROOT / "generated" / "k10" / "qos" / "cyclonedds" / "local.xml"
    try:
        line = bridge.lines.get(timeout=30)
        assert line and "ready" in line, f"{line!r} {bridge.err[-20:]}"
        res = _cmd("AccessControl", "requestControl")
        assert res.returncode == 0, res.stdout + res.stderr
        res = _cmd("Mobility", "simpleMove", "frame=site", "xyt=1,0,0")
        assert res.returncode == 0 and "COMPLETED OK  arrived at 1.00, 0.00" in res.stdout, res.stdout + res.stderr
        res = subprocess.run([sys.executable, "-m", "tests.rust_runtime.ground", "position", str(pydir), "rapid_k10red",
                              str(DOMAIN)], cwd=ROOT, capture_output=True, text=True, timeout=120,
                             env=dict(os.environ, CYCLONEDDS_URI=f"file://{local}",
                                      PYTHONPATH=f"{pydir}{os.pathsep}{ROOT}"))
        assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-4000:]
        got = json.loads(res.stdout.splitlines()[-1])
    finally:
        bridge.stop()
    assert got["xyz"] == [1.0, 0.0, 0.0] and got["values"]["odometer"] == 1.0 and got["values"]["speed"] == 0.0, got


def test_the_intake_survives_fuzzed_and_undecodable_commands(bridges):
    """A rogue on the partition writes 2000 mutated Commands (tests/hostile/rogue.py, seeded:
    Cyclone's own writer keys and sends several hundred of them), then 20 whose cmdId is
    invalid UTF-8: the bridge does not panic, drops what the codec refuses and logs that once
    per writer, and still answers a valid command."""
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}
    bridge = BridgeProcess.of_command([str(bridges["k10"]), "--simulate", "--domain", str(DOMAIN)], ROOT, env)
    pydir = ROOT / "generated" / "k10" / "python"
    local = ROOT / "generated" / "k10" / "qos" / "cyclonedds" / "local.xml"
    rogue_env = dict(os.environ, CYCLONEDDS_URI=f"file://{local}", PYTHONPATH=f"{pydir}{os.pathsep}{ROOT}")
    try:
        line = bridge.lines.get(timeout=30)
        assert line and "ready" in line, f"{line!r} {bridge.err[-20:]}"
        for mode, n in (("fuzz", "2000"), ("bad-command", "20")):
            res = subprocess.run([sys.executable, "-m", "tests.hostile.rogue", mode, str(pydir), "rapid_k10red",
                                  str(DOMAIN), "5", n], cwd=ROOT, capture_output=True, text=True, timeout=240,
                                 env=rogue_env)
            assert res.returncode == 0 and f"rogue done {n}" in res.stdout, res.stdout[-2000:] + res.stderr[-2000:]
        assert _cmd("AccessControl", "requestControl").returncode == 0
        res = _cmd("Admin", "echo", "text=alive")
        assert res.returncode == 0 and "COMPLETED OK  alive" in res.stdout, res.stdout + res.stderr
    finally:
        bridge.stop()
    err = "\n".join(bridge.err)
    assert "panicked" not in err, err[-3000:]
    dropped = [e for e in bridge.err if "dropped an undecodable Command" in e]
    assert len(dropped) == 2, dropped  # once for each of the two rogue writers, not once a sample
