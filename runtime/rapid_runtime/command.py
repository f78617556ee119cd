"""A received Command as plain data (what the protocol logic sees; dds.py builds it)."""
from __future__ import annotations

from dataclasses import dataclass, field

from rapid_runtime.acks import BYPASS


@dataclass(frozen=True)
class Cmd:
    cmd_id: str
    cmd_src: str
    subsystem: str
    name: str
    args: tuple = ()  # ((DataType name, value), ...) in the order sent
    action: str = BYPASS
    target: str = ""
    src_name: str = ""  # hdr.srcName: the commander
    asset_name: str = ""  # hdr.assetName: the addressed asset
    serial: int = 0
    raw: object = field(default=None, compare=False, repr=False)  # the DDS sample, echoed in QueueState
