"""Golden CDR vectors: `rapidgen vectors INPUT... -o FILE`.

Inputs are asset descriptors (each brings the full RAPID set plus its own IDL) and/or IDL
files (with -I); their models are merged by scoped name. For every struct and union the
file lists the deterministic samples of `rapidgen.cdr.samples` with their encodings by
the reference encoder (`rapidgen.cdr`): XCDR1 little- and big-endian and XCDR2
little-endian, each with its 4-byte encapsulation header, as lowercase hex.

The format is described in docs/cdr-and-vectors.md; the committed file for the RAPID set
and the seed assets is tests/vectors/rapid.json (a test regenerates it and compares).
"""
from __future__ import annotations

import json
import os

from rapidgen.diagnostics import DiagnosticSink, SourceLoc
from rapidgen.model import ir
from rapidgen.cdr import Codec, CdrError
from rapidgen.cdr.samples import SampleError, samples
from rapidgen.model.to_json import declaration

FORMAT = "rapidgen-vectors/1"
ENCODINGS = {
    "xcdr1_le": (1, True, "XCDR1 (CDR_LE / PL_CDR_LE), little-endian"),
    "xcdr1_be": (1, False, "XCDR1 (CDR_BE / PL_CDR_BE), big-endian"),
    "xcdr2_le": (2, True, "XCDR2 (CDR2_LE / D_CDR2_LE / PL_CDR2_LE), little-endian"),
}
# The committed vectors of the RAPID set and the seed assets (see tests/cdr/test_vectors_file.py).
COMMITTED = "tests/vectors/rapid.json"
COMMITTED_COMMAND = "rapidgen vectors specs/assets/*.yaml -o tests/vectors/rapid.json"


def source_name(paths: list[str]) -> str:
    """How the file names its inputs: stable, relative, with forward slashes."""
    return ", ".join(p.replace(os.sep, "/") for p in paths)


def load_model(paths: list[str], include: list[str], sink: DiagnosticSink,
               defines: dict[str, str] | None = None) -> ir.Model | None:
    """One model from asset descriptors and/or IDL files (merged by scoped name)."""
    models: list[ir.Model] = []
    assets = [p for p in paths if p.endswith((".yaml", ".yml"))]
    idl = [p for p in paths if p not in assets]
    for path in assets:
        from rapidgen.asset import load_asset

        loaded = load_asset(path, sink)
        if loaded is None or loaded.model is None:
            return None
        models.append(loaded.model)
    if idl:
        from rapidgen.idl.load import load_idl

        model, _ = load_idl(idl, include, sink, defines)
        if model is None:
            return None
        models.append(model)
    if sink.has_errors:
        return None
    return merge_models(models, sink)


def merge_models(models: list[ir.Model], sink: DiagnosticSink) -> ir.Model | None:
    if len(models) == 1:
        return models[0]
    decls: dict[str, ir.Declaration] = {}
    modules: dict[str, ir.Module] = {}
    files: list[str] = []
    ok = True
    for model in models:
        for mod in model.modules:
            modules.setdefault(mod.scoped_name, mod)
        for f in model.files:
            if f not in files:
                files.append(f)
        for d in model.declarations:
            first = decls.get(d.scoped_name)
            if first is None:
                decls[d.scoped_name] = d
            elif first is not d and declaration(first, loc=False) != declaration(d, loc=False):
                sink.error("RG0901", f"'{d.scoped_name}' is declared differently by two inputs", d.loc,
                           f"the other declaration is at {first.loc}")
                ok = False
    if not ok:
        return None
    return ir.Model(tuple(modules.values()), tuple(decls.values()), tuple(files))


def build(model: ir.Model, source: str) -> dict:
    """The vector file's content (a dict, before JSON)."""
    codec = Codec(model)
    vectors = []
    for s in samples(model, codec.types):
        entry: dict[str, object] = {"id": f"{s.type}/{s.name}", "type": s.type, "variant": s.name, "value": s.value}
        for key, (version, little, _) in ENCODINGS.items():
            entry[key] = codec.encode(s.type, s.value, version=version, little=little).hex()
        vectors.append(entry)
    return {
        "format": FORMAT,
        "generator": "rapidgen vectors (generated, do not edit; rerun the command to update)",
        "source": source,
        "encodings": {k: v[2] + ", with the 4-byte encapsulation header" for k, v in ENCODINGS.items()},
        "types": len({v["type"] for v in vectors}),
        "count": len(vectors),
        "vectors": vectors,
    }


def to_text(data: dict) -> str:
    """Deterministic JSON: one vector per line (readable diffs), UTF-8, sorted nowhere:
    the order is the generator's (types by scoped name, then variants)."""
    head = {k: v for k, v in data.items() if k != "vectors"}
    lines = ["{"]
    for k, v in head.items():
        lines.append(f"  {json.dumps(k)}: {json.dumps(v, ensure_ascii=False)},")
    lines.append('  "vectors": [')
    body = [f"    {json.dumps(v, ensure_ascii=False, allow_nan=False)}" for v in data["vectors"]]
    lines.append(",\n".join(body))
    lines.append("  ]")
    lines.append("}")
    return "\n".join(lines) + "\n"


def render(paths: list[str], include: list[str], sink: DiagnosticSink,
           defines: dict[str, str] | None = None) -> str | None:
    model = load_model(paths, include, sink, defines)
    if model is None:
        return None
    try:
        return to_text(build(model, source_name(paths)))
    except CdrError as exc:  # a sample the encoder refuses: a bug in the generator
        sink.error("RG0902", f"cannot encode a sample: {exc}", SourceLoc(paths[0], 1, 1))
        return None
    except SampleError as exc:
        sink.error("RG0903", f"cannot make sample values: {exc}", exc.loc or SourceLoc(paths[0], 1, 1),
                   "golden vectors are for small, readable values; leave this type out of the inputs")
        return None


def run_vectors(paths: list[str], include: list[str], output: str, sink: DiagnosticSink, report,
                defines: dict[str, str] | None = None) -> int:
    text = render(paths, include, sink, defines)
    report(sink)
    if text is None:
        return 1
    from rapidgen.writer import write_output

    failed = DiagnosticSink()  # the diagnostics above are already printed
    written = write_output(output, text, failed)
    if written is None:
        report(failed)
        return 1
    count = text.count('\n    {"id": ')
    print(f"{output}: {count} vectors, {'written' if written else 'unchanged'}")
    return 0
