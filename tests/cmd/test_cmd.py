"""Live: `rapidgen cmd` against the K10 seed asset's simulated bridge on loopback (its own
DDS domain): a valid command (exit 0, COMPLETED OK), invalid ones refused before sending
(located errors, exit 1) or answered BAD_SYNTAX by the bridge (--no-check), a queued
command cancelled by DELETE, the live CommandConfig used over the descriptor; and the
bench's no-lost-ack logic on a small flood."""
from __future__ import annotations

import subprocess
import sys

import pytest

from tests.runtime.live import ROOT, SEEDS, BridgeProcess, env_for, python_dir

K10 = str(ROOT / "specs" / "assets" / "k10.yaml")
PYDIR, PACKAGE = python_dir("k10"), SEEDS["k10"]
DOMAIN = 160


def cmd(*args: str, domain: int = DOMAIN, source: str = "RapidWorkbench") -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "rapidgen", "cmd", K10, *args, "--domain", str(domain),
                           "--source", source, "--timeout", "20"], cwd=ROOT, env=env_for(PYDIR, PACKAGE),
                          capture_output=True, text=True, timeout=120)


@pytest.fixture(scope="module")
def bridge():
    b = BridgeProcess(PYDIR, PACKAGE, DOMAIN)
    try:
        b.wait_ready()
        res = cmd("AccessControl", "requestControl")
        assert res.returncode == 0 and "COMPLETED OK  control granted to RapidWorkbench" in res.stdout, res
        yield b
    finally:
        b.stop()


def test_a_valid_command_prints_its_acks_and_exits_0(bridge):
    res = cmd("PanCam", "pointCamera", "pan=0.5")  # tilt from its default
    assert res.returncode == 0, res.stderr
    lines = res.stdout.splitlines()
    assert lines[0].startswith("K10Red <- PanCam/pointCamera pan=0.5 tilt=0.0  [cmdId ")
    assert lines[1:] == ["  EXECUTING", "  COMPLETED OK  done (simulated)"]
    assert "no CommandConfig" not in res.stderr  # the live dictionary was read


def test_invalid_arguments_are_located_errors_and_nothing_is_sent(bridge):
    res = cmd("PanCam", "pointCamera", "pan=4", "tlit=0.2", "pan=1", "tilt=x")
    assert res.returncode == 1 and res.stdout == ""  # no "K10Red <-": nothing sent
    err = res.stderr
    assert "<command line>:1:" in err and "error[RG1905]: pan: 4 not in [-3.05, 3.05]" in err
    assert "error[RG1904]: pointCamera has no parameter 'tlit'" in err and "did you mean 'tilt'?" in err
    assert "error[RG1904]: 'pan' given twice" in err
    assert "error[RG1905]: tilt: 'x' is not a number" in err
    assert "rapidgen: 4 errors" in err
    # the caret under the bad value: column of "4" in the echoed command line
    line = next(x for x in err.splitlines() if x.startswith("  1 | "))
    caret = err.splitlines()[err.splitlines().index(line) + 1]
    assert line[caret.index("^")] == "4"


@pytest.mark.parametrize("words,code,text", [
    (["PanCm", "pointCamera"], "RG1902", "did you mean 'PanCam'?"),
    (["PanCam", "pointCamra"], "RG1903", "did you mean 'pointCamera'?"),
    (["Mobility", "simpleMove", "xyt=1,0,0"], "RG1906", "simpleMove needs frame (RAPID_STRING)"),
    (["Mobility", "simpleMove", "frame=site", "xyt=1,0"], "RG1905", "xyt: needs 3 numbers"),
    (["PanCam", "takePicture", "mode=infrared"], "RG1905", "'infrared' not one of left|right|stereo"),
    (["PanCam", "takePanorama", "panStart=0", "panEnd=1", "tilt=0", "tiles=2.5"], "RG1905", "'2.5' is not a 32-bit"),
    (["Admin", "noOp", "oops"], "RG1904", "'oops' is not key=value"),
    (["Admin", "noOp", "--action", "DELETE"], "RG1907", "--action DELETE needs --target CMDID"),
    (["Admin", "noOp", "--action", "APPEND", "--target", "x"], "RG1907", "--action APPEND takes no --target"),
    (["Admin", "noOp", "--action", "PUSH"], "RG1907", "unknown queue action 'PUSH'"),
])
def test_bad_commands_are_refused_before_sending(bridge, words, code, text):
    res = cmd(*words)
    assert res.returncode == 1 and res.stdout == "", res
    assert f"error[{code}]" in res.stderr and text in res.stderr, res.stderr


def test_no_check_sends_it_and_the_bridge_answers_bad_syntax(bridge):
    res = cmd("PanCam", "pointCamera", "pan=4", "--no-check")
    assert res.returncode == 1
    assert res.stdout.splitlines()[1:] == ["  COMPLETED BAD_SYNTAX  argument 1 (pan): 4 not in [-3.05, 3.05]"]


def test_a_queued_command_cancelled_by_delete(bridge):
    queued = cmd("Mobility", "simpleMove", "frame=site", "xyt=5000,0,0", "--action", "APPEND",
                 "--id", "test-long-drive", "--no-wait")
    assert queued.returncode == 0, queued.stderr
    assert "QUEUE_APPEND" in queued.stdout and queued.stdout.splitlines()[1] == "  QUEUED"
    delete = cmd("Admin", "noOp", "--action", "DELETE", "--target", "test-long-drive")
    assert delete.returncode == 0, delete.stderr
    out = delete.stdout.splitlines()
    assert out[1:3] == ["  EXECUTING", "  COMPLETED OK  test-long-drive cancel requested; handler has not stopped yet"]
    assert out[3] == "target test-long-drive:" and out[-1] == "  COMPLETED CANCELED  canceled"


def test_unauthorized_source_is_answered_and_exits_1_with_a_hint(bridge):
    res = cmd("PanCam", "pointCamera", source="MultiCenterCockpit")
    assert res.returncode == 1 and "COMPLETED BAD_SYNTAX  RAPID access violation" in res.stdout
    assert "AccessControl requestControl --source MultiCenterCockpit" in res.stderr


def test_no_asset_is_a_located_error_after_the_timeout():
    res = subprocess.run([sys.executable, "-m", "rapidgen", "cmd", K10, "Admin", "noOp", "--domain", "161",
                          "--timeout", "1", "--discover", "0.5"], cwd=ROOT, env=env_for(PYDIR, PACKAGE),
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 1 and res.stdout == ""
    assert "using the descriptor's dictionary" in res.stderr
    assert "error[RG1908]: no asset K10Red reads commands on domain 161" in res.stderr


def test_bench_small_flood_loses_no_ack():
    res = subprocess.run([sys.executable, "bench/command_latency.py", "--latency", "20", "--flood", "200",
                          "--ddsperf-seconds", "0", "--domain", "162"], cwd=ROOT, capture_output=True, text=True,
                         timeout=300)
    assert res.returncode == 0, res.stdout + res.stderr
    assert "200 COMPLETED acks received, 0 lost" in res.stdout
    assert "(20 of 20 sequential noOps)" in res.stdout
