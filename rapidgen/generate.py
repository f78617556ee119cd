"""Fan one parsed input out to the requested back ends.

Inputs are either one asset descriptor (YAML; it names its IDL) or IDL files (types
alone). Each target's files go under `<lang>/` in the output folder.
"""
from __future__ import annotations

import os
from dataclasses import dataclass

from rapidgen import backends
from rapidgen.backends.base import GeneratedFile, GenerationError, Options
from rapidgen.diagnostics import DiagnosticSink, SourceLoc
from rapidgen.model.ir import Model


@dataclass
class Inputs:
    model: Model
    asset: object | None  # rapidgen.asset.LoadedAsset
    source: str  # how headers name the source


def is_asset(path: str) -> bool:
    return path.endswith((".yaml", ".yml"))


def source_name(paths: list[str]) -> str:
    """Stable, machine-independent name of the inputs for file headers."""
    shown = [p.replace(os.sep, "/") for p in paths]
    if len(shown) > 3:
        folders = sorted({os.path.dirname(p) or "." for p in shown})
        return ", ".join(f"{f}/*.idl" for f in folders)
    return ", ".join(shown)


def load_inputs(paths: list[str], include: list[str], sink: DiagnosticSink) -> Inputs | None:
    assets = [p for p in paths if is_asset(p)]
    if assets:
        if len(paths) != 1:
            sink.error("RG0801", "give one asset descriptor, or IDL files, not both", SourceLoc(paths[0], 1, 1),
                       "an asset descriptor names its own IDL files")
            return None
        from rapidgen.asset import load_asset

        loaded = load_asset(assets[0], sink)
        if loaded is None or loaded.model is None or sink.has_errors:
            return None
        return Inputs(loaded.model, loaded, source_name(assets))
    from rapidgen.frontend import load_idl

    model, _ = load_idl(paths, include, sink)
    if model is None:
        return None
    return Inputs(model, None, source_name(paths))


def render(inputs: Inputs, langs: list[str], sink: DiagnosticSink, package: str | None = None) -> list[GeneratedFile] | None:
    unknown = [lang for lang in langs if lang not in backends.available()]
    if unknown:
        sink.error("RG0802", f"unknown or unavailable target '{unknown[0]}'", SourceLoc("<command line>", 0, 0),
                   f"available: {', '.join(backends.available())}")
        return None
    files: list[GeneratedFile] = []
    options = Options(source=inputs.source, package=package)
    for lang in langs:
        try:
            produced = backends.get(lang).generate(inputs.model, inputs.asset, options)
        except GenerationError as exc:
            exc.report(sink)
            return None
        files += [GeneratedFile(f"{lang}/{f.path}", f.content, f.user_owned) for f in produced]
    return files
