"""rapidgen.precomputed.refresh_command: --check fails while the file differs from what
would be written, --write rewrites it only then; both refresh commands use it."""
import pytest

from rapidgen.precomputed import refresh_command


def test_write_and_check(tmp_path, capsys):
    path = tmp_path / "made.py"
    want = "X = 1\n"
    assert refresh_command("prog", "d", path, lambda: want, ["--check"]) == 1  # missing
    assert "stale:" in capsys.readouterr().err
    path.write_text("X = 0\n")
    assert refresh_command("prog", "d", path, lambda: want, ["--check"]) == 1
    assert path.read_text() == "X = 0\n"  # --check never writes
    assert refresh_command("prog", "d", path, lambda: want, ["--write"]) == 0
    assert path.read_text() == want and "wrote" in capsys.readouterr().out
    before = path.stat().st_mtime_ns
    assert refresh_command("prog", "d", path, lambda: want, ["--write"]) == 0
    assert path.stat().st_mtime_ns == before and capsys.readouterr().out == ""  # fresh: untouched
    assert refresh_command("prog", "d", path, lambda: want, ["--check"]) == 0
    with pytest.raises(SystemExit):
        refresh_command("prog", "d", path, lambda: want, [])  # one of the two is required


@pytest.mark.parametrize("module", ["rapidgen.idl.larkgrammar"])
def test_the_shipped_modules_are_fresh(module):
    import importlib

    assert importlib.import_module(module).main(["--check"]) == 0
