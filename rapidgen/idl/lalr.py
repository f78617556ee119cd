"""A lean LALR(1) driver over the parse table lark builds from grammar.lark.

Lark compiles the grammar, builds the LALR tables and wraps the syntax-tree callbacks;
this module only runs the shift/reduce loop over those same tables, with the actions
flattened once into plain dicts (lark's generic loop hashes rule objects and checks
its state on every step, which was most of the parse time). On any input the table
rejects, parsing is handed to lark's own parser, which raises its full exception (with
the expected tokens and an interactive parser) for the error translation in parse.py:
error reporting is lark's, only the happy path is ours. The grammar's transformer has
no terminal callbacks (methods named after terminals): this loop would not call them.
"""
from __future__ import annotations

from itertools import chain
from types import SimpleNamespace
from typing import Any, Callable

from lark import Lark, Token, Transformer, Tree
from lark.parse_tree_builder import ParseTreeBuilder
from lark.parsers.lalr_analysis import Shift

from rapidgen.idl.lexer import IdlLexer


_END = (Token("$END", ""),)  # end of input, fed through the same loop as the tokens


class _Rejected(Exception):
    """The table has no action: let lark's parser produce the real error."""


class LeanLALR:
    """Parses with the tables of `parser` (built without a transformer); the syntax-tree
    builder is an argument of each parse, so one LeanLALR serves any number of parses at
    once and holds nothing of any input."""

    def __init__(self, parser: Lark) -> None:
        inner = parser.parser.parser.parser  # ParsingFrontend -> LALR_Parser -> _Parser
        table = inner.parse_table
        self.fallback: Callable[[], Lark] = lambda: parser
        self.lexer = IdlLexer(parser.lexer_conf)
        self.start = table.start_states["start"]
        self.end = table.end_states["start"]
        # rule number -> rule; per parse, the builder's callbacks are listed in this order
        self.rules = list(parser.rules)
        number = {rule: i for i, rule in enumerate(self.rules)}
        # state -> symbol -> next state (int: shift / goto) or (size, rule name, rule number) to reduce
        # (Any: an int or a triple, told apart by class in the hot loop, where isinstance costs)
        self.rows: dict[int, dict[str, Any]] = {
            state: {sym: arg if action is Shift else (len(arg.expansion), arg.origin.name, number[arg])
                    for sym, (action, arg) in row.items()}
            for state, row in table.states.items()
        }
        self.terminals, self.ignore = list(parser.lexer_conf.terminals), list(parser.lexer_conf.ignore)
        self.builder = parser._parse_tree_builder

    @property
    def parser(self) -> Lark:
        """lark's own parser of the grammar (built on first use for one made by from_state)."""
        return self.fallback()

    def state(self) -> tuple:
        """What from_state() needs, all of it picklable: the flattened table, the rules and
        the terminals (lark's own objects), without the Lark instance."""
        return self.rows, self.start, self.end, self.rules, self.terminals, self.ignore

    @classmethod
    def from_state(cls, state: tuple, fallback: Callable[[], Lark]) -> "LeanLALR":
        """A LeanLALR from state() of one built from the same grammar by the same lark,
        without building a Lark instance: `fallback()` makes one only for an input the
        table rejects. The tree builder is lark's, built as Lark builds it for this
        parser (a LALR parser, Tree, no positions propagated, no placeholders)."""
        self = cls.__new__(cls)
        self.rows, self.start, self.end, self.rules, self.terminals, self.ignore = state
        self.fallback = fallback
        self.lexer = IdlLexer(SimpleNamespace(terminals=self.terminals, ignore=self.ignore))
        self.builder = ParseTreeBuilder(self.rules, Tree, False, False, False)
        return self

    def parse(self, text: str, transformer: Transformer):
        """The value of the start rule, `transformer`'s methods applied as rules reduce.

        On input the table rejects, lark's parser (a tree builder, so no callback of
        `transformer` runs twice) raises its UnexpectedInput with the full context.
        """
        # lark wraps each method (dropping punctuation tokens, inlining _rules) as it would
        # for a parser built with this transformer; terminal callbacks are not supported
        callbacks = self.builder.create_callback(transformer)
        table = [callbacks[rule] for rule in self.rules]
        try:
            return self._run(text, table)
        except _Rejected:
            pass
        self.fallback().parse(text)  # raises lark's UnexpectedToken / UnexpectedCharacters
        raise AssertionError("lark accepted an input its own table rejected")

    def _run(self, text: str, callbacks: list):
        rows, end = self.rows, self.end
        state = self.start
        states = [state]
        values: list[object] = []
        push_state, push_value = states.append, values.append
        for tok in chain(self.lexer.lex(text), _END):
            kind = tok.type
            while True:
                act = rows[state].get(kind)
                if act.__class__ is int:
                    state = act
                    push_state(state)
                    push_value(tok)
                    break
                if act is None:
                    raise _Rejected
                size, origin, rule = act
                if size:
                    args = values[-size:]
                    del values[-size:]
                    del states[-size:]
                else:
                    args = []
                push_value(callbacks[rule](args))
                state = rows[states[-1]][origin]
                push_state(state)
                if state == end and kind == "$END":  # the start rule is complete
                    return values[-1]
        raise _Rejected
