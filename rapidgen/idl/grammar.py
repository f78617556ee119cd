"""The IDL grammar (grammar.lark) and its LALR tables in plain form, with no lark imported.

A parse needs only `tables()`: dicts, tuples and strings for the lean driver
(rapidgen.idl.lalr), shipped precomputed in rapidgen/idl/packaged_tables.py and used
while that was made from the very grammar read now; otherwise they are built from the
grammar by lark (rapidgen.idl.larkgrammar, about 0.3 s). lark is imported only then, or
for an input the tables reject, whose error lark's own parser explains.
`python -m rapidgen.idl.larkgrammar --write` refreshes the packaged tables, `--check` says
if they are stale (tests/idl/test_idl_tables.py too).
"""
from __future__ import annotations

import functools

from rapidgen.packagedata import read_text
from rapidgen.speed_devices import without

TABLES_FORMAT = 2  # bump when the shape of the tables changes (rapidgen.idl.larkgrammar.build_tables)
PACKAGED_MODULE = "packaged_tables.py"


@functools.lru_cache(maxsize=1)
def grammar_text() -> str:
    return read_text("rapidgen.idl", "grammar.lark")


def tables() -> dict:
    """The plain tables: the packaged ones when made from this grammar, else built now."""
    try:
        from rapidgen.idl import packaged_tables as packaged
    except ImportError:  # a copy of the package without them
        packaged = None  # type: ignore[assignment]
    if without("lalr-tables"):
        packaged = None  # type: ignore[assignment]
    if packaged is not None and packaged.GRAMMAR == grammar_text() and packaged.TABLES.get("format") == TABLES_FORMAT:
        return packaged.TABLES
    from rapidgen.idl.larkgrammar import build_tables
    return build_tables()


def lark_parser():
    """lark's own parser of the grammar (rapidgen.idl.larkgrammar.parser)."""
    from rapidgen.idl.larkgrammar import parser
    return parser()
