"""generate and check over two processes (rapidgen.fork_ahead): the checks in
fork_ahead_checks.py, run in a fresh interpreter. fork_ahead declines to fork a process
that runs other threads (a forked child keeps only the calling one), and the pytest worker
running this file may still hold threads an earlier test in it started (a DDS listener's,
a daemon finishing): in that worker the checks would meet a one-process fork_ahead."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def test_fork_ahead_checks_pass_in_a_process_of_one_thread():
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTEST_", "RAPIDGEN_JOBS"))}
    run = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "no:xdist", "-rs",
         "tests/unit/fork_ahead_checks.py"],
        cwd=REPO, env=env, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout[-6000:] + run.stderr[-2000:]
    if len(os.sched_getaffinity(0)) >= 2:  # nothing skipped for want of a second process
        assert " skipped" not in run.stdout, run.stdout[-3000:]
    assert " passed" in run.stdout
