"""Load a descriptor end to end: read YAML, schema, build, load the IDL, check.

Where the RAPID base IDL comes from, first match wins: the caller's `rapid_dir`
(`--rapid DIR`), the descriptor's `idl.rapid`, then `specs/rapid/` in the descriptor's
folder or the nearest folder above it (the project layout rapidgen itself uses).
"""
from __future__ import annotations

import dataclasses
import glob
import os

from rapidgen.asset.build import build_spec
from rapidgen.asset.check import check_asset
from rapidgen.asset.resolved import LoadedAsset
from rapidgen.asset.schema import check_schema
from rapidgen.asset.spec import AssetSpec
from rapidgen.yamlread import load_yaml
from rapidgen.diagnostics import Diagnostic, DiagnosticSink
from rapidgen.diagnostics import display_path
from rapidgen.model.ir import Model


# (files with mtimes, include dirs) -> (model, diagnostics): validating many descriptors
# against the same RAPID set parses it once.
_IDL_CACHE: dict[tuple, tuple[Model | None, list[Diagnostic]]] = {}


def find_rapid_dir(start: str) -> str | None:
    """The nearest specs/rapid at or above start, else the RAPID IDL shipped in the package."""
    here = os.path.abspath(start)
    while True:
        cand = os.path.join(here, "specs", "rapid")
        if os.path.isfile(os.path.join(cand, "Message.idl")):
            return display_path(cand)
        parent = os.path.dirname(here)
        if parent == here:
            break
        here = parent
    # rapidgen/rapid_idl is specs/rapid in a checkout (a symlink) and a copy in the wheel.
    shipped = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "rapid_idl")
    return display_path(shipped) if os.path.isfile(os.path.join(shipped, "Message.idl")) else None


def _idl_model(spec: AssetSpec, rapid_dir: str | None, sink: DiagnosticSink) -> Model | None:
    idl_loc = spec.at("idl", "rapid") if spec.has("idl", "rapid") else spec.at("idl") if spec.has("idl") else spec.loc
    rapid = rapid_dir or spec.rapid_dir or find_rapid_dir(os.path.dirname(spec.file) or ".")
    if rapid is None:
        sink.error("RG1309", "cannot find the RAPID IDL", idl_loc,
                   "set 'idl: {rapid: path/to/rapid}' in the descriptor or pass --rapid DIR")
        return None
    base = sorted(glob.glob(os.path.join(glob.escape(rapid), "*.idl")))
    if not base:
        sink.error("RG1309", f"no RAPID IDL files in '{display_path(rapid)}'", idl_loc,
                   "the folder should hold Message.idl, Command.idl, ...")
        return None
    ok = True
    for i, f in enumerate(spec.idl_files):
        if not os.path.isfile(f):
            sink.error("RG1310", f"extension IDL file '{display_path(f)}' not found", spec.at("idl", "files", i),
                       "paths are relative to the descriptor's folder")
            ok = False
    for i, d in enumerate(spec.include_dirs):
        if not os.path.isdir(d):
            sink.error("RG1310", f"include folder '{display_path(d)}' not found", spec.at("idl", "include", i),
                       "paths are relative to the descriptor's folder")
            ok = False
    if not ok:
        return None
    files = base + [f for f in spec.idl_files if os.path.abspath(f) not in map(os.path.abspath, base)]
    includes = [rapid, *spec.include_dirs]
    # The working folder is part of the key: diagnostics name files relative to it.
    key = (tuple((os.path.abspath(f), os.stat(f).st_mtime_ns, os.stat(f).st_size) for f in files),
           tuple(os.path.abspath(d) for d in includes), os.getcwd())
    if key not in _IDL_CACHE:
        from rapidgen.idl.load import load_idl
        local = DiagnosticSink()
        model, _ = load_idl(files, includes, local)
        if len(_IDL_CACHE) > 32:
            _IDL_CACHE.clear()
        _IDL_CACHE[key] = (model, list(local.diagnostics))
    model, diags = _IDL_CACHE[key]
    sink.extend(diags)
    return model


def load_asset(path: str, sink: DiagnosticSink, rapid_dir: str | None = None) -> LoadedAsset | None:
    """The checked descriptor, or None when it could not be read or failed the schema.

    Check errors (unknown types, bounds, ...) are reported to the sink and the spec is
    still returned, so a caller can decide; `sink.has_errors` tells whether it is valid.
    """
    shown = display_path(path)
    doc = load_yaml(path, shown, sink)
    if doc is None or not check_schema(doc, sink):
        return None
    spec = build_spec(doc, os.path.dirname(path))
    loaded = LoadedAsset(spec, _idl_model(spec, rapid_dir, sink))
    check_asset(loaded, sink)
    if isinstance(doc.data, dict) and "ros2" in doc.data:
        from rapidgen.ros2.section import read_ros2  # only for descriptors that map onto ROS 2
        loaded = dataclasses.replace(loaded, ros2=read_ros2(doc, loaded, sink))
    if isinstance(doc.data, dict) and "conformance" in doc.data:
        from rapidgen.asset.conformance import read_conformance
        loaded = dataclasses.replace(loaded, conformance=read_conformance(doc, loaded, sink))
    return loaded
