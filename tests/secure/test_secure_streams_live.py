"""Setpoint streams under DDS Security, live (issue 35 item 5): seed 001's hand pose. The
simulated X-Arm-2 bridge writes handPose at 500 Hz with its enclave (granted to publish the
stream in its partition), Robonaut 2's bridge reads it with its own (granted to subscribe in
XArm2's partition), both from `rapidgen secure`, in a private network namespace (only lo),
Fast DDS's plugins on. The same Robonaut 2 bridge with permissions the same CA signed but
without the stream's grant (what `rapidgen secure` wrote before) gets nothing."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from rapidgen.secure import pki
from tests.cpp_runtime import build as B
from tests.secure.conftest import ROOT, run_scenario, secure

DOMAIN = 79  # (the scenario's namespace has only lo)
HAND_POSE = b"""        <subscribe>
          <topics>
            <topic>rapid_position_sample-handPose</topic>
          </topics>
          <partitions>
            <partition>XArm2</partition>
          </partitions>
        </subscribe>
"""


def _without_stream_grant(ks: Path, out: Path) -> Path:
    """Robonaut 2's enclave with its stream grant taken out, signed by the keystore's CA."""
    import shutil
    shutil.copytree(ks / "enclaves" / "Robonaut2", out)
    xml = (out / "permissions.xml").read_bytes()
    assert HAND_POSE in xml  # what rapidgen secure grants now
    xml = xml.replace(HAND_POSE, b"")
    ca = pki.load_pair(ks / "public" / "permissions_ca.cert.pem", ks / "private" / "permissions_ca.key.pem")
    pki.write_private(out / "permissions.xml", xml)
    pki.write_private(out / "permissions.p7s", pki.sign_smime(xml, ca))
    return out


@pytest.fixture(scope="module")
def hand_pose(tmp_path_factory) -> dict:
    bridges = B.stream_bridges(tmp_path_factory)
    tmp = tmp_path_factory.mktemp("secure-streams")
    dep = tmp / "deploy.yaml"
    dep.write_text(f"version: 1\nassets: [{ROOT / 'specs/assets/xarm2.yaml'}, {ROOT / 'specs/assets/robonaut2.yaml'}]"
                   f"\ndomains: [{DOMAIN}]\n", encoding="utf-8")
    ks = tmp / "ks"
    res = secure(str(dep), "-k", str(ks))
    assert res.returncode == 0, res.stderr
    variant = _without_stream_grant(ks, tmp / "variant" / "Robonaut2")
    env = {"RAPID_SECURITY_KEYSTORE": str(ks)}
    reader = [str(bridges["robonaut2"]), "--domain", str(DOMAIN), "--seconds", "10", "--no-journal"]
    return run_scenario(tmp, {
        "bridge": [str(bridges["xarm2"]), "--simulate", "--domain", str(DOMAIN), "--seconds", "120", "--no-journal"],
        "bridge_env": env,
        "cases": {"granted": {"argv": reader, "env": env},
                  "not_granted": {"argv": reader, "env": {**env, "RAPID_SECURITY_ENCLAVE": str(variant)}}}})


def _samples(case: dict) -> int | None:
    m = re.search(r"stream handPose: (\d+) samples", case["stdout"] + case["stderr"])
    return int(m.group(1)) if m else None


def test_the_granted_reader_gets_the_writers_samples_under_the_keystore(hand_pose):
    assert hand_pose["bridge_ready"], hand_pose["bridge"]
    case = hand_pose["cases"]["granted"]
    out = case["stdout"] + case["stderr"]
    assert "stream handPose active" in out, out[-3000:]
    n = _samples(case)
    assert n is not None and n > 100, out[-3000:]  # 500 Hz for several seconds (best effort, a loaded machine)


def test_a_reader_without_the_grant_gets_nothing(hand_pose):
    case = hand_pose["cases"]["not_granted"]
    out = case["stdout"] + case["stderr"]
    assert "stream handPose active" not in out, out[-3000:]
    # refused where Fast DDS's access control refuses it: its own plugin does not let it make
    # the reader ("topic not found in allow rule"), and the bridge ends with a clear error
    # (it used to abort with "pure virtual method called" as it unwound)
    assert "rapid_position_sample-handPose topic not found in allow rule" in out, out[-3000:]
    assert "cannot create the reader of stream handPose" in out and case["rc"] == 1, (case["rc"], out[-3000:])
    assert "pure virtual" not in out and "terminate called" not in out
