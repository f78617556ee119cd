"""jsonschema errors of a YAML document as located diagnostics, capped (descriptors, the QoS
library and the project file share this): document order, at most MAX_SHOWN, one note
counting the rest. Each caller translates an error into its own words (asset/schema.py)."""
from __future__ import annotations

import heapq
from typing import Callable, Iterable

import jsonschema
from jsonschema.exceptions import ValidationError

from rapidgen.diagnostics import Diagnostic, DiagnosticSink, Severity, SourceLoc
from rapidgen.yamlread import YamlDoc

# Schema diagnostics shown per file: a list of 100,000 wrong items is one mistake made
# many times, and printing each would bury the first (and fill a terminal for minutes).
MAX_SHOWN = 50

Translated = tuple  # (code, message, loc, hint)


def _leaves(errors):
    """Descend into if/then and allOf wrappers: report the innermost errors."""
    for e in errors:
        if e.validator in ("anyOf", "oneOf") and e.context and \
                not all(set(s) == {"required"} for s in e.validator_value):
            # anyOf over (enum | string) never fails; other anyOfs: best branch
            best = jsonschema.exceptions.best_match(e.context)
            yield from _leaves([best]) if best is not None else [e]
        else:
            yield e


def report_capped(errors: Iterable[ValidationError], sink: DiagnosticSink,
                  translate: Callable[[ValidationError], Iterable[Translated]], end: SourceLoc,
                  note_code: str = "RG1027") -> bool:
    """Report jsonschema errors in document order, at most MAX_SHOWN distinct diagnostics,
    then one note at `end` counting the rest. True when there was any error.

    Only the first MAX_SHOWN errors are kept in memory (heapq), whatever their number.
    """
    total = 0

    def counted():
        nonlocal total
        for e in errors:
            total += 1
            yield e

    # document order: indices as numbers (item 10 after item 9), keys by name
    kept = heapq.nsmallest(MAX_SHOWN, counted(), key=lambda e: [(isinstance(p, str), p) for p in e.absolute_path])
    hidden = total - len(kept)
    shown: set[tuple] = set()
    for err in _leaves(kept):
        for code, msg, loc, hint in translate(err):
            key = (code, msg, loc.line, loc.col)
            if key in shown:
                continue
            if len(shown) >= MAX_SHOWN:
                hidden += 1
                continue
            shown.add(key)
            sink.error(code, msg, loc, hint)
    if hidden:
        sink.diagnostics.append(Diagnostic(Severity.NOTE, note_code, f"{hidden} more schema error"
                                           f"{'s' * (hidden != 1)} not shown", end, "fix the ones above first"))
    return total > 0


def end_of(doc: YamlDoc) -> SourceLoc:
    """The end of the document, where a note about the errors above sorts last."""
    root = doc.loc(())
    return SourceLoc(doc.file, root.end_line or root.line, root.end_col or root.col)
