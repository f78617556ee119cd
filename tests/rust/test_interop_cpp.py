"""Live interop on loopback: the generated Rust crate on RustDDS 0.15 and the generated C++
types on Fast DDS 2.9 exchange every RAPID message type (the same 21 topics and samples as
tests/cpp/test_interop.py: K10's topics plus JointConfig, JointSample and FileAnnounce) in
both directions, field-equal to the golden vector's `max` value.

The C++ side uses K10's generated Fast DDS profiles (the loopback participant `rapid_local`,
each topic's QoS) with their <partition> elements removed: RustDDS 0.15 has no Partition
QoS, so its endpoints live in the default partition (docs/rust-backend.md)."""
from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from pathlib import Path

from tests import peers
from tests.cpp.conftest import K10
from tests.cpp.test_interop import interop_lines

DOMAIN_RUST_TO_CPP = 75
DOMAIN_CPP_TO_RUST = 76
SECONDS = 25


FASTDDS_NS = "http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles"


def _without_partitions(src: Path, dst: Path) -> Path:
    ET.register_namespace("", FASTDDS_NS)
    tree = ET.parse(src)
    removed = 0
    for parent in tree.iter():
        for child in list(parent):
            if child.tag == f"{{{FASTDDS_NS}}}partition":
                parent.remove(child)
                removed += 1
    assert removed > 0, "the generated profiles carry the asset's partition"
    tree.write(dst, xml_declaration=True, encoding="UTF-8")
    return dst


def test_rust_and_cpp_exchange_every_message_type_both_ways(rust_peer, cpp_build, tmp_path):
    lines = interop_lines()
    assert len(lines) == 21
    stdin = "\n".join(lines) + "\n"
    xml = str(_without_partitions(K10 / "qos" / "fastdds" / "rapid_qos_profiles.xml", tmp_path / "profiles.xml"))
    env = dict(os.environ)
    env.pop("FASTDDS_DEFAULT_PROFILES_FILE", None)
    cpp, rust = str(cpp_build / "peer"), str(rust_peer)
    procs = {
        "cpp_sub": peers.start([cpp, "sub", xml, str(DOMAIN_RUST_TO_CPP), str(SECONDS)], stdin, env),
        "rust_pub": peers.start([rust, "pub", str(DOMAIN_RUST_TO_CPP), str(SECONDS)], stdin, env),
        "rust_sub": peers.start([rust, "sub", str(DOMAIN_CPP_TO_RUST), str(SECONDS)], stdin, env),
        "cpp_pub": peers.start([cpp, "pub", xml, str(DOMAIN_CPP_TO_RUST), str(SECONDS)], stdin, env),
    }
    peers.exchange(procs, lines, SECONDS)
