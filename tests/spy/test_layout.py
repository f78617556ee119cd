"""SPY-TYPE-01's member diagnosis (rapidgen/spy/layout.py), without DDS: RAPID's generated
classes against hand-written ones that are one detail off."""

import importlib
import sys

import pytest

from rapidgen.spy.layout import first_difference
from tests.runtime.live import SEEDS, python_dir
from tests.spy.plain_vec3d import hand_written_command


@pytest.fixture(scope="module")
def k10():
    sys.path.insert(0, str(python_dir("k10")))
    try:
        yield (importlib.import_module(f"{SEEDS['k10']}.rapid"),
               importlib.import_module(f"{SEEDS['k10']}._idl.BaseTypes"))
    finally:
        sys.path.remove(str(python_dir("k10")))


def test_a_type_is_like_itself(k10):
    rapid, _ = k10
    assert first_difference(rapid.Command, rapid.Command) is None
    assert first_difference(rapid.CommandConfig, rapid.CommandConfig) is None


def test_a_plain_array_for_a_nested_typedef_is_named_where_it_is(k10):
    rapid, base = k10
    found = first_difference(rapid.Command, hand_written_command(rapid, base))
    assert found is not None and found.startswith("ParameterUnion.vec3d is double[3], RAPID's is Vec3d"), found
    assert "cmdName" not in found


def test_a_top_level_typedef_for_its_plain_type_is_no_difference(k10):
    from dataclasses import dataclass, field

    from cyclonedds.idl import IdlStruct, types
    rapid, base = k10

    @dataclass
    class Ack(IdlStruct, typename="rapid.Ack"):
        hdr: rapid.Header = field(default_factory=rapid.Header)
        cmdId: types.bounded_str[64] = ""  # RAPID: String64 (a typedef of it): matches at the top
        status: rapid.AckStatus = rapid.AckStatus.ACK_QUEUED
        completedStatus: rapid.AckCompletedStatus = rapid.AckCompletedStatus.ACK_COMPLETED_NOT
        message: base.String128 = ""

    assert first_difference(rapid.Ack, Ack) is None
