"""Every test file has an entry in tests/tiers.py, and the marks say what the tests need."""
from pathlib import Path

from tests.tiers import MARKS, NEEDS, needs

ROOT = Path(__file__).resolve().parents[2]


def test_every_test_file_is_covered():
    files = sorted(p.relative_to(ROOT).as_posix() for p in (ROOT / "tests").rglob("test_*.py"))
    assert files, "no test files found"
    missing = [f for f in files if needs(f) is None]
    assert not missing, f"add these to tests/tiers.py: {missing}"


def test_entries_name_real_files_and_known_marks():
    for key, marks in NEEDS.items():
        path = key.split("::", 1)[0]
        assert (ROOT / path).exists(), key
        assert marks <= set(MARKS), (key, marks - set(MARKS))
        if "::" in key:
            name = key.split("::", 1)[1]
            assert f"def {name}(" in (ROOT / path).read_text(encoding="utf-8"), key


def test_the_most_specific_entry_wins():
    assert needs("tests/cdr/test_layout.py::test_x") == frozenset()
    assert needs("tests/cdr/test_cyclone.py::test_x[param]") == {"dds"}
    assert needs("tests/hostile/test_writer.py::test_kill_at_every_mutation_leaves_exactly_old_or_new_output[a]") \
        == {"slow"}
    assert needs("tests/hostile/test_writer.py::test_other") == frozenset()
    assert needs("tests/nowhere/test_x.py") is None
