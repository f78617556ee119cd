"""What the C++ and Rust namers share: a name steps aside from a reserved word with a
trailing `_`, and a Scope hands out unique names, remembering what each stands for, so
two IDL names never become one target name. Each namer gives its reserved words, its
identifier pattern and its language's name."""
from __future__ import annotations

import re


class NameCollision(Exception):
    """Two IDL names were given one target name (a bug in the view layer)."""


def escape(name: str, reserved: frozenset[str] | set[str]) -> str:
    for _ in range(100):
        if name not in reserved:
            break
        name += "_"
    return name


class Scope:
    """One target scope (namespace, module, class, enum): unique names and their owners."""

    LANGUAGE = ""
    IDENT: re.Pattern[str] = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")

    def __init__(self, label: str, reserved: frozenset[str] | set[str]) -> None:
        self.label = label
        self.reserved = frozenset(reserved)
        self.owner: dict[str, str] = {}

    def claim(self, preferred: str, owner: str) -> str:
        name = escape(preferred, self.reserved)
        while name in self.owner:
            if self.owner[name] == owner:
                return name
            name = escape(name + "_", self.reserved)
        self.owner[name] = owner
        return name

    def check(self) -> None:
        for name, owner in self.owner.items():
            if not self.IDENT.match(name) or name in self.reserved:
                raise NameCollision(f"{self.label}: '{name}' (for {owner}) is not a usable {self.LANGUAGE} name")
