"""Python classes from a recording's own schemas, for the types no bindings know (an
extension type recorded without its descriptor at hand): each `omgidl` schema is compiled
by rapidgen's front end and Python back end into a package of its own in a temporary
folder, then imported. A schema is input like any IDL file (docs/security.md: generated code
never runs anything on import, hostile names are escaped); one that does not compile, or
that does not declare the type its name says, is reported and its channels not replayed.
Since the schema keeps RAPID's typedefs, the class's XTypes type information is the
asset's own and its readers match (tests/record).

A schema holding a preprocessor directive is refused before anything compiles it: the
`omgidl` encoding is one self-contained text (no #include), and a directive is how a file
would make the compiler read this machine's files (`#include "/etc/..."`, whose first
token an error message then showed). Refused: any line whose first thing, after blanks and
block comments, is `#` (or its digraph `%:` or trigraph `??=`): a superset of the lines
rapidgen's preprocessor acts on, whatever it would do with them. And nothing but the
schema's own file may have been read by the front end (checked after it ran)."""
from __future__ import annotations

import contextlib
import importlib
import io
import os
import re
import sys
import tempfile
from typing import Any

MAX_SCHEMA = 1 << 20  # bytes of IDL text
MAX_COMPILED = 64  # schemas compiled for one replay (each is a package imported)
MAX_COMPILED_BYTES = 4 << 20  # their IDL text together

_LEAD = re.compile(r"(?:\s|/\*.*?\*/)*", re.DOTALL)  # blanks and whole block comments at a line's start
_NAME = re.compile(r"\s*([A-Za-z_]\w*)?")


def directive(text: str) -> tuple[int, str] | None:
    """(line, directive name) of the first preprocessor directive in an IDL text, or None."""
    for number, physical in enumerate(text.split("\n"), 1):
        for line in physical.splitlines():  # and every other line break the str type knows
            rest = line[_LEAD.match(line).end():]  # type: ignore[union-attr]  # (the pattern matches empty)
            for mark in ("#", "%:", "??="):
                if rest.startswith(mark):
                    name = _NAME.match(rest, len(mark)).group(1) or ""  # type: ignore[union-attr]
                    return number, mark + name[:20]
    return None


def classes_from_schemas(schemas: dict[str, bytes]) -> tuple[dict[str, Any], dict[str, str],
                                                             tempfile.TemporaryDirectory[str]]:
    """({type name: class}, {type name: why not}, the temporary folder to keep while the
    classes are used)."""
    from rapidgen.diagnostics import DiagnosticSink
    from rapidgen.generate import Inputs, render, write_outputs
    from rapidgen.idl.load import load_idl
    from rapidgen.model import ir
    from rapidgen.textsafe import visible
    tmp = tempfile.TemporaryDirectory(prefix="rapidgen-replay-")
    found: dict[str, Any] = {}
    why: dict[str, str] = {}
    compiled = compiled_bytes = 0
    for i, (name, data) in enumerate(sorted(schemas.items())):
        if len(data) > MAX_SCHEMA:
            why[name] = f"its schema is over {MAX_SCHEMA >> 20} MiB"
            continue
        found_directive = directive(data.decode("utf-8", "replace").removeprefix("\ufeff"))
        if found_directive is not None:
            line, what = found_directive
            why[name] = (f"its schema holds a preprocessor directive ({visible(what)} on its line {line}): refused "
                         "(a recording's schema must be one self-contained IDL text; nothing on this machine is "
                         "read because of a recording)")
            continue
        compiled, compiled_bytes = compiled + 1, compiled_bytes + len(data)
        if compiled > MAX_COMPILED or compiled_bytes > MAX_COMPILED_BYTES:
            why[name] = (f"not compiled: one replay compiles at most {MAX_COMPILED} schemas, "
                         f"{MAX_COMPILED_BYTES >> 20} MiB together (give the asset's descriptor with --asset)")
            continue
        folder = os.path.join(tmp.name, str(i))
        os.makedirs(folder)
        path = os.path.join(folder, "schema.idl")
        with open(path, "wb") as fh:
            fh.write(data)
        sink = DiagnosticSink()
        model, pre = load_idl([path], [], sink)
        if len(pre.files) != 1:  # (cannot happen past directive(): a second line of defence)
            why[name] = "its schema made the IDL front end read another file: refused"
            continue
        decl = model.get(name) if model is not None and not sink.has_errors else None
        if not isinstance(decl, (ir.Struct, ir.Union)):
            first = next((d.message for d in sink.diagnostics), f"it declares no struct {name}")
            why[name] = f"its schema does not compile ({visible(first)[:120]})"
            continue
        assert model is not None
        package = f"rapidschema{i}"
        per_lang = render(Inputs(model, None, "recording schema"), ["python"], sink, package)
        with contextlib.redirect_stdout(io.StringIO()):
            written = per_lang is not None and write_outputs(folder, per_lang, sink)
        if not written:
            why[name] = "its schema does not generate Python bindings"
            continue
        pydir = os.path.join(folder, "python")
        sys.path.insert(0, pydir)
        try:
            importlib.invalidate_caches()
            parts = name.split("::")
            module = importlib.import_module(".".join([package, *parts[:-1]]))
            found[name] = getattr(module, parts[-1])
        except (ImportError, AttributeError) as exc:
            why[name] = f"its generated bindings do not import ({visible(str(exc))[:120]})"
        finally:
            sys.path.remove(pydir)
    return found, why, tmp
