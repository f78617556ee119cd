"""key=value words parsed by their parameter's type, checked against its range and allowed
values, defaults filled; every problem located at its word on the command line."""
from __future__ import annotations

import shlex

from rapidgen.cmd.line import CmdLine, did_you_mean
from rapidgen.diagnostics import DiagnosticSink

KIND = {"RAPID_BOOL": "a boolean (true/false)", "RAPID_INT": "a 32-bit integer", "RAPID_LONGLONG": "a 64-bit integer",
        "RAPID_FLOAT": "a number", "RAPID_DOUBLE": "a number", "RAPID_STRING": "a string",
        "RAPID_VEC3d": "3 numbers (x,y,z)", "RAPID_MAT33f": "9 numbers (row by row)"}


def _check_value(p, value, line: CmdLine, index: int, offset: int, sink: DiagnosticSink, limits: bool):
    from rapid_runtime.values import coerce, limit_error, shape_error

    value = coerce(p.type, value)
    why = shape_error(p.type, value) or (limit_error(p, value) if limits else None)
    if why:
        unit = f" [{p.unit}]" if p.unit else ""
        sink.error("RG1905", f"{p.name}: {why}", line.at(index, offset),
                   f"{p.name} is {KIND.get(p.type, p.type)}{unit}" + _limits_text(p))
        return None
    return value


def _limits_text(p) -> str:
    parts = []
    if p.min is not None or p.max is not None:
        parts.append(f"in [{'-inf' if p.min is None else f'{p.min:g}'}, {'inf' if p.max is None else f'{p.max:g}'}]")
    if p.allowed:
        parts.append("one of " + "|".join(map(str, p.allowed)))
    return (", " + ", ".join(parts)) if parts else ""


def complete(entry, words: list[str], first: int, line: CmdLine, sink: DiagnosticSink,
             limits: bool = True) -> list[tuple[str, object]] | None:
    """(DataType, value) per parameter in order: key=value words parsed by type, defaults
    filled, every problem reported at its word. None when any was found."""
    from rapid_runtime.values import parse_text

    by_key = {}
    for p in entry.params:
        by_key[p.name] = p
        by_key.setdefault(p.arg, p)
    given: dict[str, object] = {}
    for i, word in enumerate(words, first):
        key, eq, text = word.partition("=")
        if not eq or not key:
            sink.error("RG1904", f"'{word}' is not key=value", line.at(i),
                       f"{entry.name} takes " + (", ".join(f"{p.name}=..." for p in entry.params) or "no arguments"))
            continue
        p = by_key.get(key)
        if p is None:
            sink.error("RG1904", f"{entry.name} has no parameter '{key}'", line.at(i, 0, len(key)),
                       did_you_mean(key, [q.name for q in entry.params]))
            continue
        if p.name in given:
            sink.error("RG1904", f"'{p.name}' given twice", line.at(i, 0, len(key)), "give each parameter once")
            continue
        offset = len(key) + 1 + (shlex.quote(word) != word)  # the value's column (after an opening quote)
        try:
            value = parse_text(p.type, text)
        except ValueError:
            sink.error("RG1905", f"{p.name}: '{text}' is not {KIND.get(p.type, p.type)}", line.at(i, offset),
                       f"{p.name} is {p.type}" + (f" [{p.unit}]" if p.unit else "") + _limits_text(p))
            given[p.name] = None
            continue
        given[p.name] = _check_value(p, value, line, i, offset, sink, limits)
    missing = [p for p in entry.params if p.name not in given and not p.has_default]
    if missing:
        sink.error("RG1906", f"{entry.name} needs " + ", ".join(f"{p.name} ({p.type})" for p in missing),
                   line.at(2), "add " + " ".join(f"{p.name}=..." for p in missing))
    if sink.has_errors:
        return None
    from rapid_runtime.values import coerce
    return [(p.type, given[p.name] if p.name in given else coerce(p.type, p.default)) for p in entry.params]
