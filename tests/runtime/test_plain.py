"""rapid_runtime.plain: the one JSON form of a decoded sample (the ROS 2 ground node's
config topics, `rapidgen spy`, its echo and the monitor all use it)."""
from __future__ import annotations

import importlib
import json
import math
import sys
from pathlib import Path

import pytest

from rapid_runtime.plain import plain

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def rapid():
    """RAPID's types as generated into generated/k10 (cyclonedds IdlStruct, IdlUnion, IdlEnum)."""
    sys.path.insert(0, str(ROOT / "generated/k10/python"))
    try:
        yield importlib.import_module("rapid_k10red.rapid")
    finally:
        sys.path.remove(str(ROOT / "generated/k10/python"))


def test_structs_enums_unions_octets_and_non_numbers(rapid):
    union = rapid.ParameterUnion(discriminator=rapid.DataType.RAPID_VEC3d, value=[1.0, math.nan, -math.inf])
    triple = rapid.KeyTypeValueTriple(key="k", padding=0, value=union)
    assert plain(triple) == {"key": "k", "padding": 0,
                             "value": {"discriminator": "RAPID_VEC3d", "value": [1.0, "NaN", "-Infinity"]}}
    assert plain(rapid.ParameterUnion(discriminator=rapid.DataType.RAPID_BOOL, value=True)) == \
        {"discriminator": "RAPID_BOOL", "value": True}
    assert plain(b"\x00\xff\x10") == "00ff10" and plain(bytearray(b"\x01")) == "01"
    assert plain([math.inf, -math.inf, math.nan, 1.5, None, "x"]) == ["Infinity", "-Infinity", "NaN", 1.5, None, "x"]
    assert plain(rapid.RotationEncoding.RAPID_ROT_QUAT) == "RAPID_ROT_QUAT"


def test_the_result_is_strict_json_and_a_config_reads_back_as_its_tables_value(rapid):
    """A config's plain form is the generated tables' form of it: unions as {discriminator, value}."""
    from rapid_runtime import messages
    from rapid_runtime.tables import Tables

    sys.path.insert(0, str(ROOT / "generated/k10/python"))
    try:
        tables = Tables(importlib.import_module("rapid_k10red.asset_tables"))
    finally:
        sys.path.remove(str(ROOT / "generated/k10/python"))
    assert tables.configs
    for topic, (type_name, value) in tables.configs.items():
        sample = messages.config(rapid, type_name, value, messages.header(rapid, "K10Red", "K10Red", 3))
        got = json.loads(json.dumps(plain(sample), allow_nan=False))
        assert got["hdr"]["serial"] == 3 and {k: v for k, v in got.items() if k != "hdr"} == value, topic


def test_the_tools_use_this_one():
    spy = pytest.importorskip("rapidgen.spy.model")
    from rapid_runtime.ros2 import ground
    assert spy.plain is plain and ground.plain is plain
