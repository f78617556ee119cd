"""The conformance suite's broken-asset kinds that apply to a C++ bridge, injected into K10's
generated C++ bridge with `--break KIND` (a test build: RAPID_RUNTIME_TEST_BREAKS,
runtime/cpp/dds/include/rapid_runtime/dds/breaks.hpp; the manager's decisions through
ManagerBreaks, compiled into test builds only): each makes `rapidgen conform` fail the check
it aims at and no other, the same check the Python runtime's kind of that name fails
(tests/conformance/broken). One bridge per kind (a failure is then the kind's alone), PARALLEL
at a time, each run the checks of its area (--only CMD-, the checks it builds on included):
the full suite's judgment of the unbroken bridge is tests/conformance/test_cpp_asset.py's.
The runs wait on the network and on declared rates far more than they compute, so they
overlap well beyond the machine's cores; the longest areas start first. Domains 13-18 and
73-82, each used again once its bridge and runner left it cleanly. docs/conformance.md lists
the kinds that do not apply."""
from __future__ import annotations

import queue
import re
import subprocess
from concurrent.futures import ThreadPoolExecutor

import pytest

from tests.conformance.harness import conform, outcomes
from tests.cpp_runtime import build as B

pytest.importorskip("cyclonedds")
BREAKS_HPP = B.ROOT / "runtime" / "cpp" / "dds" / "include" / "rapid_runtime" / "dds" / "breaks.hpp"
KINDS = dict(re.findall(r'\{"([a-z0-9-]+)", "([A-Z]+-\d\d)"\}', BREAKS_HPP.read_text(encoding="utf-8")))
DOMAINS = [*range(13, 19), *range(73, 83)]
PARALLEL = 10
# Areas by how long their conform run takes (telemetry and configs wait out rates and late
# judgments, the queue its long command): started longest first, the short ones fill in.
AREA_ORDER = ("TEL-", "QUE-", "CFG-", "ACC-", "CMD-")


def _run(args) -> dict:
    kind, program, free, out = args
    domain = free.get(timeout=600)  # (none back: every bridge before it died; fails, not hangs)
    # (new_delete_type_mismatch=0: Fast DDS 2.9's own StatisticsReaderImpl at shutdown, test_fuzz.py);
    # a restart journal of its own: bridges of one asset running side by side share none
    state = out / f"state-{kind}"
    state.mkdir()
    env = dict(B.dds_env(), ASAN_OPTIONS="detect_leaks=0:new_delete_type_mismatch=0", RAPID_STATE_DIR=str(state))
    proc = subprocess.Popen([str(program), "--simulate", "--break", kind, "--domain", str(domain), "--seconds", "180"],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        ready = proc.stdout.readline()
        assert ready.startswith("bridge ready: "), (kind, ready, proc.stderr.read()[-2000:] if not ready else "")
        run = conform("k10", domain, out, "--only", KINDS[kind][:4])  # its area: the checks it builds on run first
    finally:
        if proc.poll() is None:
            proc.terminate()
        _, err = proc.communicate(timeout=60)
        if proc.returncode == 0:  # one that died leaves its participant until its lease ends
            free.put(domain)
    run["bridge_status"], run["bridge_err"] = proc.returncode, err
    return run


@pytest.fixture(scope="module")
def broken_runs(programs, tmp_path_factory):
    out = tmp_path_factory.mktemp("cpp-broken")
    free: queue.Queue[int] = queue.Queue()
    for d in DOMAINS:
        free.put(d)
    order = sorted(KINDS, key=lambda k: AREA_ORDER.index(KINDS[k][:4]))
    with ThreadPoolExecutor(PARALLEL) as pool:
        return dict(zip(order, pool.map(_run, [(k, programs["bridge_test"], free, out) for k in order])))


def test_kinds_are_the_conformance_suites():
    """Each C++ kind is a kind of tests/conformance/broken aimed at the same check."""
    from tests.conformance.broken import KINDS as PYTHON_KINDS
    assert len(KINDS) >= 44
    assert {k: PYTHON_KINDS.get(k) for k in KINDS} == KINDS


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_broken_cpp_bridge_fails_its_check(broken_runs, kind):
    run = broken_runs[kind]
    assert run["report"] is not None, run["stderr"][-3000:]
    got = outcomes(run["report"])
    failed = {c["id"]: c["message"] for c in run["report"]["checks"] if c["outcome"] in ("FAIL", "ERROR")}
    assert got[KINDS[kind]] == "FAIL", (got, failed)
    assert [c for c, o in got.items() if o in ("FAIL", "ERROR")] == [KINDS[kind]], got  # that check only
    level = next(c["level"] for c in run["report"]["checks"] if c["id"] == KINDS[kind])
    assert run["code"] == (1 if level.upper() == "REQUIRED" else 0)  # a recommended check's failure is reported only
    assert "ERROR: AddressSanitizer" not in run["bridge_err"] and "runtime error:" not in run["bridge_err"], \
        run["bridge_err"][-3000:]
    if kind == "crash-on-bad-input":
        assert run["bridge_status"] == 70
    else:
        assert run["bridge_status"] == 0, run["bridge_err"][-2000:]


def test_plain_bridge_refuses_breaks(programs):
    """Only a test build takes --break: the generated bridge refuses to start with one."""
    res = subprocess.run([str(programs["k10"]), "--break", "wrong-ack-order", "--domain", "27", "--seconds", "0"],
                         capture_output=True, text=True, timeout=60, env=B.dds_env())
    assert res.returncode == 1 and "--break is for test builds only" in res.stderr, res.stderr
