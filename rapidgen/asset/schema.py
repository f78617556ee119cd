"""JSON Schema check of a descriptor, with every error turned into a located diagnostic.

jsonschema's own messages quote whole instances and schema fragments; operators need
"unknown key 'rat' (did you mean 'rate'?)" at the key's line and column instead. Each
validator keyword we use has a translation below; the rest fall back to a short
generic message, never the raw text.
"""
from __future__ import annotations

import json
from functools import lru_cache
from typing import Any, Callable, Iterable

import jsonschema
from jsonschema.exceptions import ValidationError

from rapidgen.asset.facts import STATIC_SHAPES
from rapidgen.schema_report import Translated, end_of, report_capped
from rapidgen.yamlread import YamlDoc
from rapidgen.packagedata import read_text
from rapidgen.diagnostics import DiagnosticSink, SourceLoc, did_you_mean

_NAMES = {dict: "a mapping", list: "a list", str: "a string", bool: "true or false",
          int: "a number", float: "a number", type(None): "nothing"}
_SCHEMA_TYPES = {"object": "a mapping", "array": "a list", "string": "a string",
                 "boolean": "true or false", "integer": "a whole number", "number": "a number",
                 "null": "nothing"}


@lru_cache(maxsize=1)
def schema() -> dict:
    return json.loads(read_text("rapidgen.asset", "asset.schema.json"))


@lru_cache(maxsize=1)
def _validator() -> jsonschema.Draft202012Validator:
    return jsonschema.Draft202012Validator(schema())


def _what(path) -> str:
    """A readable name for a path: telemetry[2].rate."""
    out = ""
    for p in path:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else str(p))
    return out or "the descriptor"


def _shown(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (dict, list)) or value is None:
        return _NAMES[type(value)]
    text = str(value)
    return repr(text if len(text) <= 40 else text[:37] + "...") if isinstance(value, str) else text


def check_schema(doc: YamlDoc, sink: DiagnosticSink) -> bool:
    """True when the document satisfies the schema; diagnostics for every violation."""
    if doc.data is None:
        sink.error("RG1020", "the descriptor is empty", doc.loc(()),
                   "start with 'version: 1' and an 'asset:' section")
        return False
    return not report_capped(_validator().iter_errors(doc.data), sink, lambda e: _translate(e, doc), end_of(doc))


def _translate(e: ValidationError, doc: YamlDoc):
    path = tuple(e.absolute_path)
    where = _what(path)
    kw = e.validator
    inst: Any = e.instance  # the value that failed: any JSON value
    val: Any = e.validator_value  # the keyword's value: any JSON value
    sch: dict = e.schema if isinstance(e.schema, dict) else {}  # (our schemas are never bare booleans)
    loc = doc.loc(path)
    hint = sch.get("x-hint")
    if kw == "required":
        missing = [k for k in val if isinstance(inst, dict) and k not in inst]
        for k in missing:
            yield ("RG1020", f"{where} needs '{k}'" if path else f"the descriptor needs '{k}'",
                   doc.key_loc(path) if path else loc, _required_hint(k, sch.get("properties", {}).get(k)))
    elif kw == "additionalProperties":
        allowed = list(sch.get("properties", {}))
        for k in (k for k in inst if k not in allowed):
            yield ("RG1021", f"unknown key {_shown(k)} in {where}", doc.key_loc(path + (k,)),
                   did_you_mean(k, allowed) or _comma_hint(doc, path, k) or f"allowed here: {', '.join(allowed)}")
    elif kw == "type":
        want = " or ".join(_SCHEMA_TYPES.get(t, str(t)) for t in (val if isinstance(val, list) else [val]))
        got = _NAMES.get(type(inst), "a value")
        if not isinstance(inst, (dict, list)) and inst is not None:
            shown = _shown(inst)
            written = doc.written(path, shown) if isinstance(inst, (int, float, bool)) else shown
            # YAML 1.1 reads `on`, `yes`, `0x10` as true, true, 16: name both spellings
            got += f" ({shown})" if written == shown else f" ({written}, which YAML reads as {shown})"
            if val == "string" and isinstance(inst, (int, float, bool)):
                hint = _string_hint(doc, path, written)
        yield "RG1022", f"{where} must be {want}, not {got}", loc, hint
    elif kw in ("enum", "const"):
        options = [str(v) for v in (val if kw == "enum" else [val])]
        close = did_you_mean(inst, options) if isinstance(inst, str) else None
        listed = " or ".join(options) if len(options) < 3 else "one of: " + ", ".join(options)
        yield "RG1023", f"{where} cannot be {_shown(inst)}", loc, close or f"expected {listed}"
    elif kw in ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum"):
        rel = {"minimum": ">=", "maximum": "<=", "exclusiveMinimum": ">", "exclusiveMaximum": "<"}[kw]
        yield "RG1024", f"{where} is {_shown(inst)}; it must be {rel} {val}", loc, hint
    elif kw == "pattern":
        yield "RG1025", f"{where} {_shown(inst)} is not valid here", loc, hint
    elif kw in ("minItems", "maxItems", "minLength", "maxLength", "minProperties", "uniqueItems"):
        yield "RG1026", _size_message(kw, val, where, inst), loc, hint
    elif kw == "not" and "dependentSchemas" in e.relative_schema_path:
        yield ("RG1021", f"'{path[-1]}' cannot be combined with 'range'", doc.key_loc(path),
               "give either range: [min, max] or min:/max:")
    elif kw == "anyOf" and all(set(s) == {"required"} for s in val):
        names = [s["required"][0] for s in val]
        yield ("RG1020", f"{where} needs at least one of: {', '.join(names)}",
               doc.key_loc(path) if path else loc, None)
    else:  # a keyword the schema may grow later: short and located, never jsonschema's dump
        yield "RG1029", f"{where} is not valid here ({kw})", loc, hint


def _comma_hint(doc: YamlDoc, path: tuple, key: str) -> str | None:
    """In {a: b, c} a comma ends b: an unknown key right after unquoted text is most
    likely the rest of that text."""
    prev = doc.split_values.get(path + (key,))
    if prev is None:
        return None
    value = _value_at(doc.data, path + (prev,))
    whole = f"{value}, {key}" if isinstance(value, str) else ""
    example = f' ({prev}: "{whole}")' if whole and len(whole) <= 60 and not set(whole) & set('"\\') else ""
    return f"a comma inside {{ }} ends a value: quote the value of '{prev}' if the comma is part of it{example}"


def _string_hint(doc: YamlDoc, path: tuple, written: str) -> str:
    """What to do about a number or boolean where a string belongs: usually quote it, but
    not in the 'allowed' list of a numeric value, where a quoted number only meets RG1205."""
    if len(path) >= 2 and path[-2] == "allowed":
        owner = _value_at(doc.data, path[:-2])
        dtype = owner.get("type") if isinstance(owner, dict) else None
        shape = STATIC_SHAPES.get(dtype) if isinstance(dtype, str) else None
        if shape is not None and shape.kind != "string":
            instead = "it needs none" if shape.kind == "bool" else "give range: [min, max] or min:/max: instead"
            return f"'allowed' values exist only for RAPID_STRING; for a {dtype} {instead}"
    return f"quote it: '{written}'"


def _value_at(data: object, path: tuple) -> object:
    for p in path:
        if isinstance(p, int) and isinstance(data, list) and p < len(data):
            data = data[p]
        elif isinstance(p, str) and isinstance(data, dict) and p in data:
            data = data[p]
        else:
            return None
    return data


def _size_message(kw: str, val, where: str, inst) -> str:
    if kw == "minItems":
        return f"{where} needs at least {val} item{'s' * (val != 1)}"
    if kw == "maxItems":
        return f"{where} has {len(inst)} items; at most {val} are allowed"
    if kw == "minLength":
        return f"{where} must not be empty"
    if kw == "maxLength":
        return f"{where} is longer than {val} characters"
    if kw == "minProperties":
        return f"{where} must not be empty"
    dupes = sorted({str(x) for x in inst if inst.count(x) > 1}) if isinstance(inst, list) else []
    return f"{where} repeats {', '.join(repr(d) for d in dupes)}" if dupes else f"{where} has repeated items"


_REQUIRED_HINTS = {
    "version": "add 'version: 1' at the top",
    "type": "a RAPID DataType such as RAPID_DOUBLE, RAPID_STRING or RAPID_VEC3d",
}


def _required_hint(key: str, prop) -> str | None:
    if isinstance(prop, dict) and "enum" in prop:
        return f"{key}: one of {', '.join(map(str, prop['enum']))}"
    return _REQUIRED_HINTS.get(key)
