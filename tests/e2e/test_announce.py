"""End to end: an asset process announces its computed configs over Cyclone DDS with the
committed generated bindings; a late-joining ground process receives and checks them.
Real DDS processes, loopback only (the generated "local" transport), one DDS domain per case
(31, 32) so the two cases never see each other; QoS from the generated DDS-XML through
Cyclone's QoS provider, read by the generated package's QoS runtime (`<package>.qos`)."""
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[2]


@pytest.mark.parametrize("asset, domain", [("robonaut2", 31), ("k10", 32)])
def test_ground_receives_every_config_the_descriptor_computes(asset, domain):
    loopback = ROOT / "generated" / asset / "qos" / "cyclonedds" / "local.xml"
    env = dict(os.environ, CYCLONEDDS_URI=f"file://{loopback}")
    args = [f"specs/assets/{asset}.yaml", f"generated/{asset}", "--domain", str(domain)]
    script = str(ROOT / "scripts" / "demo_live.py")
    publisher = subprocess.Popen([sys.executable, script, "asset", *args, "--seconds", "10"], cwd=ROOT, env=env,
                                 stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        time.sleep(1.0)  # join late: the configs are transient-local
        ground = subprocess.run([sys.executable, script, "ground", *args, "--seconds", "15"], cwd=ROOT, env=env,
                                capture_output=True, text=True, timeout=60)
    finally:
        publisher.kill()
        published = publisher.communicate(timeout=30)[0]
    assert ground.returncode == 0, ground.stdout + ground.stderr + published
    announced = [ln for ln in published.splitlines() if "published" in ln]
    checked = [ln for ln in ground.stdout.splitlines() if "matches the descriptor" in ln]
    assert announced and len(checked) == len(announced)
    assert any("rapid::CommandConfig" in ln for ln in checked)
