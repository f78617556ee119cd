"""A lean LALR(1) driver over the IDL grammar's tables, with no dependency on lark.

lark compiles the grammar and builds the LALR tables (rapidgen.idl.grammar, shipped
precomputed); this module only runs the shift/reduce loop over them and shapes each
rule's children as lark's tree builder would (punctuation dropped, `_rule`s inlined,
`?rule`s with one child collapsed) before calling the syntax-tree builder's method of
that rule. On any input the tables reject, the parse is handed to lark's own parser,
which raises its full exception (the expected tokens, an interactive parser) for the
error translation in parse.py: error reporting is lark's, only the happy path is ours.
The builder has no methods named after terminals (lark would call them for tokens; this
loop does not).
"""
from __future__ import annotations

from itertools import chain
from typing import Any, Callable

from rapidgen.idl.lexer import IdlLexer, LexError, LexSpec

_END = ("$END", None)  # end of input, fed through the same loop as the tokens


class Rejected(Exception):
    """The tables have no action for the input: lark's parser says why."""


class Node:
    """What a rule without a builder method makes (as lark's Tree): its name and children."""

    __slots__ = ("data", "children")

    def __init__(self, data: str, children: list) -> None:
        self.data, self.children = data, children

    def __repr__(self) -> str:
        return f"Node({self.data!r}, {self.children!r})"


def _shaped(method: Callable[[list], Any], keep: tuple | None, expand1: bool) -> Callable[[list], Any]:
    """`method` called with the children lark's tree builder would give it."""
    if expand1:
        inner = method

        def method(children: list) -> Any:
            return children[0] if len(children) == 1 else inner(children)
    if keep is None:
        return method
    inner2 = method

    def filtered(children: list) -> Any:
        out: list = []
        for i, expand in keep:
            if expand:  # an inlined `_rule`: its children take its place
                if out:
                    out += children[i].children
                else:
                    out = children[i].children
            else:
                out.append(children[i])
        return inner2(out)
    return filtered


class LeanLALR:
    """Parses with plain tables (rapidgen.idl.grammar.tables()); the syntax-tree builder is
    an argument of each parse, so one LeanLALR serves any number of parses at once and holds
    nothing of any input."""

    def __init__(self, tables: dict, fallback: Callable[[], Any]) -> None:
        self.rows: dict[int, dict[str, Any]] = tables["rows"]
        self.start: int = tables["start"]
        self.end: int = tables["end"]
        self.rules: tuple = tables["rules"]
        self.lexer = IdlLexer(LexSpec(*tables["lexer"]))
        self.fallback = fallback  # -> lark's parser of the grammar, built only for an input rejected

    def parse(self, text: str, builder: object):
        """The value of the start rule, `builder`'s methods applied as rules reduce (a rule
        without a method makes a Node).

        On input the tables reject, lark's parser (a tree builder, so no method of `builder`
        runs twice) raises its UnexpectedInput with the full context.
        """
        callbacks = []
        for name, keep, expand1 in self.rules:
            method = getattr(builder, name, None)
            if method is None:
                method = (lambda name: lambda children: Node(name, children))(name)
            callbacks.append(_shaped(method, keep, expand1))
        try:
            return self._run(text, callbacks)
        except (Rejected, LexError):
            pass
        self.fallback().parse(text)  # raises lark's UnexpectedToken / UnexpectedCharacters
        raise AssertionError("lark accepted an input its own tables rejected")

    def _run(self, text: str, callbacks: list):
        rows, end = self.rows, self.end
        state = self.start
        states = [state]
        values: list[object] = []
        push_state, push_value = states.append, values.append
        for kind, tok in chain(self.lexer.lex(text), (_END,)):
            while True:
                act = rows[state].get(kind)
                if act.__class__ is int:
                    state = act
                    push_state(state)
                    push_value(tok)
                    break
                if act is None:
                    raise Rejected
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
        raise Rejected
