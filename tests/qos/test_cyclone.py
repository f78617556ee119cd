"""Cyclone DDS reads what the qos back end writes.

- its QoS provider loads the DDS-XML and returns, for every profile, the spec's QoS;
- a participant runs with the generated `local` domain config, on its fixed ports;
- every domain config validates against cyclonedds.xsd (from the `cyclors` crate, whose
  bundled Cyclone DDS is 11.0.1 like the Python wheel).
"""
from __future__ import annotations

import glob
import os
import shutil
import subprocess
from pathlib import Path

import pytest
from cyclonedds.core import Policy
from cyclonedds.qos import Qos
from cyclonedds.qos_provider import QosProvider

from tests.qos.conftest import DOMAIN_CYCLONE_LOCAL, PYTHON, render, udp_ports, write_tree
from tests.qos.test_spec import SECTION_6, expected

HERE = Path(__file__).resolve().parent
CYCLORS = "0.4.0"  # bundles Cyclone DDS 11.0.1


def policies(p) -> list:
    out = [Policy.Reliability.Reliable(max_blocking_time=100_000_000) if p.reliability == "reliable"
           else Policy.Reliability.BestEffort,
           Policy.Durability.TransientLocal if p.durability == "transient_local" else Policy.Durability.Volatile,
           Policy.History.KeepAll if p.history.kind == "keep_all" else Policy.History.KeepLast(p.history.depth)]
    return out


@pytest.mark.parametrize("case", ["rover", "library"])
def test_qos_provider_returns_the_spec_for_every_profile(library, rover_dir, tmp_path, case):
    folder = rover_dir if case == "rover" else write_tree(render(library, None), tmp_path)
    provider = QosProvider(str(folder / "dds-xml" / "rapid_qos.xml"))
    for profile in library.profiles:
        key = f"{library.library}::{profile.name}"
        writer, reader = library.effective(profile.name)
        assert provider.get_datawriter_qos(key) == Qos(*policies(writer)).datawriter(), key
        assert provider.get_datareader_qos(key) == Qos(*policies(reader)).datareader(), key
        if profile.name in SECTION_6:  # and, directly, rapid-protocol.md section 6
            for side, got in (("writer", provider.get_datawriter_qos(key)),
                              ("reader", provider.get_datareader_qos(key))):
                rel, dur, (kind, depth) = expected(profile.name, side)
                assert got[Policy.Durability] == (Policy.Durability.TransientLocal if dur == "transient_local"
                                                  else Policy.Durability.Volatile)
                assert isinstance(got[Policy.Reliability], Policy.Reliability.Reliable if rel == "reliable"
                                  else type(Policy.Reliability.BestEffort))
                assert got[Policy.History] == (Policy.History.KeepAll if kind == "keep_all"
                                               else Policy.History.KeepLast(depth))
        if case == "rover":
            part = Qos(Policy.Partition(["QosTestRover"]))
            assert provider.get_publisher_qos(key) == part.publisher()
            assert provider.get_subscriber_qos(key) == part.subscriber()


def test_participant_runs_with_the_local_config(rover_dir, procs):
    uri = f"file://{rover_dir / 'cyclonedds' / 'local.xml'}"
    proc = procs.start("cyclone", [PYTHON, str(HERE / "cyclone_peer.py"), "participant", str(DOMAIN_CYCLONE_LOCAL),
                                   "3"], timeout=20, env={"CYCLONEDDS_URI": uri})
    assert procs.wait_for(proc, "ok", 15), procs.log(proc)
    ports = udp_ports(proc.pid)
    base = 7400 + 250 * DOMAIN_CYCLONE_LOCAL
    # `local`: participant index auto, so discovery and data sit on well-known unicast
    # ports; no multicast socket (d0, d2).
    assert any(base + 10 + 2 * i in ports for i in range(20)), ports
    assert any(base + 11 + 2 * i in ports for i in range(20)), ports
    assert base not in ports and base + 1 not in ports
    assert procs.wait(proc, 15) == 0, procs.log(proc)
    assert "error" not in procs.log(proc).lower()


def cargo_program() -> str | None:
    """cargo on PATH, else rustup's usual place (a shell that did not source ~/.cargo/env)."""
    found = shutil.which("cargo")
    if found:
        return found
    home = os.environ.get("CARGO_HOME", os.path.expanduser("~/.cargo"))
    candidate = Path(home) / "bin" / "cargo"
    return str(candidate) if os.access(candidate, os.X_OK) else None


@pytest.mark.parametrize("config, domain, why", [
    (None, DOMAIN_CYCLONE_LOCAL, "CYCLONEDDS_URI is not set"),
    ("lan.xml", DOMAIN_CYCLONE_LOCAL, "AllowMulticast"),
    ("wan.xml", DOMAIN_CYCLONE_LOCAL, "NetworkInterface"),  # shipped wan: no interface pinned
    ("local.xml", 0, "outside the QoS tier"),
    ("<CycloneDDS/>", DOMAIN_CYCLONE_LOCAL, "one config file"),
])
def test_cyclone_peer_refuses_configs_that_may_leave_loopback(rover_dir, config, domain, why):
    env = {k: v for k, v in os.environ.items() if k != "CYCLONEDDS_URI"}
    if config is not None:
        env["CYCLONEDDS_URI"] = config if config.startswith("<") else f"file://{rover_dir / 'cyclonedds' / config}"
    res = subprocess.run([PYTHON, str(HERE / "cyclone_peer.py"), "participant", str(domain), "0"], env=env,
                         capture_output=True, text=True, timeout=30)
    assert res.returncode == 2 and "refusing to run" in res.stderr and why in res.stderr, res.stderr
    assert "participant" not in res.stdout  # no DomainParticipant was created


@pytest.fixture(scope="session")
def cyclone_xsd(tmp_path_factory) -> Path:
    """cyclonedds.xsd from the `cyclors` crate's sources (cargo's registry, fetched if absent).

    Never skips: the schema check is a requirement, so a machine without cargo, or where
    the crate cannot be had, fails here with the reason. The fetch tries cargo's local
    cache first (`--offline`), then the registry."""
    def found():
        home = os.environ.get("CARGO_HOME", os.path.expanduser("~/.cargo"))
        hits = sorted(glob.glob(f"{home}/registry/src/*/cyclors-{CYCLORS}/cyclonedds/etc/cyclonedds.xsd"))
        return Path(hits[0]) if hits else None
    xsd = found()
    if xsd is not None:
        return xsd
    cargo = cargo_program()
    if cargo is None:
        pytest.fail(f"cargo is needed to fetch the cyclors {CYCLORS} crate, whose cyclonedds.xsd validates the "
                    "generated Cyclone DDS domain configs: install Rust (rustup) or Debian's `cargo` "
                    "(scripts/setup.sh installs it when no cargo is found)", pytrace=False)
    project = tmp_path_factory.mktemp("cyclors")
    (project / "src").mkdir()
    (project / "src" / "lib.rs").write_text("")
    (project / "Cargo.toml").write_text(
        '[package]\nname = "fetch-cyclors"\nversion = "0.0.0"\nedition = "2021"\n\n'
        f'[dependencies]\ncyclors = "={CYCLORS}"\n')
    errors = []
    # offline first: cargo's cache; then the registry (an old cargo without the sparse
    # protocol clones the whole index first, hence the long deadline)
    for extra, deadline in ((["--offline"], 120), ([], 900)):
        res = subprocess.run([cargo, "fetch", "--quiet", *extra], cwd=project, capture_output=True, text=True,
                             timeout=deadline)
        xsd = found()
        if xsd is not None:
            return xsd
        errors.append(f"$ cargo fetch {' '.join(extra)} (exit {res.returncode})\n{res.stderr[-1500:]}")
    pytest.fail(f"could not fetch the cyclors {CYCLORS} crate for cyclonedds.xsd:\n" + "\n".join(errors),
                pytrace=False)


@pytest.mark.parametrize("transport", ["local", "lan", "wan"])
def test_domain_config_validates_against_cyclonedds_xsd(rover_dir, cyclone_xsd, transport):
    if shutil.which("xmllint") is None:
        pytest.fail("xmllint is needed (Debian libxml2-utils; scripts/setup.sh installs it)")
    res = subprocess.run(["xmllint", "--noout", "--schema", str(cyclone_xsd),
                          str(rover_dir / "cyclonedds" / f"{transport}.xml")], capture_output=True, text=True, timeout=30)
    assert res.returncode == 0, res.stderr
    assert "validates" in res.stderr
