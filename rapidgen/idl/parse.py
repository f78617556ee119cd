"""Parse preprocessed IDL text into the syntax tree (rapidgen.idl.ast).

The lark LALR parser is built once per process (and cached on disk by lark). Lark's
exceptions never reach the user: they are translated into diagnostics with the
original file:line:col and a hint.
"""
from __future__ import annotations

import copy
import functools
import re
from dataclasses import replace
from decimal import Decimal, InvalidOperation
from importlib import resources

import lark
from lark import Lark, Token, Transformer, v_args
from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedInput, UnexpectedToken, VisitError

from rapidgen.diagnostics import DiagnosticSink, SourceLoc
from rapidgen.idl import ast
from rapidgen.idl.preprocess import PreprocessResult

_KEY_COMMENT = re.compile(r"//\s*@key\b")

# Friendly names for the grammar's named terminals in "expected ..." messages.
_TERMINAL_NAMES = {
    "IDENT": "an identifier", "INT_LIT": "an integer", "FLOAT_LIT": "a number",
    "FIXED_LIT": "a fixed-point number", "CHAR_LIT": "a character literal",
    "WCHAR_LIT": "a character literal", "STRING_LIT": "a string literal",
    "WSTRING_LIT": "a string literal", "VISIBILITY": "'public' or 'private'",
    "PRAGMA_KEYLIST": "'#pragma keylist'", "ANNOTATION_KW": "'@annotation'",
    "$END": "end of input",
}


# The parser is built once, so its comment callback writes to whichever dict the
# current parse() installed here (the front end runs one parse at a time per process).
_key_comments: dict[int, int] = {}


def _on_line_comment(tok: Token) -> Token:
    if tok.startswith("//") and _KEY_COMMENT.match(tok):
        _key_comments[tok.line] = tok.column
    return tok


_CALLBACKS = {"LINE_COMMENT": _on_line_comment}


@functools.lru_cache(maxsize=1)
def _parser() -> Lark:
    grammar = resources.files("rapidgen.idl").joinpath("grammar.lark").read_text(encoding="utf-8")
    try:
        return Lark(grammar, parser="lalr", lexer="contextual", propagate_positions=True,
                    maybe_placeholders=False, lexer_callbacks=_CALLBACKS, cache=True)
    except OSError:  # unwritable temp dir: build without the on-disk cache
        return Lark(grammar, parser="lalr", lexer="contextual", propagate_positions=True,
                    maybe_placeholders=False, lexer_callbacks=_CALLBACKS)


@functools.lru_cache(maxsize=1)
def _terminal_text() -> dict[str, str]:
    """Terminal name -> how to show it ('struct', ';', an identifier)."""
    out: dict[str, str] = dict(_TERMINAL_NAMES)
    for term in _parser().terminals:
        if term.name in out:
            continue
        pat = term.pattern
        if isinstance(pat, lark.lexer.PatternStr):
            out[term.name] = f"'{pat.value}'"
        else:
            out[term.name] = term.name.lower()
    return out


@functools.lru_cache(maxsize=1)
def _keywords() -> frozenset[str]:
    return frozenset(t.pattern.value for t in _parser().terminals
                     if isinstance(t.pattern, lark.lexer.PatternStr) and t.pattern.value.isidentifier())


class _Locator:
    """Maps positions in the preprocessed text back to original files."""

    def __init__(self, pre: PreprocessResult) -> None:
        self.pre = pre

    def at(self, line: int, col: int, end_line: int | None = None, end_col: int | None = None) -> SourceLoc:
        file, oline = self.pre.origin(line)
        if end_line is not None and end_line == line and end_col is not None:
            return SourceLoc(file, oline, col, oline, end_col)
        return SourceLoc(file, oline, col, oline, col + 1)

    def meta(self, meta, fallback: SourceLoc | None = None) -> SourceLoc:
        if getattr(meta, "empty", True):
            return fallback or SourceLoc(self.pre.files[0] if self.pre.files else "<input>", 1, 1)
        return self.at(meta.line, meta.column, meta.end_line, meta.end_column)

    def token(self, tok: Token) -> SourceLoc:
        return self.at(tok.line, tok.column, tok.end_line, tok.end_column)


class _Label:
    __slots__ = ("expr",)

    def __init__(self, expr: ast.Expr | None) -> None:
        self.expr = expr


def _unescape(body: str) -> str:
    """Decode IDL escapes (C-style, plus \\uXXXX)."""
    def repl(m: re.Match[str]) -> str:
        esc = m.group(1)
        simple = {"n": "\n", "t": "\t", "v": "\v", "b": "\b", "r": "\r", "f": "\f", "a": "\a",
                  "\\": "\\", "?": "?", "'": "'", '"': '"'}
        if esc in simple:
            return simple[esc]
        if esc[0] == "x":
            return chr(int(esc[1:], 16))
        if esc[0] == "u":
            return chr(int(esc[1:], 16))
        if esc[0] in "01234567":
            return chr(int(esc, 8))
        return esc
    return re.sub(r"\\(x[0-9a-fA-F]{1,2}|u[0-9a-fA-F]{1,4}|[0-7]{1,3}|.)", repl, body)


@v_args(meta=True)
class _ToAst(Transformer):
    def __init__(self, loc: _Locator, key_comments: dict[int, int], sink: DiagnosticSink) -> None:
        super().__init__()
        self.loc = loc
        self.key_comments = key_comments  # output line -> column of a //@key comment
        self.sink = sink

    def _name(self, tok: Token) -> str:
        """A declared name; `_name` escapes a keyword (IDL 7.2.3.1), a bare keyword is warned about."""
        text = str(tok)
        if text.startswith("_"):
            return text[1:]
        if text in _keywords():
            self.sink.warning("RG0313", f"'{text}' is an IDL keyword used as a name", self.loc.token(tok),
                              f"write '_{text}' to escape it")
        return text

    # -- helpers
    def _m(self, meta) -> SourceLoc:
        return self.loc.meta(meta)

    @staticmethod
    def _anns(items) -> tuple[ast.AnnotationAppl, ...]:
        return tuple(i for i in items if isinstance(i, ast.AnnotationAppl))

    # -- top level
    def start(self, meta, items):
        return list(items)

    def annotated_definition(self, meta, items):
        *anns, definition = items
        if anns and hasattr(definition, "annotations"):
            definition = replace(definition, annotations=tuple(anns) + definition.annotations)
        return definition

    def module_dcl(self, meta, items):
        name, *defs = items
        return ast.ModuleDecl(self._name(name), tuple(defs), (), self.loc.token(name))

    def const_dcl(self, meta, items):
        type_spec, name, value = items
        return ast.ConstDecl(type_spec, self._name(name), value, (), self.loc.token(name))

    def __default__(self, data, children, meta):
        raise NotImplementedError(f"no transformer rule for '{data}'")

    # -- names and expressions
    def rel_name(self, meta, items):
        (ident,) = items
        return ast.ScopedName((str(ident),), False, self.loc.token(ident))

    def abs_name(self, meta, items):
        (ident,) = items
        return ast.ScopedName((str(ident),), True, self._m(meta))

    def sub_name(self, meta, items):
        base, ident = items
        return ast.ScopedName(base.parts + (str(ident),), base.absolute, self._m(meta))

    def name_expr(self, meta, items):
        return ast.NameRef(items[0], items[0].loc)

    def _bin(op):  # noqa: N805 - builds methods
        def method(self, meta, items):
            return ast.Binary(op, items[0], items[1], self._m(meta))
        return method

    bin_or, bin_xor, bin_and = _bin("|"), _bin("^"), _bin("&")
    bin_shr, bin_shl = _bin(">>"), _bin("<<")
    bin_add, bin_sub, bin_mul, bin_div, bin_mod = _bin("+"), _bin("-"), _bin("*"), _bin("/"), _bin("%")

    def _un(op):  # noqa: N805
        def method(self, meta, items):
            return ast.Unary(op, items[0], self._m(meta))
        return method

    neg, pos, inv = _un("-"), _un("+"), _un("~")

    def int_lit(self, meta, items):
        text = str(items[0])
        if text.lower().startswith("0x"):
            value = int(text, 16)
        elif len(text) > 1 and text.startswith("0"):
            value = int(text, 8)
        else:
            value = int(text)
        return ast.Literal("int", value, self.loc.token(items[0]))

    def float_lit(self, meta, items):
        return ast.Literal("float", float(str(items[0]).rstrip("fF")), self.loc.token(items[0]))

    def fixed_lit(self, meta, items):
        try:
            value = Decimal(str(items[0])[:-1])
        except InvalidOperation:
            value = Decimal(0)
        return ast.Literal("fixed", value, self.loc.token(items[0]))

    def char_lit(self, meta, items):
        text = str(items[0])
        wide = text.startswith("L")
        return ast.Literal("wchar" if wide else "char", _unescape(text[2 if wide else 1:-1]),
                           self.loc.token(items[0]))

    def string_lit(self, meta, items):
        wide = any(str(t).startswith("L") for t in items)
        value = "".join(_unescape(str(t)[2 if str(t).startswith("L") else 1:-1]) for t in items)
        return ast.Literal("wstring" if wide else "string", value, self._m(meta))

    def true_lit(self, meta, items):
        return ast.Literal("bool", True, self._m(meta))

    def false_lit(self, meta, items):
        return ast.Literal("bool", False, self._m(meta))

    # -- types
    def _base(name):  # noqa: N805
        def method(self, meta, items):
            return ast.BaseType(name, self._m(meta))
        return method

    t_int8, t_uint8, t_int16, t_uint16 = _base("int8"), _base("uint8"), _base("int16"), _base("uint16")
    t_int32, t_uint32, t_int64, t_uint64 = _base("int32"), _base("uint32"), _base("int64"), _base("uint64")
    t_float32, t_float64, t_float128 = _base("float32"), _base("float64"), _base("float128")
    t_char, t_wchar, t_boolean, t_octet = _base("char8"), _base("char16"), _base("boolean"), _base("octet")

    def named_type(self, meta, items):
        return ast.NamedType(items[0], items[0].loc)

    def sequence_type(self, meta, items):
        return ast.SequenceType(items[0], items[1] if len(items) > 1 else None, self._m(meta))

    def string_type(self, meta, items):
        return ast.StringType(items[0] if items else None, False, self._m(meta))

    def wide_string_type(self, meta, items):
        return ast.StringType(items[0] if items else None, True, self._m(meta))

    def fixed_pt_type(self, meta, items):
        return ast.FixedType(items[0], items[1], self._m(meta))

    def fixed_pt_const_type(self, meta, items):
        return ast.FixedType(None, None, self._m(meta))

    def map_type(self, meta, items):
        return ast.MapType(items[0], items[1], items[2] if len(items) > 2 else None, self._m(meta))

    # -- constructed types
    def struct_inheritance(self, meta, items):
        return items[0]

    def struct_dcl(self, meta, items):
        name, *rest = items
        base = rest.pop(0) if rest and isinstance(rest[0], ast.ScopedName) else None
        return ast.StructDecl(self._name(name), base, tuple(rest), (), self.loc.token(name))

    def struct_forward_dcl(self, meta, items):
        return ast.ForwardDecl("struct", str(items[0]), (), self.loc.token(items[0]))

    def union_forward_dcl(self, meta, items):
        return ast.ForwardDecl("union", str(items[0]), (), self.loc.token(items[0]))

    def value_forward_dcl(self, meta, items):
        return ast.ForwardDecl("valuetype", str(items[0]), (), self.loc.token(items[0]))

    def _is_key(self, meta) -> bool:
        if getattr(meta, "empty", True):
            return False
        col = self.key_comments.get(meta.end_line)
        return col is not None and col >= meta.end_column

    def member(self, meta, items):
        *anns, type_spec, decls = items
        return ast.MemberDecl(tuple(anns), type_spec, decls, self._m(meta), self._is_key(meta))

    def state_member(self, meta, items):
        anns = self._anns(items)
        vis, type_spec, decls = items[len(anns):]
        return ast.MemberDecl(anns, type_spec, decls, self._m(meta), self._is_key(meta), str(vis))

    def declarators(self, meta, items):
        return tuple(items)

    def declarator(self, meta, items):
        name, *dims = items
        return ast.Declarator(self._name(name), tuple(dims), self.loc.token(name))

    def fixed_array_size(self, meta, items):
        return items[0]

    def union_dcl(self, meta, items):
        name, *rest = items
        anns = self._anns(rest)
        disc = rest[len(anns)]
        cases = tuple(rest[len(anns) + 1:])
        return ast.UnionDecl(self._name(name), disc, anns, cases, (), self.loc.token(name))

    def case_label(self, meta, items):
        return _Label(items[0])

    def default_label(self, meta, items):
        return _Label(None)

    def case(self, meta, items):
        labels = tuple(i.expr for i in items if isinstance(i, _Label))
        rest = [i for i in items if not isinstance(i, _Label)]
        anns = self._anns(rest)
        type_spec, decl = rest[len(anns):]
        member = ast.MemberDecl(anns, type_spec, (decl,), decl.loc, self._is_key(meta))
        return ast.CaseDecl(labels, member, self._m(meta))

    def enum_dcl(self, meta, items):
        name, *enumerators = items
        return ast.EnumDecl(self._name(name), tuple(enumerators), (), self.loc.token(name))

    def enumerator(self, meta, items):
        anns = self._anns(items)
        name, *value = items[len(anns):]
        return ast.EnumeratorDecl(self._name(name), value[0] if value else None, anns, self.loc.token(name))

    def native_dcl(self, meta, items):
        return ast.NativeDecl(str(items[0]), (), self.loc.token(items[0]))

    def typedef_dcl(self, meta, items):
        return ast.TypedefDecl(items[0], items[1], (), self._m(meta))

    def bitset_dcl(self, meta, items):
        name, *rest = items
        base = rest.pop(0) if rest and isinstance(rest[0], ast.ScopedName) else None
        return ast.BitsetDecl(self._name(name), base, tuple(rest), (), self.loc.token(name))

    def bitfield(self, meta, items):
        anns = self._anns(items)
        width, *rest = items[len(anns):]
        type_spec = rest.pop(0) if rest and not isinstance(rest[0], Token) else None
        return ast.BitfieldDecl(width, type_spec, tuple(str(t) for t in rest), anns, self._m(meta))

    def bitmask_dcl(self, meta, items):
        name, *values = items
        return ast.BitmaskDecl(self._name(name), tuple(values), (), self.loc.token(name))

    def bit_value(self, meta, items):
        anns = self._anns(items)
        name = items[len(anns)]
        return ast.BitValueDecl(self._name(name), anns, self.loc.token(name))

    # -- value types (RTI dialect)
    def value_dcl(self, meta, items):
        name, *rest = items
        base = rest.pop(0) if rest and isinstance(rest[0], ast.ScopedName) else None
        members = tuple(r for r in rest if isinstance(r, ast.MemberDecl))
        exports = tuple(r for r in rest if not isinstance(r, ast.MemberDecl))
        return ast.StructDecl(self._name(name), base, members, (), self.loc.token(name), "valuetype", exports)

    def value_export(self, meta, items):
        *anns, definition = items
        return replace(definition, annotations=tuple(anns))

    # -- annotations
    def annotation_appl(self, meta, items):
        name, *args = items
        return ast.AnnotationAppl("::".join(name.parts) if not name.absolute else str(name),
                                  args[0] if args else (), self._m(meta))

    def default_name(self, meta, items):
        return ast.ScopedName(("default",), False, self._m(meta))

    def annotation_args(self, meta, items):
        if len(items) == 1 and not isinstance(items[0], tuple):
            return ((None, items[0]),)
        return tuple(items)

    def annotation_param(self, meta, items):
        return (str(items[0]), items[1])

    def annotation_dcl(self, meta, items):
        return ast.AnnotationDecl(str(items[1]), self.loc.token(items[1]))

    def annotation_member(self, meta, items):
        return None

    def annotation_export(self, meta, items):
        return None

    def any_type(self, meta, items):
        return None

    def pragma_keylist(self, meta, items):
        _kw, type_name, *members = items
        return ast.KeylistPragma(type_name, tuple(members), self._m(meta))

    def keylist_member(self, meta, items):
        return (".".join(str(t) for t in items), self._m(meta))


# Big families of tokens are named as one thing: (tokens that show the family, its members, name).
_TOKEN_FAMILIES = (
    ({"'struct'", "'module'", "'const'"},
     {"'#pragma keylist'", "'@'", "'@annotation'", "'bitmask'", "'bitset'", "'const'", "'enum'", "'module'",
      "'native'", "'struct'", "'typedef'", "'union'", "'valuetype'"},
     "a definition (struct, union, enum, typedef, const, module, ...)"),
    ({"an integer", "'('", "an identifier"},
     {"'('", "'+'", "'-'", "'~'", "'::'", "'TRUE'", "'FALSE'", "an integer", "a number", "a fixed-point number",
      "a character literal", "a string literal", "an identifier"},
     "a constant expression"),
)


def _describe_expected(expected: set[str], limit: int = 6) -> str:
    names = sorted({_terminal_text().get(e, e.lower()) for e in expected})
    for marks, members, label in _TOKEN_FAMILIES:
        if marks <= set(names):
            names = [label] + [n for n in names if n not in members]
    if len(names) > limit:
        return ", ".join(names[:limit]) + ", ..."
    if len(names) == 1:
        return names[0]
    return ", ".join(names[:-1]) + " or " + names[-1]


def _viable(exc: UnexpectedInput, fallback) -> set[str]:
    """Terminals that really let the parse go on where it stopped.

    LALR merges look-ahead sets, so lark's `expected` can list tokens that would fail a
    few reductions later (e.g. ')' after a member's type); each candidate is tried on a
    copy of the parser state and kept only when it is shifted.
    """
    fallback = set(fallback or ())
    state = getattr(exc, "state", None)
    try:
        conf = copy.copy(state.parse_conf)  # type: ignore[union-attr]
        conf.callbacks = {}
        candidates = [t for t in conf.states[state.position] if t.isupper()]  # type: ignore[union-attr]
    except Exception:  # no parser state to try (other lark versions): keep lark's answer
        return fallback
    out: set[str] = set()
    for term in candidates:
        probe = state.copy(deepcopy_values=False)  # type: ignore[union-attr]
        probe.parse_conf = conf
        try:
            probe.feed_token(Token(term, ""), is_end=term == "$END")
        except Exception:  # UnexpectedToken: not viable here
            continue
        out.add(term)
    return out or fallback


def _prev_token_end(lines: list[str], line: int, col: int) -> tuple[int, int] | None:
    """1-based (line, col) just after the last non-blank, non-comment text before (line, col)."""
    ln, upto = line, col - 1
    while ln >= 1:
        text = lines[ln - 1][:upto] if ln - 1 < len(lines) else ""
        code = text.split("//", 1)[0].rstrip()
        if code.strip():
            return ln, len(code) + 1
        ln -= 1
        upto = None  # type: ignore[assignment]
        upto = len(lines[ln - 1]) if ln >= 1 else 0
    return None


def _syntax_error(exc: UnexpectedInput, text: str, locator: _Locator, sink: DiagnosticSink) -> None:
    lines = text.split("\n")
    if isinstance(exc, UnexpectedCharacters):
        ch = text[exc.pos_in_stream] if exc.pos_in_stream < len(text) else ""
        loc = locator.at(exc.line, exc.column, exc.line, exc.column + 1)
        if ch == '"':
            sink.error("RG0202", "unterminated string literal", loc, "close the string with \" on the same line")
        elif ch == "'":
            sink.error("RG0202", "invalid character literal", loc, "a char literal holds one character, e.g. 'a' or '\\n'")
        elif text.startswith("/*", exc.pos_in_stream):
            sink.error("RG0108", "unterminated /* comment", loc, "close the comment with */")
        else:
            shown = repr(ch)[1:-1] if ch.isprintable() is False else ch
            sink.error("RG0202", f"unexpected character '{shown}'", loc,
                       f"expected {_describe_expected(_viable(exc, exc.allowed))}" if exc.allowed else None)
        return
    if isinstance(exc, UnexpectedToken) and exc.token.type != "$END":
        tok = exc.token
        expected = _viable(exc, exc.expected)
        found = str(tok)
        loc = locator.token(tok)
        if "SEMICOLON" in expected and tok.type != "SEMICOLON":
            prev = _prev_token_end(lines, tok.line, tok.column)
            if prev is not None:
                where = locator.at(prev[0], prev[1], prev[0], prev[1] + 1)
                sink.error("RG0201", f"expected ';' before '{found}'", where, "add ';' here")
                return
        if found == "interface":
            sink.error("RG0201", "interfaces are not supported", loc,
                       "rapidgen compiles DDS data types; remove the interface or move it to another file")
            return
        if "IDENT" in expected and found in _keywords():
            sink.error("RG0201", f"'{found}' is a reserved word in IDL and cannot be used as a name", loc,
                       f"rename it, e.g. '{found}_'")
            return
        sink.error("RG0201", f"unexpected '{found}'; expected {_describe_expected(expected)}", loc)
        return
    # End of input.
    expected = _viable(exc, getattr(exc, "expected", ()))
    opened = _unclosed_brace(text)
    if "RBRACE" in expected and opened is not None:
        sink.error("RG0201", "unexpected end of input: this '{' is never closed",
                   locator.at(opened[0], opened[1], opened[0], opened[1] + 1), "add the missing '};'")
        return
    last_line = max(1, len(text.rstrip("\n").split("\n")))
    loc = locator.at(last_line, max(1, len(lines[last_line - 1]) + 1 if last_line <= len(lines) else 1))
    sink.error("RG0201", f"unexpected end of input; expected {_describe_expected(expected)}" if expected
               else "unexpected end of input", loc,
               "a ';' is probably missing" if "SEMICOLON" in expected else None)


def _unclosed_brace(text: str) -> tuple[int, int] | None:
    """(line, col) of the innermost '{' left open, skipping comments and strings."""
    stack: list[tuple[int, int]] = []
    for tok in re.finditer(r'//[^\n]*|/\*.*?\*/|"(?:[^"\\\n]|\\.)*"|[{}]', text, re.S):
        if tok.group(0) == "{":
            line = text.count("\n", 0, tok.start()) + 1
            stack.append((line, tok.start() - text.rfind("\n", 0, tok.start())))
        elif tok.group(0) == "}" and stack:
            stack.pop()
    return stack[-1] if stack else None


def parse(pre: PreprocessResult, sink: DiagnosticSink) -> ast.Specification | None:
    """Parse preprocessed text; on a syntax error report it and return None."""
    locator = _Locator(pre)
    parser = _parser()
    _key_comments.clear()
    try:
        tree = parser.parse(pre.text)
    except UnexpectedInput as exc:
        _syntax_error(exc, pre.text, locator, sink)
        return None
    except RecursionError:
        sink.error("RG0201", "input is nested too deeply",
                   SourceLoc(pre.files[0] if pre.files else "<input>", 1, 1))
        return None
    key_comments = dict(_key_comments)
    try:
        definitions = _ToAst(locator, key_comments, sink).transform(tree)
    except (VisitError, RecursionError) as exc:  # never let a transformer problem escape raw
        sink.error("RG0299", f"internal error while reading the syntax tree: {getattr(exc, 'orig_exc', exc)}",
                   SourceLoc(pre.files[0] if pre.files else "<input>", 1, 1),
                   "please report this with the input file")
        return None
    return ast.Specification(tuple(d for d in definitions if d is not None), tuple(pre.files))
