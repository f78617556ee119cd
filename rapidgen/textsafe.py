"""Text from inputs and from the wire, made safe to show: one printable line, everything
else as a backslash escape. A leaf every stage may import (the terminal tools, reports,
describe, the back ends' comments); rapid_runtime/untrusted.py keeps the robot's copy,
held to the same answers by tests/hostile/test_live_helpers.py."""
from __future__ import annotations

SHORT = {"\\": "\\\\", "\n": "\\n", "\t": "\\t", "\r": "\\r"}


def code_escape(ch: str) -> str:
    """`ch` as a Python (and C/JSON-like) backslash escape."""
    code = ord(ch)
    if ch in SHORT:
        return SHORT[ch]
    if code < 0x80:
        return f"\\x{code:02x}"
    return f"\\u{code:04x}" if code <= 0xFFFF else f"\\U{code:08x}"


def visible(text: str) -> str:
    """One line of printable text: what is not printable (newlines, controls, escape
    sequences, C1 codes, bidi overrides, lone surrogates) shown as a backslash escape such
    as \\x1b."""
    if text.isprintable():  # nearly always: no character to look at one by one
        return text
    return "".join(ch if ch.isprintable() else code_escape(ch) for ch in text)
