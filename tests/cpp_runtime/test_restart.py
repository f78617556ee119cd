"""The C++ bridge's restart journal, live (issues 21 and 23; docs/runtime.md "Restarts: the
journal"): what tests/field/test_restart.py shows for the Python bridge, shown for the C++ one.

The Restarter test asset (tests/field/restart_asset.py) generated for C++, its user-owned
handlers replaced by tests/cpp_runtime/restarter/handlers.cpp (Worker/work appends each cmdId
it runs to a file), built against the session's runtime (one unity build, -O0: about a minute).
The ground is tests/field/restart_ground.py's, unchanged (Python, Cyclone DDS), run by
tests/cpp_runtime/restart_ground.py: a stream of 60 commands (queued, beside the queue, noOp;
200 with RAPIDGEN_FIELD_FULL=1) while the bridge is killed with SIGKILL at 5 random moments
(20 with RAPIDGEN_FIELD_FULL=1) and started again on the same journal; before the second
restart a torn record and a garbage line are appended to the journal. Every command gets a
final ack, at the sender and at a late-joining ground tool, the same; none ran twice;
"before it ran" ones never ran; the damage is reported once and set aside; no crash.
Cross-runtime: a journal left by a killed C++ bridge is answered from by the Python bridge,
and the other way round. Domains 66, 67 and 68.
"""
from __future__ import annotations

import json
import os
import random
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from tests.cpp_runtime import build as B
from tests.field.restart_asset import DESCRIPTOR, RESTARTED, ROOT, check_kill_run, generate

KILL_DOMAIN, CROSS_DOMAIN = 66, 67  # (cross: 67 and 68)
FULL = os.environ.get("RAPIDGEN_FIELD_FULL") == "1"
KILLS = 20 if FULL else 5
COMMANDS = 200 if FULL else 60
HANDLERS = Path(__file__).parent / "restarter" / "handlers.cpp"


@pytest.fixture(scope="module")
def restarter(tmp_path_factory) -> tuple[Path, Path]:
    """(the C++ Restarter bridge, the Python Restarter package's folder for the ground)."""
    runtime = B.runtime_dir(tmp_path_factory)
    base = tmp_path_factory.mktemp("restarter")
    desc = base / "restarter.yaml"
    desc.write_text(DESCRIPTOR.format(rapid=ROOT / "specs" / "rapid"))
    B.run([sys.executable, "-m", "rapidgen", "generate", str(desc), "--lang", "cpp", "-o", str(base / "out")])
    cpp = base / "out" / "cpp"
    shutil.copyfile(HANDLERS, cpp / "bridge" / "handlers.cpp")  # the user's file: regeneration keeps it
    B.configure(cpp, base / "build", f"-Drapid_runtime_cpp_DIR={runtime}", "-DCMAKE_CXX_FLAGS_RELEASE=-O0",
                "-DCMAKE_UNITY_BUILD=ON", "-DCMAKE_UNITY_BUILD_BATCH_SIZE=16")
    B.build(base / "build", "rapid_restarter_bridge")
    return base / "build" / "rapid_restarter_bridge", generate(base / "py")


def _ground(args: list[str], timeout: float) -> dict:
    # its own process group: if it has to be killed, its bridges go with it (a bridge left
    # running would answer the next run's commands on this domain)
    proc = subprocess.Popen([sys.executable, "-m", "tests.cpp_runtime.restart_ground", *args], cwd=ROOT,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
                            env=B.dds_env())
    try:
        out, err = proc.communicate(timeout=timeout)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.communicate()
    assert proc.returncode == 0, f"{args}: {out[-2000:]} {err[-4000:]}"
    return json.loads(out.splitlines()[-1])  # type: ignore[no-any-return]


def test_kill_9_at_random_moments_leaves_no_command_without_an_outcome(restarter, tmp_path):
    exe, pydir = restarter
    seed = random.SystemRandom().randrange(1_000_000)
    got = _ground(["kills", str(exe), str(pydir), str(tmp_path), str(KILL_DOMAIN), str(COMMANDS), str(KILLS),
                   str(seed)], 600)
    why = f"seed {seed}: {json.dumps({k: v for k, v in got.items() if k != 'plan'})[-6000:]}"
    assert got["starts"] == KILLS + 1 and got["stop_code"] == 0 and got["crashes"] == [], why

    restarted = check_kill_run(got, KILLS, why)
    print(f"seed {seed}: {len(got['finals'])} commands, {KILLS} kills, {restarted} answered 'restarted', "
          f"{sum(got['retried'].values())} sent again, {len(got['runs'])} ran")


def test_one_runtimes_journal_is_answered_from_by_the_other(restarter, tmp_path):
    exe, pydir = restarter
    got = _ground(["cross", str(exe), str(pydir), str(tmp_path), str(CROSS_DOMAIN)], 300)
    for way, first in (("cpp-then-py", "cpp"), ("py-then-cpp", "py")):
        seen = got[way]
        why = f"{way}: {json.dumps(seen)[-4000:]}"
        assert seen["finals"] == {
            f"{first}-long": ["ACK_COMPLETED", "ACK_COMPLETED_EXEC_FAILED", RESTARTED[1]],
            f"{first}-next": ["ACK_COMPLETED", "ACK_COMPLETED_CANCELED", RESTARTED[0]]}, why
        assert seen["runs"] == [f"{first}-long"] and seen["stop_code"] == 0, why  # the waiting one never ran
        assert any("restarted after a crash; 2 unfinished command(s) answered" in ln for ln in seen["logs"]), why
        assert not any("damaged" in ln or "Traceback" in ln for ln in seen["logs"]), why
