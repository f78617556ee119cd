"""What the Python, C++ and Rust namers share: a name steps aside from a reserved word
with a trailing `_`, and a Scope hands out unique names, remembering what each stands for,
so two IDL names never become one target name. Each namer gives its reserved words, its
identifier pattern and its language's name (and Python its magic names and case folding)."""
from __future__ import annotations

import re
from typing import Callable


class NameCollision(Exception):
    """Two IDL names were given one target name (a bug in the view layer)."""


def escape(name: str, reserved: frozenset[str] | set[str], also: Callable[[str], bool] | None = None) -> str:
    """The name with underscores appended while it is reserved (or `also` says it is)."""
    for _ in range(100):
        if name not in reserved and not (also is not None and also(name)):
            break
        name += "_"
    return name


class Scope:
    """One target scope (namespace, module, class, enum): unique names and their owners.

    fold_case: names must differ in more than case (file and folder names, which a
    case-insensitive file system would merge)."""

    LANGUAGE = ""
    IDENT: re.Pattern[str] = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")

    def __init__(self, label: str, reserved: frozenset[str] | set[str] = frozenset(), *,
                 fold_case: bool = False) -> None:
        self.label = label
        self.reserved = frozenset(reserved)
        self.fold_case = fold_case
        self.owner: dict[str, str] = {}  # target name -> what it names (IDL scoped name, file, ...)
        self._folded: dict[str, str] = {}

    def also_reserved(self, name: str) -> bool:
        """Names a language reserves by shape rather than by list (Python's dunders)."""
        return False

    def usable(self, name: str) -> bool:
        """What check() accepts: a valid identifier that is not reserved."""
        return bool(self.IDENT.match(name)) and name not in self.reserved

    def claim(self, preferred: str, owner: str) -> str:
        """A free name as close to `preferred` as possible, recorded as naming `owner`."""
        name = preferred
        if name in self.reserved or self.also_reserved(name):
            name = escape(name, self.reserved, self.also_reserved)
        while (holder := self._holder(name)) is not None:
            if holder == owner:
                return name
            name = escape(name + "_", self.reserved, self.also_reserved)
        self._record(name, owner)
        return name

    def take(self, name: str, owner: str) -> None:
        """Record a name that must be used exactly as given (imports, fixed names)."""
        holder = self._holder(name)
        if holder is not None and holder != owner:
            raise NameCollision(f"{self.label}: '{name}' names both {holder} and {owner}")
        self._record(name, owner)

    def _holder(self, name: str) -> str | None:
        return self._folded.get(name.lower()) if self.fold_case else self.owner.get(name)

    def _record(self, name: str, owner: str) -> None:
        self.owner[name] = owner
        self._folded[name.lower()] = owner

    def check(self) -> None:
        for name, owner in self.owner.items():
            if not self.usable(name):
                raise NameCollision(f"{self.label}: '{name}' (for {owner}) is not a usable {self.LANGUAGE} name")


def param_summary(name: str, p, quote: str = "") -> str:
    """A command parameter described for a handler's doc comment (the C++ and Rust bridges):
    its name in the code (between `quote`s), descriptor name if other, type, unit, range,
    allowed values, default and description. Unescaped: each back end passes it through its
    own comment escaper."""
    parts = [f"{quote}{name}{quote} ({p.name + ', ' if p.name != name else ''}{p.type})"]
    if p.unit:
        parts.append(f"[{p.unit}]")
    if p.min is not None or p.max is not None:
        parts.append(f"range [{p.min if p.min is not None else '-inf'}, {p.max if p.max is not None else 'inf'}]")
    if p.allowed:
        parts.append("one of " + ", ".join(map(str, p.allowed)))
    if p.has_default:
        parts.append(f"default {p.default!r}")
    return " ".join(parts) + (f": {p.description}" if p.description else "")
