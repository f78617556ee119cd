"""Interop on loopback, real processes, every way the Rust ground side meets the others: the
generated `rapid_k10red_cmd` (rapid_dds::cmd on rapid_dds::client, Cyclone through cyclors)
drives K10's Python bridge and K10's generated C++ bridge (Fast DDS), and `rapidgen cmd`
(Python, cyclonedds) and the C++ client (rapid_cmd, Fast DDS) drive K10's generated Rust
bridge, through the C++ client tests' scenario (tests/cpp_client/drive.py: valid, invalid,
queued with APPEND/INSERT/REPLACE/DELETE, cancelled). Every command gets the same exit status and ack lines every way, the ones the
protocol asks for (tests/cpp_client/test_interop.py's EXPECTED). The three bridges run at
once, on domains 1, 2 (the Rust one, driven by Python, then by C++) and 4; the refusals
without an asset on domain 6.

The Rust programs are the run's build (conftest.py's `bridges`: `<crate>_cmd` is built
beside each `<crate>_bridge`), the C++ bridge and client the C++ tests' seeds build
(tests/cpp_runtime/build.py seed_bridges and client_programs, once per session:
RAPIDGEN_CPP_SEEDS=k10 limits it to K10)."""
from __future__ import annotations

import os
import subprocess
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from tests.cpp_client.drive import Driver, assert_refuses_bad_input, scenario
from tests.cpp_client.test_interop import EXPECTED, _settled
from tests.cpp_runtime import build as B
from tests.runtime.live import ROOT, SEEDS, BridgeProcess, python_dir
from tests.rust.conftest import cargo
from tests.rust_runtime.build import libclang

pytest.importorskip("cyclonedds")

PY_BRIDGE_DOMAIN, RUST_BRIDGE_DOMAIN, CPP_BRIDGE_DOMAIN, NO_ASSET_DOMAIN = 1, 2, 4, 6


def _cmd_program(bridges: dict[str, Path]) -> Path:
    return bridges["k10"].parent / "rapid_k10red_cmd"


def _own_transport() -> dict[str, str]:
    """The environment without CYCLONEDDS_URI: the Rust program's built-in `local` (loopback)."""
    return {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}


def _rust_drives_python_bridge(cmd: Path) -> dict:
    bridge = BridgeProcess(python_dir("k10"), SEEDS["k10"], PY_BRIDGE_DOMAIN, "--sim-speed", "1")  # (as the C++ one)
    try:
        bridge.wait_ready()
        return scenario(Driver("rust", PY_BRIDGE_DOMAIN, cmd))
    finally:
        bridge.stop()


def _drives_rust_bridge(binary: Path, driver: Driver) -> dict:
    """A fresh bridge each time: the scenario's cmdIds repeat, a bridge answers a repeated one
    from its history."""
    bridge = BridgeProcess.of_command([str(binary), "--simulate", "--domain", str(RUST_BRIDGE_DOMAIN)], ROOT,
                                      _own_transport())
    try:
        line = bridge.lines.get(timeout=30)
        assert line and "ready" in line, f"{line!r} {bridge.err[-20:]}"
        return scenario(driver)
    finally:
        bridge.stop()


def _python_then_cpp_drive_rust_bridge(binary: Path, cpp_cmd: Path) -> tuple[dict, dict]:
    return (_drives_rust_bridge(binary, Driver("python", RUST_BRIDGE_DOMAIN)),
            _drives_rust_bridge(binary, Driver("cpp", RUST_BRIDGE_DOMAIN, cpp_cmd)))


def _rust_drives_cpp_bridge(bridge_binary: Path, cmd: Path) -> dict:
    proc = subprocess.Popen([str(bridge_binary), "--simulate", "--domain", str(CPP_BRIDGE_DOMAIN), "--seconds", "240"],
                            env=B.dds_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().startswith("bridge ready: asset K10Red")
        return scenario(Driver("rust", CPP_BRIDGE_DOMAIN, cmd))
    except AssertionError as e:  # with the bridge's log (the commands it refused, from whom)
        proc.terminate()
        raise AssertionError(f"{e}\nthe C++ bridge's log: {proc.communicate(timeout=30)[1][-3000:]}") from e
    finally:
        if proc.poll() is None:
            proc.terminate()
            proc.communicate(timeout=30)


def test_same_acks_every_way(bridges, tmp_path_factory):
    cpp_bridge = B.seed_bridges(tmp_path_factory)["k10"]
    cpp_cmd = B.client_programs(tmp_path_factory)["cmd"]
    cmd = _cmd_program(bridges)
    with ThreadPoolExecutor(3) as pool:
        to_python = pool.submit(_rust_drives_python_bridge, cmd)
        to_rust = pool.submit(_python_then_cpp_drive_rust_bridge, bridges["k10"], cpp_cmd)
        to_cpp = pool.submit(_rust_drives_cpp_bridge, cpp_bridge, cmd)
        by_python, by_cpp = to_rust.result()
        runs = {"Rust cmd -> Python bridge": to_python.result(), "rapidgen cmd -> Rust bridge": by_python,
                "C++ rapid_cmd -> Rust bridge": by_cpp, "Rust cmd -> C++ bridge": to_cpp.result()}
    got = {way: _settled(acks) for way, acks in runs.items()}
    for way, acks in got.items():
        print(f"{way}: " + "; ".join(f"{k} -> {code} {lines}" for k, (code, lines) in acks.items()))
    wrong = {way: {k: v for k, v in acks.items() if EXPECTED.get(k) != v} for way, acks in got.items()}
    assert all(acks == EXPECTED for acks in got.values()), wrong


def test_cmd_program_refuses_bad_input_with_a_clear_error(bridges):
    """Checked before anything is sent (no asset needed: the built-in tables are the
    dictionary); exit 2 for usage, 1 for a command the dictionary refuses; every name from
    the command line escaped. The C++ rapid_cmd's words (tests/cpp_client/test_interop.py)."""
    def run(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run([str(_cmd_program(bridges)), *args, "--domain", str(NO_ASSET_DOMAIN), "--discover",
                               "0.1", "--timeout", "0.5"], capture_output=True, text=True, timeout=60,
                              env=_own_transport())
    assert_refuses_bad_input(run, NO_ASSET_DOMAIN)
    # its own: it says when it falls back on the built-in tables, and names what it has
    res = run("Nowhere", "echo")
    assert "no CommandConfig from K10Red within 0.1 s (domain 6); using the built-in tables" in res.stderr
    res = run("PanCam", "wipeLens")
    assert res.returncode == 1 and "subsystem PanCam has no command 'wipeLens' (known: " in res.stderr
    res = run("Admin", "echo", "text=hi")
    assert "partition 'K10Red'" in res.stderr and "COMPLETED" not in res.stdout


def test_the_client_and_cmd_unit_tests(bridges):
    """rapid_dds's own tests (`cargo test --lib`, in the bridges' target folder: cyclors as
    their build left it): the live dictionary merged with the tables, ack lines, the command
    line, the percentiles of --repeat."""
    env = dict(os.environ, CARGO_TARGET_DIR=str(bridges["target"]), CARGO_TERM_COLOR="never", LIBCLANG_PATH=libclang() or "")
    res = subprocess.run([cargo(), "test", "--offline", "--lib"], cwd=ROOT / "runtime" / "rust" / "rapid_dds", env=env,
                         capture_output=True, text=True, timeout=1800, stdin=subprocess.DEVNULL)
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr[-3000:]
    for name in ("client::tests::the_live_dictionary_keeps_the_tables_limits_where_name_and_type_agree",
                 "client::tests::acks_print_as_the_other_clients_print_them",
                 "cmd::tests::the_command_line_reads_as_rapid_cmds"):
        assert f"test {name} ... ok" in res.stdout, res.stdout[-3000:]


def test_cmd_program_says_when_two_bridges_answer(bridges):
    """Every RAPID runtime answers a command through one ack writer: acks of one cmdId from
    two writers mean something else answers as the asset (here a second K10 bridge on the
    domain; a stranger in the field). The program shows every ack and says so, as `rapidgen
    cmd` does."""
    def run(*words: str) -> subprocess.CompletedProcess:
        return subprocess.run([str(_cmd_program(bridges)), "--domain", str(NO_ASSET_DOMAIN), "--source",
                               "RapidWorkbench", "--timeout", "20", *words], capture_output=True, text=True,
                              timeout=60, env=_own_transport())
    started = [BridgeProcess.of_command([str(bridges["k10"]), "--simulate", "--domain", str(NO_ASSET_DOMAIN)], ROOT,
                                        _own_transport()) for _ in range(2)]
    try:
        for bridge in started:
            line = bridge.lines.get(timeout=30)
            assert line and "ready" in line, f"{line!r} {bridge.err[-20:]}"
        # Commands are volatile: a bridge that matches a run's writer only after its command
        # went out never sees it (one run in CI: the second bridge missed requestControl and
        # refused the drive). Each run is a new participant, so a run that reached one bridge
        # only is tried again, at most three times.
        for _ in range(3):
            assert run("AccessControl", "requestControl").returncode == 0
            # a drive of 1 s (0.5 m at 0.5 m/s): both bridges' EXECUTING are in before the
            # first COMPLETED ends the wait
            res = run("Mobility", "simpleMove", "frame=site", "xyt=0.5,0,0")
            if res.returncode == 0 and res.stdout.count("  EXECUTING") == 2:
                break
    finally:
        for bridge in started:
            bridge.stop()
    assert res.returncode == 0, res.stdout + res.stderr
    assert "acks of 1-RapidWorkbench-" in res.stderr and "came from 2 writers" in res.stderr, res.stderr
    assert res.stdout.count("  EXECUTING") == 2 and "COMPLETED OK  arrived at 0.50, 0.00" in res.stdout, res.stdout
