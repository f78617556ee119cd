"""The spy's plain form of a sample is the runtime's (rapid_runtime.plain), and what reads it
(config_lines' value keys) reads that form."""
from __future__ import annotations

import enum
from types import SimpleNamespace as NS

from rapidgen.spy.collect import config_lines
from rapidgen.spy.model import plain


class DataType(enum.Enum):
    RAPID_FLOAT = 1
    RAPID_STRING = 2


def test_value_keys_of_an_agent_config_in_plain_form():
    union = lambda d, v: plain(NS(discriminator=d, value=v))  # noqa: E731 (an IdlUnion's two attributes)
    cfg = {"valueKeys": [{"key": "batteryCharge", "value": union(DataType.RAPID_FLOAT, 0.5)},
                         {"key": "mode", "value": union(DataType.RAPID_STRING, "idle")},
                         {"key": "odd", "value": {"RAPID_FLOAT": 1.0}}]}  # not a union's plain form
    assert cfg["valueKeys"][0]["value"] == {"discriminator": "RAPID_FLOAT", "value": 0.5}
    assert config_lines(cfg) == ["value keys: batteryCharge:FLOAT, mode:STRING, odd:?"]
