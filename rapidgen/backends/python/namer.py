"""Python names for IDL names: keyword escaping, no shadowing of what generated code uses.

Only Python-side names change; DDS names never do: registered type names, the XTypes
member names (kept with `annotate.member_name`) and every wire byte stay the IDL ones.

Rules (docs/python-backend.md has the table):
- A name that is a Python keyword, or would shadow a name the generated code relies on,
  gets a trailing underscore: `class` -> `class_`, `types` -> `types_`.
- Each scope (a module's globals, a package's exports, a class body, an enum) hands out
  names through a `Scope`, which adds underscores until the name is free, so two IDL
  names can never end up as one Python name. `Scope.check()` re-verifies before rendering.

Every list here is fixed in this file (not taken from the running interpreter), so the
output is the same whichever Python runs rapidgen.
"""
from __future__ import annotations

import re

from rapidgen.backends import naming

NameCollision = naming.NameCollision  # namer.NameCollision, as for the other namers

# Python 3 keywords (hard keywords only; soft keywords such as `match`, `case`, `type`
# are valid identifiers).
KEYWORDS = frozenset("""
    False None True and as assert async await break class continue def del elif else except
    finally for from global if import in is lambda nonlocal not or pass raise return try while
    with yield
""".split())

# Names the generated modules import or call; an IDL name equal to one of them would
# shadow it (at module level, or inside a class body where later members still use it).
RUNTIME = frozenset({
    "dataclass", "field", "idl", "annotate", "types", "Optional", "Decimal",
    "IdlStruct", "IdlUnion", "IdlEnum", "IdlBitmask",
})
# Builtins the generated code uses (annotations, defaults, factories, constants). Other
# builtins (`type`, `id`, `object`, ...) stay usable as IDL names: nothing generated needs them.
BUILTINS = frozenset({"bool", "str", "float", "list", "range"})

MODULE_RESERVED = KEYWORDS | RUNTIME | BUILTINS
# Builtins a class body may evaluate directly (annotations, default factories); members
# never take these names, whatever the other members are, so a member's name is stable.
CLASS_BUILTINS = frozenset({"bool", "str", "list"})

# Attributes of the cyclonedds base classes that a member must not hide.
STRUCT_ATTRS = frozenset({"serialize", "deserialize", "serialize_key", "deserialize_key"})
UNION_ATTRS = frozenset({"value", "discriminator", "get", "set", "serialize", "deserialize", "deserialize_key"})
# Enum member names Python's Enum refuses or that hide Enum attributes.
ENUM_RESERVED = frozenset({"mro", "name", "value"})

_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


def escape(name: str, reserved: frozenset[str] | set[str]) -> str:
    """The name with underscores appended while it is a reserved word or a magic name."""
    return naming.escape(name, reserved, _is_magic)


def _is_magic(name: str) -> bool:
    """Dunder (`__x__`) and Enum sunder (`_x_`) names are reserved by Python."""
    if len(name) > 4 and name.startswith("__") and name.endswith("__"):
        return True
    return len(name) > 2 and name[0] == "_" and name[-1] == "_" and name[1] != "_" and name[-2] != "_"


def identifier(text: str) -> str:
    """A valid Python identifier from any text (file names): other characters become `_`,
    leading underscores go (no dunder names), a leading digit gets one `_`."""
    out = re.sub(r"[^A-Za-z0-9_]", "_", text).lstrip("_") or "idl"
    if out[0].isdigit():
        out = "_" + out
    return out


class Scope(naming.Scope):
    """One Python namespace (backends/naming.py): dunder and sunder names are reserved too;
    check() refuses keywords (a scope's extra reserved names are only stepped around)."""

    LANGUAGE = "Python"
    IDENT = _IDENT

    def also_reserved(self, name: str) -> bool:
        return _is_magic(name)

    def usable(self, name: str) -> bool:
        return bool(_IDENT.match(name)) and name not in KEYWORDS


def member_reserved(kind: str, used_in_body: set[str]) -> frozenset[str]:
    """Names a member of a class of this kind must not take.

    `used_in_body` holds the names the class body itself evaluates (type names in
    annotations, default values): a member with one of those names would rebind it for
    every later line of the body.
    """
    extra = STRUCT_ATTRS if kind == "struct" else UNION_ATTRS if kind == "union" else frozenset()
    return KEYWORDS | RUNTIME | CLASS_BUILTINS | extra | frozenset(used_in_body)


def enumerator_reserved() -> frozenset[str]:
    return KEYWORDS | ENUM_RESERVED


def package_name(text: str) -> str:
    """A lower-case distribution/package name from an asset name: `K10Red` -> `rapid_k10red`."""
    slug = re.sub(r"[^a-z0-9]+", "_", text.lower()).strip("_") or "asset"
    return escape(identifier(f"rapid_{slug}"), KEYWORDS)
