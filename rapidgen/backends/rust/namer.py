"""Rust names for IDL names: case conventions, keyword escaping, one Scope per Rust scope.

Only Rust names change; DDS names never do (registered type names are the IDL scoped
names, kept in `TYPE_NAME`; XCDR1 final types carry no member names). Types, union
variants and enumerators become CamelCase, fields and modules snake_case, constants
UPPER_SNAKE_CASE, so rustc's naming lints stay quiet without allows. A name that Rust
reserves or that the generated code relies on gets a trailing `_` (`type` -> `type_`;
raw identifiers cannot spell `self`, `Self`, `super` or `crate`); a Scope adds more while
the name is taken, so two IDL names never become one Rust name.
"""
from __future__ import annotations

import re

from rapidgen.backends import naming

# Rust 2021 strict and reserved keywords, and 2024's `gen`.
KEYWORDS = frozenset("""
    as async await break const continue crate dyn else enum extern false fn for if impl in let loop
    match mod move mut pub ref return self Self static struct super trait true type unsafe use where
    while abstract become box do final macro override priv try typeof unsized virtual yield gen
    macro_rules union
""".split())
# The crate root also holds the runtime, asset, dds and serde_arrays modules, the type visitor
# and the crates the features bring; paths start with these names, so no IDL module may take them.
ROOT_RESERVED = KEYWORDS | {"cdr", "asset", "dds", "serde_arrays", "serde", "rustdds", "std", "core", "alloc",
                             "TopicType", "TypeVisitor", "visit_types"}
# A union's variant for a discriminator value that selects no member.
NO_MEMBER = "NoMember"

# Words of an identifier; digits stay with the word before them (`Vec3d`, `mat33f`).
_WORDS = re.compile(r"[A-Z]+(?=[A-Z][a-z])|[A-Z]?[a-z0-9]+|[A-Z]+[0-9a-z]*")


def _words(name: str) -> list[str]:
    return [w for part in name.split("_") for w in _WORDS.findall(part)]


def snake(name: str) -> str:
    """`srcName` -> `src_name`, `HTTPServer2` -> `http_server2`, `Vec3d` -> `vec3d`."""
    out = ""
    for w in _words(name):
        out += ("_" if out else "") + w.lower()
    return out or "field"


def camel(name: str) -> str:
    """`ACK_COMPLETED` -> `AckCompleted`, `GPS` -> `Gps`, `myType` -> `MyType`."""
    out = "".join(w[:1].upper() + w[1:].lower() for w in _words(name))
    return out or "Type"


def upper(name: str) -> str:
    """`maxItems` -> `MAX_ITEMS` (constants)."""
    return snake(name).upper()


class Scope(naming.Scope):
    """One Rust scope (module, struct, enum); Rust's keywords are always reserved."""

    LANGUAGE = "Rust"
    IDENT = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")

    def __init__(self, label: str, reserved: frozenset[str] | set[str] = KEYWORDS) -> None:
        super().__init__(label, frozenset(reserved) | KEYWORDS)
