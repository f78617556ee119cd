"""Checks of one typed value (a command parameter or a telemetry value key).

The DataType must be one the ParameterUnion carries; limits, allowed values, the default
and thresholds must make sense for the member that carries it (a RAPID_INT default
must fit a 32-bit long, a RAPID_MAT33f default has 9 elements, ...).
"""
from __future__ import annotations

from decimal import Decimal

from rapidgen.asset.facts import FLOAT32_MAX, IDL_TO_DATATYPE, STATIC_SHAPES, Facts, Shape, fits, utf8_len
from rapidgen.asset.spec import Threshold, TypedValue, ValueKey
from rapidgen.diagnostics import DiagnosticSink, SourceLoc, did_you_mean

_ELEMENT_MAX = {"float32": FLOAT32_MAX, "float64": 1.7976931348623157e308}


def _g(x) -> str:
    """Short number text; ints as written (a huge int has no float form)."""
    if isinstance(x, int):
        return str(x) if abs(x) < 10**15 else f"{Decimal(x):.6e}"
    return f"{x:g}"


def _num(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool)


class ValueChecker:
    def __init__(self, facts: Facts, sink: DiagnosticSink) -> None:
        self.facts, self.sink = facts, sink

    def shape_of(self, name: str, loc: SourceLoc, what: str) -> Shape | None:
        """The Shape of a DataType name, or None after a diagnostic."""
        known = self.facts.data_types or tuple(STATIC_SHAPES)
        shapes = self.facts.shapes
        carried = [d for d in known if d in shapes]
        if name in shapes:
            return shapes[name]
        if name in known:
            self.sink.error("RG1202", f"the ParameterUnion has no member for DataType '{name}'", loc,
                            f"it carries {', '.join(carried)}")
        elif self.facts.is_idl_type(name) or name in IDL_TO_DATATYPE:
            better = IDL_TO_DATATYPE.get(name)
            self.sink.error("RG1202", f"a {what} cannot be of IDL type '{name}': the ParameterUnion "
                            "carries only RAPID DataTypes", loc,
                            f"use {better}" if better in shapes else f"use one of {', '.join(carried)}")
        else:
            # the whole list, not only the nearest name: a near miss may not be what was meant
            close = did_you_mean(name, carried)
            listed = f"the DataTypes are {', '.join(carried)}"
            self.sink.error("RG1201", f"unknown DataType '{name}'", loc, f"{close} {listed}" if close else listed)
        return None

    def check(self, v: TypedValue, what: str) -> Shape | None:
        shape = self.shape_of(v.type, v.at("type"), what)
        if shape is None:
            return None
        ranged = v.min is not None or v.max is not None
        if ranged and shape.kind in ("bool", "string"):
            field = "range" if v.range_given else ("min" if v.min is not None else "max")
            self.sink.error("RG1205", f"a {v.type} {what} has no numeric range", v.at(field),
                            "list the 'allowed' values instead" if shape.kind == "string"
                            else "remove the range")
            ranged = False
        if v.allowed and shape.kind != "string":
            self.sink.error("RG1205", f"'allowed' values apply to RAPID_STRING, not {v.type}", v.at("allowed"),
                            "give a range (min/max) for numbers" if shape.kind != "bool" else "remove them")
        if ranged:
            self.limits(v, shape)
        for i, text in enumerate(v.allowed if shape.kind == "string" else ()):
            if shape.bound is not None and not fits(text, shape.bound):
                self.sink.error("RG1106", f"allowed value is {utf8_len(text)} bytes; a RAPID_STRING holds at most "
                                f"{shape.bound - 1}", v.at("allowed", i), "shorten it")
        if v.has_default:
            self.default(v, shape, what)
        if isinstance(v, ValueKey):
            self.thresholds(v, shape)
        return shape

    def number_error(self, x, shape: Shape, dtype: str) -> str | None:
        """Why x cannot be a value of the shape (or one element of it), or None."""
        if shape.kind == "int":
            if isinstance(x, float) and not x.is_integer():
                return f"{_g(x)} is not a whole number"
            if not shape.lo <= x <= shape.hi:
                return f"{_g(x)} does not fit {dtype} ({shape.lo} .. {shape.hi})"
        limit = _ELEMENT_MAX.get(shape.element) if shape.kind == "array" else shape.hi
        if shape.kind in ("float", "array") and limit is not None and abs(x) > limit:
            return f"{_g(x)} does not fit {dtype} (largest {limit:g})"
        return None

    def limits(self, v: TypedValue, shape: Shape) -> None:
        for field, x in (("min", v.min), ("max", v.max)):
            err = None if x is None else self.number_error(x, shape, v.type)
            if err:
                self.sink.error("RG1207", f"{field} of '{v.name}': {err}", v.at(field))
        if _reversed(v):
            self.sink.error("RG1203", f"min {_g(v.min)} is greater than max {_g(v.max)} for '{v.name}'",
                            v.at("min"), "swap them")

    def default(self, v: TypedValue, shape: Shape, what: str) -> None:
        d, loc = v.default, v.at("default")
        if shape.kind == "bool":
            ok = isinstance(d, bool)
        elif shape.kind in ("int", "float"):
            ok = _num(d)
        elif shape.kind == "string":
            ok = isinstance(d, str)
        else:
            ok = isinstance(d, list) and len(d) == shape.count and all(_num(x) for x in d)
        if not ok:
            want = {"bool": "true or false", "int": "a whole number", "float": "a number",
                    "string": "a string"}.get(shape.kind, f"a list of {shape.count} numbers")
            self.sink.error("RG1204", f"default of {v.type} {what} '{v.name}' must be {want}", loc,
                            "quote it to make it a string" if shape.kind == "string" else None)
            return
        # (ok above: an array's default is a list, a number's is not, a string's is a str)
        elements = d if isinstance(d, list) else [d] if shape.kind in ("int", "float") else []
        for x in elements:
            err = self.number_error(x, shape, v.type)
            if err:
                self.sink.error("RG1207", f"default of '{v.name}': {err}", loc)
                return
            if _reversed(v):
                continue  # RG1203 names the real mistake; no value lies in a reversed range
            assert isinstance(x, (int, float))  # number_error accepted it
            if (v.min is not None and x < v.min) or (v.max is not None and x > v.max):
                self.sink.error("RG1204", f"default {_g(x)} of '{v.name}' is outside its range "
                                f"{_range_text(v)}", loc, "change the default or widen the range")
                return
        if shape.kind == "string" and isinstance(d, str):
            if shape.bound is not None and not fits(d, shape.bound):
                self.sink.error("RG1106", f"default is {utf8_len(d)} bytes; a RAPID_STRING holds at most "
                                f"{shape.bound - 1}", loc, "shorten it")
            elif v.allowed and d not in v.allowed:
                self.sink.error("RG1204", f"default '{d}' of '{v.name}' is not an allowed value", loc,
                                did_you_mean(d, v.allowed) or f"allowed: {', '.join(v.allowed)}")

    def thresholds(self, v: ValueKey, shape: Shape) -> None:
        levels = [(n, t) for n, t in (("warning", v.warning), ("critical", v.critical)) if t is not None]
        if not levels:
            return
        if shape.kind not in ("int", "float"):
            self.sink.error("RG1307", f"thresholds need a numeric value; '{v.name}' is {v.type}",
                            v.at(levels[0][0]), "watch a RAPID_DOUBLE, RAPID_FLOAT, RAPID_INT or RAPID_LONGLONG")
            return
        for name, t in levels:
            if t.below is not None and t.above is not None and t.below >= t.above:
                self.sink.error("RG1306", f"{name} 'below: {t.below}' is not under 'above: {t.above}'",
                                t.at("below"), "the normal band [below, above] would be empty")
            for side, x in (("below", t.below), ("above", t.above)):
                if x is None or _reversed(v):  # a reversed range is reported once, as RG1203
                    continue
                out = (v.min is not None and x <= v.min) if side == "below" else (v.max is not None and x >= v.max)
                if out:
                    self.sink.error("RG1306", f"{name} threshold '{side}: {_g(x)}' can never be passed: "
                                    f"'{v.name}' ranges over {_range_text(v)}", t.at(side),
                                    "move it inside the range")
        if v.warning is not None and v.critical is not None:
            self.ordered(v.warning, v.critical)

    def ordered(self, warn: Threshold, crit: Threshold) -> None:
        """A critical threshold lies beyond the warning one: warnings come first."""
        if warn.below is not None and crit.below is not None and crit.below > warn.below:
            self.sink.error("RG1306", f"critical 'below: {crit.below}' is above warning 'below: {warn.below}'",
                            crit.at("below"), "a value falling must pass the warning threshold first")
        if warn.above is not None and crit.above is not None and crit.above < warn.above:
            self.sink.error("RG1306", f"critical 'above: {crit.above}' is below warning 'above: {warn.above}'",
                            crit.at("above"), "a value rising must pass the warning threshold first")


def _reversed(v: TypedValue) -> bool:
    """min above max: every check against the range would fail, so only RG1203 reports it."""
    return v.min is not None and v.max is not None and v.min > v.max


def _range_text(v: TypedValue) -> str:
    lo = "-inf" if v.min is None else _g(v.min)
    hi = "inf" if v.max is None else _g(v.max)
    return f"[{lo}, {hi}]"
