"""One side of a diff: an IDL file, a folder of IDL files, or an asset descriptor."""
from __future__ import annotations

import glob
import os
from dataclasses import dataclass

from rapidgen.asset.resolved import LoadedAsset
from rapidgen.diagnostics import DiagnosticSink, SourceLoc
from rapidgen.diagnostics import display_path
from rapidgen.model.ir import Model

ASSET_SUFFIXES = (".yaml", ".yml")


@dataclass(frozen=True)
class Side:
    model: Model
    asset: LoadedAsset | None  # the resolved descriptor; None: an IDL set


def kind_of(path: str) -> str:
    return "asset" if path.lower().endswith(ASSET_SUFFIXES) else "idl"


def load_side(path: str, include: list[str], defines: dict[str, str], sink: DiagnosticSink) -> Side | None:
    """The side's model (and descriptor), or None after located diagnostics."""
    here = SourceLoc(display_path(path), 0, 0)
    if not os.path.exists(path):
        sink.error("RG1801", f"'{display_path(path)}' does not exist", here,
                   "give an IDL file, a folder of IDL files or an asset descriptor (.yaml)")
        return None
    if kind_of(path) == "asset" and os.path.isfile(path):
        from rapidgen.asset.load import load_asset
        loaded = load_asset(path, sink)
        if loaded is None or loaded.model is None or sink.has_errors:
            return None
        return Side(loaded.model, loaded)
    if os.path.isdir(path):
        files = sorted(glob.glob(os.path.join(glob.escape(path), "*.idl")))
        include = [path, *include]
        if not files:
            sink.error("RG1801", f"no IDL files in '{display_path(path)}'", here, "the folder should hold *.idl files")
            return None
    elif os.path.isfile(path):
        files = [path]
    else:
        sink.error("RG1801", f"'{display_path(path)}' is not a file or a folder", here)
        return None
    from rapidgen.idl.load import load_idl
    model, _ = load_idl(files, include, sink, defines)
    return Side(model, None) if model is not None and not sink.has_errors else None
