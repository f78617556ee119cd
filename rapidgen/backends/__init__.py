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


def parse_langs(text: str | list[str] | tuple[str, ...]) -> tuple[list[str], str | None]:
    """The targets of `--lang a,b` or a project's `lang: [a, b]` (order kept, repeats
    dropped), and what is wrong with them (None: nothing). The one place targets are checked."""
    items = text.split(",") if isinstance(text, str) else list(text)
    langs = list(dict.fromkeys(x.strip() for x in items if x.strip()))
    present = available()  # once: each call looks every back end up on the import path
    unknown = [lang for lang in langs if lang not in present]
    if unknown:
        return langs, f"unknown or unavailable target '{unknown[0]}'; available: {', '.join(present)}"
    if not langs:
        return langs, f"no target given; available: {', '.join(present)}"
    return langs, None


__all__ = ["Backend", "GeneratedFile", "Options", "available", "get", "known", "parse_langs"]
