"""Fast DDS 2.9 reads what the qos back end writes (tests/qos/cpp/qos_probe.cpp).

The probe loads the generated XML (any Fast DDS error or warning while loading fails
it), creates a participant with the `local` profile, then a publisher, subscriber,
writer and reader with every RAPID profile, and prints their QoS: it must equal the
spec, with the Fast DDS additions (resource limits, SYNCHRONOUS reliable writers). Participant profiles of every transport are read back without being created.
"""
from __future__ import annotations

import json
import subprocess

import pytest

from tests.qos.conftest import (DOMAIN_FASTDDS_EXCHANGE, DOMAIN_FASTDDS_QOS, ECHO_ALL, ROVER, render, variant,
                                write_tree)
from tests.qos.test_spec import SECTION_6, expected

PARTICIPANTS = ["rapid_local", "rapid_lan", "rapid_wan", "rapid_wan_tcp", "rapid_wan_tcp_server"]
SIMPLE, CLIENT, SERVER = 1, 3, 4  # eprosima::fastrtps::rtps::DiscoveryProtocol_t


def run_probe(probe, *args: str) -> list[dict]:
    res = subprocess.run([str(probe), *args], capture_output=True, text=True, timeout=60)
    assert res.returncode == 0, f"probe exit {res.returncode}\n{res.stdout}\n{res.stderr}"
    return [json.loads(line) for line in res.stdout.splitlines() if line.startswith("{")]


def test_writers_and_readers_of_every_profile_have_the_spec_qos(probe, library, rover_dir):
    names = [p.name for p in library.profiles]
    rows = run_probe(probe, "qos", str(rover_dir / "fastdds" / "rapid_qos_profiles.xml"), str(DOMAIN_FASTDDS_QOS),
                     "rapid_local", *names)
    got = {(r["profile"], r["side"]): r for r in rows if "profile" in r}
    assert len(got) == 2 * len(names)
    for name in names:
        for side, want in zip(("writer", "reader"), library.effective(name)):
            row = got[(name, side)]
            assert (row["reliability"], row["durability"], row["history"]) == \
                (want.reliability, want.durability, want.history.kind), (name, side)
            if want.history.kind == "keep_last":
                assert row["depth"] == want.history.depth, (name, side)
            assert row["partition"] == ["QosTestRover"]
            if side == "writer":  # Fast DDS: reliable writers SYNCHRONOUS whatever the library says
                assert want.publish_mode == "asynchronous"
                assert row["publish_mode"] == ("synchronous" if want.reliability == "reliable" else "asynchronous")
            # every RAPID type is keyed: no instance limit, the history depth per instance
            per = want.history.depth if want.history.kind == "keep_last" else 400
            assert (row["max_samples"], row["max_instances"], row["max_samples_per_instance"]) == (0, 0, per)
    for name in SECTION_6:  # and, directly, rapid-protocol.md section 6
        for side in ("writer", "reader"):
            row = got[(name, side)]
            rel, dur, (kind, depth) = expected(name, side)
            assert (row["reliability"], row["durability"], row["history"]) == (rel, dur, kind)
            assert depth is None or row["depth"] == depth


def test_participant_profiles_of_every_transport(probe, library, rover_dir):
    rows = run_probe(probe, "pqos", str(rover_dir / "fastdds" / "rapid_qos_profiles.xml"), "-", *PARTICIPANTS)
    got = {r["participant"]: r for r in rows}
    ports = library.participant("RapidDefaultQos").ports
    for name in PARTICIPANTS:
        r = got[name]
        assert (r["port_base"], r["domain_gain"], r["participant_gain"], r["d0"], r["d1"], r["d2"], r["d3"]) == \
            (ports.base, ports.domain_gain, ports.participant_gain, ports.d0, ports.d1, ports.d2, ports.d3)
        assert r["builtin_transports"] is False and r["transports"] == 1  # no SHM, no default UDP
        assert r["multicast_locators"] == 0
    for name in ("rapid_local", "rapid_lan", "rapid_wan"):
        assert got[name]["discovery"] == SIMPLE
    assert got["rapid_lan"]["max_message_size"] == got["rapid_wan"]["max_message_size"] == 1250
    # loopback: Fast DDS's default, its receive buffer too (a capped one drops RustDDS's 64 KiB datagrams)
    assert got["rapid_local"]["max_message_size"] == 65500
    assert got["rapid_local"]["initial_peers"] == 1 and got["rapid_wan"]["initial_peers"] == 1
    assert got["rapid_wan_tcp"]["discovery"] == CLIENT and got["rapid_wan_tcp_server"]["discovery"] == SERVER


def test_library_without_asset_loads(probe, library, tmp_path):
    folder = write_tree(render(library, None), tmp_path)
    rows = run_probe(probe, "pqos", str(folder / "fastdds" / "rapid_qos_profiles.xml"), "-", *PARTICIPANTS)
    assert len(rows) == len(PARTICIPANTS)


def test_broken_xml_is_refused(probe, rover_files, tmp_path):
    """The probe really checks: an unknown element in a profile fails the load."""
    text = rover_files["fastdds/rapid_qos_profiles.xml"].replace("<maxMessageSize>", "<maxMesageSize>", 1)
    text = text.replace("</maxMessageSize>", "</maxMesageSize>", 1)
    path = tmp_path / "broken.xml"
    path.write_text(text)
    res = subprocess.run([str(probe), "pqos", str(path), "-", "rapid_local"], capture_output=True, text=True,
                         timeout=60)
    assert res.returncode != 0


@pytest.mark.parametrize("profile", sorted(DOMAIN_FASTDDS_EXCHANGE))
def test_local_exchange_between_two_fastdds_programs(probe, rover_dir, procs, profile):
    xml = str(rover_dir / "fastdds" / "rapid_qos_profiles.xml")
    domain = str(DOMAIN_FASTDDS_EXCHANGE[profile])  # its own domain, so its own RTPS ports
    echo = procs.start("echo", [str(probe), "echo", xml, domain, "rapid_local", profile, "15", ECHO_ALL], timeout=25)
    assert procs.wait_for(echo, "ready", 10), procs.log(echo)
    ping = procs.start("ping", [str(probe), "ping", xml, domain, "rapid_local", profile, "15", "3"], timeout=25)
    assert procs.wait(ping, 25) == 0, procs.log(ping) + procs.log(echo)
    assert "received 3" in procs.log(ping)


def test_a_slow_link_reaches_fast_dds_timers_and_lease(probe, library, tmp_path):
    """A transport with rtt/lease (docs/qos.md "Slow links"): its participant carries the lease,
    the announcement period and `rapid.link`; every RAPID profile has a copy <profile>@wan
    whose reliable writers heartbeat once per round trip; the plain profiles keep Fast DDS's
    defaults (heartbeat 3 s, lease 20 s), as do transports without rtt."""
    spec = variant(rtt=2.6, lease=120)
    xml = str(write_tree(render(spec, ROVER), tmp_path) / "fastdds" / "rapid_qos_profiles.xml")
    got = {r["participant"]: r for r in run_probe(probe, "pqos", xml, "-", *PARTICIPANTS)}
    assert (got["rapid_wan"]["lease"], got["rapid_wan"]["announcement"], got["rapid_wan"]["link"]) == \
        (120.0, 5.2, "wan")
    assert got["rapid_wan_tcp"]["link"] == "wan" and got["rapid_wan_tcp"]["lease"] == 120.0
    assert (got["rapid_local"]["lease"], got["rapid_local"]["announcement"], got["rapid_local"]["link"]) == \
        (20.0, 3.0, "")
    names = [p.name for p in library.profiles]
    rows = run_probe(probe, "qos", xml, str(DOMAIN_FASTDDS_QOS), "rapid_local", *names,
                     *(f"{n}@wan" for n in names))
    writers = {r["profile"]: r for r in rows if r.get("side") == "writer"}
    readers = {(r["profile"]) for r in rows if r.get("side") == "reader"}
    assert len(writers) == len(readers) == 2 * len(names)
    for name in names:
        plain, linked = writers[name], writers[f"{name}@wan"]
        assert plain["heartbeat"] == 3.0 and plain["nack_suppression"] == 0.0
        assert (linked["heartbeat"], linked["nack_suppression"]) == (2.6, pytest.approx(2.08))
        if linked["reliability"] == "reliable":
            assert linked["max_blocking"] == pytest.approx(5.2) and plain["max_blocking"] == pytest.approx(0.1)
        # the copy is the same profile otherwise
        strip = ("profile", "heartbeat", "nack_suppression", "max_blocking")
        assert {k: v for k, v in plain.items() if k not in strip} == {k: v for k, v in linked.items() if k not in strip}


def test_lease_alone_keeps_the_default_timers(probe, tmp_path):
    xml = str(write_tree(render(variant(lease=2.5), None), tmp_path) / "fastdds" / "rapid_qos_profiles.xml")
    got = {r["participant"]: r for r in run_probe(probe, "pqos", xml, "-", "rapid_wan")}
    assert (got["rapid_wan"]["lease"], got["rapid_wan"]["announcement"], got["rapid_wan"]["link"]) == (2.5, 2.0, "")
    assert "@wan" not in open(xml, encoding="utf-8").read()
