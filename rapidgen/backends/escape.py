"""How input text is written into each kind of generated file.

Every string that comes from an input (file names, IDL string constants, descriptor
names, partition names, ...) reaches a generated file through one of these: templating.py
registers them as Jinja2 filters, view layers call py_str for code they compose. Literals
keep the value exactly (it round-trips); comments only need to stay comments, so they
show what cannot be printed as escapes. XML goes through Jinja2's autoescape, and
check_output (base.py) refuses what no escape can carry (XML 1.0's forbidden characters,
lone surrogates).
"""
from __future__ import annotations

import re

import markupsafe

from rapidgen.textsafe import code_escape as _code_escape
from rapidgen.textsafe import visible

# PEP 263: a comment on line 1 or 2 matching this names the source encoding.
_CODING = re.compile(r"coding([:=])")


def py_str(text: str) -> str:
    """A double-quoted, ASCII-only Python string literal of `text` (same bytes on every machine)."""
    if text.isascii() and text.isprintable() and '"' not in text and "\\" not in text:  # the usual: as it is
        return '"' + text + '"'
    return '"' + "".join(ch if " " <= ch < "\x7f" and ch not in '"\\' else
                         "\\" + ch if ch in '"\\' else _code_escape(ch) for ch in text) + '"'


def py_docstring(text: str) -> str:
    """The body of a `\"\"\"...\"\"\"` docstring whose value is `text`: printable characters and
    newlines as they are, quotes and backslashes escaped (no early end, no escape
    surprises), anything else as a backslash escape."""
    if '"' not in text and "\\" not in text and text.replace("\n", "").isprintable():  # the usual: as it is
        return text
    return "".join(ch if ch == "\n" or (ch.isprintable() and ch not in '"\\') else
                   "\\" + ch if ch in '"\\' else _code_escape(ch) for ch in text)


def line_comment(text: str) -> str:
    """Text for a `#` comment (Python, TOML): one printable line, and never read as a
    PEP 263 encoding declaration (`coding:` in a file name would make the module unloadable)."""
    return _CODING.sub(r"coding \1", visible(text))


_TOML_SHORT = {'"': '\\"', "\\": "\\\\", "\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f", "\r": "\\r"}


def toml_str(text: str) -> str:
    """A TOML basic string of `text` (TOML 1.0: quote, backslash and controls escaped).
    Lone surrogates have no TOML form; they are left for check_output to refuse."""
    return '"' + "".join(_TOML_SHORT.get(ch) or (f"\\u{ord(ch):04x}" if ch < " " or ch == "\x7f" else ch)
                         for ch in text) + '"'


def xml_comment(text: str) -> str:
    """One visible line that is safe inside an XML comment (no '--', no trailing '-')."""
    text = visible(" ".join(text.split()))
    while "--" in text:
        text = text.replace("--", "- -")
    return text.rstrip("-")


# Whitespace an XML parser would normalize (attribute values: to spaces; CR: to LF) and
# what str.splitlines, hence Jinja2's indent filter, treats as a line break.
_XML_REFS = re.compile("[\t\n\r\x85\u2028\u2029]")


def xml_text(value: object) -> markupsafe.Markup:
    """Any value as XML character data or attribute text: markup characters escaped, and
    the whitespace above as character references, so the value is read back exactly.
    Markup (a macro's output) is already escaped."""
    if isinstance(value, markupsafe.Markup):
        return value
    text = str(markupsafe.escape(str(value)))
    return markupsafe.Markup(_XML_REFS.sub(lambda m: f"&#{ord(m.group())};", text))


# What XML 1.0 cannot carry even escaped: C0 controls but tab/LF/CR, surrogates, U+FFFE/U+FFFF.
XML_FORBIDDEN = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")
# What no UTF-8 file can carry.
UNENCODABLE = re.compile("[\ud800-\udfff]")


# -- C++ and CMake ----------------------------------------------------------------------
# Printable ASCII but '"', '?' and '\\': text that cpp_str and rust_str print as it is (most
# names and messages), with no loop over its characters.
_PLAIN = re.compile(r'[ !#->@-\[\]-~]*\Z')


def cpp_str(text: str) -> str:
    """A C++ narrow string literal whose value is exactly the UTF-8 bytes of `text`.

    Printable ASCII stays (`"`, `\\` and `?` escaped: no early end, no trigraph), every
    other byte is a 3-digit octal escape (fixed length, so a following digit is never
    absorbed as \\x escapes would). A lone surrogate has no UTF-8 form: it is left in the
    text for check_output to refuse (RG0830)."""
    if _PLAIN.match(text):
        return f'"{text}"'
    out = ['"']
    for ch in text:
        if " " <= ch < "\x7f":
            out.append("\\" + ch if ch in '"\\?' else ch)
        elif "\ud800" <= ch <= "\udfff":
            out.append(ch)
        else:
            out.extend(f"\\{b:03o}" for b in ch.encode("utf-8"))
    return "".join(out) + '"'


def cpp_comment(text: str) -> str:
    """One line for a `//` comment (or inside `/* */`): printable, no `*/` or `/*`, no `??`
    (a trigraph to old compilers, a warning to new ones), no trailing backslash (a line
    splice would swallow the next line)."""
    text = visible(" ".join(text.split()))
    for bad, good in (("*/", "* /"), ("/*", "/ *")):
        text = text.replace(bad, good)
    while "??" in text:
        text = text.replace("??", "?_?")
    return text + "_" if text.endswith("\\") else text


def cmake_name(text: str) -> str:
    """A CMake package/target name (and C++ identifier) from any text: [A-Za-z0-9_], not
    starting with a digit."""
    out = re.sub(r"[^A-Za-z0-9_]", "_", text) or "rapid_types"
    return "_" + out if out[0].isdigit() else out


# -- Rust and Cargo ---------------------------------------------------------------------
def rust_str(text: str) -> str:
    """A Rust string literal whose value is exactly `text`.

    Printable ASCII stays (`"` and `\\` escaped); everything else is a `\\u{...}` escape,
    so no bidirectional-override or other invisible character (which rustc refuses in
    literals) is ever written raw. A lone surrogate has no Rust form: it is left in the
    text for check_output to refuse (RG0830)."""
    if _PLAIN.match(text):
        return f'"{text}"'
    out = ['"']
    for ch in text:
        if " " <= ch < "\x7f":
            out.append("\\" + ch if ch in '"\\' else ch)
        elif "\ud800" <= ch <= "\udfff":
            out.append(ch)
        else:
            out.append(f"\\u{{{ord(ch):x}}}")
    return "".join(out) + '"'


def rust_comment(text: str) -> str:
    """One line for a Rust `//` or `///` comment: printable (no newline ends it early, no
    bare CR, no bidirectional override rustc refuses), whitespace runs as one space."""
    return visible(" ".join(text.split()))


def crate_name(text: str) -> str:
    """A Cargo package (and Rust crate) name from any text: [a-z0-9_], starting with a
    letter, not a name Cargo refuses (a keyword or a built-in crate)."""
    out = re.sub(r"[^a-z0-9_]", "_", text.lower()).strip("_") or "rapid_types"
    if not out[0].isalpha():
        out = "rapid_" + out
    return out + "_rs" if out in _CARGO_REFUSED else out


_CARGO_REFUSED = frozenset("""
    test core std alloc proc_macro self super crate as async await break const continue dyn else
    enum extern false fn for if impl in let loop match mod move mut pub ref return static struct
    trait true type unsafe use where while abstract become box do final macro override priv try
    typeof unsized virtual yield gen
""".split())
