"""Source locations and compiler-style diagnostics.

Every front-end stage reports problems through a DiagnosticSink instead of raising,
so one run can report every error it finds. Rendering follows the rustc/clang shape:

    file.idl:12:5: error[RG0203]: unknown type 'Mesage'
       12 |     valuetype Ack : Mesage {
          |                     ^^^^^^ did you mean 'Message'?
"""
from __future__ import annotations

import enum
import os
from dataclasses import dataclass, field
from typing import Callable, Iterable, NamedTuple

from rapidgen import codes


class SourceLoc(NamedTuple):
    """A span in a source file; lines and columns are 1-based, the span ends before end_col.

    A NamedTuple rather than a frozen dataclass: the parser makes one per token, and a
    tuple is several times cheaper to create; it is just as immutable.
    """

    file: str
    line: int
    col: int
    end_line: int = 0
    end_col: int = 0

    def __str__(self) -> str:
        # line 0: about the file (or the command line) as a whole
        return f"{self.file}:{self.line}:{self.col}" if self.line > 0 else self.file


UNKNOWN_LOC = SourceLoc("<unknown>", 0, 0)


class Severity(enum.Enum):
    ERROR = "error"
    WARNING = "warning"
    NOTE = "note"


@dataclass(frozen=True, slots=True)
class Diagnostic:
    severity: Severity
    code: str
    message: str
    loc: SourceLoc
    hint: str | None = None


class DiagnosticError(Exception):
    """Raised to abandon a stage after its errors are already in the sink."""


@dataclass
class DiagnosticSink:
    """Collects diagnostics; warnings whose code is in `silenced` are dropped."""

    silenced: frozenset[str] = frozenset()
    warnings_as_errors: bool = False
    diagnostics: list[Diagnostic] = field(default_factory=list)

    def error(self, code: str, message: str, loc: SourceLoc, hint: str | None = None) -> None:
        if codes.checking():
            codes.check(code, "error")
        self.diagnostics.append(Diagnostic(Severity.ERROR, code, message, loc, hint))

    def warning(self, code: str, message: str, loc: SourceLoc, hint: str | None = None) -> None:
        if codes.checking():
            codes.check(code, "warning")
        if code in self.silenced:
            return
        sev = Severity.ERROR if self.warnings_as_errors else Severity.WARNING
        self.diagnostics.append(Diagnostic(sev, code, message, loc, hint))

    @property
    def has_errors(self) -> bool:
        return any(d.severity is Severity.ERROR for d in self.diagnostics)

    @property
    def errors(self) -> list[Diagnostic]:
        return [d for d in self.diagnostics if d.severity is Severity.ERROR]

    def extend(self, diags: Iterable[Diagnostic]) -> None:
        for d in diags:
            if d.severity is Severity.WARNING:
                self.warning(d.code, d.message, d.loc, d.hint)
            else:
                if codes.checking():
                    codes.check(d.code, d.severity.value)
                self.diagnostics.append(d)

    def sorted(self) -> list[Diagnostic]:
        """Stable order for output: by file, then line, then column (sink order breaks ties)."""
        return sorted(self.diagnostics, key=lambda d: (d.loc.file, d.loc.line, d.loc.col))


def did_you_mean(name: str, candidates: Iterable[str]) -> str | None:
    """A 'did you mean' hint for a misspelt name, or None when nothing is close."""
    pool = sorted(set(candidates))
    import difflib  # only where a name is unknown

    best = difflib.get_close_matches(name, pool, n=1, cutoff=0.6)
    if not best:
        lowered = {c.lower(): c for c in pool}
        if name.lower() in lowered:
            best = [lowered[name.lower()]]
    return f"did you mean '{best[0]}'?" if best else None


SourceReader = Callable[[str], "list[str] | None"]


def _gutter(width: int, text: str = "") -> str:
    return f"{text:>{width}} | "


def _printable(text: str) -> str:
    """Control characters (e.g. ESC from a binary file) become '?', so they never reach the
    terminal; one character each, so carets stay aligned."""
    return "".join(ch if ch.isprintable() else "?" for ch in text) if not text.isprintable() else text


def escaped(text: str) -> str:
    """Text with every non-printable character written as a Python escape (ESC -> \\x1b):
    messages and hints quote names from untrusted inputs, which must not drive the terminal."""
    if text.isprintable():
        return text
    return "".join(ch if ch.isprintable() else repr(ch)[1:-1] for ch in text)


def render(diag: Diagnostic, read_lines: SourceReader | None = None) -> str:
    """Render one diagnostic; the source excerpt is shown when the line can be read."""
    hint = escaped(diag.hint) if diag.hint else None
    head = escaped(f"{diag.loc}: {diag.severity.value}[{diag.code}]: {diag.message}")
    lines = read_lines(diag.loc.file) if read_lines and diag.loc.line > 0 else None
    if not lines or diag.loc.line > len(lines):
        return head + (f"\n  = hint: {hint}" if hint else "")
    src = _printable(lines[diag.loc.line - 1].rstrip("\r\n").expandtabs(1))
    if len(src) > 200:  # keep huge one-line inputs readable
        start = max(0, diag.loc.col - 80)
        src = src[start:start + 160]
        col = diag.loc.col - start
    else:
        col = diag.loc.col
    width = max(3, len(str(diag.loc.line)))
    span = 1
    if diag.loc.end_line == diag.loc.line and diag.loc.end_col > diag.loc.col:
        span = diag.loc.end_col - diag.loc.col
    span = max(1, min(span, max(1, len(src) - col + 1)))
    caret = " " * max(0, col - 1) + "^" * span
    out = [head, _gutter(width, str(diag.loc.line)) + src,
           _gutter(width) + caret + (f" {hint}" if hint else "")]
    return "\n".join(out)


class FileLineCache:
    """Reads source lines for rendering, tolerating unreadable or binary files."""

    def __init__(self) -> None:
        self._cache: dict[str, list[str] | None] = {}

    def add_text(self, path: str, text: str) -> None:
        self._cache[path] = text.splitlines()

    def __call__(self, path: str) -> list[str] | None:
        if path not in self._cache:
            try:
                with open(path, "rb") as fh:
                    data = fh.read(16 * 1024 * 1024)
                self._cache[path] = None if b"\0" in data else data.decode(
                    "utf-8", errors="replace").splitlines()
            except OSError:
                self._cache[path] = None
        return self._cache[path]


def display_path(path: str) -> str:
    """Paths shown to the user: relative to the working folder when inside it."""
    norm = os.path.normpath(path)
    if os.path.isabs(norm):
        try:
            rel = os.path.relpath(norm)
        except ValueError:
            return norm
        if not rel.startswith(".."):
            return rel
    return norm
