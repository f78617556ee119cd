"""The lean driver's tables cached on disk (rapidgen.idl.parse._lean): loaded from the cache
they are the tables lark builds, they parse the same, and a damaged, foreign or unreadable
cache file is rebuilt, never trusted."""
import os

from rapidgen.idl import parse as parse_mod
from rapidgen.idl.lalr import LeanLALR


def test_cached_tables_are_lark_s(tmp_path, monkeypatch):
    built = LeanLALR(parse_mod._parser())
    path = tmp_path / "tables.pickle"
    parse_mod._save_tables(str(path), built.state())
    state = parse_mod._load_tables(str(path))
    assert state is not None
    loaded = LeanLALR.from_state(state, parse_mod._parser)
    assert loaded.rows == built.rows and (loaded.start, loaded.end) == (built.start, built.end)
    assert [str(r) for r in loaded.rules] == [str(r) for r in built.rules]
    assert loaded.lexer.master.pattern == built.lexer.master.pattern
    assert loaded.lexer.keywords == built.lexer.keywords
    assert loaded.parser is parse_mod._parser()  # lark's parser, for syntax errors only


def test_a_damaged_or_foreign_file_is_not_used(tmp_path):
    path = tmp_path / "tables.pickle"
    path.write_bytes(b"not a pickle")
    assert parse_mod._load_tables(str(path)) is None
    parse_mod._save_tables(str(path), LeanLALR(parse_mod._parser()).state())
    assert parse_mod._load_tables(str(path)) is not None
    os.chmod(path, 0o666)  # others may write it: not read
    assert parse_mod._load_tables(str(path)) is None
    assert parse_mod._load_tables(str(tmp_path / "missing.pickle")) is None


def test_the_cache_is_rebuilt_when_unusable(tmp_path, monkeypatch):
    path = tmp_path / "tables.pickle"
    path.write_bytes(b"\x80\x05junk")
    monkeypatch.setattr(parse_mod, "_tables_path", lambda: str(path))
    parse_mod._lean.cache_clear()
    try:
        lean = parse_mod._lean()
        assert lean.rows and parse_mod._load_tables(str(path)) is not None
    finally:
        parse_mod._lean.cache_clear()
