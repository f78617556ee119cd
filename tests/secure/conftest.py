"""Fixtures of the DDS Security tests, made once per session: keystores (`rapidgen secure`
on a deployment of K10 and Chariot), variants of enclaves an attacker or an accident
makes (expired certificate, tampered permissions, another CA), and the programs (K10's
generated bridge with the runtime's security hook, and tests/secure/cpp/ground.cpp)."""
from __future__ import annotations

import contextlib
import datetime
import io
import json
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DEPLOYMENT = """\
version: 1
assets: [{k10}, {chariot}]
domains: [{domain}]
ground:
  - {{source: RapidWorkbench, command: [K10Red], watch: ["*"], audit: [K10Red]}}
  - {{source: ChariotCrewDisplay, command: [Chariot]}}
  - {{source: ScienceBackroom, command: ["*"]}}
  - {{source: Outsider, watch: [K10Red]}}
  - {{source: Conformance, audit: [K10Red]}}
"""
DOMAIN = 124  # one of this suite's domains (the live tests run in a private namespace anyway)


def secure(*args: str) -> subprocess.CompletedProcess:
    """`rapidgen secure ARGS` in this process (the console's start-up is most of a run's time
    on a loaded machine; test_cli_process runs the real command once)."""
    from rapidgen.cli import main
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(["secure", *args])
        except SystemExit as exc:  # argparse
            code = int(exc.code or 0)
    return subprocess.CompletedProcess(["rapidgen", "secure", *args], code, out.getvalue(), err.getvalue())


def secure_process(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "rapidgen", "secure", *args], capture_output=True, text=True,
                          cwd=ROOT, timeout=120)


def exited(rc: int, code: int, what: object) -> None:
    """The process ended itself with `code`; a negative rc is the signal that killed it (a
    SIGSEGV at exit printed nothing wrong before it: rapidgen/live/teardown.py)."""
    if rc < 0:
        pytest.fail(f"killed by {signal.Signals(-rc).name} ({rc}) instead of exiting {code}: {what}")
    assert rc == code, what


def write_deployment(folder: Path, text: str = DEPLOYMENT) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "deploy.yaml"
    assets = ROOT / "specs" / "assets"
    path.write_text(text.format(k10=assets / "k10.yaml", chariot=assets / "chariot.yaml", domain=DOMAIN),
                    encoding="utf-8")
    return path


@pytest.fixture(scope="session")
def keystores(tmp_path_factory) -> dict[str, Path]:
    """"main": the deployment's keystore; "other": the same deployment under other CAs;
    "variants": enclaves made wrong on purpose (expired, tampered) beside main's."""
    base = tmp_path_factory.mktemp("keystores")
    dep = write_deployment(base)
    out = {"deployment": dep}
    for name in ("main", "other"):
        res = secure(str(dep), "-k", str(base / name))
        assert res.returncode == 0, res.stderr
        out[name] = base / name
    variants = base / "variants" / "enclaves"
    main = out["main"] / "enclaves"
    # A certificate the right CA signed, expired yesterday.
    from rapidgen.secure import pki
    ca = pki.load_pair(out["main"] / "public" / "identity_ca.cert.pem",
                       out["main"] / "private" / "identity_ca.key.pem")
    expired = variants / "expired"
    shutil.copytree(main / "RapidWorkbench", expired)
    now = pki.now()
    pair = pki.issue(ca, "RapidWorkbench", now - datetime.timedelta(days=30), now - datetime.timedelta(days=1))
    pki.write_private(expired / "cert.pem", pki.cert_pem(pair.cert))
    pki.write_private(expired / "key.pem", pki.key_pem(pair.key))
    # A ground tool that widened its own permissions: Chariot's partition became K10Red's.
    tampered = variants / "tampered"
    shutil.copytree(main / "ChariotCrewDisplay", tampered)
    _tamper(tampered / "permissions.p7s", b"<partition>Chariot</partition>", b"<partition>K10Red</partition>")
    # The asset's own permissions edited by hand (granting itself another partition).
    asset = base / "tampered_asset"
    shutil.copytree(out["main"], asset)
    _tamper(asset / "enclaves" / "K10Red" / "permissions.p7s", b"<partition>K10Red</partition>",
            b"<partition>*</partition>")
    out["variants"] = variants
    out["tampered_asset"] = asset
    return out


def _tamper(path: Path, old: bytes, new: bytes) -> None:
    data = path.read_bytes()
    assert old in data
    path.write_bytes(data.replace(old, new))


@pytest.fixture(scope="session")
def programs(tmp_path_factory) -> dict[str, Path]:
    """K10's generated bridge (with the runtime's security hook: the seeds' build's, shared
    with the other C++ tiers) and secure_ground; skips when RAPIDGEN_CPP_SEEDS leaves out k10."""
    from tests.cpp_runtime import build as B
    return B.once(tmp_path_factory, "secure", lambda: _programs(tmp_path_factory))  # type: ignore[no-any-return]


def _programs(tmp_path_factory) -> dict[str, Path]:
    from tests.cpp_runtime import build as B
    runtime = B.runtime_dir(tmp_path_factory)
    k10 = B.k10_bridge(tmp_path_factory)
    out = B.base(tmp_path_factory) / "secure"
    B.configure(ROOT / "tests" / "secure" / "cpp", out, f"-Drapid_runtime_cpp_DIR={runtime}",
                f"-DK10_DIR={B.generated(tmp_path_factory, 'k10')}", f"-DK10_TYPES={k10['types']}")
    B.build(out, "secure_ground")
    profiles = out / "rapid_qos_profiles.xml"
    # The generated Fast DDS profiles (the bridge carries the same built in): rapid_local is loopback only.
    B.run([sys.executable, "-m", "rapidgen", "generate", str(ROOT / "specs" / "assets" / "k10.yaml"), "--lang", "qos",
           "-o", str(out / "qos")])
    shutil.copy(next((out / "qos").rglob("fastdds/rapid_qos_profiles.xml")), profiles)
    return {"bridge": k10["bridge"], "ground": out / "secure_ground", "profiles": profiles}


def run_scenario(tmp: Path, spec: dict) -> dict:
    """tests/secure/scenario.py in a private network namespace (only lo): its JSON result."""
    if shutil.which("unshare") is None:
        pytest.fail("unshare (util-linux) is needed: the live tests run in a private network namespace")
    path = tmp / "scenario.json"
    path.write_text(json.dumps(spec), encoding="utf-8")
    res = subprocess.run(["unshare", "-n", sys.executable, "-m", "tests.secure.scenario", str(path)],
                         capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert res.returncode == 0, res.stderr[-4000:]
    return json.loads(res.stdout)  # type: ignore[no-any-return]
