"""Cyclone DDS's warnings in rapidgen's live tools (issue 39 item 6).

A C++ bridge (Fast DDS 2.9) retires each old command's ack instance by unregistering it. A
RAPID key (the header's names and the cmdId) is longer than 16 bytes, so the unregister carries
only the key's MD5 hash, and Fast DDS 2.9 sends no serialized key beside it; Cyclone cannot
turn an MD5 back into the key, drops the message and warns, once per retired instance:

    recv: data(application, vendor 1.15): ... deserialization rapid_ack/rapid::Ack failed
    (keyhash is MD5 and can't be converted to key value)

Nothing is lost by the drop (the instance's acks were all delivered before), and a tool
watching a busy bridge printed thousands of these lines. Fast DDS 2.9's liveliness messages
give another such line per announcement (docs/realtime.md). The library this Python package
bundles exports only its global log mask (no log sink to filter by text), so the tools
leave Cyclone's warnings out and keep its errors; RAPIDGEN_DDS_WARNINGS=1 shows them again.
"""
from __future__ import annotations

import ctypes
import os

FATAL, ERROR, WARNING = 1, 2, 4  # DDS_LC_* (dds/ddsrt/log.h)
SHOW_ENV = "RAPIDGEN_DDS_WARNINGS"


def quiet_warnings() -> bool:
    """Cyclone's warnings off in this process (errors still shown), unless RAPIDGEN_DDS_WARNINGS
    is set. True when they were turned off. Call before or after DDS starts (the mask is read
    on each message)."""
    if os.environ.get(SHOW_ENV, "") not in ("", "0"):
        return False
    try:
        from cyclonedds.internal import load_cyclonedds
        lib = load_cyclonedds()
        lib.dds_get_log_mask.restype = ctypes.c_uint32
        mask = lib.dds_get_log_mask()
        lib.dds_set_log_mask(ctypes.c_uint32((mask & ~WARNING) | ERROR | FATAL))
    except (ImportError, OSError, AttributeError):  # no cyclonedds, or a library without the call: say all
        return False
    return True
