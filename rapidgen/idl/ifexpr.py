"""`#if` / `#elif` expressions with C's grammar and semantics.

Precedence climbing over C's operator table (so `A & 4 == 4` is `A & (4 == 4)`, as in
C), integers in 64 bits, `/` and `%` truncating toward zero, `!`/`&&`/`||`/comparisons
giving 0 or 1, and short-circuit: the unevaluated side of `&&`/`||` is parsed but not
computed, so `0 && 1/0` is 0. A macro name evaluates its value (recursively); an
undefined or empty one is 0, and each macro is evaluated once per expression (macros
that use others twice would otherwise cost 2**depth). Every problem is a ValueError with
a message for the user.
"""
from __future__ import annotations

import re

_TOKEN = re.compile(r"\s+|0[xX][0-9a-fA-F]+[uUlL]*|\d+[uUlL]*|[A-Za-z_]\w*"
                    r"|&&|\|\||==|!=|<=|>=|<<|>>|[-+*/%()!~<>&|^?:]")
_INT = re.compile(r"(0[xX][0-9a-fA-F]+|0[0-7]*|[1-9][0-9]*)[uUlL]*")
_DEFINED = re.compile(r"\bdefined\s*\(\s*([A-Za-z_]\w*)\s*\)|\bdefined\s+([A-Za-z_]\w*)")
_BINARY = {"||": 1, "&&": 2, "|": 3, "^": 4, "&": 5, "==": 6, "!=": 6, "<": 7, "<=": 7, ">": 7, ">=": 7,
           "<<": 8, ">>": 8, "+": 9, "-": 9, "*": 10, "/": 10, "%": 10}
_MIN, _MAX = -2**63, 2**64 - 1
MAX_MACRO_DEPTH = 16


def evaluate(expr: str, macros: dict[str, str], depth: int = 0, memo: dict[str, int] | None = None) -> int:
    if depth > MAX_MACRO_DEPTH:
        raise ValueError("macro expansion too deep")
    tokens = _tokens(expr, macros, depth, {} if memo is None else memo)
    if not tokens:
        raise ValueError("empty expression")
    value, i = _Parser(tokens, expr.strip()).binary(0, 1, True)
    if i != len(tokens):
        raise ValueError(f"unexpected '{tokens[i]}' in '{expr.strip()}'")
    return value


def _tokens(expr: str, macros: dict[str, str], depth: int, memo: dict[str, int]) -> list[int | str]:
    """Integers (macros already evaluated) and operator strings."""
    expr = _DEFINED.sub(lambda m: "1" if (m.group(1) or m.group(2)) in macros else "0", expr)
    if re.search(r"\bdefined\b", expr):
        raise ValueError("'defined' needs a macro name")
    out: list[int | str] = []
    pos = 0
    for m in _TOKEN.finditer(expr):
        if m.start() != pos:
            break
        pos = m.end()
        tok = m.group(0)
        if tok.isspace():
            continue
        if tok[0].isdigit():
            if not _INT.fullmatch(tok):
                raise ValueError(f"invalid integer '{tok}'")
            digits = tok.rstrip("uUlL")
            out.append(int(digits, 8) if re.fullmatch(r"0[0-7]+", digits) else int(digits, 0))
        elif tok[0].isalpha() or tok[0] == "_":
            if tok not in memo:
                value = macros.get(tok, "")
                memo[tok] = evaluate(value, macros, depth + 1, memo) if value.strip() else 0
            out.append(memo[tok])
        elif tok in ("?", ":"):
            raise ValueError("the ?: operator is not supported")
        else:
            out.append(tok)
    if pos != len(expr):
        raise ValueError(f"unexpected '{expr[pos:].strip()[:20]}'")
    return out


class _Parser:
    def __init__(self, tokens: list[int | str], text: str) -> None:
        self.tokens = tokens
        self.text = text  # for messages

    def binary(self, i: int, min_prec: int, live: bool) -> tuple[int, int]:
        """Parse operators of precedence >= min_prec from i; compute only when live."""
        left, i = self.unary(i, live)
        toks = self.tokens
        while i < len(toks):
            op = toks[i]
            prec = _BINARY.get(op, 0) if isinstance(op, str) else 0
            if not isinstance(op, str) or prec < min_prec:
                break
            # Short-circuit: the right side of `0 && x` / `1 || x` is parsed but not computed.
            right_live = live and not (op == "&&" and not left) and not (op == "||" and left)
            right, i = self.binary(i + 1, prec + 1, right_live)
            left = _apply(op, left, right) if right_live else (int(bool(left)) if op in ("&&", "||") else 0)
        return left, i

    def unary(self, i: int, live: bool) -> tuple[int, int]:
        toks = self.tokens
        if i >= len(toks):
            raise ValueError(f"'{self.text}' ends where an operand is expected")
        tok = toks[i]
        if isinstance(tok, int):
            return tok, i + 1
        if tok in ("!", "~", "-", "+"):
            value, i = self.unary(i + 1, live)
            return {"!": int(not value), "~": ~value, "-": -value, "+": value}[tok], i
        if tok == "(":
            value, i = self.binary(i + 1, 1, live)
            if i >= len(toks) or toks[i] != ")":
                raise ValueError(f"missing ')' in '{self.text}'")
            return value, i + 1
        raise ValueError(f"unexpected '{tok}' in '{self.text}'")


def _apply(op: str, a: int, b: int) -> int:
    if op in ("<<", ">>") and not 0 <= b < 64:
        raise ValueError(f"shift count {b} is outside 0..63")
    if op in ("/", "%") and b == 0:
        raise ValueError("division by zero")
    if op == "/":
        q = abs(a) // abs(b)
        result = q if (a >= 0) == (b >= 0) else -q
    elif op == "%":
        result = abs(a) % abs(b) * (1 if a >= 0 else -1)
    elif op in ("&&", "||"):
        result = int(bool(a) and bool(b)) if op == "&&" else int(bool(a) or bool(b))
    else:
        result = {"|": a | b, "^": a ^ b, "&": a & b, "==": int(a == b), "!=": int(a != b), "<": int(a < b),
                  "<=": int(a <= b), ">": int(a > b), ">=": int(a >= b), "+": a + b, "-": a - b,
                  "*": a * b}[op] if op not in ("<<", ">>") else (a << b if op == "<<" else a >> b)
    if not _MIN <= result <= _MAX:
        raise ValueError("integer overflow (the value does not fit in 64 bits)")
    return result
