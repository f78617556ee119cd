"""The IDL front end in one call: preprocess, parse, resolve."""
from __future__ import annotations

import gc

from rapidgen.diagnostics import DiagnosticSink, SourceLoc
from rapidgen.idl.parse import parse
from rapidgen.idl.preprocess import PreprocessResult, preprocess
from rapidgen.model.ir import Model
from rapidgen.idl.resolve import resolve


def load_idl(paths: list[str], include_dirs: list[str], sink: DiagnosticSink,
             defines: dict[str, str] | None = None) -> tuple[Model | None, PreprocessResult]:
    """The resolved model of the IDL files, or None when there were errors (all in sink)."""
    # The syntax tree and the model hold no reference cycles, so the cyclic GC only costs
    # time here: its full collections over a growing heap make large inputs superlinear.
    was_enabled = gc.isenabled()
    gc.disable()
    try:
        return _load(paths, include_dirs, sink, defines)
    finally:
        if was_enabled:
            gc.enable()


def _load(paths: list[str], include_dirs: list[str], sink: DiagnosticSink,
          defines: dict[str, str] | None) -> tuple[Model | None, PreprocessResult]:
    pre = preprocess(paths, include_dirs, sink, defines)
    if sink.has_errors:
        return None, pre
    if not pre.text.strip():
        where = pre.files[0] if pre.files else (paths[0] if paths else "<input>")
        sink.error("RG0004", "no IDL definitions in the input", SourceLoc(where, 1, 1),
                   "the file is empty or everything in it is excluded by #if")
        return None, pre
    spec = parse(pre, sink)
    if spec is None:
        return None, pre
    if not spec.definitions:
        where = pre.files[0] if pre.files else "<input>"
        sink.error("RG0004", "no IDL definitions in the input", SourceLoc(where, 1, 1),
                   "the file holds only comments or preprocessor lines")
        return None, pre
    model = resolve(spec, sink)
    return (None if sink.has_errors else model), pre
