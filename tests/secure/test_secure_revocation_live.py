"""Rotation and withdrawn grants cut the old enclaves off, live (issue 35 item 3): K10's
secured C++ bridge with the keystore after `rapidgen secure --rotate`, or after a run that
withdrew a grant, and ground tools (tests/secure/cpp/ground.cpp) holding the enclaves
handed out before, in a private network namespace (only lo), Fast DDS's plugins on.

What Fast DDS 2.9 honours (docs/secure.md, "Rotation and withdrawn grants"): a certificate
from its identity CA, and permissions its permissions CA signed while their <validity>
lasts, with no revocation of either: so `--rotate` makes new CAs and a withdrawal a new
permissions CA. Counted as in test_secure_live.py: an authorised watcher reads the asset's
acks (transient-local: every command the bridge took has acks)."""
from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from tests.secure.conftest import DEPLOYMENT, run_scenario, secure, write_deployment

N = 5
WAIT_S = "8"
AUTHORISED_WAIT_S = "40"
ROTATE_DOMAIN = 77  # (the scenario's namespace has only lo: no other test can see these)
WITHDRAW_DOMAIN = 78


def _deployment(folder: Path, domain: int, text: str = DEPLOYMENT) -> Path:
    return write_deployment(folder, text.replace("domains: [{domain}]", f"domains: [{domain}]"))


def _ground(programs: dict, domain: int, source: str, prefix: str, env: dict, wait: str = WAIT_S) -> dict:
    return {"argv": [str(programs["ground"]), "command", str(programs["profiles"]), str(domain), "K10Red", source,
                     prefix, str(N), wait], "env": env}


def _run(programs: dict, tmp: Path, ks: Path, domain: int, cases: dict) -> dict:
    env = {"RAPID_SECURITY_KEYSTORE": str(ks)}
    watch = {"argv": [str(programs["ground"]), "watch", str(programs["profiles"]), str(domain), "K10Red", "15",
                      *(c["argv"][6] for c in cases.values())],
             "env": {**env, "RAPID_SECURITY_ENCLAVE": "RapidWorkbench"}}
    return run_scenario(tmp, {"bridge": [str(programs["bridge"]), "--simulate", "--domain", str(domain),
                                         "--seconds", "120"],
                              "bridge_env": env, "cases": cases, "watch": watch})


def _acked(result: dict) -> dict[str, int]:
    return {line.split(":")[0][len("acked "):]: int(line.rsplit(":", 1)[1])
            for line in result["watch"]["stdout"].splitlines() if line.startswith("acked ")}


def _enclave_env(ks: Path, folder: Path) -> dict:
    return {"RAPID_SECURITY_KEYSTORE": str(ks), "RAPID_SECURITY_ENCLAVE": str(folder)}


@pytest.fixture(scope="module")
def rotated(programs, tmp_path_factory) -> dict:
    """A keystore, RapidWorkbench's enclave kept as handed out, then `--rotate`."""
    tmp = tmp_path_factory.mktemp("rotated")
    dep = _deployment(tmp, ROTATE_DOMAIN)
    ks = tmp / "ks"
    assert secure(str(dep), "-k", str(ks)).returncode == 0
    old = tmp / "handed_out" / "RapidWorkbench"
    shutil.copytree(ks / "enclaves" / "RapidWorkbench", old)
    rot = secure(str(dep), "-k", str(ks), "--rotate")
    assert rot.returncode == 0, rot.stderr
    ks_env = {"RAPID_SECURITY_KEYSTORE": str(ks)}
    return _run(programs, tmp, ks, ROTATE_DOMAIN, {
        "new": _ground(programs, ROTATE_DOMAIN, "RapidWorkbench", "rotatednew", ks_env, AUTHORISED_WAIT_S),
        "old": _ground(programs, ROTATE_DOMAIN, "RapidWorkbench", "rotatedold", _enclave_env(ks, old)),
    })


def test_after_rotate_the_new_enclave_commands(rotated):
    assert rotated["bridge_ready"], rotated["bridge"]
    assert f"completed: {N} of {N}" in rotated["cases"]["new"]["stdout"], rotated["cases"]["new"]
    assert _acked(rotated)["rotatednew"] == N + 1  # the commands and the control command


def test_after_rotate_the_enclave_handed_out_before_runs_nothing(rotated):
    assert "matched: 1" in rotated["watch"]["stdout"]  # the watcher saw the asset
    assert _acked(rotated)["rotatedold"] == 0  # 0 of N (nor the control command)
    assert f"completed: {N} of {N}" not in rotated["cases"]["old"]["stdout"]
    assert "rotatedold" not in rotated["bridge"]["stderr"]


@pytest.fixture(scope="module")
def withdrawn(programs, tmp_path_factory) -> dict:
    """ScienceBackroom may command K10 (its access_control admits it); the grant is then
    withdrawn (watch only): the run makes a new permissions CA. Tried: its old enclave as
    handed out, and its new enclave with the old, validly signed permissions.p7s (and the
    old permissions CA) put back."""
    tmp = tmp_path_factory.mktemp("withdrawn")
    dep = _deployment(tmp, WITHDRAW_DOMAIN)
    ks = tmp / "ks"
    assert secure(str(dep), "-k", str(ks)).returncode == 0
    old = tmp / "handed_out" / "ScienceBackroom"
    shutil.copytree(ks / "enclaves" / "ScienceBackroom", old)
    _deployment(tmp, WITHDRAW_DOMAIN, DEPLOYMENT.replace('{source: ScienceBackroom, command: ["*"]}',
                                                         '{source: ScienceBackroom, watch: ["*"]}'))
    res = secure(str(dep), "-k", str(ks))
    assert res.returncode == 0 and "new permissions_ca (grants withdrawn)" in res.stdout, res.stdout + res.stderr
    mixed = tmp / "mixed" / "ScienceBackroom"
    shutil.copytree(ks / "enclaves" / "ScienceBackroom", mixed)
    for f in ("permissions.p7s", "permissions.xml", "permissions_ca.cert.pem", "governance.p7s"):
        shutil.copy(old / f, mixed / f)
    ks_env = {"RAPID_SECURITY_KEYSTORE": str(ks)}
    return _run(programs, tmp, ks, WITHDRAW_DOMAIN, {
        "authorised": _ground(programs, WITHDRAW_DOMAIN, "RapidWorkbench", "stillgranted", ks_env, AUTHORISED_WAIT_S),
        "old": _ground(programs, WITHDRAW_DOMAIN, "ScienceBackroom", "withdrawnold", _enclave_env(ks, old)),
        "mixed": _ground(programs, WITHDRAW_DOMAIN, "ScienceBackroom", "withdrawnmixed", _enclave_env(ks, mixed)),
        "new": _ground(programs, WITHDRAW_DOMAIN, "ScienceBackroom", "withdrawnnew", ks_env),
    })


def test_after_a_withdrawal_the_others_still_command(withdrawn):
    assert withdrawn["bridge_ready"], withdrawn["bridge"]
    assert f"completed: {N} of {N}" in withdrawn["cases"]["authorised"]["stdout"], withdrawn["cases"]["authorised"]
    assert _acked(withdrawn)["stillgranted"] == N + 1


@pytest.mark.parametrize("case, prefix", [("old", "withdrawnold"), ("mixed", "withdrawnmixed"),
                                          ("new", "withdrawnnew")])
def test_a_withdrawn_grant_runs_nothing(withdrawn, case, prefix):
    """old: the enclave as handed out; mixed: the new certificate with the old signed
    permissions put back; new: the new enclave, which grants watching only."""
    assert "matched: 1" in withdrawn["watch"]["stdout"]
    assert _acked(withdrawn)[prefix] == 0, withdrawn["cases"][case]
    assert f"completed: {N} of {N}" not in withdrawn["cases"][case]["stdout"]
    assert prefix not in withdrawn["bridge"]["stderr"]
