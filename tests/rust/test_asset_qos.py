"""An asset crate's QoS profiles (src/asset.rs QOS_PROFILES, used by dds::qos_of) are the
RAPID QoS library's, resolved as the qos target writes them: every profile a topic names,
writer and reader side, for every seed's committed crate."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from rapidgen.qos.spec import default_library

ROOT = Path(__file__).resolve().parents[2]
SEEDS = ["athlete", "chariot", "eva-suit", "k10", "robonaut2", "xarm2"]
SIDE = r"QosSide \{ reliable: (true|false), transient_local: (true|false), history: QosHistory::(KeepAll|KeepLast\((\d+)\)) \}"


def _side(m: tuple[str, ...]) -> tuple:
    reliable, durable, history, depth = m
    return (reliable == "true", durable == "true", "keep_all" if history == "KeepAll" else ("keep_last", int(depth)))


def _expected(policies) -> tuple:
    h = policies.history
    return (policies.reliability == "reliable", policies.durability == "transient_local",
            "keep_all" if h.kind == "keep_all" else ("keep_last", h.depth))


@pytest.mark.parametrize("seed", SEEDS)
def test_profiles_are_the_librarys(seed):
    text = (ROOT / "generated" / seed / "rust" / "src" / "asset.rs").read_text(encoding="utf-8")
    named = set(re.findall(r'qos: "(\w+)", rate:', text))
    rows = re.findall(r'QosProfile \{ name: "(\w+)", writer: ' + SIDE + ", reader: " + SIDE + " },", text)
    assert named and {r[0] for r in rows} == named
    library = default_library()
    for name, *sides in rows:
        writer, reader = library.effective(name)
        assert (_side(tuple(sides[:4])), _side(tuple(sides[4:]))) == (_expected(writer), _expected(reader)), name
