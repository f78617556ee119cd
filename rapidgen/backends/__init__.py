"""Back ends, by target name. Each module exposes NAME and generate(model, asset, options)."""
from __future__ import annotations

import importlib
import importlib.util

from rapidgen.backends.base import Backend, GeneratedFile, Options

# target name -> module; a module is imported only when its target is asked for.
_MODULES = {
    "python": "rapidgen.backends.python",
    "qos": "rapidgen.backends.qos",
    "cpp": "rapidgen.backends.cpp",
    "rust": "rapidgen.backends.rust",
}


def available() -> list[str]:
    """Targets whose back end is present in this installation."""
    return [name for name, module in _MODULES.items() if importlib.util.find_spec(module) is not None]


def get(name: str) -> Backend:
    return importlib.import_module(_MODULES[name])


def known() -> list[str]:
    return list(_MODULES)


__all__ = ["Backend", "GeneratedFile", "Options", "available", "get", "known"]
