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
import yaml

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
        data = yaml.safe_load(text)
        root_node = yaml.compose(text)  # the same document as nodes: positions for schema errors
    except OSError as exc:
        sink.error("RG0810", f"cannot read project file '{path}': {exc.strerror or exc}", loc,
                   f"run from the project root, or pass --project FILE")
        return None
    except UnicodeDecodeError as exc:
        sink.error("RG0811", f"project file is not UTF-8 text (byte 0x{exc.object[exc.start]:02x})", loc)
        return None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = SourceLoc(path, mark.line + 1, mark.column + 1) if mark else loc
        sink.error("RG0811", f"project file is not valid YAML: {getattr(exc, 'problem', exc)}", where)
        return None
    errors = sorted(jsonschema.Draft202012Validator(_SCHEMA).iter_errors(data), key=lambda e: list(e.path))
    if errors:
        for err in errors:
            where = "/".join(str(p) for p in err.path) or "(top level)"
            sink.error("RG0812", f"project file: at {where}: {err.message}", _locate(root_node, err.path, path))
        return None
    root = os.path.dirname(path)
    targets = []
    for t in data["targets"]:
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


def _locate(node: yaml.Node | None, path, file: str) -> SourceLoc:
    """Where the value at a jsonschema error path starts (the deepest node found)."""
    for part in path:
        if isinstance(node, yaml.MappingNode):
            node = next((v for k, v in node.value if k.value == part), node)
        elif isinstance(node, yaml.SequenceNode) and isinstance(part, int) and part < len(node.value):
            node = node.value[part]
        else:
            break
    if node is None:
        return SourceLoc(file, 1, 1)
    mark = node.start_mark
    return SourceLoc(file, mark.line + 1, mark.column + 1)


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
