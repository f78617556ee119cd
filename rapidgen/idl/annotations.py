"""Checking of annotation applications.

Any `@name(...)` parses; the annotations below are known and their parameters are
checked and evaluated. Unknown annotations are kept out of the model with a warning
(RG0501) that can be silenced.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from rapidgen.diagnostics import DiagnosticSink, did_you_mean
from rapidgen.idl import ast
from rapidgen.model import ir
from rapidgen.idl.consts import ConstEvaluator, NameLookup, Target

class _Required:
    """The default of a parameter that must be given."""


REQUIRED = _Required()
Value = ir.ConstValue | None  # an evaluated parameter (None: not given, no default)

_PLACEMENTS = ("BEGIN_FILE", "BEFORE_DECLARATION", "BEGIN_DECLARATION", "END_DECLARATION",
               "AFTER_DECLARATION", "END_FILE")

# name -> ((parameter, kind, default), ...); kind: bool, uint16, uint32, string, const, any, or
# "ident:A|B" for an enumerated identifier.
KNOWN: dict[str, tuple[tuple[str, str, Value | _Required], ...]] = {
    "key": (("value", "bool", True),),
    "optional": (("value", "bool", True),),
    "external": (("value", "bool", True),),
    "nested": (("value", "bool", True),),
    "must_understand": (("value", "bool", True),),
    "id": (("value", "uint32", REQUIRED),),
    "hashid": (("value", "string", ""),),
    "autoid": (("value", "ident:SEQUENTIAL|HASH", "SEQUENTIAL"),),
    "final": (), "appendable": (), "mutable": (),
    "extensibility": (("value", "ident:FINAL|APPENDABLE|MUTABLE", REQUIRED),),
    "default": (("value", "const", REQUIRED),),
    "range": (("min", "const", REQUIRED), ("max", "const", REQUIRED)),
    "min": (("value", "const", REQUIRED),),
    "max": (("value", "const", REQUIRED),),
    "unit": (("value", "string", REQUIRED),),
    "topic": (("name", "string", ""), ("platform", "string", "*")),
    "bit_bound": (("value", "uint16", REQUIRED),),
    "value": (("value", "const", REQUIRED),),
    "position": (("value", "uint16", REQUIRED),),
    "verbatim": (("language", "string", "*"), ("placement", "ident:" + "|".join(_PLACEMENTS),
                 "BEFORE_DECLARATION"), ("text", "string", REQUIRED)),
    "default_literal": (),
    "ignore_literal_names": (("value", "bool", True),),
    "non_serialized": (("value", "bool", True),),
    "data_representation": (("value", "any", REQUIRED),),
    "try_construct": (("value", "any", "DISCARD"),),
}

# Where each annotation has an effect; elsewhere it draws a warning.
_WHERE = {
    "key": {"member", "discriminator"}, "optional": {"member"}, "external": {"member"},
    "id": {"member"}, "hashid": {"member"}, "default": {"member"}, "range": {"member"},
    "min": {"member"}, "max": {"member"}, "unit": {"member"},
    "nested": {"struct", "union"}, "final": {"struct", "union", "enum"},
    "appendable": {"struct", "union", "enum"}, "mutable": {"struct", "union"},
    "extensibility": {"struct", "union", "enum"}, "autoid": {"struct", "union"},
    "topic": {"struct", "union"}, "bit_bound": {"enum", "bitmask"}, "value": {"enumerator"},
    "position": {"bit_value"},
}


@dataclass(frozen=True, slots=True)
class Checked:
    annotations: tuple[ir.Annotation, ...]
    values: dict[str, dict[str, Value]]

    def get(self, name: str, param: str = "value", default: Value = None) -> Value:
        return self.values.get(name, {}).get(param, default)

    def integer(self, name: str, param: str = "value", default: int | None = None) -> int | None:
        """A parameter of an integer kind (uint16, uint32: evaluated to an int)."""
        value = self.get(name, param, default)
        assert value is None or isinstance(value, int), (name, param, value)
        return value

    def has(self, name: str) -> bool:
        return name in self.values


_NONE = Checked((), {})


class AnnotationChecker:
    def __init__(self, sink: DiagnosticSink, evaluator: ConstEvaluator) -> None:
        self.sink = sink
        self.evaluator = evaluator
        self.declared: set[str] = set()  # names from `@annotation X { ... }` in the input

    def check(self, anns: tuple[ast.AnnotationAppl, ...], where: str, lookup: NameLookup,
              value_target: Callable[[], Target] | None = None) -> Checked:
        if not anns:  # the common case: nothing to check
            return _NONE
        out: list[ir.Annotation] = []
        values: dict[str, dict[str, Value]] = {}
        for appl in anns:
            name = appl.name.lstrip(":")
            if name not in KNOWN and name.rsplit("::", 1)[-1] in self.declared:
                user = {p or "value": self.evaluator.evaluate(e, Target("any"), lookup) for p, e in appl.params}
                out.append(ir.Annotation(name, tuple(user.items()), appl.loc))
                continue
            if name not in KNOWN:
                self.sink.warning("RG0501", f"unknown annotation '@{appl.name}' is ignored", appl.loc,
                                  did_you_mean(name, KNOWN))
                continue
            if name in values:
                self.sink.error("RG0502", f"'@{name}' is applied twice", appl.loc)
                continue
            allowed = _WHERE.get(name)
            if allowed is not None and where not in allowed:
                self.sink.warning("RG0503", f"'@{name}' has no effect on {where.replace('_', ' ')}s",
                                  appl.loc)
            params = self._params(name, appl, lookup, value_target)
            if params is None:
                continue
            values[name] = params
            out.append(ir.Annotation(name, tuple(params.items()), appl.loc))
        kinds = [n for n in ("final", "appendable", "mutable", "extensibility") if n in values]
        if len(kinds) > 1:
            self.sink.error("RG0504", "conflicting extensibility annotations: " +
                            ", ".join(f"@{k}" for k in kinds), anns[0].loc)
        if "key" in values and "optional" in values and values["key"]["value"] and values["optional"]["value"]:
            self.sink.error("RG0504", "a key member cannot be @optional", anns[0].loc,
                            "remove @optional or @key")
        return Checked(tuple(out), values)

    def _params(self, name: str, appl: ast.AnnotationAppl, lookup: NameLookup,
                value_target: Callable[[], Target] | None) -> dict[str, Value] | None:
        spec = KNOWN[name]
        names = [p[0] for p in spec]
        given: dict[str, ast.Expr] = {}
        for pname, expr in appl.params:
            if pname is None:
                if not spec:
                    self.sink.error("RG0502", f"'@{name}' takes no parameters", appl.loc)
                    return None
                pname = names[0]
            if pname not in names:
                self.sink.error("RG0502", f"'@{name}' has no parameter '{pname}'", appl.loc,
                                f"parameters: {', '.join(names)}" if names else "it takes none")
                return None
            given[pname] = expr
        result: dict[str, Value] = {}
        for pname, kind, default in spec:
            if pname not in given:
                if isinstance(default, _Required):
                    self.sink.error("RG0502", f"'@{name}' needs a value for '{pname}'", appl.loc,
                                    f"write @{name}(...)")
                    return None
                result[pname] = default
                continue
            value = self._value(name, kind, given[pname], lookup, value_target)
            if value is None:
                return None
            result[pname] = value
        return result

    def _value(self, name: str, kind: str, expr: ast.Expr, lookup: NameLookup,
               value_target: Callable[[], Target] | None) -> Value:
        if kind.startswith("ident:") or kind == "any":
            if isinstance(expr, ast.NameRef):
                word = expr.name.parts[-1]
                choices = kind[6:].split("|") if kind.startswith("ident:") else None
                if choices is not None and word not in choices:
                    self.sink.error("RG0502", f"'@{name}' expects one of {', '.join(choices)}, not '{word}'",
                                    expr.loc, did_you_mean(word, choices))
                    return None
                return word
            if kind == "any" and isinstance(expr, ast.Literal):
                return expr.value
            if kind == "any":
                return "<expression>"
            self.sink.error("RG0502", f"'@{name}' expects one of {kind[6:].replace('|', ', ')}", expr.loc)
            return None
        target = {"bool": Target("bool", "boolean"), "uint16": Target("int", "uint16"),
                  "uint32": Target("int", "uint32"), "string": Target("string")}.get(kind)
        if target is None:  # const: typed by the member when known
            target = value_target() if value_target else Target("any")
        return self.evaluator.evaluate(expr, target, lookup)
