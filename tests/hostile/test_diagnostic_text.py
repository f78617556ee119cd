"""Diagnostics quote names from untrusted inputs: none of their control characters may reach
the terminal (an ESC sequence in a descriptor could rewrite what the user sees)."""
from rapidgen.diagnostics import Diagnostic, FileLineCache, Severity, SourceLoc, render


def test_message_hint_and_file_name_are_escaped(tmp_path):
    src = tmp_path / "a\x1b[2J.yaml"
    src.write_text("name: x\n", encoding="utf-8")
    diag = Diagnostic(Severity.ERROR, "RG1101", "duplicate name '\x1b]0;owned\x07'",
                      SourceLoc(str(src), 1, 1, 1, 5), "rename \x9b one\nof them")
    text = render(diag, FileLineCache())
    assert not any(ord(ch) < 0x20 and ch != "\n" or 0x7f <= ord(ch) < 0xa0 for ch in text)
    assert "\\x1b]0;owned\\x07" in text and "\\x9b" in text and "rename \\x9b one\\nof them" in text
    assert text.count("\n") == 2  # head, source line, caret line: the hint's newline is escaped


def test_source_line_keeps_caret_alignment(tmp_path):
    src = tmp_path / "t.idl"
    src.write_text("\x07ab cd\n", encoding="utf-8")
    text = render(Diagnostic(Severity.ERROR, "RG0203", "unknown", SourceLoc(str(src), 1, 5, 1, 7)),
                  FileLineCache())
    line, caret = text.splitlines()[1:]
    assert line.endswith("?ab cd") and caret.index("^") == line.index("cd")
