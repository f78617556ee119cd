"""Python classes from a recording's own schemas, for the types no bindings know (an
extension type recorded without its descriptor at hand): each `omgidl` schema is compiled
by rapidgen's front end and Python back end into a package of its own in a temporary
folder, then imported. A schema is input like any IDL file (docs/security.md: generated code
never runs anything on import, hostile names are escaped); one that does not compile, or
that does not declare the type its name says, is reported and its channels not replayed.
Since the schema keeps RAPID's typedefs, the class's XTypes type information is the
asset's own and its readers match (tests/record)."""
from __future__ import annotations

import contextlib
import importlib
import io
import os
import sys
import tempfile
from typing import Any

MAX_SCHEMA = 1 << 20  # bytes of IDL text


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
    for i, (name, data) in enumerate(sorted(schemas.items())):
        if len(data) > MAX_SCHEMA:
            why[name] = f"its schema is over {MAX_SCHEMA >> 20} MiB"
            continue
        folder = os.path.join(tmp.name, str(i))
        os.makedirs(folder)
        path = os.path.join(folder, "schema.idl")
        with open(path, "wb") as fh:
            fh.write(data)
        sink = DiagnosticSink()
        model, _ = load_idl([path], [], sink)
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
