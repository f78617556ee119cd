"""Live interop on loopback: the generated Rust crate on RustDDS 0.15 and the generated
Python bindings on cyclonedds exchange every RAPID message type (K10's 18 topics with their
generated QoS, plus FileAnnounce, JointConfig and JointSample on test topics, and
KeyTypeValueTriple, a type without key, on a NO_KEY topic) in both directions, each
field-equal to the golden vector's `max` value. The Rust side is the generated crate's
`dds` module (feature `dds`) and nothing else.

RustDDS 0.15 has no Partition QoS, so the Python side here uses the default partition
(tests/py_peer.py --default-partition); RTPS stays on 127.0.0.1 (RustDDS `with_only_networks`, Cyclone
through K10's generated loopback configuration)."""
from __future__ import annotations

import json
import os
import sys

from tests import peers
from tests.rust.conftest import K10, ROOT, VECTORS

DOMAIN_RUST_TO_PY = 73
DOMAIN_PY_TO_RUST = 74
SECONDS = 25
EXTRA = ["rapid::FileAnnounce", "rapid::JointConfig", "rapid::JointSample", "rapid::KeyTypeValueTriple"]


def _lines() -> list[str]:
    vectors = {v["id"]: v for v in json.loads(VECTORS.read_text(encoding="utf-8"))["vectors"]}
    topics = json.loads((K10.parent / "qos" / "topics.json").read_text(encoding="utf-8"))["topics"]
    lines = [f"{t['topic']} {t['type']} {t['profile']} {vectors[t['type'] + '/max']['xcdr1_le']}" for t in topics]
    covered = {t["type"] for t in topics}
    lines += [f"rapidgen_test_{t.split('::')[-1].lower()} {t} - {vectors[t + '/max']['xcdr1_le']}"
              for t in EXTRA if t not in covered]
    return lines


def test_rust_and_python_exchange_every_message_type_both_ways(rust_peer):
    lines = _lines()
    assert len(lines) == 22
    stdin = "\n".join(lines) + "\n"
    env = dict(os.environ, CYCLONEDDS_URI="file://" + str(K10.parent / "qos" / "cyclonedds" / "local.xml"),
               PYTHONPATH=os.pathsep.join([str(K10.parent / "python"), str(ROOT)]))
    peer, py = str(rust_peer), [sys.executable, str(peers.PY_PEER)]
    procs = {
        "py_sub": peers.start(py + ["sub", str(DOMAIN_RUST_TO_PY), str(SECONDS), "--default-partition"], stdin, env),
        "rust_pub": peers.start([peer, "pub", str(DOMAIN_RUST_TO_PY), str(SECONDS)], stdin, env),
        "rust_sub": peers.start([peer, "sub", str(DOMAIN_PY_TO_RUST), str(SECONDS)], stdin, env),
        "py_pub": peers.start(py + ["pub", str(DOMAIN_PY_TO_RUST), str(SECONDS), "--default-partition"], stdin, env),
    }
    peers.exchange(procs, lines, SECONDS)
