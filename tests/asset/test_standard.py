"""The standard subsystem dictionaries agree with the protocol and with specs/rapid/CommandConstants.idl.

PROTOCOL is written from rapid-protocol.md section 5 ("Standard subsystems and commands
(CommandConstants)"), not from our code: both rapidgen's STANDARD_TYPES and the IDL
constants are checked against it (subsystem and command names; parameters are rapidgen's
choice, checked against the IDL only).
"""
import re

import pytest

from rapidgen.asset.standard import STANDARD_TYPES
from rapidgen.model.ir import Const

PROTOCOL = {
    "Admin": ["echo", "shutdown", "noOp"],
    "Mobility": ["stopAllMotion", "simpleMove", "move", "move6DOF"],
    "ImageSensor": [],
    "Queue": ["cancelAll", "loadMacro"],
    "AccessControl": ["requestControl", "grabControl", "releaseControl", "transferControl"],
}
STANDARD_FRAMES = ["RAPID_SITE_FRAME", "RAPID_ROVER_FRAME", "RAPID_UTM_FRAME"]


@pytest.fixture(scope="module")
def constants(seed):
    model = seed("robonaut2").model  # the full RAPID set
    return {d.name: d for d in model.declarations if isinstance(d, Const)}


def test_standard_types_follow_the_protocol():
    assert list(STANDARD_TYPES) == list(PROTOCOL)
    for name, commands in PROTOCOL.items():
        assert [c.name for c in STANDARD_TYPES[name].commands] == commands, name
        assert STANDARD_TYPES[name].standard, name


def test_idl_constants_follow_the_protocol(constants):
    """Constant naming (section 5): GROUP, GROUP_METHOD_X, with X the upper-cased name."""
    groups = {n: c.value for n, c in constants.items() if re.fullmatch(r"[A-Z]+", n) and isinstance(c.value, str)}
    assert groups == {name.upper(): name for name in PROTOCOL}
    for name, commands in PROTOCOL.items():
        group = name.upper()
        methods = {n: c.value for n, c in constants.items() if re.fullmatch(rf"{group}_METHOD_[A-Z0-9]+", n)}
        assert methods == {f"{group}_METHOD_{cmd.upper()}": cmd for cmd in commands}, name
    for frame in STANDARD_FRAMES:
        assert isinstance(constants[frame].value, str) and constants[frame].value, frame


def test_every_group_is_a_standard_type(constants):
    groups = {c.value for n, c in constants.items() if re.fullmatch(r"[A-Z]+", n) and isinstance(c.value, str)}
    assert groups == set(STANDARD_TYPES)


@pytest.mark.parametrize("type_name", sorted(STANDARD_TYPES))
def test_commands_parameters_and_types(constants, type_name):
    group = type_name.upper()
    assert constants[group].value == type_name
    t = STANDARD_TYPES[type_name]
    methods = {n: c.value for n, c in constants.items() if re.fullmatch(rf"{group}_METHOD_[A-Z0-9]+", n)}
    assert sorted(methods.values()) == sorted(c.name for c in t.commands)
    for cmd in t.commands:
        prefix = f"{group}_METHOD_{cmd.name.upper()}"
        assert constants[prefix].value == cmd.name
        params = sorted((c for n, c in constants.items() if n.startswith(prefix + "_PARAM_")),
                        key=lambda c: c.loc.line)  # argument order is declaration order
        assert [c.value for c in params] == [p.name for p in cmd.parameters]
        for p in cmd.parameters:
            assert constants[f"{prefix}_DTYPE_{p.name.upper()}"].value.name == p.type
