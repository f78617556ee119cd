"""The `wan` transport on loopback, with the generated files.

- Fast DDS over TCP: two programs that only know a `fastdds discovery` server (run from
  the generated rapid_wan_tcp_server profile) exchange samples; without the server
  they do not.
- Fast DDS and Cyclone DDS over UDP unicast: static peers, well-known (fixed) ports,
  no multicast socket on either side; the Cyclone side takes its QoS (partition
  included) from the generated DDS-XML.

Ports come from the tests' domain ids. The TCP exchange runs in a private network
namespace that has only `lo` (the shipped `wan` transport as is, its ports changed);
where no namespace can be made, and for the UDP exchange, the transport is pinned to
127.0.0.1 with the library's own `interfaces` setting.
"""
from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from tests.qos.conftest import (DOMAIN_NEGATIVE_TCP, DOMAIN_TCP, DOMAIN_UDP_WAN, ECHO_ALL, PYTHON, ROVER, render,
                                tcp_port, udp_ports, variant, write_tree)

HERE = Path(__file__).resolve().parent
PROFILE = "RapidReliableQos"


def private_namespace() -> list[str] | None:
    """A command prefix running its command in a new network namespace with only `lo` up."""
    if shutil.which("unshare") is None or shutil.which("ip") is None:
        return None
    prefix = ["unshare", "-n", "--", "sh", "-c", 'ip link set lo up && exec "$0" "$@"']
    ok = subprocess.run([*prefix, "true"], capture_output=True, timeout=10).returncode == 0
    return prefix if ok else None


def tcp_sites(tmp_path: Path, domain: int, pinned: bool) -> tuple[Path, Path, int]:
    """Two sites' files: `a` accepts TCP connections, `b` only connects out."""
    server, listen = tcp_port(domain, 0), tcp_port(domain, 2)
    pin = {"interfaces": ["127.0.0.1"]} if pinned else {}
    a = write_tree(render(variant(server_port=server, listening_port=listen, **pin), ROVER), tmp_path / "a")
    b = write_tree(render(variant(server_port=server, listening_port=0, **pin), ROVER), tmp_path / "b")
    return a, b, server


def fastdds_xml(site: Path) -> str:
    return str(site / "fastdds" / "rapid_qos_profiles.xml")


def run_tcp_exchange(probe, tmp_path: Path, domain: int, with_server: bool, attempts: int):
    """The exchange of tcp_exchange.py: in a private network namespace (the shipped `wan`
    transport, only its ports changed) when this machine allows one, else on the host
    with the transport pinned to 127.0.0.1."""
    if shutil.which("fastdds") is None:
        pytest.fail("the fastdds tool is needed (Debian fastdds-tools; scripts/setup.sh installs it)")
    prefix = private_namespace()
    a, b, port = tcp_sites(tmp_path, domain, pinned=prefix is None)
    assert f"<physical_port>{port}</physical_port>" in Path(fastdds_xml(a)).read_text()
    args = [PYTHON, str(HERE / "tcp_exchange.py"), str(probe), fastdds_xml(a), fastdds_xml(b), str(domain),
            str(attempts)] + ([] if with_server else ["--no-server"])
    res = subprocess.run([*(prefix or []), *args], capture_output=True, text=True, timeout=150)
    return res, prefix is not None


def test_fastdds_tcp_through_a_discovery_server(probe, tmp_path):
    # Fast DDS 2.9.1's TCP logical-port negotiation between two clients sometimes stalls
    # at start-up (1 run in 2 to 1 in 10 here, more under CPU load; TCP fixes landed
    # upstream after 2.9): an attempt that exchanged nothing in 5 s is retried with fresh
    # processes, up to 6 times. A working attempt exchanges within about a second.
    res, isolated = run_tcp_exchange(probe, tmp_path, DOMAIN_TCP, True, 6)
    assert res.returncode == 0, res.stdout + res.stderr
    assert "Server is running" in res.stdout and "TCPv4:[" in res.stdout
    assert "ping: received 5" in res.stdout and "echo: fastdds ping" in res.stdout
    print(f"TCP exchange ({'private namespace' if isolated else 'pinned to 127.0.0.1'}):",
          [line for line in res.stdout.splitlines() if line.startswith("attempt")])


def test_fastdds_tcp_clients_do_not_meet_without_the_server(probe, tmp_path):
    res, _ = run_tcp_exchange(probe, tmp_path, DOMAIN_NEGATIVE_TCP, False, 1)
    assert res.returncode == 1, res.stdout + res.stderr
    assert "ping: received 0" in res.stdout


def test_fastdds_and_cyclone_over_udp_unicast_without_multicast(probe, procs, tmp_path):
    site = write_tree(render(variant(interfaces=["127.0.0.1"]), ROVER), tmp_path / "site")
    wan = (site / "cyclonedds" / "wan.xml").read_text()
    assert "<AllowMulticast>false</AllowMulticast>" in wan and '<Peer Address="127.0.0.1"/>' in wan
    domain = DOMAIN_UDP_WAN
    # The echo answers every ping for its 30 s (ECHO_ALL), not only the first 10 (beside a CPU hog
    # the first echo was lost and the pinger got 9 of 10)
    echo = procs.start("fastdds", [str(probe), "echo", fastdds_xml(site), str(domain), "rapid_wan", PROFILE, "30",
                                   ECHO_ALL], timeout=40)
    assert procs.wait_for(echo, "ready", 10), procs.log(echo)
    cyclone = procs.start("cyclone", [PYTHON, str(HERE / "cyclone_peer.py"), "ping",
                                      str(site / "dds-xml" / "rapid_qos.xml"), str(domain), PROFILE, "30", "10"],
                          timeout=40, env={"CYCLONEDDS_URI": f"file://{site / 'cyclonedds' / 'wan.xml'}"})
    assert procs.wait_for(cyclone, "got ", 30), procs.log(cyclone) + procs.log(echo)
    # Both sides talking: every UDP socket they hold is on a well-known unicast port of
    # the domain (or an ephemeral sender); none on the multicast ports d0/d2.
    base = 7400 + 250 * domain
    fixed = {base + off + 2 * i for off in (10, 11) for i in range(10)}
    for proc in (echo, cyclone):
        ports = udp_ports(proc.pid)
        assert ports & {base + 10 + 2 * i for i in range(10)}, (proc.args, ports)
        assert ports & {base + 11 + 2 * i for i in range(10)}, (proc.args, ports)
        assert not ports & {base, base + 1}, (proc.args, ports)
        assert all(p in fixed or p >= 32768 for p in ports), (proc.args, ports)
    assert procs.wait(cyclone, 40) == 0, procs.log(cyclone) + procs.log(echo)
    assert "received 10" in procs.log(cyclone) and "echo: cyclone ping" in procs.log(cyclone)
    assert "got " in procs.log(echo)
