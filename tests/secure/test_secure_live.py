"""DDS Security, live (issue 24): K10's generated C++ bridge secured by the runtime's hook
with a keystore from `rapidgen secure`, and ground tools (tests/secure/cpp/ground.cpp)
with good and bad credentials, all in a private network namespace (only lo), Fast DDS's
builtin plugins on (PKI-DH, Access-Permissions, AES-GCM-GMAC).

What executed is counted by an authorised watcher reading the asset's acks (transient-
local: every command the bridge took has acks): a refused tool's commands have none."""
from __future__ import annotations

import struct

import pytest

from tests.secure.conftest import DOMAIN, run_scenario

N = 5  # commands each tool sends
WAIT_S = "8"  # a refused tool's wait for the asset and its acks (it waits it all)
AUTHORISED_WAIT_S = "40"  # an authorised one ends when its commands completed: a loaded machine's margin
MARK = "authorisedCMD"  # the authorised tool's cmdId prefix


def _ground(programs: dict, source: str, prefix: str, env: dict, wait: str = WAIT_S) -> dict:
    return {"argv": [str(programs["ground"]), "command", str(programs["profiles"]), str(DOMAIN), "K10Red", source,
                     prefix, str(N), wait], "env": env}


def _bridge(programs: dict) -> list[str]:
    return [str(programs["bridge"]), "--simulate", "--domain", str(DOMAIN), "--seconds", "120"]


def _cdr_string(text: str) -> bytes:
    """How a string is on the wire in CDR: length with its NUL, little-endian, then the bytes."""
    data = text.encode() + b"\0"
    return struct.pack("<I", len(data)) + data


def _acked(watch: dict) -> dict[str, int]:
    return {line.split(":")[0][len("acked "):]: int(line.rsplit(":", 1)[1])
            for line in watch["stdout"].splitlines() if line.startswith("acked ")}


def _in_clear(wire: bytes) -> list[str]:
    """Which of the authorised command's names and ids are on the wire in clear."""
    needles = {"cmdName echo": _cdr_string("echo"), "cmdId": _cdr_string(f"{MARK}-0"),
               "argument": _cdr_string(f"plaintext {MARK}-0"), "cmdId text": f"{MARK}-1".encode()}
    return [name for name, b in needles.items() if b in wire]


@pytest.fixture(scope="module")
def secured(keystores, programs, tmp_path_factory) -> dict:
    """One run: the secured bridge; the authorised tool and every refused one at once; then
    the watcher; the loopback traffic captured."""
    ks, var = str(keystores["main"]), keystores["variants"]
    secured_env = {"RAPID_SECURITY_KEYSTORE": ks}
    cases = {
        "authorised": _ground(programs, "RapidWorkbench", MARK, secured_env, AUTHORISED_WAIT_S),
        "no_certificate": _ground(programs, "RapidWorkbench", "nocert", {}),
        "other_ca": _ground(programs, "RapidWorkbench", "otherca", {"RAPID_SECURITY_KEYSTORE": str(keystores["other"])}),
        "expired": _ground(programs, "RapidWorkbench", "expired",
                           {"RAPID_SECURITY_KEYSTORE": ks, "RAPID_SECURITY_ENCLAVE": str(var / "expired")}),
        # granted rapid_command in Chariot's partition only, writing in K10Red's
        "not_granted": _ground(programs, "ChariotCrewDisplay", "notgranted", secured_env),
        # granted nothing to write at all (watch only)
        "watch_only": _ground(programs, "Outsider", "outsider", secured_env),
        "tampered": _ground(programs, "ChariotCrewDisplay", "tampered",
                            {"RAPID_SECURITY_KEYSTORE": ks, "RAPID_SECURITY_ENCLAVE": str(var / "tampered")}),
    }
    watch = {"argv": [str(programs["ground"]), "watch", str(programs["profiles"]), str(DOMAIN), "K10Red", "15",
                      MARK, *(c["argv"][6] for name, c in cases.items() if name != "authorised")],
             "env": {"RAPID_SECURITY_KEYSTORE": ks, "RAPID_SECURITY_ENCLAVE": "RapidWorkbench"}}
    return run_scenario(tmp_path_factory.mktemp("secured"), {
        "bridge": _bridge(programs), "bridge_env": secured_env, "cases": cases, "watch": watch, "capture": True})


REFUSED = ["no_certificate", "other_ca", "expired", "not_granted", "watch_only", "tampered"]


def test_authorised_ground_tool_commands_the_secured_bridge(secured):
    assert secured["bridge_ready"], secured["bridge"]
    case = secured["cases"]["authorised"]
    assert "participant: ok (secured)" in case["stdout"]
    assert f"completed: {N} of {N}" in case["stdout"], case
    assert case["rc"] == 0
    assert _acked(secured["watch"])[MARK] == N + 1  # the commands and the control command


@pytest.mark.parametrize("case", REFUSED)
def test_refused_tools_execute_nothing(secured, case):
    result = secured["cases"][case]
    acked = _acked(secured["watch"])
    prefix = {"no_certificate": "nocert", "other_ca": "otherca", "not_granted": "notgranted",
              "watch_only": "outsider"}.get(case, case)
    assert "matched: 1" in secured["watch"]["stdout"]  # the watcher did see the asset's acks
    assert acked[prefix] == 0, (case, result)  # 0 of N executed (nor the control command)
    assert f"completed: {N} of {N}" not in result["stdout"]
    assert prefix not in secured["bridge"]["stderr"]  # the bridge never logged one of them
    how = {  # how each is refused: at start by its own plugins, or never discovered
        "no_certificate": ["participant: ok (unsecured)", "matched: 0"],
        "other_ca": ["participant: ok (secured)", "matched: 0"],
        "expired": ["participant: refused: DDS Security refused"],
        "not_granted": ["writer: refused"],
        "watch_only": ["writer: refused"],
        "tampered": ["participant: refused: DDS Security refused"],
    }[case]
    for text in how:
        assert text in result["stdout"], (case, result)
    assert result["rc"] in (1, 4), result  # an answer, not a crash (no signal)


def test_encrypted_topics_carry_no_plaintext(secured):
    wire = bytes.fromhex(secured["wire"])
    assert secured["packets"] > 50 and b"RTPS" in wire  # the capture saw the run's RTPS traffic
    assert f"completed: {N} of {N}" in secured["cases"]["authorised"]["stdout"]  # the commands crossed it
    assert _in_clear(wire) == []


def test_without_security_the_same_capture_shows_the_command(programs, tmp_path):
    """The capture's control: the same command unsecured is readable on the wire."""
    result = run_scenario(tmp_path, {"bridge": _bridge(programs), "capture": True, "cases": {
        "plain": _ground(programs, "RapidWorkbench", MARK, {}, AUTHORISED_WAIT_S)}})
    assert f"completed: {N} of {N}" in result["cases"]["plain"]["stdout"], result["cases"]
    assert sorted(_in_clear(bytes.fromhex(result["wire"]))) == ["argument", "cmdId", "cmdId text", "cmdName echo"]


def test_asset_with_tampered_permissions_refuses_to_start(keystores, programs, tmp_path):
    result = run_scenario(tmp_path, {"bridge": _bridge(programs), "cases": {}, "ready_s": 20,
                                     "bridge_env": {"RAPID_SECURITY_KEYSTORE": str(keystores["tampered_asset"])}})
    bridge = result["bridge"]
    assert not result["bridge_ready"]
    assert bridge["rc"] == 1, bridge  # a clear refusal, not a crash
    assert "DDS Security refused this participant's keystore" in bridge["stderr"]
    assert "enclaves/K10Red" in bridge["stderr"]


def test_asset_without_its_keystore_files_refuses_to_start(programs, tmp_path):
    result = run_scenario(tmp_path, {"bridge": _bridge(programs), "cases": {},
                                     "bridge_env": {"RAPID_SECURITY_KEYSTORE": str(tmp_path / "none")}})
    assert not result["bridge_ready"] and result["bridge"]["rc"] == 1
    assert "cannot read identity_ca.cert.pem, cert.pem, key.pem" in result["bridge"]["stderr"]


