"""A site's QoS library with `rtt` and `lease` (docs/qos.md, "Slow links"): the Cyclone
file carries the timers they imply and still validates against cyclonedds.xsd; the
shipped library gives none of them (its files stay the middleware's defaults)."""
from __future__ import annotations

import shutil
import subprocess
import xml.etree.ElementTree as ET

import pytest

from tests.field.site import site_library
from tests.qos.test_cyclone import cyclone_xsd  # noqa: F401 (the fixture)

NS = {"c": "https://cdds.io/config"}


def _get(path, root) -> str | None:
    node = root.find(path, NS)
    return None if node is None else node.text


def test_rtt_and_lease_become_cyclone_timers_and_validate(tmp_path, cyclone_xsd):  # noqa: F811
    config = site_library(tmp_path, rtt=2.6, lease=120)
    root = ET.parse(config).getroot()
    d = "c:Domain/"
    assert _get(d + "c:Discovery/c:LeaseDuration", root) == "120000ms"
    assert _get(d + "c:Discovery/c:SPDPInterval", root) == "5200ms"
    hb = root.find(d + "c:Internal/c:HeartbeatInterval", NS)
    assert hb is not None and hb.text == "2600ms" and hb.get("minsched") == "2600ms"
    assert _get(d + "c:Internal/c:AutoReschedNackDelay", root) == "5200ms"
    peers = [p.get("Address") for p in root.findall(d + "c:Discovery/c:Peers/c:Peer", NS)]
    assert peers == ["10.231.0.1", "10.231.0.2"]
    if shutil.which("xmllint") is None:
        pytest.fail("xmllint is needed (Debian libxml2-utils; scripts/setup.sh installs it)")
    res = subprocess.run(["xmllint", "--noout", "--schema", str(cyclone_xsd), str(config)], capture_output=True,
                         text=True, timeout=30)
    assert res.returncode == 0 and "validates" in res.stderr, res.stderr


def test_lease_alone_and_the_spdp_interval_bounds(tmp_path):
    root = ET.parse(site_library(tmp_path, rtt=None, lease=30)).getroot()
    assert _get("c:Domain/c:Discovery/c:LeaseDuration", root) == "30000ms"
    assert root.find("c:Domain/c:Internal", NS) is None and _get("c:Domain/c:Discovery/c:SPDPInterval", root) is None
    short = ET.parse(site_library(tmp_path, rtt=0.05, lease=4)).getroot()  # 5 s floor, 0.8 x lease ceiling
    assert _get("c:Domain/c:Discovery/c:SPDPInterval", short) == "3200ms"
    far = ET.parse(site_library(tmp_path, rtt=40.0, lease=3600)).getroot()  # 30 s ceiling
    assert _get("c:Domain/c:Discovery/c:SPDPInterval", far) == "30000ms"


def test_the_shipped_library_keeps_the_middleware_defaults(tmp_path):
    root = ET.parse(site_library(tmp_path, rtt=None, lease=None)).getroot()
    assert root.find("c:Domain/c:Internal", NS) is None
    assert _get("c:Domain/c:Discovery/c:LeaseDuration", root) is None


def test_rtt_out_of_range_is_a_located_schema_error(tmp_path):
    from rapidgen.diagnostics import DiagnosticSink
    from rapidgen.qos.spec import load_qos
    lib = tmp_path / "bad.yaml"
    text = (site_library.__globals__["ROOT"] / "specs" / "qos" / "rapid.yaml").read_text()
    lib.write_text(text.replace("    max_participants_per_host: 10\n", "    max_participants_per_host: 10\n    rtt: -1\n"))
    sink = DiagnosticSink()
    assert load_qos(str(lib), sink) is None or sink.has_errors
    codes = [d.code for d in sink.diagnostics]
    assert "RG1602" in codes, codes
