"""A fast lexer for the IDL grammar, with no dependency on lark.

One master regex (alternatives in a fixed order) plus a keyword table after each
identifier match: about twice as fast as lark's contextual lexer, which tries each parser
state's terminals in turn. Keywords are reserved everywhere, as IDL 4.2 (7.2.4) says: a
keyword used as a name is a syntax error with its own message (parse.py).

The lexer's tables (`LexSpec`) are derived from the grammar's terminals once, when the
parse tables are built (rapidgen.idl.larkgrammar), and ship precomputed with them
(rapidgen.idl.grammar), so a parse imports no lark. lark's own parser, used only to
explain a syntax error, runs this same lexer through an adapter (larkgrammar.LarkLexer).
"""
from __future__ import annotations

import re
from typing import Callable, Iterator, NamedTuple


class Token(str):
    """A token: its text (the str), its terminal's name and where it lies, with the same
    attribute names as lark's Token (the error translation reads either)."""

    __slots__ = ("type", "value", "start_pos", "end_pos", "line", "column", "end_line", "end_column")

    type: str
    value: str
    start_pos: int
    end_pos: int
    line: int
    column: int
    end_line: int
    end_column: int

    def __repr__(self) -> str:
        return f"Token({self.type!r}, {self.value!r})"


class LexError(Exception):
    """No terminal matches at `pos` (1-based line and column)."""

    def __init__(self, text: str, pos: int, line: int, column: int) -> None:
        super().__init__(f"no token at line {line} column {column}")
        self.text, self.pos, self.line, self.column = text, pos, line, column


class LexSpec(NamedTuple):
    master: str  # what the text skips (white space, comments), then one named group per terminal
    skip: str  # what the text skips, alone
    keywords: dict[str, str]  # word -> terminal name
    greater: str  # the terminal of '>' (one '>>' closes two template lists)
    dropped: tuple[str, ...]  # terminals no rule keeps (punctuation, most keywords): no Token made


# `sequence<sequence<long>>`: inside two open template lists '>>' closes both (as in C++11).
_TEMPLATE_WORDS = frozenset({"sequence", "string", "wstring", "map", "fixed", "bitfield"})


class IdlLexer:
    def __init__(self, spec: LexSpec) -> None:
        self.spec = spec
        self.master = re.compile(spec.master)
        self.skip = re.compile(spec.skip)
        self.keywords = spec.keywords
        self.greater = spec.greater
        self.dropped = frozenset(spec.dropped)

    def lex(self, text: str, token: type[Token] = Token, every: bool = False) -> Iterator[tuple[str, Token | None]]:
        """(terminal name, token) for each token of `text`, the token made as `token` (a
        str subclass with Token's slots); None for a terminal no rule keeps, unless
        `every`. LexError where nothing matches."""
        match = self.master.match
        new_str: Callable[[type[Token], str], Token] = str.__new__
        keywords, dropped = self.keywords, frozenset() if every else self.dropped
        line, line_start, pos, n = 1, 0, 0, len(text)
        prev, templates = "", 0  # previous token's text; template '<' lists open
        while pos < n:
            m = match(text, pos)
            if m is None:  # the end of the text, or a character no terminal matches
                skipped = self.skip.match(text, pos)  # (it matches the empty string too)
                at = skipped.end() if skipped else pos
                if at < n:
                    line += text.count("\n", pos, at)
                    line_start = text.rfind("\n", 0, at) + 1
                    raise LexError(text, at, line, at - line_start + 1)
                return
            kind = m.lastgroup or ""  # every alternative is a named group
            start, end = m.span(kind)
            if start != pos:  # white space or comments skipped first
                newlines = text.count("\n", pos, start)
                if newlines:
                    line += newlines
                    line_start = text.rfind("\n", pos, start) + 1
            value = m.group(kind)
            if kind == "IDENT":
                kind = keywords.get(value, "IDENT")
            if value[0] in "<>":
                if value == "<" and prev in _TEMPLATE_WORDS:
                    templates += 1
                elif value == ">" and templates:
                    templates -= 1
                elif value == ">>" and templates >= 2:
                    templates -= 2
                    for at in (start, start + 1):
                        if self.greater in dropped:
                            yield self.greater, None
                            continue
                        tok = new_str(token, ">")
                        tok.type, tok.value, tok.start_pos, tok.end_pos = self.greater, ">", at, at + 1
                        tok.line = tok.end_line = line
                        tok.column, tok.end_column = at - line_start + 1, at - line_start + 2
                        yield self.greater, tok
                    prev, pos = ">", end
                    continue
            prev = value
            pos = end
            if kind in dropped:
                yield kind, None
                continue
            # filling the slots directly: a constructor would cost Python frames per token
            tok = new_str(token, value)
            tok.type, tok.value, tok.start_pos, tok.end_pos = kind, value, start, end
            tok.line = tok.end_line = line
            col = start - line_start + 1
            tok.column, tok.end_column = col, col + end - start
            yield kind, tok
