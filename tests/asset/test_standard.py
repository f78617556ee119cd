"""The standard subsystem dictionaries agree with specs/rapid/CommandConstants.idl."""
import re

import pytest

from rapidgen.asset.standard import STANDARD_TYPES
from rapidgen.model.ir import Const


@pytest.fixture(scope="module")
def constants(seed):
    model = seed("robonaut2").model  # the full RAPID set
    return {d.name: d for d in model.declarations if isinstance(d, Const)}


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
