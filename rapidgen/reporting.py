"""How a command prints its diagnostics: every one, then a count; `--format github` as
GitHub Actions annotations. Every subcommand reports through this (the CLI and the
packages of the live tools alike), so none imports the CLI for it."""
from __future__ import annotations

import sys

from rapidgen import codes
from rapidgen.diagnostics import DiagnosticSink, FileLineCache, Severity, render


def report(sink: DiagnosticSink, stream=None, fmt: str = "text") -> None:
    """Print every diagnostic, then a count (`fmt` github: each as a GitHub Actions
    annotation on stdout, the count on stderr)."""
    stream = stream or sys.stderr
    lines = FileLineCache()
    if codes.checking():  # diagnostics some stages add to the sink directly (notes)
        for d in sink.diagnostics:
            promoted = d.severity is Severity.ERROR and sink.warnings_as_errors
            if not (promoted and codes.can_be_silenced(d.code)):
                codes.check(d.code, d.severity.value)
    if fmt == "github":
        from rapidgen.github_annotations import of_diagnostic
        for d in sink.sorted():
            print(of_diagnostic(d), file=sys.stdout)
    else:
        for d in sink.sorted():
            print(render(d, lines), file=stream)
    errors = sum(1 for d in sink.diagnostics if d.severity is Severity.ERROR)
    warnings = sum(1 for d in sink.diagnostics if d.severity is Severity.WARNING)
    if errors or warnings:
        parts = [f"{errors} error{'s' * (errors != 1)}"] if errors else []
        parts += [f"{warnings} warning{'s' * (warnings != 1)}"] if warnings else []
        print(f"rapidgen: {', '.join(parts)}", file=stream)
