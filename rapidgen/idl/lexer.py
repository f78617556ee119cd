"""A fast lexer for the IDL grammar, plugged into lark's LALR parser.

Lark's contextual lexer tries each parser state's terminals in turn; for IDL one master
regex (alternatives in a fixed order) plus a keyword table after each identifier match
is about twice as fast. Keywords are reserved everywhere, as IDL 4.2 (7.2.4) says: a
keyword used as a name is a syntax error with its own message (parse.py).
"""
from __future__ import annotations

import re
from typing import Iterator

from lark.exceptions import UnexpectedCharacters
from lark.lexer import Lexer, PatternStr, Token

# Regex terminals tried before punctuation, in this order: comments before '/', wide
# literals before identifiers (L'x'), fixed before float before integer literals.
_ORDER = ("WS", "LINE_COMMENT", "BLOCK_COMMENT", "PRAGMA_KEYLIST", "ANNOTATION_KW", "WCHAR_LIT",
          "WSTRING_LIT", "FIXED_LIT", "FLOAT_LIT", "INT_LIT", "CHAR_LIT", "STRING_LIT", "IDENT")
# `sequence<sequence<long>>`: inside two open template lists '>>' closes both (as in C++11).
_TEMPLATE_WORDS = frozenset({"sequence", "string", "wstring", "map", "fixed", "bitfield"})
_WORD_ALTERNATION = re.compile(r"\(\?:([A-Za-z_][A-Za-z0-9_|]*)\)")


class IdlLexer(Lexer):
    def __init__(self, lexer_conf) -> None:
        self.ignore = frozenset(lexer_conf.ignore)
        self.keywords: dict[str, str] = {}
        ordered: list[tuple[str, str]] = []
        rest: list[tuple[int, str, str]] = []
        by_name = {t.name: t for t in lexer_conf.terminals}
        for term in lexer_conf.terminals:
            pattern = term.pattern
            if isinstance(pattern, PatternStr) and pattern.value.isidentifier():
                self.keywords[pattern.value] = term.name
                continue
            words = _WORD_ALTERNATION.fullmatch(pattern.to_regexp())
            if words and not isinstance(pattern, PatternStr):
                for word in words.group(1).split("|"):
                    self.keywords[word] = term.name
                continue
            if term.name not in _ORDER:
                rest.append((pattern.max_width, term.name, pattern.to_regexp()))
        for name in _ORDER:
            if name in by_name:
                ordered.append((name, by_name[name].pattern.to_regexp()))
        # Punctuation: longest first, so '::' wins over ':' and '>>' over '>'.
        ordered += [(name, regex) for _, name, regex in sorted(rest, key=lambda r: (-r[0], r[1]))]
        self.master = re.compile("|".join(f"(?P<{name}>{regex})" for name, regex in ordered))
        self.greater = next((t.name for t in lexer_conf.terminals
                             if isinstance(t.pattern, PatternStr) and t.pattern.value == ">"), "MORETHAN")

    # lark's custom-lexer interface for a whole text: lark wraps a lexer without
    # __future_interface__ and calls lex(text), not the (lexer_state, parser_state) of its base
    def lex(self, text: str) -> Iterator[Token]:  # type: ignore[override]
        match = self.master.match
        new_str = str.__new__
        ignore, keywords = self.ignore, self.keywords
        line, line_start, pos, n = 1, 0, 0, len(text)
        prev, templates = "", 0  # previous token's text; template '<' lists open
        while pos < n:
            m = match(text, pos)
            if m is None:
                raise UnexpectedCharacters(text, pos, line, pos - line_start + 1)
            kind = m.lastgroup or ""  # every alternative is a named group
            end = m.end()
            if kind in ignore:
                newlines = text.count("\n", pos, end)
                if newlines:
                    line += newlines
                    line_start = text.rfind("\n", pos, end) + 1
                pos = end
                continue
            value = m.group()
            if kind == "IDENT":
                kind = keywords.get(value, "IDENT")
            col = pos - line_start + 1
            if value[0] in "<>":
                if value == "<" and prev in _TEMPLATE_WORDS:
                    templates += 1
                elif value == ">" and templates:
                    templates -= 1
                elif value == ">>" and templates >= 2:
                    templates -= 2
                    yield Token(self.greater, ">", pos, line, col, line, col + 1, pos + 1)
                    yield Token(self.greater, ">", pos + 1, line, col + 1, line, col + 2, end)
                    prev, pos = ">", end
                    continue
            prev = value
            # Token(...) goes through two Python frames per token; fill its slots directly.
            tok = new_str(Token, value)
            tok.type, tok.value, tok.start_pos, tok.end_pos = kind, value, pos, end
            tok.line = tok.end_line = line
            tok.column, tok.end_column = col, col + end - pos
            yield tok
            pos = end
