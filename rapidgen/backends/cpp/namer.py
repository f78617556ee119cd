"""C++ names for IDL names: keyword and macro escaping, one Scope per C++ scope.

Only C++ names change; DDS names never do (registered type names are the IDL scoped
names, and the wire has no member names in XCDR1 final types). A name that C++ reserves
or that the generated code relies on gets a trailing `_` (`class` -> `class_`); a Scope
adds more while the name is taken, so two IDL names never become one C++ name. Every
list is fixed here, so output does not depend on the machine.
"""
from __future__ import annotations

from rapidgen.backends import naming

# C++17 keywords, alternative tokens, and C++20 keywords (so the code survives -std=c++20).
KEYWORDS = frozenset("""
    alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t char16_t
    char32_t class compl concept const consteval constexpr constinit const_cast continue co_await
    co_return co_yield decltype default delete do double dynamic_cast else enum explicit export
    extern false float for friend goto if inline int long mutable namespace new noexcept not
    not_eq nullptr operator or or_eq private protected public register reinterpret_cast requires
    return short signed sizeof static static_assert static_cast struct switch template this
    thread_local throw true try typedef typeid typename union unsigned using virtual void volatile
    wchar_t while xor xor_eq
""".split())
# Macros the standard headers (glibc, GNU mode) define: a member named `errno` or `linux`
# would be rewritten by the preprocessor.
MACROS = frozenset("""
    NULL EOF errno assert offsetof setjmp stdin stdout stderr linux unix i386 BIG_ENDIAN
    LITTLE_ENDIAN BYTE_ORDER PDP_ENDIAN TRUE FALSE major minor
""".split())
RESERVED = KEYWORDS | MACROS
# What the generated code declares beside IDL names at namespace scope, and the
# namespaces it names: an IDL declaration or module with one of these names steps aside.
NAMESPACE_RESERVED = RESERVED | {"encode", "decode", "encode_key", "std", "rapidgen", "eprosima"}
# Union classes: the discriminator accessor and the private state.
UNION_RESERVED = RESERVED | {"_d", "m_d", "m_v", "case_of"}


class Scope(naming.Scope):
    """One C++ scope (namespace, class, enum)."""

    LANGUAGE = "C++"

    def __init__(self, label: str, reserved: frozenset[str] | set[str] = RESERVED) -> None:
        super().__init__(label, reserved)
