"""cmdSrc bound to the certificate, live (issue 35 item 1; docs/secure.md, "cmdSrc bound to
the certificate"): K10's generated C++ bridge secured with a `rapidgen secure` keystore runs
a command only when its cmdSrc is the identity of the participant that wrote it. The
ground tools are tests/secure/cpp/ground.cpp, whose enclave (RAPID_SECURITY_ENCLAVE) and
cmdSrc are set apart here; everything runs in a private network namespace (only lo).

- RapidWorkbench as itself: N of N.
- ScienceBackroom's own valid certificate, permissions that let it write K10's commands,
  and cmdSrc RapidWorkbench (it took control "as RapidWorkbench" first): 0 of N, each
  answered EXEC_FAILED "cmdSrc 'RapidWorkbench' is not the writer's identity
  'ScienceBackroom'", and the bridge logs each naming both.
- MultiCenterCockpit, authenticated and granted, but not in the bridge's identities.txt
  (a tool the bridge's copy of the keystore does not know): 0 of N.
- Unsecured, the same spoofing tool runs N of N: nothing binds cmdSrc without DDS Security.
- A secured bridge whose enclave has no identities.txt refuses to start."""
from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

from rapidgen.secure.identities import ground_certs, guid_prefix_head, subject_digest
from tests.secure.conftest import ROOT, run_scenario, secure

SECURED_DOMAIN = 87
UNSECURED_DOMAIN = 89
N = 5
WAIT_S = "40"  # each tool ends once its N commands are answered; a loaded machine's margin
ASSETS = ROOT / "specs" / "assets"
DEPLOYMENT = f"""\
version: 1
assets: [{ASSETS / 'k10.yaml'}]
domains: [{SECURED_DOMAIN}]
ground:
  - {{source: RapidWorkbench, command: [K10Red]}}
  - {{source: ScienceBackroom, command: ["*"]}}
  - {{source: MultiCenterCockpit, command: [K10Red]}}
"""
SPOOFED = "cmdSrc 'RapidWorkbench' is not the writer's identity 'ScienceBackroom'"
UNKNOWN = "cmdSrc 'MultiCenterCockpit' is not the writer's identity (its certificate is none of this keystore's " \
          "ground sources)"


@pytest.fixture(scope="module")
def keystore(tmp_path_factory) -> dict[str, Path]:
    """The keystore, and a copy of K10Red's enclave whose identities.txt leaves
    MultiCenterCockpit out (the bridge's list does not know it; its certificate and
    permissions are still valid) and one with no identities.txt at all."""
    base = tmp_path_factory.mktemp("cmdsrc")
    dep = base / "deploy.yaml"
    dep.write_text(DEPLOYMENT, encoding="utf-8")
    res = secure(str(dep), "-k", str(base / "ks"))
    assert res.returncode == 0, res.stderr
    enclave = base / "ks" / "enclaves" / "K10Red"
    lines = (enclave / "identities.txt").read_text(encoding="utf-8").splitlines(keepends=True)
    assert [ln.split()[0] for ln in lines if not ln.startswith("#")] == \
        ["MultiCenterCockpit", "RapidWorkbench", "ScienceBackroom"]
    partial = base / "K10Red-partial"
    shutil.copytree(enclave, partial)
    (partial / "identities.txt").write_text("".join(ln for ln in lines if not ln.startswith("MultiCenterCockpit")),
                                            encoding="utf-8")
    bare = base / "K10Red-bare"
    shutil.copytree(enclave, bare)
    (bare / "identities.txt").unlink()
    return {"keystore": base / "ks", "partial": partial, "bare": bare}


def _ground(programs: dict, domain: int, cmd_src: str, prefix: str, env: dict) -> dict:
    return {"argv": [str(programs["ground"]), "command", str(programs["profiles"]), str(domain), "K10Red", cmd_src,
                     prefix, str(N), WAIT_S], "env": env}


def _bridge(programs: dict, domain: int) -> list[str]:
    return [str(programs["bridge"]), "--simulate", "--domain", str(domain), "--seconds", "120"]


def _failed(out: str) -> dict[str, str]:
    """cmdId -> the message of its COMPLETED ack that was not OK (ground.cpp's "failed" lines)."""
    found = {}
    for line in out.splitlines():
        if line.startswith("failed "):
            cmd_id, message = line[len("failed "):].split(": ", 1)
            found[cmd_id] = message
    return found


@pytest.fixture(scope="module")
def secured(keystore, programs, tmp_path_factory) -> dict:
    ks = str(keystore["keystore"])

    def as_(enclave: str) -> dict:
        return {"RAPID_SECURITY_KEYSTORE": ks, "RAPID_SECURITY_ENCLAVE": enclave}
    cases = {
        "operator": _ground(programs, SECURED_DOMAIN, "RapidWorkbench", "operator", as_("RapidWorkbench")),
        "spoof": _ground(programs, SECURED_DOMAIN, "RapidWorkbench", "spoof", as_("ScienceBackroom")),
        "unknown": _ground(programs, SECURED_DOMAIN, "MultiCenterCockpit", "unknown", as_("MultiCenterCockpit")),
    }
    return run_scenario(tmp_path_factory.mktemp("cmdsrc-secured"), {
        "bridge": _bridge(programs, SECURED_DOMAIN), "bridge_env": as_(str(keystore["partial"])), "cases": cases})


def test_the_real_operator_runs_every_command(secured):
    assert secured["bridge_ready"], secured["bridge"]
    assert "cmdSrc bound to the writer's certificate (2 ground source(s)" in secured["bridge"]["stderr"]
    case = secured["cases"]["operator"]
    assert "participant: ok (secured)" in case["stdout"], case
    assert f"completed: {N} of {N}" in case["stdout"], case
    assert _failed(case["stdout"]) == {}
    assert case["rc"] == 0


def test_a_tool_claiming_another_source_runs_nothing(secured, keystore):
    case = secured["cases"]["spoof"]
    assert "participant: ok (secured)" in case["stdout"] and "writer: ok" in case["stdout"], case  # DDS let it write
    assert "matched: 1" in case["stdout"], case
    assert f"completed: 0 of {N}" in case["stdout"], case
    # every command, the control command too, answered with the refusal naming both
    assert _failed(case["stdout"]) == {f"spoof-{i}": SPOOFED for i in [*map(str, range(N)), "control"]}, case
    bridge = secured["bridge"]["stderr"]
    for cmd_id in ("spoof-control", *(f"spoof-{i}" for i in range(N))):
        assert f"refused '{cmd_id}' from writer " in bridge
    assert bridge.count(f": {SPOOFED}") == N + 1, bridge
    # the writer's GUID is the one PKI-DH made from ScienceBackroom's certificate (Fast DDS's
    # own derivation, independent of the bridge's check): bit 1 and 47 bits of its subject's digest
    writer = re.search(r"refused 'spoof-0' from writer ([0-9a-f]{32}): ", bridge)
    assert writer is not None, bridge
    cert = ground_certs(keystore["keystore"], ["ScienceBackroom"])["ScienceBackroom"]
    assert writer[1].startswith(guid_prefix_head(subject_digest(cert)).hex())
    assert case["rc"] == 4


def test_a_tool_the_bridge_does_not_know_runs_nothing(secured):
    case = secured["cases"]["unknown"]
    assert "writer: ok" in case["stdout"] and "matched: 1" in case["stdout"], case
    assert f"completed: 0 of {N}" in case["stdout"], case
    assert set(_failed(case["stdout"]).values()) == {UNKNOWN}, case
    assert len(_failed(case["stdout"])) == N + 1
    assert secured["bridge"]["stderr"].count(f": {UNKNOWN}") == N + 1


def test_unsecured_nothing_binds_cmdsrc(programs, tmp_path):
    """Today's behaviour without a keystore: the same tool claiming RapidWorkbench runs all."""
    result = run_scenario(tmp_path, {"bridge": _bridge(programs, UNSECURED_DOMAIN), "cases": {
        "spoof": _ground(programs, UNSECURED_DOMAIN, "RapidWorkbench", "spoof", {})}})
    case = result["cases"]["spoof"]
    assert "participant: ok (unsecured)" in case["stdout"], case
    assert f"completed: {N} of {N}" in case["stdout"], case
    assert "writer's identity" not in result["bridge"]["stderr"]


def test_secured_bridge_without_identities_refuses_to_start(keystore, programs, tmp_path):
    result = run_scenario(tmp_path, {"bridge": _bridge(programs, SECURED_DOMAIN), "cases": {}, "bridge_env": {
        "RAPID_SECURITY_KEYSTORE": str(keystore["keystore"]), "RAPID_SECURITY_ENCLAVE": str(keystore["bare"])}})
    assert not result["bridge_ready"]
    assert result["bridge"]["rc"] == 1, result["bridge"]
    assert f"cannot read {keystore['bare']}/identities.txt" in result["bridge"]["stderr"]
    assert "run rapidgen secure" in result["bridge"]["stderr"]


def test_check_reports_identities_missing_or_stale(keystore, tmp_path):
    ks = tmp_path / "ks"
    shutil.copytree(keystore["keystore"], ks)
    dep = keystore["keystore"].parent / "deploy.yaml"
    assert secure(str(dep), "-k", str(ks), "--check").returncode == 0
    ids = ks / "enclaves" / "K10Red" / "identities.txt"
    text = ids.read_text(encoding="utf-8")
    # ScienceBackroom's line naming another subject's digest
    ids.write_text("".join(f"ScienceBackroom {'0' * 64} CN=Other\n" if ln.startswith("ScienceBackroom ") else ln
                           for ln in text.splitlines(keepends=True)), encoding="utf-8")
    res = secure(str(dep), "-k", str(ks), "--check")
    assert res.returncode == 1 and "enclaves/K10Red/identities.txt" in res.stdout + res.stderr, res
    assert "does not list the ground tools' certificates" in res.stdout + res.stderr
    ids.unlink()
    res = secure(str(dep), "-k", str(ks), "--check")
    assert res.returncode == 1 and "identities.txt" in res.stdout + res.stderr
    assert "missing" in res.stdout + res.stderr
    assert secure(str(dep), "-k", str(ks)).returncode == 0  # a run writes it again
    assert ids.read_text(encoding="utf-8") == text
