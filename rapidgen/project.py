"""The project file (rapidgen.yaml at the repository root): what generated/ holds.

    targets:
      - name: rapid                 # the RAPID message set alone
        idl: [specs/rapid/*.idl]    # globs, expanded and sorted
        include: [specs/rapid]
        lang: [python]
        out: generated/rapid
      - name: k10
        asset: specs/assets/k10.yaml
        lang: [python, qos]
        out: generated/k10

`rapidgen check` regenerates every target in memory and reports what is stale;
`rapidgen check --fix` rewrites it. Paths are relative to the project file.
"""
from __future__ import annotations

import glob
import os
from dataclasses import dataclass

import jsonschema

from rapidgen.schema_report import end_of, report_capped
from rapidgen.yamlread import parse_yaml
from rapidgen.diagnostics import DiagnosticSink, SourceLoc

PROJECT_FILE = "rapidgen.yaml"
_MAX_CHARS = 1024 * 1024

_SCHEMA = {
    "type": "object",
    "required": ["targets"],
    "additionalProperties": False,
    "properties": {"targets": {"type": "array", "items": {
        "type": "object",
        "required": ["name", "lang", "out"],
        "additionalProperties": False,
        "properties": {
            "name": {"type": "string", "pattern": "^[A-Za-z0-9_.-]+$"},
            "idl": {"type": "array", "items": {"type": "string"}, "minItems": 1},
            "include": {"type": "array", "items": {"type": "string"}},
            "asset": {"type": "string"},
            "lang": {"type": "array", "items": {"type": "string"}, "minItems": 1},
            "out": {"type": "string"},
            "package": {"type": "string"},
        },
        "oneOf": [{"required": ["idl"]}, {"required": ["asset"]}],
    }}},
}


@dataclass(frozen=True)
class Target:
    name: str
    inputs: tuple[str, ...]  # an asset descriptor, or IDL files
    include: tuple[str, ...]
    lang: tuple[str, ...]
    out: str
    package: str | None = None
    source: str = ""  # the inputs as the project file names them, for file headers


def load_project(path: str, sink: DiagnosticSink) -> list[Target] | None:
    loc = SourceLoc(path, 1, 1)
    try:
        with open(path, encoding="utf-8") as fh:
            text = fh.read(_MAX_CHARS + 1)
        if len(text) > _MAX_CHARS:
            sink.error("RG0811", "project file is larger than 1 MiB", loc, "is this the right file?")
            return None
    except OSError as exc:
        sink.error("RG0810", f"cannot read project file '{path}': {exc.strerror or exc}", loc,
                   f"run from the project root, or pass --project FILE")
        return None
    except UnicodeDecodeError as exc:
        sink.error("RG0811", f"project file is not UTF-8 text (byte 0x{exc.object[exc.start]:02x})", loc)
        return None
    # The descriptor loader: positions for every value, and its limits on size, nesting,
    # aliases and control characters (no field here is free text).
    doc = parse_yaml(text.lstrip("\ufeff"), path, sink, free_text=())
    if doc is None:
        return None
    data = doc.data
    errors = jsonschema.Draft202012Validator(_SCHEMA).iter_errors(data)
    if report_capped(errors, sink, lambda err: [(
            "RG0812", f"project file: at {'/'.join(str(p) for p in err.absolute_path) or '(top level)'}: "
            f"{_clip(err.message)}", doc.loc(tuple(err.absolute_path)), None)], end_of(doc), "RG0812"):
        return None
    assert isinstance(data, dict)  # the schema's top level is an object
    root = os.path.dirname(path)
    targets = []
    for i, t in enumerate(data["targets"]):
        if not _inside(root, t["out"]):
            sink.error("RG0815", f"target '{t['name']}': output folder '{t['out']}' is outside the project",
                       doc.loc(("targets", i, "out")), "`rapidgen check --fix` writes there: give a folder "
                       "inside the project, relative to rapidgen.yaml, not through a link that leaves it")
            continue
        if "asset" in t:
            inputs: tuple[str, ...] = (os.path.join(root, t["asset"]),)
            source = t["asset"]
        else:
            found: list[str] = []
            for pattern in t["idl"]:
                matches = sorted(glob.glob(os.path.join(root, pattern)))
                if not matches:
                    sink.error("RG0813", f"target '{t['name']}': no IDL file matches '{pattern}'", loc)
                found += matches
            inputs = tuple(found)
            source = ", ".join(t["idl"])
        targets.append(Target(t["name"], inputs, tuple(os.path.join(root, i) for i in t.get("include", [])),
                              tuple(t["lang"]), os.path.join(root, t["out"]), t.get("package"), source))
    _check_outputs(targets, loc, sink)
    return None if sink.has_errors else targets


def _inside(root: str, out: str) -> bool:
    """True when out, relative to the project folder, stays inside it once links are resolved
    (a project file comes from a repository; its outputs must not land elsewhere)."""
    if os.path.isabs(out):
        return False
    top = os.path.realpath(root or ".")
    return os.path.commonpath([top, os.path.realpath(os.path.join(top, out))]) == top


def _clip(message: str, limit: int = 160) -> str:
    """jsonschema quotes the whole offending value; a long one is cut."""
    return message if len(message) <= limit else message[:limit - 3] + "..."


def _check_outputs(targets: list[Target], loc: SourceLoc, sink: DiagnosticSink) -> None:
    """Targets must not share a name or write into each other's output folders."""
    seen: dict[str, Target] = {}
    for t in targets:
        if t.name in seen:
            sink.error("RG0814", f"two targets are named '{t.name}'", loc, "give each target its own name")
        seen.setdefault(t.name, t)
    outs = [(os.path.normpath(os.path.abspath(t.out)), t) for t in targets]
    for i, (a, ta) in enumerate(outs):
        for b, tb in outs[i + 1:]:
            if a == b or b.startswith(a + os.sep) or a.startswith(b + os.sep):
                sink.error("RG0814", f"targets '{ta.name}' and '{tb.name}' write into the same folder "
                           f"({ta.out}, {tb.out})", loc, "each target needs its own output folder; "
                           "one target can list several languages")
