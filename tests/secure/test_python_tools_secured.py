"""The operator's Python tools on a secured domain (issue 35 item 7; docs/security.md, "The
Python side"): `rapidgen cmd` and `rapidgen conform`, on the Cyclone DDS with DDS Security
that scripts/setup.sh builds, join K10's secured C++ bridge (Fast DDS 2.9's plugins) with
an enclave of a `rapidgen secure` keystore, in a private network namespace (only lo).

- `rapidgen cmd --enclave RapidWorkbench` (granted command on K10Red): the command runs.
- `rapidgen conform --enclave RapidWorkbench` (granted command and audit on K10Red): every
  required check passes; the checks that speak as a second source are unsupported (the
  bridge binds cmdSrc to the certificate: one enclave is one source).
- `rapidgen spy echo --enclave RapidWorkbench` (granted watch) reads K10's positions; without
  an enclave, nothing.
- Without an enclave, or with one the deployment did not grant commanding K10Red (Outsider:
  watch only; Conformance: audit only), nothing runs: cmd finds no asset, or (Outsider) says
  that DDS Security refused its command topic; conform finds none or says that DDS Security
  refused its command writer (its topic, for Outsider). Each exits 1 itself: a refused
  conform once died at exit with SIGSEGV (test_conform_teardown.py, test_tools_teardown.py)."""
from __future__ import annotations

import sys

import pytest

from tests.secure.conftest import DOMAIN, ROOT, exited, run_scenario

K10 = str(ROOT / "specs" / "assets" / "k10.yaml")


def _cmd(enclave: str | None, wait: str = "15") -> dict:
    extra = ["--enclave", enclave] if enclave else []
    return {"argv": [sys.executable, "-m", "rapidgen", "cmd", K10, "AccessControl", "requestControl",
                     "--source", "RapidWorkbench", "--domain", str(DOMAIN), "--timeout", wait, *extra], "env": {}}


def _conform(enclave: str | None) -> dict:
    extra = ["--enclave", enclave] if enclave else []
    return {"argv": [sys.executable, "-m", "rapidgen", "conform", K10, "--domain", str(DOMAIN), "--timeout", "10",
                     *extra], "env": {}}


def _spy(enclave: str | None, wait: str = "20") -> dict:
    """(a refused tool waits all of `wait`: on loopback discovery takes well under a second)"""
    extra = ["--enclave", enclave] if enclave else []
    return {"argv": [sys.executable, "-m", "rapidgen", "spy", "echo", "rapid_position_sample", "--asset", K10,
                     "--domain", str(DOMAIN), "--count", "1", "--seconds", wait, "--json", *extra], "env": {}}


@pytest.fixture(scope="module")
def secured(keystores, programs, tmp_path_factory) -> dict:
    enclaves = keystores["main"] / "enclaves"
    return run_scenario(tmp_path_factory.mktemp("python_tools"), {
        "bridge": [str(programs["bridge"]), "--simulate", "--domain", str(DOMAIN), "--seconds", "150"],
        "bridge_env": {"RAPID_SECURITY_KEYSTORE": str(keystores["main"])}, "ready_s": 60,
        "cases": {"cmd": _cmd(str(enclaves / "RapidWorkbench")), "cmd_no_enclave": _cmd(None, "8"),
                  "cmd_watch_only": _cmd(str(enclaves / "Outsider"), "8"),
                  "conform_no_enclave": _conform(None),
                  "spy": _spy(str(enclaves / "RapidWorkbench")), "spy_no_enclave": _spy(None, "8"),
                  "conform_audit_only": _conform(str(enclaves / "Conformance")),
                  "conform_watch_only": _conform(str(enclaves / "Outsider"))},
        # after the cases (the scenario's watch slot): alone, as a conformance run is
        "watch": _conform(str(enclaves / "RapidWorkbench"))})


def test_cmd_with_an_enclave_commands_the_secured_cpp_bridge(secured):
    assert secured["bridge_ready"], secured["bridge"]
    case = secured["cases"]["cmd"]
    assert case["rc"] == 0 and "COMPLETED OK" in case["stdout"], case


def test_conform_with_an_audit_grant_passes_against_the_secured_cpp_bridge(secured):
    case = secured["watch"]
    exited(case["rc"], 0, case)
    assert "every required check passed" in case["stdout"], case
    assert "ACC-04   required     UNSUPPORTED" in case["stdout"], case  # a second source: its own enclave


@pytest.mark.parametrize("name", ["conform_audit_only", "conform_watch_only"])
def test_conform_without_a_command_grant_is_refused_plainly(secured, name):
    """Exit 1, itself: beside the secured bridge a refused run once died at exit (SIGSEGV,
    after its refusal; test_conform_teardown.py)."""
    case = secured["cases"][name]
    exited(case["rc"], 1, case)
    assert "DDS Security refused what the runner needs" in case["stderr"], case
    assert "Traceback" not in case["stderr"] and "Fatal Python error" not in case["stderr"], case


@pytest.mark.parametrize("name", ["cmd_no_enclave", "conform_no_enclave"])
def test_without_a_grant_the_tools_find_no_asset(secured, name):
    case = secured["cases"][name]
    exited(case["rc"], 1, case)  # found nothing: 1, not a signal
    assert "COMPLETED OK" not in case["stdout"] and "every required check passed" not in case["stdout"], case


def test_cmd_with_a_watch_only_enclave_is_refused_plainly(secured):
    """DDS Security refuses Outsider the command topic: said as conform says it, exit 1 (it
    was an internal error, exit 3, 'please report this'); its participant deleted, beside the
    secured bridge, before it exits (test_tools_teardown.py)."""
    case = secured["cases"]["cmd_watch_only"]
    exited(case["rc"], 1, case)
    assert "rapidgen cmd: DDS Security refused what the command needs with the enclave" in case["stderr"], case
    assert "docs/secure.md" in case["stderr"], case
    assert "internal error" not in case["stderr"] and "Traceback" not in case["stderr"] \
        and "Fatal Python error" not in case["stderr"], case
    assert "COMPLETED OK" not in case["stdout"], case


def test_spy_with_an_enclave_reads_the_secured_bridge_s_telemetry(secured):
    case = secured["cases"]["spy"]
    assert '"topic": "rapid_position_sample"' in case["stdout"] or "rapid_position_sample" in case["stdout"], case
    assert "K10Red" in case["stdout"], case
    stranger = secured["cases"]["spy_no_enclave"]
    assert "K10Red" not in stranger["stdout"], stranger
