"""`--format github`: diagnostics and findings as GitHub Actions workflow commands.

    ::error file=specs/rapid/Ack.idl,line=12,col=21,title=error[RG0203]::unknown base type 'Mesage' (hint: ...)

GitHub reads these lines from a step's standard output and shows each as an annotation on
the file and line (in the pull request's diff too). Values are escaped as the runner
expects: '%', CR and LF in the message; also ':' and ',' in a property. Everything else
(control characters, bidirectional overrides) goes through diagnostics.escaped first, like
the text output. Docs: docs/ci.md.
"""
from __future__ import annotations

from rapidgen.diagnostics import Diagnostic, Severity, SourceLoc, escaped

FORMATS = ("text", "github")
LEVELS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.NOTE: "notice"}


def escape_data(text: str) -> str:
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def escape_property(text: str) -> str:
    return escape_data(text).replace(":", "%3A").replace(",", "%2C")


def command(level: str, message: str, loc: SourceLoc | None = None, title: str | None = None,
            with_line: bool = True) -> str:
    """One workflow command; a location that is no file ('<command line>', '') names none,
    line 0 (the file as a whole) no line."""
    props = []
    if loc is not None and loc.file and not loc.file.startswith("<"):
        props.append(f"file={escape_property(escaped(loc.file))}")
        if with_line and loc.line > 0:
            props.append(f"line={loc.line}")
            if loc.col > 0:
                props.append(f"col={loc.col}")
    if title:
        props.append(f"title={escape_property(escaped(title))}")
    return f"::{level} {','.join(props)}::{escape_data(escaped(message))}" if props else \
        f"::{level}::{escape_data(escaped(message))}"


def of_diagnostic(d: Diagnostic) -> str:
    message = d.message + (f" (hint: {d.hint})" if d.hint else "")
    return command(LEVELS[d.severity], message, d.loc, f"{d.severity.value}[{d.code}]")
