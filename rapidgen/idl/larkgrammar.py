"""lark's side of the IDL parser: the grammar compiled to LALR tables, and lark's own
parser, which explains a syntax error. Imported only to build the tables (when the
packaged ones are stale) or for an input the tables reject (rapidgen.idl.grammar).

python -m rapidgen.idl.larkgrammar --write | --check: the packaged tables
(rapidgen/idl/packaged_tables.py), refreshed or checked.
"""
from __future__ import annotations

import functools
import re
import sys
from functools import partial
from pathlib import Path

from lark import Lark
from lark.exceptions import UnexpectedCharacters
from lark.lexer import Lexer, PatternStr, Token
from lark.parse_tree_builder import ChildFilterLALR_NoPlaceholders, ExpandSingleChild
from lark.parsers.lalr_analysis import Shift

from rapidgen.idl.grammar import PACKAGED_MODULE, TABLES_FORMAT, grammar_text
from rapidgen.idl.lexer import IdlLexer, LexError, LexSpec

# Regex terminals tried before punctuation, in this order: comments before '/', wide
# literals before identifiers (L'x'), fixed before float before integer literals.
# Identifiers (the commonest token) come as early as that allows: no later alternative
# can start with a letter or '_', so trying them first changes no match, only its speed
# (about 15% of the regex's time).
_ORDER = ("WS", "LINE_COMMENT", "BLOCK_COMMENT", "PRAGMA_KEYLIST", "ANNOTATION_KW", "WCHAR_LIT",
          "WSTRING_LIT", "IDENT", "FIXED_LIT", "FLOAT_LIT", "INT_LIT", "CHAR_LIT", "STRING_LIT")
_WORD_ALTERNATION = re.compile(r"\(\?:([A-Za-z_][A-Za-z0-9_|]*)\)")


def lex_spec(terminals, ignore, kept: set[str] | None = None) -> LexSpec:
    """The lexer's tables from lark's terminal definitions of the grammar; `kept`: the
    terminals some rule keeps (the others are `dropped`), None for all."""
    keywords: dict[str, str] = {}
    ordered: list[tuple[str, str]] = []
    rest: list[tuple[int, str, str]] = []
    by_name = {t.name: t for t in terminals}
    for term in terminals:
        pattern = term.pattern
        if isinstance(pattern, PatternStr) and pattern.value.isidentifier():
            keywords[pattern.value] = term.name
            continue
        words = _WORD_ALTERNATION.fullmatch(pattern.to_regexp())
        if words and not isinstance(pattern, PatternStr):
            for word in words.group(1).split("|"):
                keywords[word] = term.name
            continue
        if term.name not in _ORDER:
            rest.append((pattern.max_width, term.name, pattern.to_regexp()))
    for name in _ORDER:
        if name in by_name and name not in ignore:
            ordered.append((name, by_name[name].pattern.to_regexp()))
    # Punctuation: longest first, so '::' wins over ':' and '>>' over '>'.
    ordered += [(name, regex) for _, name, regex in sorted(rest, key=lambda r: (-r[0], r[1]))]
    greater = next((t.name for t in terminals if isinstance(t.pattern, PatternStr) and t.pattern.value == ">"),
                   "MORETHAN")
    # What is ignored, in _ORDER's order (comments before '/'), skipped possessively: once
    # skipped, never given back for a token to match instead (the '/' of a comment).
    skip = "(?:" + "|".join(by_name[name].pattern.to_regexp() for name in _ORDER if name in ignore) + ")*+"
    if set(ignore) - set(_ORDER):
        raise RuntimeError(f"ignored terminals without a place in the lexer's order: {set(ignore) - set(_ORDER)}")
    names = {t.name for t in terminals} | set(keywords.values())
    dropped = () if kept is None else tuple(sorted(names - set(kept) - set(ignore)))
    return LexSpec(skip + "(?:" + "|".join(f"(?P<{name}>{regex})" for name, regex in ordered) + ")", skip,
                   dict(sorted(keywords.items())), greater, dropped)


class LarkLexer(Lexer):
    """IdlLexer for lark's own parser (lark's Tokens, lark's UnexpectedCharacters)."""

    def __init__(self, lexer_conf) -> None:
        self.core = IdlLexer(lex_spec(lexer_conf.terminals, lexer_conf.ignore))

    # lark's custom-lexer interface for a whole text: lark wraps a lexer without
    # __future_interface__ and calls lex(text), not the (lexer_state, parser_state) of its base
    def lex(self, text: str):  # type: ignore[override]
        try:
            for _, tok in self.core.lex(text, Token, every=True):  # type: ignore[arg-type]  # the same slots
                yield tok
        except LexError as exc:
            raise UnexpectedCharacters(text, exc.pos, exc.line, exc.column) from None


@functools.lru_cache(maxsize=1)
def parser() -> Lark:
    """lark's LALR parser of the grammar (a plain tree builder): the source of the tables,
    and what explains a syntax error."""
    options = dict(parser="lalr", lexer=LarkLexer, maybe_placeholders=False)
    try:
        return Lark(grammar_text(), cache=True, **options)
    except OSError:  # unwritable temp dir: build without lark's on-disk cache
        return Lark(grammar_text(), **options)


def build_tables() -> dict:
    """The tables of lark's parser in plain form, states numbered canonically (breadth
    first from the start state, symbols in sorted order), so the same grammar always gives
    the same tables whatever order lark's sets came out in:

    rows: state -> symbol -> next state (shift or goto), or (size, rule name, rule number)
        to reduce;
    rules: per rule number (lark's order), (callback name, children kept or None for all,
        expand a single child): how lark's tree builder shapes the children it hands a
        callback (punctuation dropped, `_rule`s inlined, `?rule`s collapsed);
    lexer: LexSpec's fields.
    """
    lark = parser()
    table = lark.parser.parser.parser.parse_table  # ParsingFrontend -> LALR_Parser -> _Parser
    rules = list(lark.rules)
    number = {rule: i for i, rule in enumerate(rules)}
    start, end = table.start_states["start"], table.end_states["start"]
    order, seen = [start], {start}
    for state in order:  # breadth first; the list grows as it is walked
        for sym in sorted(table.states[state]):
            action, arg = table.states[state][sym]
            if action is Shift and arg not in seen:
                seen.add(arg)
                order.append(arg)
    missing = set(table.states) - seen
    order += sorted(missing)  # none in an LALR automaton; kept for completeness
    new = {old: i for i, old in enumerate(order)}
    rows = {new[state]: {sym: new[arg] if action is Shift else (len(arg.expansion), str(arg.origin.name), number[arg])
                         for sym, (action, arg) in sorted(table.states[state].items())}
            for state in order}
    recipes = []
    for rule, chain in lark._parse_tree_builder.rule_builders:
        keep, expand1 = None, False
        for wrapper in chain:
            if wrapper is ExpandSingleChild:
                expand1 = True
            elif isinstance(wrapper, partial) and wrapper.func is ChildFilterLALR_NoPlaceholders:
                keep = tuple((i, bool(expand)) for i, expand in wrapper.args[0])
            else:  # a tree-building option this driver does not reproduce
                raise RuntimeError(f"lark's tree builder wraps rule {rule} in {wrapper!r}")
        name = rule.alias or rule.options.template_source or rule.origin.name
        recipes.append((str(name), keep, expand1))
    assert [r for r, _ in lark._parse_tree_builder.rule_builders] == rules
    kept = set()  # the terminals some rule hands its callback
    for rule, (_, keep, _) in zip(rules, recipes):
        for i in (range(len(rule.expansion)) if keep is None else (i for i, _ in keep)):
            if rule.expansion[i].is_term:
                kept.add(rule.expansion[i].name)
    lexer = lex_spec(lark.lexer_conf.terminals, lark.lexer_conf.ignore, kept)
    return {"format": TABLES_FORMAT, "rows": rows, "start": new[start], "end": new[end],
            "rules": tuple(recipes), "lexer": tuple(lexer)}


def packaged_module_text() -> str:
    """rapidgen/idl/packaged_tables.py as build_tables() makes it now."""
    import pprint

    return ("# mypy: ignore-errors\n"
            "# The IDL grammar's LALR tables (rapidgen/idl/grammar.lark, compiled by lark), plain; do not edit.\n"
            "# python -m rapidgen.idl.larkgrammar --write refreshes them; stale ones are ignored (built from the grammar).\n"
            f"GRAMMAR = {grammar_text()!r}\n"
            f"TABLES = {pprint.pformat(build_tables(), width=110, sort_dicts=False)}\n")


def main(argv: list[str] | None = None) -> int:
    from rapidgen.precomputed import refresh_command

    return refresh_command("python -m rapidgen.idl.larkgrammar", "the IDL grammar's packaged LALR tables: "
                           "refresh or check them", Path(__file__).resolve().parent / PACKAGED_MODULE,
                           packaged_module_text, argv)


if __name__ == "__main__":
    sys.exit(main())
