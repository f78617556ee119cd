"""Parse preprocessed IDL text into the syntax tree (rapidgen.idl.ast).

A lean LALR driver runs over the grammar's tables (shipped precomputed, see
rapidgen.idl.grammar: a parse imports no lark); everything a parse needs to know of its
input (the locator, //@key comments, the sink) lives in a syntax-tree builder made for
that call, so parses are re-entrant and nothing keeps an input alive once its parse
returns. An input the tables reject is parsed again by lark's own parser for its
detailed exception, which never reaches the user: it is translated into diagnostics
with the original file:line:col and a hint.
"""
from __future__ import annotations

import bisect
import copy
import functools
import re
from decimal import Decimal, InvalidOperation
from typing import TYPE_CHECKING, Callable

from rapidgen.diagnostics import DiagnosticSink, SourceLoc
from rapidgen.idl import ast, grammar
from rapidgen.idl.lalr import LeanLALR
from rapidgen.idl.lexer import Token
from rapidgen.idl.preprocess import PreprocessResult

if TYPE_CHECKING:  # lark is imported only to explain a syntax error (rapidgen.idl.grammar)
    from lark.exceptions import UnexpectedInput


# Longest integer literal accepted, leading zeros aside: uint64 needs 20 decimal digits
# and fixed 31, so 40 leaves room while keeping int() far from its 4300-digit limit.
MAX_LITERAL_DIGITS = 40
MAX_FIXED_DIGITS = 31  # IDL 4.2 7.4.1.4.4.2: fixed-point types have at most 31 digits

# Friendly names for the grammar's named terminals in "expected ..." messages.
_TERMINAL_NAMES = {
    "IDENT": "an identifier", "INT_LIT": "an integer", "FLOAT_LIT": "a number",
    "FIXED_LIT": "a fixed-point number", "CHAR_LIT": "a character literal",
    "WCHAR_LIT": "a character literal", "STRING_LIT": "a string literal",
    "WSTRING_LIT": "a string literal", "VISIBILITY": "'public' or 'private'",
    "PRAGMA_KEYLIST": "'#pragma keylist'", "ANNOTATION_KW": "'@annotation'",
    "$END": "end of input",
}


@functools.lru_cache(maxsize=1)
def _lean() -> LeanLALR:
    """The driver over the grammar's tables (packaged: no lark imported); lark's parser is
    built only to explain an input they reject."""
    return LeanLALR(grammar.tables(), grammar.lark_parser)


@functools.lru_cache(maxsize=1)
def _terminal_text() -> dict[str, str]:
    """Terminal name -> how to show it ('struct', ';', an identifier)."""
    from lark.lexer import PatternStr

    out: dict[str, str] = dict(_TERMINAL_NAMES)
    for term in grammar.lark_parser().terminals:
        if term.name in out:
            continue
        pat = term.pattern
        if isinstance(pat, PatternStr):
            out[term.name] = f"'{pat.value}'"
        else:
            out[term.name] = term.name.lower()
    return out


@functools.lru_cache(maxsize=1)
def _keywords() -> frozenset[str]:
    from lark.lexer import PatternStr

    return frozenset(t.pattern.value for t in grammar.lark_parser().terminals
                     if isinstance(t.pattern, PatternStr) and t.pattern.value.isidentifier())


class _Locator:
    """Maps positions in the preprocessed text back to original files.

    Tokens arrive in order, so the run of lines (preprocess.LineMap) of the last lookup is
    kept: most lookups are then one comparison, not a walk through the line map."""

    def __init__(self, pre: PreprocessResult) -> None:
        self.pre = pre
        self._lo = self._hi = self._base = 0  # output lines [lo, hi) come from file's lines base...
        self._file = ""

    def origin(self, line: int) -> tuple[str, int]:
        """pre.origin(line)."""
        if self._lo <= line < self._hi:
            return self._file, self._base + line - self._lo
        lines = self.pre.line_map
        if not 1 <= line <= len(lines):
            return self.pre.origin(line)
        run = bisect.bisect_right(lines.starts, line - 1) - 1
        start = lines.starts[run]
        end = lines.starts[run + 1] if run + 1 < len(lines.starts) else lines.count
        self._file, self._base = lines.origins[run]
        self._lo, self._hi = start + 1, end + 1
        return self._file, self._base + line - self._lo

    def at(self, line: int, col: int, end_line: int | None = None, end_col: int | None = None) -> SourceLoc:
        file, oline = self.origin(line)
        if end_line is not None and end_line == line and end_col is not None:
            return SourceLoc(file, oline, col, oline, end_col)
        return SourceLoc(file, oline, col, oline, col + 1)

    def token(self, tok: Token) -> SourceLoc:
        line = tok.line
        assert line is not None and tok.column is not None  # the lexer places every token
        if self._lo <= line < self._hi:
            file, oline = self._file, self._base + line - self._lo
        else:
            file, oline = self.origin(line)
        if tok.end_line == line and tok.end_column is not None:
            return SourceLoc(file, oline, tok.column, oline, tok.end_column)
        return SourceLoc(file, oline, tok.column, oline, tok.column + 1)


class _Label:
    __slots__ = ("expr", "loc")

    def __init__(self, expr: ast.Expr | None, loc: SourceLoc) -> None:
        self.expr = expr
        self.loc = loc


_SIMPLE_ESCAPES = {"n": "\n", "t": "\t", "v": "\v", "b": "\b", "r": "\r", "f": "\f", "a": "\a",
                   "\\": "\\", "?": "?", "'": "'", '"': '"'}
_ESCAPE = re.compile(r"\\(x[0-9a-fA-F]{1,2}|u[0-9a-fA-F]{1,4}|[0-7]{1,3}|.)")


def _unescape_one(m: re.Match[str]) -> str:
    esc = m.group(1)
    simple = _SIMPLE_ESCAPES.get(esc)
    if simple is not None:
        return simple
    if esc[0] in "xu":
        return chr(int(esc[1:], 16))
    if esc[0] in "01234567":
        return chr(int(esc, 8))
    return esc


def _unescape(body: str) -> str:
    """Decode IDL escapes (C-style, plus \\uXXXX)."""
    return _ESCAPE.sub(_unescape_one, body) if "\\" in body else body


class _ToAst:
    """Builds the syntax tree while the LALR parser reduces (no intermediate lark tree).

    Lark gives inline transformers no position metadata, so locations come from tokens:
    names, literals and the type keywords, which the grammar keeps as named terminals.
    One instance per parse() call: it holds that call's locator, //@key comments and sink.
    """

    def __init__(self, loc: _Locator, key_comments: dict[tuple[str, int], int], sink: DiagnosticSink) -> None:
        self.loc = loc
        self.key_comments = key_comments
        self.sink = sink

    def _name(self, tok: Token) -> str:
        """A declared name; a leading underscore escapes a keyword (IDL 7.2.3.1) and is dropped."""
        text = str(tok)
        if text.startswith("_"):
            return text[1:]
        return text

    @staticmethod
    def _anns(items) -> tuple[ast.AnnotationAppl, ...]:
        return tuple(i for i in items if isinstance(i, ast.AnnotationAppl))

    def _is_key(self, decl: ast.Declarator) -> bool:
        col = self.key_comments.get((decl.loc.file, decl.loc.line))
        return col is not None and col > decl.loc.col

    # -- top level
    def start(self, items):
        return list(items)

    def annotated_definition(self, items):
        *anns, definition = items
        if anns and hasattr(definition, "annotations"):
            definition = definition._replace(annotations=tuple(anns) + definition.annotations)
        return definition

    def module_dcl(self, items):
        name, *defs = items
        return ast.ModuleDecl(self._name(name), tuple(defs), (), self.loc.token(name))

    def const_dcl(self, items):
        type_spec, name, value = items
        return ast.ConstDecl(type_spec, self._name(name), value, (), self.loc.token(name))

    # -- names and expressions
    def rel_name(self, items):
        (ident,) = items
        return ast.ScopedName((str(ident),), False, self.loc.token(ident))

    def abs_name(self, items):
        (ident,) = items
        loc = self.loc.token(ident)
        return ast.ScopedName((str(ident),), True, loc._replace(col=max(1, loc.col - 2)))

    def sub_name(self, items):
        base, ident = items
        end = self.loc.token(ident)
        loc = base.loc._replace(end_line=end.end_line, end_col=end.end_col) if end.line == base.loc.line else end
        return ast.ScopedName(base.parts + (str(ident),), base.absolute, loc)

    def name_expr(self, items):
        return ast.NameRef(items[0], items[0].loc)

    def const_expr(self, items):
        """Apply IDL operator precedence to the flat `operand (op operand)*` list."""
        if len(items) == 1:
            return items[0]
        operands: list[ast.Expr] = [items[0]]
        pending: list[str] = []
        for op_tok, rhs in zip(items[1::2], items[2::2]):
            op = str(op_tok)
            while pending and _PRECEDENCE[pending[-1]] >= _PRECEDENCE[op]:
                _fold(operands, pending.pop())
            pending.append(op)
            operands.append(rhs)
        while pending:
            _fold(operands, pending.pop())
        return operands[0]

    @staticmethod
    def _un(op: str) -> Callable[[_ToAst, list], ast.Unary]:
        """The transformer method for a unary operator's rule."""
        def method(self: _ToAst, items: list) -> ast.Unary:
            operand = items[-1]
            loc = self.loc.token(items[0]) if isinstance(items[0], Token) else \
                operand.loc._replace(col=max(1, operand.loc.col - 1))
            return ast.Unary(op, operand, loc._replace(end_line=operand.loc.end_line, end_col=operand.loc.end_col)
                             if loc.line == operand.loc.line else loc)
        return method

    neg, pos, inv = _un("-"), _un("+"), _un("~")

    def int_lit(self, items):
        text = str(items[0])
        hexa = text[:2] in ("0x", "0X")
        digits = len(text[2 if hexa else 0:].lstrip("0"))
        if digits > MAX_LITERAL_DIGITS:  # (int() refuses more than 4300 decimal digits anyway)
            self.sink.error("RG0402", f"integer literal of {digits} digits is too large for any IDL type",
                            self.loc.token(items[0]), f"the widest types hold {MAX_LITERAL_DIGITS} digits or "
                            "fewer; write a floating-point literal such as 1e40")
            return ast.Literal("int", 0, self.loc.token(items[0]))
        if hexa:
            value = int(text, 16)
        elif len(text) > 1 and text.startswith("0"):
            value = int(text, 8)
        else:
            value = int(text)
        return ast.Literal("int", value, self.loc.token(items[0]))

    def float_lit(self, items):
        value = float(str(items[0]).rstrip("fF"))
        if value in (float("inf"), float("-inf")):  # the literal is finite; only its value overflowed
            self.sink.error("RG0402", f"floating-point literal {items[0]} is out of range",
                            self.loc.token(items[0]), "the largest double is about 1.8e308")
        return ast.Literal("float", value, self.loc.token(items[0]))

    def fixed_lit(self, items):
        digits = len(str(items[0])[:-1].replace(".", "").strip("0"))
        if digits > MAX_FIXED_DIGITS:
            self.sink.error("RG0402", f"fixed-point literal of {digits} digits; fixed holds at most {MAX_FIXED_DIGITS}",
                            self.loc.token(items[0]))
            return ast.Literal("fixed", Decimal(0), self.loc.token(items[0]))
        try:
            value = Decimal(str(items[0])[:-1])
        except InvalidOperation:
            value = Decimal(0)
        return ast.Literal("fixed", value, self.loc.token(items[0]))

    def char_lit(self, items):
        text = str(items[0])
        wide = text.startswith("L")
        return ast.Literal("wchar" if wide else "char", _unescape(text[2 if wide else 1:-1]),
                           self.loc.token(items[0]))

    def string_lit(self, items):
        wide = any(str(t).startswith("L") for t in items)
        value = "".join(_unescape(str(t)[2 if str(t).startswith("L") else 1:-1]) for t in items)
        return ast.Literal("wstring" if wide else "string", value, self.loc.token(items[0]))

    def true_lit(self, items):
        return ast.Literal("bool", True, self.loc.token(items[0]))

    def false_lit(self, items):
        return ast.Literal("bool", False, self.loc.token(items[0]))

    # -- types
    @staticmethod
    def _base(name: str) -> Callable[[_ToAst, list], ast.BaseType]:
        """The transformer method for a base type's rule."""
        def method(self: _ToAst, items: list) -> ast.BaseType:
            first, last = self.loc.token(items[0]), self.loc.token(items[-1])
            return ast.BaseType(name, first._replace(end_col=last.end_col) if first.line == last.line else first)
        return method

    t_int8, t_uint8, t_int16, t_uint16 = _base("int8"), _base("uint8"), _base("int16"), _base("uint16")
    t_int32, t_uint32, t_int64, t_uint64 = _base("int32"), _base("uint32"), _base("int64"), _base("uint64")
    t_float32, t_float64, t_float128 = _base("float32"), _base("float64"), _base("float128")
    t_char, t_wchar, t_boolean, t_octet = _base("char8"), _base("char16"), _base("boolean"), _base("octet")

    def named_type(self, items):
        return ast.NamedType(items[0], items[0].loc)

    def sequence_type(self, items):
        kw, elem, *bound = items
        return ast.SequenceType(elem, bound[0] if bound else None, self.loc.token(kw))

    def string_type(self, items):
        kw, *bound = items
        return ast.StringType(bound[0] if bound else None, False, self.loc.token(kw))

    def wide_string_type(self, items):
        kw, *bound = items
        return ast.StringType(bound[0] if bound else None, True, self.loc.token(kw))

    def fixed_pt_type(self, items):
        kw, digits, scale = items
        return ast.FixedType(digits, scale, self.loc.token(kw))

    def fixed_pt_const_type(self, items):
        return ast.FixedType(None, None, self.loc.token(items[0]))

    def map_type(self, items):
        kw, key, value, *bound = items
        return ast.MapType(key, value, bound[0] if bound else None, self.loc.token(kw))

    # -- constructed types
    def struct_inheritance(self, items):
        return items[0]

    def struct_dcl(self, items):
        name, *rest = items
        base = rest.pop(0) if rest and isinstance(rest[0], ast.ScopedName) else None
        return ast.StructDecl(self._name(name), base, tuple(rest), (), self.loc.token(name))

    def struct_forward_dcl(self, items):
        return ast.ForwardDecl("struct", self._name(items[0]), (), self.loc.token(items[0]))

    def union_forward_dcl(self, items):
        return ast.ForwardDecl("union", self._name(items[0]), (), self.loc.token(items[0]))

    def value_forward_dcl(self, items):
        return ast.ForwardDecl("valuetype", self._name(items[0]), (), self.loc.token(items[0]))

    # Declarators are direct children (no wrapper rule): one reduction less per member.
    def member(self, items):
        n = 0
        while items[n].__class__ is ast.AnnotationAppl:
            n += 1
        decls = tuple(items[n + 1:])
        return ast.MemberDecl(tuple(items[:n]), items[n], decls, decls[0].loc, self._is_key(decls[-1]))

    def state_member(self, items):
        anns = self._anns(items)
        vis, type_spec, *rest = items[len(anns):]
        decls = tuple(rest)
        return ast.MemberDecl(anns, type_spec, decls, decls[0].loc, self._is_key(decls[-1]), str(vis))

    def declarator(self, items):
        name, *dims = items
        return ast.Declarator(self._name(name), tuple(dims), self.loc.token(name))

    def fixed_array_size(self, items):
        return items[0]

    def union_dcl(self, items):
        name, *rest = items
        anns = self._anns(rest)
        disc = rest[len(anns)]
        cases = tuple(rest[len(anns) + 1:])
        return ast.UnionDecl(self._name(name), disc, anns, cases, (), self.loc.token(name))

    def case_label(self, items):
        return _Label(items[0], items[0].loc)

    def default_label(self, items):
        return _Label(None, self.loc.token(items[0]))

    def case(self, items):
        labels = [i for i in items if isinstance(i, _Label)]
        rest = [i for i in items if not isinstance(i, _Label)]
        anns = self._anns(rest)
        type_spec, decl = rest[len(anns):]
        member = ast.MemberDecl(anns, type_spec, (decl,), decl.loc, self._is_key(decl))
        return ast.CaseDecl(tuple(lb.expr for lb in labels), member, labels[0].loc)

    def enum_dcl(self, items):
        name, *enumerators = items
        return ast.EnumDecl(self._name(name), tuple(enumerators), (), self.loc.token(name))

    def enumerator(self, items):
        anns = self._anns(items)
        name, *value = items[len(anns):]
        return ast.EnumeratorDecl(self._name(name), value[0] if value else None, anns, self.loc.token(name))

    def native_dcl(self, items):
        return ast.NativeDecl(self._name(items[0]), (), self.loc.token(items[0]))

    def typedef_dcl(self, items):
        decls = tuple(items[1:])
        return ast.TypedefDecl(items[0], decls, (), decls[0].loc)

    def bitset_dcl(self, items):
        name, *rest = items
        base = rest.pop(0) if rest and isinstance(rest[0], ast.ScopedName) else None
        return ast.BitsetDecl(self._name(name), base, tuple(rest), (), self.loc.token(name))

    def bitfield(self, items):
        anns = self._anns(items)
        width, *rest = items[len(anns):]
        type_spec = rest.pop(0) if rest and not isinstance(rest[0], Token) else None
        return ast.BitfieldDecl(width, type_spec, tuple(self._name(t) for t in rest), anns, width.loc)

    def bitmask_dcl(self, items):
        name, *values = items
        return ast.BitmaskDecl(self._name(name), tuple(values), (), self.loc.token(name))

    def bit_value(self, items):
        anns = self._anns(items)
        name = items[len(anns)]
        return ast.BitValueDecl(self._name(name), anns, self.loc.token(name))

    # -- value types (RTI dialect)
    def value_dcl(self, items):
        name, *rest = items
        base = rest.pop(0) if rest and isinstance(rest[0], ast.ScopedName) else None
        members = tuple(r for r in rest if isinstance(r, ast.MemberDecl))
        exports = tuple(r for r in rest if not isinstance(r, ast.MemberDecl))
        return ast.StructDecl(self._name(name), base, members, (), self.loc.token(name), "valuetype", exports)

    def value_export(self, items):
        *anns, definition = items
        return definition._replace(annotations=tuple(anns))

    # -- annotations
    def annotation_appl(self, items):
        name, *args = items
        loc = name.loc._replace(col=max(1, name.loc.col - 1))  # include the '@'
        return ast.AnnotationAppl("::".join(name.parts) if not name.absolute else str(name),
                                  args[0] if args else (), loc)

    def default_name(self, items):
        return ast.ScopedName(("default",), False, self.loc.token(items[0]))

    def annotation_args(self, items):
        if len(items) == 1 and type(items[0]) is not tuple:  # an expression, not (name, expr) pairs
            return ((None, items[0]),)
        return tuple(items)

    def annotation_param(self, items):
        return (str(items[0]), items[1])

    def annotation_dcl(self, items):
        return ast.AnnotationDecl(str(items[1]), self.loc.token(items[1]))

    def annotation_member(self, items):
        return None

    def annotation_export(self, items):
        return None

    def any_type(self, items):
        return None

    def pragma_keylist(self, items):
        kw, type_name, *members = items
        return ast.KeylistPragma(type_name, tuple(members), self.loc.token(kw))

    def keylist_member(self, items):
        return (".".join(str(t) for t in items), self.loc.token(items[0]))


_PRECEDENCE = {"|": 1, "^": 2, "&": 3, ">>": 4, "<<": 4, "+": 5, "-": 5, "*": 6, "/": 6, "%": 6}


def _fold(operands: list[ast.Expr], op: str) -> None:
    """Replace the last two operands with their left-associative combination."""
    right = operands.pop()
    left = operands.pop()
    loc = left.loc
    if right.loc.line == loc.line and right.loc.file == loc.file:
        loc = loc._replace(end_line=right.loc.end_line, end_col=right.loc.end_col)
    operands.append(ast.Binary(op, left, right, loc))


_TOKEN_FAMILIES = (
    ({"'struct'", "'module'", "'const'"},
     {"'#pragma keylist'", "'@'", "'@annotation'", "'bitmask'", "'bitset'", "'const'", "'enum'", "'module'",
      "'native'", "'struct'", "'typedef'", "'union'", "'valuetype'"},
     "a definition (struct, union, enum, typedef, const, module, ...)"),
    ({"an integer", "'('", "an identifier"},
     {"'('", "'+'", "'-'", "'~'", "'::'", "'TRUE'", "'FALSE'", "an integer", "a number", "a fixed-point number",
      "a character literal", "a string literal", "an identifier"},
     "a constant expression"),
    ({"'sequence'", "'long'", "an identifier"},
     {"'boolean'", "'char'", "'double'", "'fixed'", "'float'", "'int16'", "'int32'", "'int64'", "'int8'",
      "'long'", "'map'", "'octet'", "'sequence'", "'short'", "'string'", "'uint16'", "'uint32'", "'uint64'",
      "'uint8'", "'unsigned'", "'wchar'", "'wstring'", "'::'", "an identifier"},
     "a type"),
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
    if state is None:
        return fallback
    try:
        conf = copy.copy(state.parse_conf)
        conf.callbacks = {}
        candidates = [t for t in conf.states[state.position] if t.isupper()]
    except Exception:  # no parser state to try (other lark versions): keep lark's answer
        return fallback
    from lark import Token as LarkToken

    out: set[str] = set()
    for term in candidates:
        probe = state.copy(deepcopy_values=False)
        probe.parse_conf = conf
        try:
            probe.feed_token(LarkToken(term, ""), is_end=term == "$END")
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
        upto = len(lines[ln - 1]) if ln >= 1 else 0
    return None


def _syntax_error(exc: UnexpectedInput, text: str, locator: _Locator, sink: DiagnosticSink) -> None:
    from lark.exceptions import UnexpectedCharacters, UnexpectedToken

    lines = text.split("\n")
    if isinstance(exc, UnexpectedCharacters):
        at = exc.pos_in_stream or 0  # lark always sets it on UnexpectedCharacters
        ch = text[at] if at < len(text) else ""
        loc = locator.at(exc.line, exc.column, exc.line, exc.column + 1)
        if ch == '"':
            sink.error("RG0202", "unterminated string literal", loc, "close the string with \" on the same line")
        elif ch == "'":
            sink.error("RG0202", "invalid character literal", loc, "a char literal holds one character, e.g. 'a' or '\\n'")
        elif text.startswith("/*", at):
            sink.error("RG0108", "unterminated /* comment", loc, "close the comment with */")
        else:
            shown = repr(ch)[1:-1] if ch.isprintable() is False else ch
            sink.error("RG0202", f"unexpected character '{shown}'", loc,
                       f"expected {_describe_expected(_viable(exc, exc.allowed))}" if exc.allowed
                       else "this character can appear only in comments and string literals")
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
        after = text[tok.end_pos or 0:].lstrip()[:1]
        if "IDENT" in expected and found in _keywords() and not (after.isalnum() or after in "_<:"):
            # (a keyword followed by a name or '<' is not itself meant as a name: `struct Inner;`)
            sink.error("RG0201", f"'{found}' is a reserved word in IDL and cannot be used as a name", loc,
                       f"rename it, e.g. '{found}_'")
            return
        if "IDENT" in expected and found in (";", ",", "[", "=", "{", ":", ")"):
            # `long long;`: the name is missing, or the last word was meant as the name
            prev = _prev_token_end(lines, tok.line, tok.column)
            word = re.search(r"[A-Za-z_]\w*$", lines[prev[0] - 1][:prev[1] - 1]) if prev else None
            if prev and word and word.group(0) in _keywords():
                sink.error("RG0201", f"'{word.group(0)}' is a reserved word in IDL and cannot be used as a name",
                           locator.at(prev[0], word.start() + 1, prev[0], prev[1]),
                           f"rename it, e.g. '{word.group(0)}_', or add the missing name")
                return
        stray = found == "}" and _unclosed_brace(text[:tok.start_pos or 0]) is None
        sink.error("RG0201", f"unexpected '{found}'; expected {_describe_expected(expected)}", loc,
                   "this '}' has no matching '{'" if stray else None)
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
    lean = _lean()
    builder = _ToAst(locator, pre.key_comments, sink)
    try:
        definitions = lean.parse(pre.text, builder)
    except RecursionError:
        sink.error("RG0201", "input is nested too deeply",
                   SourceLoc(pre.files[0] if pre.files else "<input>", 1, 1))
        return None
    except Exception as exc:
        from lark.exceptions import UnexpectedInput
        if not isinstance(exc, UnexpectedInput):
            raise
        _syntax_error(exc, pre.text, locator, sink)
        return None
    return ast.Specification(tuple(d for d in definitions if d is not None), tuple(pre.files))
