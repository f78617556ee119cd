"""The command's words as one line, so a diagnostic can point at a word (column), and its
report."""
from __future__ import annotations

import difflib
import shlex
import sys

from rapidgen.diagnostics import DiagnosticSink, FileLineCache, SourceLoc, render

CMDLINE = "<command line>"


class CmdLine:
    """The command's words as one line, so a diagnostic can point at a word (column)."""

    def __init__(self, words: list[str]) -> None:
        self.words = words
        self.text = " ".join(shlex.quote(w) for w in words)
        self.cols, col = [], 1
        for w in words:
            self.cols.append(col)
            col += len(shlex.quote(w)) + 1

    def at(self, index: int, offset: int = 0, length: int | None = None) -> SourceLoc:
        col = self.cols[index] + offset
        width = len(shlex.quote(self.words[index])) - offset if length is None else length
        return SourceLoc(CMDLINE, 1, col, 1, col + max(1, width))


def report(sink: DiagnosticSink, line: CmdLine) -> None:
    lines = FileLineCache()
    lines.add_text(CMDLINE, line.text)
    for d in sink.sorted():
        print(render(d, lines), file=sys.stderr)
    n = len(sink.errors)
    print(f"rapidgen: {n} error{'s' * (n != 1)}", file=sys.stderr)


def did_you_mean(name: str, choices) -> str:
    close = difflib.get_close_matches(name, list(choices), n=1, cutoff=0.6)
    shown = ", ".join(sorted(choices)) or "none"
    return f"did you mean '{close[0]}'? (known: {shown})" if close else f"known: {shown}"


