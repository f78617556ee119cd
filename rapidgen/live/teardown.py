"""The tools' way to delete their participant before the interpreter ends: the runtime's
rapid_runtime.teardown (why it is needed: its docstring), named here so that every live tool
reaches it through `live`, as it reaches the runtime's security module (docs/architecture.md,
"Import rules")."""
from __future__ import annotations

from rapid_runtime.teardown import delete_participant

__all__ = ["delete_participant"]
