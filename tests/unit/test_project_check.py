"""`rapidgen generate` and `rapidgen check` over a project file, through the real python back end."""
from tests.helpers import rapidgen

IDL = "module m { struct S { @key long id; string<8> name; }; };\n"


def make_project(tmp_path):
    (tmp_path / "idl").mkdir()
    (tmp_path / "idl" / "s.idl").write_text(IDL)
    (tmp_path / "rapidgen.yaml").write_text(
        "targets:\n  - name: s\n    idl: [idl/*.idl]\n    lang: [python]\n    out: gen/s\n")


def test_check_fix_then_up_to_date_then_stale(tmp_path, monkeypatch):
    make_project(tmp_path)
    monkeypatch.chdir(tmp_path)
    stale = rapidgen("check")
    assert stale.code == 1 and "s: stale" in stale.out and "missing:" in stale.out
    fixed = rapidgen("check", "--fix")
    assert fixed.code == 0, fixed.err
    ok = rapidgen("check")
    assert ok.code == 0 and "s: up to date" in ok.out
    (tmp_path / "idl" / "s.idl").write_text(IDL.replace("string<8>", "string<9>"))
    again = rapidgen("check")
    assert again.code == 1 and "differs:" in again.out


def test_generate_is_deterministic(tmp_path, monkeypatch):
    make_project(tmp_path)
    monkeypatch.chdir(tmp_path)
    assert rapidgen("generate", "idl/s.idl", "-o", "one").code == 0
    assert rapidgen("generate", "idl/s.idl", "-o", "two").code == 0
    one = {p.relative_to(tmp_path / "one"): p.read_bytes() for p in (tmp_path / "one").rglob("*") if p.is_file()}
    two = {p.relative_to(tmp_path / "two"): p.read_bytes() for p in (tmp_path / "two").rglob("*") if p.is_file()}
    assert one == two and one


def test_bad_project_file_is_a_located_error(tmp_path, monkeypatch):
    (tmp_path / "rapidgen.yaml").write_text("targets:\n  - name: x\n    lang: [python\n")
    monkeypatch.chdir(tmp_path)
    res = rapidgen("check")
    assert res.code == 1 and "rapidgen.yaml:" in res.err and "error[RG0811]" in res.err


def test_unknown_target_language(tmp_path, monkeypatch):
    make_project(tmp_path)
    monkeypatch.chdir(tmp_path)
    res = rapidgen("generate", "idl/s.idl", "--lang", "cobol", "-o", "out")
    assert res.code == 1 and "unknown or unavailable target 'cobol'" in res.err
