"""Read a YAML file into plain data, keeping a SourceLoc for every value and key.

PyYAML's composer gives nodes with marks; we turn them into dicts/lists/scalars
ourselves (instead of yaml.safe_load) so that every value keeps its position, duplicate
keys are errors rather than silently overwritten, and hostile inputs (alias bombs,
recursive aliases, deep nesting, huge documents, binary, control characters) end as
diagnostics instead of exceptions. Asset descriptors, the QoS library and the project
file (rapidgen.yaml) all load through `parse_yaml`, so they share these limits.
"""
from __future__ import annotations

import datetime
import math
import os
import re
from dataclasses import dataclass, field

import yaml

from rapidgen.diagnostics import DiagnosticSink, SourceLoc

MAX_BYTES = 8 * 1024 * 1024
MAX_NODES = 200_000  # while parsing, and again after alias expansion: a descriptor has a few thousand
MAX_DEPTH = 64
FREE_TEXT = ("description",)  # the only fields where a tab or a line break is text

# Never text: C0 controls but tab and line feed, DEL, C1 controls, surrogates (a YAML
# "\ud800" escape makes a lone one) and the noncharacters (U+FDD0..U+FDEF, U+xFFFE/xFFFF).
_NEVER = "\x00-\x08\x0b-\x1f\x7f-\x9f\ud800-\udfff\ufdd0-\ufdef" + "".join(
    chr(plane << 16 | 0xFFFE) + chr(plane << 16 | 0xFFFF) for plane in range(17))
_BAD_FREE = re.compile(f"[{_NEVER}]")
_BAD = re.compile(f"[{_NEVER}\t\n]")

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
    # key path -> the key before it, for a key in a flow mapping ({a: b, c}) that may be
    # the rest of an unquoted value the comma cut short ({description: two modules, 12 nozzles})
    split_values: dict[Path, str] = field(default_factory=dict)

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


def bad_char(text: str, free_text: bool = False) -> int | None:
    """Index of the first character a loaded string may not hold, else None.

    Such characters break the XML, Python and JSON rapidgen writes, or hide text from
    the operator reading it; free text (a description) may also hold tabs and line feeds.
    """
    m = (_BAD_FREE if free_text else _BAD).search(text)
    return m.start() if m else None


def char_name(ch: str) -> str:
    code = ord(ch)
    kind = ("a tab" if ch == "\t" else "a line break" if ch == "\n" else
            "a surrogate" if 0xD800 <= code <= 0xDFFF else
            "a noncharacter" if 0xFDD0 <= code <= 0xFDEF or code & 0xFFFE == 0xFFFE else
            "a control character")
    return f"{kind} (U+{code:04X})"


class _Abort(Exception):
    """Stop converting; the diagnostic is already in the sink."""


class _TooBig(Exception):
    def __init__(self, what: str, mark) -> None:
        super().__init__(what)
        self.what, self.mark = what, mark


class _BoundedLoader(yaml.SafeLoader):
    """SafeLoader whose composer counts nodes and nesting as it goes: a huge or deep
    document stops at the limit instead of being built whole first."""

    def __init__(self, stream) -> None:
        super().__init__(stream)
        self.nodes = 0
        self.depth = 0

    def compose_node(self, parent, index):
        mark = self.peek_event().start_mark
        if not self.check_event(yaml.AliasEvent):  # aliases are counted after expansion
            self.nodes += 1
            if self.nodes > MAX_NODES:
                raise _TooBig("nodes", mark)
        self.depth += 1
        try:
            if self.depth > MAX_DEPTH:
                raise _TooBig("depth", mark)
            return super().compose_node(parent, index)
        finally:
            self.depth -= 1


_FastBoundedLoader: type | None = None
if yaml.__with_libyaml__:
    from yaml._yaml import CParser

    class _FastBoundedLoader(CParser, _BoundedLoader):  # type: ignore[no-redef]
        """The same composer, counts and resolver on libyaml's events (PyYAML's C extension):
        the pure-Python scanner and parser are about three quarters of a load (a `rapidgen
        conform` run spent 0.5 s of its 1 s of CPU on the spec cases' YAML). CParser's own
        composing methods would skip the counts: Composer's are taken back."""
        get_single_node = yaml.composer.Composer.get_single_node
        get_node = yaml.composer.Composer.get_node
        check_node = yaml.composer.Composer.check_node

        def __init__(self, stream) -> None:
            CParser.__init__(self, stream)
            yaml.constructor.SafeConstructor.__init__(self)
            yaml.resolver.Resolver.__init__(self)
            self.anchors: dict = {}
            self.nodes = 0
            self.depth = 0

        def compose_scalar_node(self, anchor):
            node = super().compose_scalar_node(anchor)
            node.style = node.style or None  # (libyaml says '' for a plain scalar, PyYAML None)
            return node


def _compose(text: str):
    """(loader, the document's node): libyaml's parser when it takes the text, else PyYAML's,
    whose diagnostics are the ones the tests pin (libyaml words its errors differently)."""
    if _FastBoundedLoader is not None:
        try:
            fast = _FastBoundedLoader(text)
            return fast, fast.get_single_node()
        except Exception:  # (an error or a limit: said by the loader whose words are pinned)
            pass
    loader = _BoundedLoader(text)
    return loader, loader.get_single_node()


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
        at = bad if nul < 0 and bad is not None else nul
        line = data.count(b"\n", 0, at) + 1
        col = at - (data.rfind(b"\n", 0, at) + 1) + 1
        msg = ("file contains a NUL byte; is it a binary file?" if nul >= 0
               else f"file is not valid UTF-8 (byte 0x{data[at]:02x})")
        sink.error("RG1002" if nul >= 0 else "RG1003", msg, SourceLoc(shown, line, col, line, col + 1),
                   "asset descriptors are UTF-8 YAML text")
        return None
    return text[1:] if text.startswith("\ufeff") else text


def parse_yaml(text: str, file: str, sink: DiagnosticSink,
               free_text: tuple[str, ...] = FREE_TEXT) -> YamlDoc | None:
    """Compose one YAML document and convert it; None after diagnostics.

    Strings under a key named in free_text may hold tabs and line feeds; no string or
    key may hold the other characters `bad_char` refuses.
    """
    loader = None
    try:
        loader, node = _compose(text)  # the reader already rejects raw control characters here
    except _TooBig as exc:
        loc = _mark_loc(file, exc.mark)
        if exc.what == "nodes":
            sink.error("RG1012", f"the document has more than {MAX_NODES} YAML values", loc,
                       "a descriptor has a few thousand; is this the right file?")
        else:
            sink.error("RG1012", f"YAML nesting deeper than {MAX_DEPTH} levels", loc)
        return None
    except yaml.MarkedYAMLError as exc:
        _syntax_error(exc, text, file, sink)
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
    conv = _Converter(doc, loader, sink, free_text)
    try:
        doc.data = conv.value(node, (), 0)
    except _Abort:
        return None
    return None if conv.failed else doc


def _syntax_error(exc: yaml.MarkedYAMLError, text: str, file: str, sink: DiagnosticSink) -> None:
    mark = exc.problem_mark or exc.context_mark
    indentation = _indentation_error(exc, text)
    if indentation is not None:  # at the offending line's first character, not at PyYAML's token
        message, where, line, col = indentation
        sink.error("RG1010", f"YAML indentation error: {message}", SourceLoc(file, line, col, line, col + 1), where)
        return
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


def _spaces(n: int) -> str:
    return f"{n} space{'s' * (n != 1)}"


def _indentation_error(exc: yaml.MarkedYAMLError, text: str) -> tuple[str, str, int, int] | None:
    """(message, hint, line, column of the line's first character) in plain words when the error comes from a line's indentation, naming
    the offending line and the line it fails to line up with; None for other errors.

    PyYAML says "expected <block end>, but found ..." (context: the block the line falls
    in) or, for a line indented deeper than a `key: value` above it, "mapping values are
    not allowed here" (the line was read as more of that value, then its ':' is stray).
    """
    p, c = exc.problem_mark, exc.context_mark
    problem, context = exc.problem or "", exc.context or ""
    if p is None:
        return None
    lines = text.splitlines()
    if p.line >= len(lines):
        return None
    here = lines[p.line]
    pi = len(here) - len(here.lstrip(" "))
    at = (p.line + 1, pi + 1)
    if problem.startswith("expected <block end>") and context.startswith("while parsing a block") \
            and c is not None and c.line < p.line:
        kind, items = ("mapping", "keys") if "mapping" in context else ("list", "items")
        ci, pl, cl = c.column, p.line + 1, c.line + 1
        if p.column == ci and kind == "mapping" and "'-'" in problem:
            return (f"line {pl} starts a list item at the indentation of the keys of the mapping "
                    f"that starts at line {cl}",
                    f"a list goes under a key ending in ':', indented more than that key; the keys "
                    f"from line {cl} are indented {_spaces(ci)}", *at)
        if p.column == ci and kind == "list":
            return (f"line {pl} is at the indentation of the '-' of the list that starts at line {cl}",
                    f"to put it in the item above, indent it like that item's first key; "
                    f"to start a new item, begin line {pl} with '- '", *at)
        return (f"line {pl} is indented {_spaces(pi)}, which lines up with no {kind} above it",
                f"the {kind} it falls in starts at line {cl} with its {items} indented {_spaces(ci)}; "
                f"indent line {pl} like the {items} it belongs with", *at)
    if problem.startswith("mapping values are not allowed"):
        colon = re.search(r":(\s|$)", here)
        above = next((i for i in range(p.line - 1, -1, -1)
                      if lines[i].strip() and not lines[i].lstrip().startswith("#")), None)
        if colon is None or colon.start() != p.column or above is None:
            return None
        prev = lines[above]
        lead = re.match(r" *(?:- +)*", prev)  # (matches every line, maybe empty)
        qi = lead.end() if lead else 0  # where its text starts, after any list dashes
        if pi <= qi or prev.rstrip().endswith((":", "{", "[", ",")):
            return None
        return (f"line {p.line + 1} is indented more than line {above + 1}, so YAML reads it as more "
                f"of line {above + 1}'s value",
                f"line {above + 1} starts at column {qi + 1}, line {p.line + 1} at column {pi + 1}; "
                f"indent line {p.line + 1} like the keys it belongs with", *at)
    return None


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
    def __init__(self, doc: YamlDoc, loader: yaml.SafeLoader, sink: DiagnosticSink,
                 free_text: tuple[str, ...]) -> None:
        self.doc, self.loader, self.sink, self.free_text = doc, loader, sink, free_text
        self.count = 0
        self.active: set[int] = set()  # collections being converted: a recursive alias loops
        self.failed = False

    def error(self, code: str, msg: str, loc: SourceLoc, hint: str | None = None) -> None:
        self.sink.error(code, msg, loc, hint)
        self.failed = True

    def value(self, node: yaml.Node, path: Path, depth: int) -> object:
        self.count += 1
        loc = _span(self.doc.file, node)
        if self.count > MAX_NODES:  # the composer counted without aliases: they did this
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
            assert isinstance(node, yaml.MappingNode)  # scalars and sequences are handled above
            return self.mapping(node, path, depth)
        finally:
            self.active.discard(id(node))

    def text_ok(self, text: str, loc: SourceLoc, path: Path, what: str) -> bool:
        """Refuse a string holding a character `bad_char` names (RG1014)."""
        keys = [k for k in path if isinstance(k, str)]
        free = what == "value" and bool(keys) and keys[-1] in self.free_text
        at = bad_char(text, free)
        if at is None:
            return True
        ch = text[at]
        if ch in "\t\n":
            hint = "tabs and line breaks are text only in " + (
                " and ".join(f"'{k}'" for k in self.free_text) or "no field of this file")
        elif 0xD800 <= ord(ch) <= 0xDFFF:
            hint = "write a character above U+FFFF as one escape (\"\\U0001F600\"), not as a surrogate pair"
        else:
            hint = "remove it; YAML escapes in double quotes (\"\\x01\", \"\\uFFFE\") are how such characters get in"
        where = "".join(f"[{k}]" if isinstance(k, int) else f".{k}" for k in path).lstrip(".") or "the document"
        subject = where if what == "value" else f"a key in {where}"
        self.error("RG1014", f"{subject} holds {char_name(ch)} at character {at + 1}", loc, hint)
        return False

    def scalar(self, node: yaml.ScalarNode, loc: SourceLoc, path: Path = ()) -> object:
        if isinstance(node.value, str) and not self.text_ok(node.value, loc, path, "value"):
            return None
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
        before = None  # (key, value node) of the previous entry of a flow mapping
        for key_node, value_node in node.value:
            if node.flow_style and isinstance(key_node, yaml.ScalarNode):
                if before is not None and _cut_by_comma(before[1], key_node, value_node):
                    self.doc.split_values[path + (key_node.value,)] = before[0]
                before = (key_node.value, value_node)
            kloc = _span(self.doc.file, key_node)
            if not isinstance(key_node, yaml.ScalarNode):
                self.error("RG1012", "mapping keys must be plain names", kloc)
                continue
            if key_node.tag == "tag:yaml.org,2002:merge":
                self.error("RG1012", "YAML merge keys ('<<') are not supported", kloc,
                           "write the keys out; anchors and aliases of whole values do work")
                continue
            key = key_node.value  # the text as written: 'on:' stays "on", not True
            if not self.text_ok(key, kloc, path, "key"):
                continue
            if key in out:
                first = self.doc.key_locs[path + (key,)]
                shown = key if len(key) <= 40 else key[:37] + "..."
                self.error("RG1011", f"duplicate key '{shown}'", kloc,
                           f"'{shown}' is already given at line {first.line}")
                continue
            self.doc.key_locs[path + (key,)] = kloc
            out[key] = self.value(value_node, path + (key,), depth + 1)
        return out


def _cut_by_comma(prev_value: yaml.Node, key: yaml.ScalarNode, value: yaml.Node) -> bool:
    """Whether a flow-mapping key probably continues the previous text value: it has no
    value of its own and follows unquoted text, or reads as prose (has a space)."""
    text = "tag:yaml.org,2002:str"
    if not isinstance(prev_value, yaml.ScalarNode) or prev_value.tag != text:
        return False
    bare = isinstance(value, yaml.ScalarNode) and value.tag == "tag:yaml.org,2002:null" and value.value == ""
    return bare and (prev_value.style is None or " " in key.value.strip())


def load_yaml(path: str, shown: str, sink: DiagnosticSink) -> YamlDoc | None:
    text = read_text(path, shown, sink)
    return None if text is None else parse_yaml(text, shown, sink)
