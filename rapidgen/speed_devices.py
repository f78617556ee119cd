"""What rapidgen does only to be fast, each of which a run can be told to go without:
`RAPIDGEN_WITHOUT=name[,name...]`. The output is the same with or without any of them (each
device's own tests compare); bench/codegen.py --devices times a run without each, and
docs/ci.md ("Speed") keeps the figures beside each device: one is kept only while it saves a
tenth or more of the run it targets (the QoS library shipped parsed saved 1.5% and was
removed)."""
from __future__ import annotations

import os

DEVICES = {
    "two-processes": "back ends (or a project's targets) in a forked child beside the parent; the worker "
                     "forked ahead of the front end (rapidgen.fork_ahead; RAPIDGEN_JOBS=1 too)",
    "codecache": "the dataclasses' compiled methods kept per user (rapidgen.codecache)",
    "precompiled-templates": "templates shipped compiled to Python (rapidgen/backends/precompiled)",
    "lalr-tables": "the IDL grammar's LALR tables shipped built (rapidgen/idl/packaged_tables.py)",
}


def without(device: str) -> bool:
    """True when RAPIDGEN_WITHOUT names `device` (one of DEVICES)."""
    assert device in DEVICES, device
    return device in os.environ.get("RAPIDGEN_WITHOUT", "").replace(" ", "").split(",")
