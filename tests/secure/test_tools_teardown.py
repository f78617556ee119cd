"""The live tools delete their participant before they return, refused or not, so no DDS
thread outlives the interpreter (runtime/rapid_runtime/teardown.py: a secured conform's
threads, left to the garbage collector, once crashed the process at exit with SIGSEGV).

Each runs in its own process (a private network namespace, the suite's DOMAIN):
refused_exit.py runs a tool as the command line does, closed_threads.py closes each tool's
DDS holder while a reference to it remains (as a cycle keeps one), and both say which of the
process's threads are left."""
from __future__ import annotations

import json
import subprocess
import sys

from tests.secure.conftest import DOMAIN, ROOT, exited

K10 = str(ROOT / "specs" / "assets" / "k10.yaml")


def run_tool(tool: str, keystores, enclave: str) -> tuple[subprocess.CompletedProcess, dict]:
    """(the process, {"code", "threads"}: its last line of output)."""
    res = subprocess.run(["unshare", "-n", sys.executable, "-m", "tests.secure.refused_exit", tool,
                          str(keystores["main"] / "enclaves" / enclave), str(DOMAIN), K10],
                         capture_output=True, text=True, cwd=ROOT, timeout=120)
    lines = res.stdout.strip().splitlines()
    assert lines, res
    return res, json.loads(lines[-1])


def test_cmd_refused_by_dds_security_says_so_and_exits_1_with_no_dds_thread_left(keystores):
    """Outsider: watch only, so DDS Security refuses the command topic. Once an internal error
    (exit 3, 'please report this')."""
    res, left = run_tool("cmd", keystores, "Outsider")
    exited(res.returncode, 1, res)
    assert "rapidgen cmd: DDS Security refused what the command needs with the enclave" in res.stderr, res
    assert "docs/secure.md" in res.stderr and "NOT_ALLOWED_BY_SECURITY" in res.stderr, res
    assert "internal error" not in res.stderr and "Traceback" not in res.stderr, res
    assert left == {"code": 1, "threads": []}, f"DDS threads outlived the command: {left}"


def test_cmd_finding_no_asset_returns_with_no_dds_thread_left(keystores):
    """Granted, but no asset runs: its ack reader's thread and its participant are gone."""
    res, left = run_tool("cmd", keystores, "RapidWorkbench")
    exited(res.returncode, 1, res)
    assert "no asset K10Red reads commands" in res.stderr, res
    assert left == {"code": 1, "threads": []}, f"DDS threads outlived the command: {left}"


def test_spy_reading_a_peer_returns_with_no_dds_thread_left(keystores):
    res, left = run_tool("spy", keystores, "RapidWorkbench")
    exited(res.returncode, 0, res)
    snapshot = json.loads(res.stdout[:res.stdout.rstrip().rfind("\n")])
    topics = {t["topic"]: t for a in snapshot["assets"] if a["partition"] == "K10Red" for t in a["topics"]}
    assert topics.get("rapid_command", {}).get("writers"), snapshot  # the peer seen: readers were opened
    assert left == {"code": 0, "threads": []}, f"DDS threads outlived the spy: {left}"


def test_spy_echo_returns_with_no_dds_thread_left(keystores):
    res, left = run_tool("spy-echo", keystores, "RapidWorkbench")
    exited(res.returncode, 0, res)
    assert left == {"code": 0, "threads": []}, f"DDS threads outlived the spy: {left}"


def test_each_tool_s_close_deletes_its_participant_even_while_referred_to(keystores):
    res = subprocess.run(["unshare", "-n", sys.executable, "-m", "tests.secure.closed_threads",
                          str(keystores["main"] / "enclaves" / "RapidWorkbench"), str(DOMAIN), K10],
                         capture_output=True, text=True, cwd=ROOT, timeout=120)
    exited(res.returncode, 0, res)
    left = json.loads(res.stdout)
    assert set(left) == {"spy Watcher", "record Recorder", "replay Replayer", "cmd Commander"}, left
    assert all(threads == [] for threads in left.values()), f"DDS threads left after close(): {left}"
