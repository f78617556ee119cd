"""Read a YAML file into plain data, keeping a SourceLoc for every value and key.

PyYAML's composer gives nodes with marks; we turn them into dicts/lists/scalars
ourselves (instead of yaml.safe_load) so that every value keeps its position, duplicate
keys are errors rather than silently overwritten, and hostile inputs (alias bombs,
recursive aliases, deep nesting, binary) end as diagnostics instead of exceptions.
"""
from __future__ import annotations

import datetime
import math
import os
from dataclasses import dataclass, field

import yaml

from rapidgen.diagnostics import DiagnosticSink, SourceLoc

MAX_BYTES = 8 * 1024 * 1024
MAX_NODES = 200_000  # after alias expansion: a descriptor has a few thousand at most
MAX_DEPTH = 64

Path = tuple  # keys (str) and indices (int) from the document root


@dataclass
class YamlDoc:
    """Plain data plus the location of every value (`locs`) and mapping key (`key_locs`),
    and the source text of every scalar that YAML read as a boolean or a number (`texts`:
    `on` for True), so that diagnostics can repeat what the user wrote."""

    file: str
    data: object
    locs: dict[Path, SourceLoc] = field(default_factory=dict)
    key_locs: dict[Path, SourceLoc] = field(default_factory=dict)
    texts: dict[Path, str] = field(default_factory=dict)

    def written(self, path: Path, default: str) -> str:
        """The scalar at path as written in the file (booleans and numbers), else default."""
        return self.texts.get(tuple(path), default)

    def loc(self, path: Path) -> SourceLoc:
        """Location of the value at path, or of its nearest located ancestor."""
        p = tuple(path)
        while p not in self.locs and p:
            p = p[:-1]
        return self.locs.get(p, SourceLoc(self.file, 1, 1))

    def key_loc(self, path: Path) -> SourceLoc:
        """Location of the key naming path's last element (the value's when not a key)."""
        return self.key_locs.get(tuple(path)) or self.loc(path)


class _Abort(Exception):
    """Stop converting; the diagnostic is already in the sink."""


def _span(file: str, node: yaml.Node) -> SourceLoc:
    s, e = node.start_mark, node.end_mark
    return SourceLoc(file, s.line + 1, s.column + 1, e.line + 1, e.column + 1)


def _mark_loc(file: str, mark) -> SourceLoc:
    if mark is None:
        return SourceLoc(file, 1, 1)
    return SourceLoc(file, mark.line + 1, mark.column + 1, mark.line + 1, mark.column + 2)


def read_text(path: str, shown: str, sink: DiagnosticSink) -> str | None:
    """The file as text, or None after a located diagnostic (missing, binary, not UTF-8)."""
    here = SourceLoc(shown, 1, 1)
    try:
        if os.path.isdir(path):
            sink.error("RG1001", f"'{shown}' is a directory, not an asset descriptor", here)
            return None
        with open(path, "rb") as fh:  # read at most one byte past the limit (devices report size 0)
            data = fh.read(MAX_BYTES + 1)
        if len(data) > MAX_BYTES:
            sink.error("RG1004", f"'{shown}' is larger than {MAX_BYTES // (1024 * 1024)} MiB", here,
                       "an asset descriptor is a small YAML file")
            return None
    except OSError as exc:
        sink.error("RG1001", f"cannot read '{shown}': {exc.strerror or exc}", here)
        return None
    nul = data.find(b"\0")
    bad = None
    if nul < 0:
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as exc:
            bad = exc.start
    if nul >= 0 or bad is not None:
        at = nul if nul >= 0 else bad
        line = data.count(b"\n", 0, at) + 1
        col = at - (data.rfind(b"\n", 0, at) + 1) + 1
        msg = ("file contains a NUL byte; is it a binary file?" if nul >= 0
               else f"file is not valid UTF-8 (byte 0x{data[at]:02x})")
        sink.error("RG1002" if nul >= 0 else "RG1003", msg, SourceLoc(shown, line, col, line, col + 1),
                   "asset descriptors are UTF-8 YAML text")
        return None
    return text[1:] if text.startswith("\ufeff") else text


def parse_yaml(text: str, file: str, sink: DiagnosticSink) -> YamlDoc | None:
    """Compose one YAML document and convert it; None after diagnostics."""
    loader = None
    try:
        loader = yaml.SafeLoader(text)  # the reader already rejects control characters here
        node = loader.get_single_node()
    except yaml.MarkedYAMLError as exc:
        _syntax_error(exc, file, sink)
        return None
    except yaml.reader.ReaderError as exc:  # a control character the YAML reader refuses
        line = text.count("\n", 0, exc.position) + 1
        col = exc.position - (text.rfind("\n", 0, exc.position) + 1) + 1
        sink.error("RG1010", f"YAML cannot contain the character U+{exc.character:04X}",
                   SourceLoc(file, line, col, line, col + 1), "remove it or quote the text")
        return None
    except RecursionError:
        sink.error("RG1012", "YAML nesting is too deep", SourceLoc(file, 1, 1))
        return None
    except yaml.YAMLError as exc:
        sink.error("RG1010", f"invalid YAML: {exc}", SourceLoc(file, 1, 1))
        return None
    finally:
        if loader is not None:
            loader.dispose()
    doc = YamlDoc(file, None)
    if node is None:
        return doc
    conv = _Converter(doc, loader, sink)
    try:
        doc.data = conv.value(node, (), 0)
    except _Abort:
        return None
    return None if conv.failed else doc


def _syntax_error(exc: yaml.MarkedYAMLError, file: str, sink: DiagnosticSink) -> None:
    mark = exc.problem_mark or exc.context_mark
    problem = (exc.problem or "syntax error").strip()
    hint = None
    if exc.context and exc.context_mark and exc.problem_mark and \
            exc.context_mark.line != exc.problem_mark.line:
        hint = f"{exc.context.strip()} at line {exc.context_mark.line + 1}"
    elif exc.context:
        hint = exc.context.strip()
    if "expected a single document" in (exc.context or ""):
        problem, hint = "more than one YAML document ('---') in the descriptor", "keep one asset per file"
    if "\t" in problem or "found character '\\t'" in problem:
        hint = "YAML indentation must use spaces, not tabs"
    sink.error("RG1010", f"YAML syntax error: {problem}", _mark_loc(file, mark), hint)


_SCALAR_TAGS = {
    "tag:yaml.org,2002:null", "tag:yaml.org,2002:bool", "tag:yaml.org,2002:int",
    "tag:yaml.org,2002:float", "tag:yaml.org,2002:str",
}
_AS_TEXT_TAGS = {"tag:yaml.org,2002:timestamp", "tag:yaml.org,2002:binary"}


def _finite_hint(path: Path) -> str:
    """What to write instead of .inf/.nan, for the field at path."""
    keys = [k for k in path if isinstance(k, str)]
    field_name = keys[-1] if keys else ""
    if field_name == "range":
        return "a range is two finite numbers; for a one-sided bound give only min: or max:"
    if field_name in ("min", "max"):
        return f"leave '{field_name}' out for no {'lower' if field_name == 'min' else 'upper'} bound"
    if field_name in ("below", "above"):
        return f"give a finite threshold, or leave '{field_name}' out"
    if field_name == "rate":
        return "a rate in Hz is a finite number above 0; leave 'rate' out for a topic published on change"
    return f"give '{field_name}' a finite number" if field_name else "use a finite number"


class _Converter:
    def __init__(self, doc: YamlDoc, loader: yaml.SafeLoader, sink: DiagnosticSink) -> None:
        self.doc, self.loader, self.sink = doc, loader, sink
        self.count = 0
        self.active: set[int] = set()  # collections being converted: a recursive alias loops
        self.failed = False

    def error(self, code: str, msg: str, loc: SourceLoc, hint: str | None = None) -> None:
        self.sink.error(code, msg, loc, hint)
        self.failed = True

    def value(self, node: yaml.Node, path: Path, depth: int) -> object:
        self.count += 1
        loc = _span(self.doc.file, node)
        if self.count > MAX_NODES:
            self.error("RG1012", f"the document expands to more than {MAX_NODES} values",
                       loc, "are aliases (*name) repeating large parts of it?")
            raise _Abort
        if depth > MAX_DEPTH:
            self.error("RG1012", f"YAML nesting deeper than {MAX_DEPTH} levels", loc)
            raise _Abort
        self.doc.locs[path] = loc
        if isinstance(node, yaml.ScalarNode):
            return self.scalar(node, loc, path)
        if id(node) in self.active:
            self.error("RG1012", "recursive YAML alias", loc, "an alias may not refer to a node containing it")
            raise _Abort
        if node.tag not in ("tag:yaml.org,2002:seq", "tag:yaml.org,2002:map"):
            self.error("RG1012", f"YAML tag '{node.tag}' is not supported", loc,
                       "remove the tag; descriptors use plain mappings and lists")
            return None
        self.active.add(id(node))
        try:
            if isinstance(node, yaml.SequenceNode):
                return [self.value(item, path + (i,), depth + 1) for i, item in enumerate(node.value)]
            return self.mapping(node, path, depth)
        finally:
            self.active.discard(id(node))

    def scalar(self, node: yaml.ScalarNode, loc: SourceLoc, path: Path = ()) -> object:
        if node.tag in _AS_TEXT_TAGS:
            return node.value  # dates and binary stay text: a descriptor has no use for them
        if node.tag not in _SCALAR_TAGS:
            self.error("RG1012", f"YAML tag '{node.tag}' is not supported", loc,
                       "remove the tag; descriptors use plain strings, numbers and booleans")
            return None
        try:
            value = self.loader.construct_object(node)
        except (yaml.YAMLError, ValueError, OverflowError):
            self.error("RG1012", f"cannot read the scalar '{node.value[:40]}'", loc)
            return None
        if isinstance(value, float) and not math.isfinite(value):
            self.error("RG1013", f"'{node.value}' is not a finite number", loc, _finite_hint(path))
            return None
        if isinstance(value, (datetime.date, bytes)):
            return node.value
        if isinstance(value, (bool, int, float)):
            self.doc.texts[path] = node.value
        return value

    def mapping(self, node: yaml.MappingNode, path: Path, depth: int) -> dict:
        out: dict[str, object] = {}
        for key_node, value_node in node.value:
            kloc = _span(self.doc.file, key_node)
            if not isinstance(key_node, yaml.ScalarNode):
                self.error("RG1012", "mapping keys must be plain names", kloc)
                continue
            if key_node.tag == "tag:yaml.org,2002:merge":
                self.error("RG1012", "YAML merge keys ('<<') are not supported", kloc,
                           "write the keys out; anchors and aliases of whole values do work")
                continue
            key = key_node.value  # the text as written: 'on:' stays "on", not True
            if key in out:
                first = self.doc.key_locs[path + (key,)]
                self.error("RG1011", f"duplicate key '{key}'", kloc,
                           f"'{key}' is already given at line {first.line}")
                continue
            self.doc.key_locs[path + (key,)] = kloc
            out[key] = self.value(value_node, path + (key,), depth + 1)
        return out


def load_yaml(path: str, shown: str, sink: DiagnosticSink) -> YamlDoc | None:
    text = read_text(path, shown, sink)
    return None if text is None else parse_yaml(text, shown, sink)
