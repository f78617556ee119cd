"""Broken assets: a rule only the protocol's cases pin (SPEC-01, conformance/spec.py)."""
from __future__ import annotations

from . import kind


@kind("transfer-to-any-name", "SPEC-01")
def transfer_to_any_name(a):
    """transferControl hands control to any name, a blank one or one AccessControlState's
    String32 cannot hold (runtime/spec/cases/access.yaml: refused, EXEC_FAILED)."""
    control = a.manager.control

    def transfer(source, new):
        if not control.holds(source):
            return f"{source} does not have control", ""
        control._give(new)
        return None, f"control transferred to {new}"
    control.transfer = transfer
