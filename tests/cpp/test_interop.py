"""Live interop on loopback: the generated C++ types on Fast DDS 2.9 and the generated Python
bindings on cyclonedds exchange every K10 topic (every RAPID message type K10 uses, plus
its GPS extension), each side with its generated QoS, in both directions, field-equal to
the golden vector's value."""
from __future__ import annotations

import json
import os
import sys

from tests import peers
from tests.cpp.conftest import K10, ROOT, topics

DOMAIN_CPP_TO_PY = 97
DOMAIN_PY_TO_CPP = 98
SECONDS = 25


# RAPID message types K10 does not publish, on their standard topics with a profile of
# the same generated QoS library.
EXTRA = [("rapid_joint_config", "rapid::JointConfig", "RapidConfigQos"),
         ("rapid_joint_sample", "rapid::JointSample", "RapidSampleQos"),
         ("rapid_file_announce", "rapid::FileAnnounce", "RapidReliableDurableQos")]


def interop_lines() -> list[str]:
    vectors = {v["id"]: v for v in json.loads((ROOT / "tests/vectors/rapid.json").read_text(encoding="utf-8"))["vectors"]}
    rows = [(t["topic"], t["type"], t["profile"]) for t in topics()] + EXTRA
    # every RAPID message type (the vectors' types with a header) is exchanged
    messages = {v["type"] for v in vectors.values() if isinstance(v["value"], dict) and "hdr" in v["value"]}
    assert messages - {"rapid::Message"} == {ty for _, ty, _ in rows}
    return [f"{topic} {ty} {profile} {vectors[ty + '/max']['xcdr1_le']}" for topic, ty, profile in rows]


def test_cpp_and_python_exchange_every_topic_both_ways(cpp_build, tmp_path):
    lines = interop_lines()
    assert len(lines) == 21
    stdin = "\n".join(lines) + "\n"
    xml = str(K10 / "qos" / "fastdds" / "rapid_qos_profiles.xml")
    env = dict(os.environ, CYCLONEDDS_URI="file://" + str(K10 / "qos" / "cyclonedds" / "local.xml"),
               PYTHONPATH=os.pathsep.join([str(K10 / "python"), str(ROOT)]))
    env.pop("FASTDDS_DEFAULT_PROFILES_FILE", None)
    peer, py = str(cpp_build / "peer"), [sys.executable, str(peers.PY_PEER)]
    procs = {
        "py_sub": peers.start(py + ["sub", str(DOMAIN_CPP_TO_PY), str(SECONDS)], stdin, env),
        "cpp_pub": peers.start([peer, "pub", xml, str(DOMAIN_CPP_TO_PY), str(SECONDS)], stdin, env),
        "cpp_sub": peers.start([peer, "sub", xml, str(DOMAIN_PY_TO_CPP), str(SECONDS)], stdin, env),
        "py_pub": peers.start(py + ["pub", str(DOMAIN_PY_TO_CPP), str(SECONDS)], stdin, env),
    }
    peers.exchange(procs, lines, SECONDS)
