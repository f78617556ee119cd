"""The loopback guards: no DDS process of the live test or the demo starts unless
CYCLONEDDS_URI names one file that pins Cyclone to 127.0.0.1 with multicast off
(shared/dds-local/README.md). Nothing here starts DDS."""
from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.python_backend.fill import REPO
from tests.python_backend.live_peer import loopback_refusal as peer_refusal

DEMO_LIVE = Path(REPO) / "scripts" / "demo_live.py"
REFERENCE = Path(REPO) / "tests" / "interop" / "cyclonedds-loopback.xml"
GOOD = REFERENCE.read_text(encoding="utf-8")


def _demo_module():
    spec = importlib.util.spec_from_file_location("rapidgen_test_demo_live", DEMO_LIVE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


demo_refusal = _demo_module().loopback_refusal
GUARDS = {"live_peer": peer_refusal, "demo_live": demo_refusal}


def _config(tmp_path: Path, text: str, name: str = "c.xml") -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return f"file://{path}"


@pytest.mark.parametrize("guard", GUARDS, ids=list(GUARDS))
def test_loopback_files_are_accepted(guard):
    assert GUARDS[guard](f"file://{REFERENCE}") is None
    for asset in ("robonaut2", "k10"):
        local = Path(REPO) / "generated" / asset / "qos" / "cyclonedds" / "local.xml"
        assert GUARDS[guard](f"file://{local}") is None, local


BAD_FILES = {
    "multicast on": GOOD.replace("<AllowMulticast>false</AllowMulticast>", "<AllowMulticast>true</AllowMulticast>"),
    "multicast default": GOOD.replace("<AllowMulticast>false</AllowMulticast>", ""),
    "multicast off only in a comment": GOOD.replace("<AllowMulticast>false</AllowMulticast>",
                                                    "<!-- <AllowMulticast>false</AllowMulticast> -->"),
    "multicast twice, once on": GOOD.replace("</General>", "<AllowMulticast>spdp</AllowMulticast></General>"),
    "no 127.0.0.1": GOOD.replace("127.0.0.1", "192.0.2.7"),
    "no interface pinned": GOOD.replace('<NetworkInterface address="127.0.0.1"/>', ""),
    "another interface too": GOOD.replace('<NetworkInterface address="127.0.0.1"/>',
                                          '<NetworkInterface address="127.0.0.1"/><NetworkInterface name="eth0"/>'),
    "a peer elsewhere": GOOD.replace('<Peer Address="127.0.0.1"/>',
                                     '<Peer Address="127.0.0.1"/><Peer Address="192.0.2.7"/>'),
    "a second domain not pinned": GOOD.replace("</CycloneDDS>", '<Domain Id="7"><General>'
                                               "<AllowMulticast>false</AllowMulticast></General></Domain></CycloneDDS>"),
    "not a Cyclone config": '<dds><Domain><AllowMulticast>false</AllowMulticast>'
                            '<NetworkInterface address="127.0.0.1"/></Domain></dds>',
    "not XML": "127.0.0.1 <AllowMulticast>false</AllowMulticast>",
    "not text": b"\xff\xfe<CycloneDDS/>",
}


@pytest.mark.parametrize("guard", GUARDS, ids=list(GUARDS))
@pytest.mark.parametrize("case", BAD_FILES, ids=list(BAD_FILES))
def test_files_that_could_leave_loopback_are_refused(guard, case, tmp_path):
    path = tmp_path / "c.xml"
    content = BAD_FILES[case]
    path.write_bytes(content if isinstance(content, bytes) else content.encode("utf-8"))
    refusal = GUARDS[guard](f"file://{path}")
    assert refusal and str(path) in refusal, (case, refusal)


BAD_URIS = {
    "unset": None,
    "empty": "",
    "inline XML": GOOD.split("\n", 1)[1],
    "inline XML after spaces": "  <CycloneDDS><Domain/></CycloneDDS>",
    "not a file": "file:///nonexistent/cyclonedds.xml",
    "a folder": f"file://{REPO}",
    "http": "http://127.0.0.1/cyclonedds.xml",
    "a list": f"file://{REFERENCE},file://{REFERENCE}",
    "a variable": "file://${HOME}/cyclonedds.xml",
    "NUL": f"file://{REFERENCE}\x00",
}


@pytest.mark.parametrize("guard", GUARDS, ids=list(GUARDS))
@pytest.mark.parametrize("case", BAD_URIS, ids=list(BAD_URIS))
def test_uris_that_are_not_one_loopback_file_are_refused(guard, case):
    refusal = GUARDS[guard](BAD_URIS[case])
    assert isinstance(refusal, str) and refusal, case


def test_live_peer_refuses_to_start_without_loopback(tmp_path):
    env = dict(os.environ, CYCLONEDDS_URI=_config(tmp_path, BAD_FILES["multicast on"]), PYTHONPATH=REPO)
    res = subprocess.run([sys.executable, "-m", "tests.python_backend.live_peer", "sub", "--domain", "43",
                          "--partition", "x", "--timeout", "1"], cwd=REPO, env=env, capture_output=True,
                         text=True, timeout=60)
    assert res.returncode != 0
    assert "refusing to start DDS" in res.stderr and "Traceback" not in res.stderr


@pytest.mark.parametrize("uri", ["<CycloneDDS><Domain/></CycloneDDS>", "udp://127.0.0.1", "file:///nonexistent.xml",
                                 None], ids=["inline", "not-a-file-uri", "missing", "unset"])
def test_demo_refuses_clearly_without_a_traceback(uri):
    env = dict(os.environ)
    env.pop("CYCLONEDDS_URI", None)
    if uri is not None:
        env["CYCLONEDDS_URI"] = uri
    res = subprocess.run([sys.executable, str(DEMO_LIVE), "ground", "specs/assets/robonaut2.yaml",
                          "generated/robonaut2", "--seconds", "1"], cwd=REPO, env=env, capture_output=True,
                         text=True, timeout=60)
    assert res.returncode == 2, res.stderr
    assert "refusing to start DDS" in res.stderr and "local.xml" in res.stderr
    assert "Traceback" not in res.stderr
