"""The conformance suite's broken-asset kinds that the Rust runtime can express, injected into
K10's generated Rust bridge with `--break KIND` (compiled only with the cargo feature
test-breaks: rapid_runtime's src/breaks.rs, which lists every kind, and rapid_dds's
src/breaks.rs for the ack writer, the configs and the simulated telemetry): each makes
`rapidgen conform` fail the check it aims at and no other, the check the Python kind of that
name fails (tests/conformance/broken) and the C++ bridge's (tests/cpp_client/test_broken.py).
docs/rust-backend.md lists the kinds that are not injected (QoS and types).

One feature-enabled build of K10's bridge, in the target folder of the folder's bridges
(cyclors is not built again; the runtime, its DDS layer and the bridge are), under a package
name of its own so that the plain `rapid_k10red_bridge` the other tests run stays as it is.
One bridge per kind (a failure is then the kind's alone), each run the checks of its area
(--only CMD-, TEL- or CFG-, the checks it builds on included; every bridge --simulate: the
telemetry kinds break its simulated telemetry): the full suite's judgment of the unbroken
bridge is test_dds_bridge.py's. The runs wait on discovery and the checks' windows (rates,
late judgments) far more than they compute, so PARALLEL run at a time, the longest first, on
domains 73 and 74.

Each kind's bridge and runner carry a Cyclone domain tag of their own (Discovery/Tag, added
to K10's loopback configuration): participants with another tag, or none, ignore them and
are ignored. So the runs sharing a domain do not see each other, nor does a run see the
participant a crashed bridge leaves until its lease ends, nor the other tests on domains 73
and 74 (tests/rust/test_interop.py's, and among tests/cpp_client/test_broken.py's, whose
K10Red bridges would otherwise answer this runner)."""
from __future__ import annotations

import json
import os
import re
import resource
import shutil
import subprocess
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from tests.conformance.harness import DESCRIPTORS, RAPIDGEN, outcomes
from tests.runtime.live import ROOT, env_for, python_dir
from tests.rust.conftest import cargo
from tests.rust_runtime.build import RUNTIME

BREAKS_RS = RUNTIME / "rapid_runtime" / "src" / "breaks.rs"
KINDS = dict(re.findall(r'\("([a-z0-9-]+)", "([A-Z]+-\d\d)"\)', BREAKS_RS.read_text(encoding="utf-8")))
DOMAINS = (73, 74)
PARALLEL = 4
PACKAGE = "rapid_k10red_bridge_breaks"
CRASH = "crash-on-bad-input"
# runs that wait out a command's answer (CMD-14 and CMD-16's 10 s) start first, then by area
# (telemetry runs wait out rates: 4 to 8 s; configs CFG-05's 4 s of watching)
LONG = (CRASH, "nan-unanswered", "every-20th-lost")
AREA_ORDER = ("TEL-", "CFG-", "CMD-", "QUE-", "ACC-", "SPEC-")
LOCAL = ROOT / "generated" / "k10" / "qos" / "cyclonedds" / "local.xml"  # the bridge's built-in `local`


def _cyclone(kind: str) -> str:
    """K10's loopback configuration with a domain tag of this run's and kind's own."""
    tag = f"rapidgen-rust-broken-{os.getpid()}-{kind}"
    return f'file://{LOCAL},<CycloneDDS><Domain id="any"><Discovery><Tag>{tag}</Tag></Discovery></Domain></CycloneDDS>'


def _children_cpu() -> float:
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def _area(check: str) -> str:
    return check.split("-")[0] + "-"


def _conform(domain: int, cyclone: str, out: Path, only: str) -> dict:
    """`rapidgen conform` on K10 (tests.conformance.harness.conform's run, in the kind's tag)."""
    report = out / "conform.json"
    env = dict(env_for(python_dir("k10"), "rapid_k10red"), CYCLONEDDS_URI=cyclone)
    res = subprocess.run([*RAPIDGEN, "conform", str(DESCRIPTORS["k10"]), "--domain", str(domain), "--json", str(report),
                          "--only", only], cwd=ROOT, env=env, capture_output=True, text=True, timeout=240)
    data = json.loads(report.read_text()) if report.exists() else None
    return {"code": res.returncode, "stdout": res.stdout, "stderr": res.stderr, "report": data}


@pytest.fixture(scope="module")
def broken_bridge(bridges, tmp_path_factory) -> Path:
    """K10's bridge built with rapid_dds/test-breaks: a workspace of its own beside the
    folder's (the same layout, K10's generated crate copied and its bridge package renamed),
    built into the same target folder."""
    ws = tmp_path_factory.mktemp("rust-broken-ws")
    (ws / "generated" / "k10").mkdir(parents=True)
    (ws / "runtime").symlink_to(bridges["ws"] / "runtime")
    (ws / "generated" / "rapid").symlink_to(bridges["ws"] / "generated" / "rapid")
    shutil.copytree(bridges["ws"] / "generated" / "k10" / "rust", ws / "generated" / "k10" / "rust")
    manifest = ws / "generated" / "k10" / "rust" / "bridge" / "Cargo.toml"
    text = manifest.read_text(encoding="utf-8")
    assert 'name = "rapid_k10red_bridge"' in text and 'name = "rapid_k10red_cmd"' in text, text
    manifest.write_text(text.replace('name = "rapid_k10red_bridge"', f'name = "{PACKAGE}"')
                        .replace('name = "rapid_k10red_cmd"', 'name = "rapid_k10red_cmd_breaks"'), encoding="utf-8")
    shutil.copy(bridges["ws"] / "Cargo.toml", ws / "Cargo.toml")
    shutil.copy(bridges["ws"] / "Cargo.lock", ws / "Cargo.lock")
    env = dict(os.environ, CARGO_TARGET_DIR=str(bridges["target"]), CARGO_TERM_COLOR="never")
    start, cpu = time.monotonic(), _children_cpu()
    for mode in (["--offline"], []):  # (as build.py: offline when the crates are cached)
        res = subprocess.run([cargo(), "build", *mode, "--bin", PACKAGE, "--features", "rapid_dds/test-breaks"],
                             cwd=ws, env=env, capture_output=True, text=True, timeout=1800, stdin=subprocess.DEVNULL)
        if res.returncode == 0:
            break
    print(f"\ncargo build of K10's bridge with test-breaks: {time.monotonic() - start:.1f} s, "
          f"{_children_cpu() - cpu:.1f} s CPU")
    assert res.returncode == 0, res.stderr[-4000:]
    assert not [line for line in res.stderr.splitlines() if line.startswith("warning")], res.stderr[-4000:]
    return Path(bridges["target"]) / "debug" / PACKAGE


def _run(args) -> dict:
    kind, domain, program, out = args
    folder = out / kind
    folder.mkdir()
    env = dict(os.environ, CYCLONEDDS_URI=_cyclone(kind))
    proc = subprocess.Popen([str(program), "--simulate", "--break", kind, "--domain", str(domain),
                             "--journal", str(folder / "state")],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        ready = proc.stdout.readline()
        assert "ready on domain" in ready, (kind, ready, proc.stderr.read()[-2000:] if not ready else "")
        run = _conform(domain, _cyclone(kind), folder, _area(KINDS[kind]))  # its area: the checks it builds on first
    finally:
        if proc.poll() is None:
            proc.terminate()
        _, err = proc.communicate(timeout=60)
    run["bridge_status"], run["bridge_err"] = proc.returncode, err
    return run


@pytest.fixture(scope="module")
def broken_runs(broken_bridge, tmp_path_factory):
    out = tmp_path_factory.mktemp("rust-broken")
    order = sorted(KINDS, key=lambda k: (k not in LONG, AREA_ORDER.index(_area(KINDS[k]))))
    start, cpu = time.monotonic(), _children_cpu()
    with ThreadPoolExecutor(PARALLEL) as pool:
        jobs = [(k, DOMAINS[i % len(DOMAINS)], broken_bridge, out) for i, k in enumerate(order)]
        runs = dict(zip(order, pool.map(_run, jobs)))
    print(f"\n{len(runs)} broken Rust bridges judged in {time.monotonic() - start:.1f} s, "
          f"{_children_cpu() - cpu:.1f} s CPU (bridges and runners)")
    return runs


def test_kinds_are_the_conformance_suites():
    """Each Rust kind is a kind of tests/conformance/broken aimed at the same check."""
    from tests.conformance.broken import KINDS as PYTHON_KINDS
    assert len(KINDS) >= 56
    assert {k: PYTHON_KINDS.get(k) for k in KINDS} == KINDS


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_broken_rust_bridge_fails_its_check(broken_runs, kind):
    run = broken_runs[kind]
    assert run["report"] is not None, run["stderr"][-3000:]
    got = outcomes(run["report"])
    failed = {c["id"]: c["message"] for c in run["report"]["checks"] if c["outcome"] in ("FAIL", "ERROR")}
    assert got[KINDS[kind]] == "FAIL", (got, failed)
    assert [c for c, o in got.items() if o in ("FAIL", "ERROR")] == [KINDS[kind]], failed  # that check only
    level = next(c["level"] for c in run["report"]["checks"] if c["id"] == KINDS[kind])
    assert run["code"] == (1 if level.upper() == "REQUIRED" else 0)  # a recommended check's failure is reported only
    assert "panicked" not in run["bridge_err"], run["bridge_err"][-3000:]
    if kind == CRASH:
        assert run["bridge_status"] == 70
    else:
        assert run["bridge_status"] == 0, run["bridge_err"][-2000:]


def test_plain_bridge_refuses_breaks(bridges, broken_bridge):
    """Only a test build takes --break: the generated bridge refuses to start with one, and
    has none of the kinds in it (their names are in the test build only)."""
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}
    res = subprocess.run([str(bridges["k10"]), "--break", "wrong-ack-order", "--domain", "73", "--no-journal"],
                         capture_output=True, text=True, timeout=60, env=env)
    assert res.returncode == 1 and "--break is for test builds only" in res.stderr, res.stderr
    plain, test_build = Path(bridges["k10"]).read_bytes(), broken_bridge.read_bytes()
    assert [k for k in KINDS if k.encode() in plain] == []
    assert [k for k in KINDS if k.encode() not in test_build] == []


def test_unknown_kind_is_a_usage_error(broken_bridge):
    res = subprocess.run([str(broken_bridge), "--break", "no-such-kind", "--domain", "73", "--no-journal"],
                         capture_output=True, text=True, timeout=60)
    assert res.returncode == 2 and 'unknown break "no-such-kind"' in res.stderr, res.stderr
