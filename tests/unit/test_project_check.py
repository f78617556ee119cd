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
    # the descriptor's YAML loader reads the project file too: its codes, located
    assert res.code == 1 and res.err.startswith("rapidgen.yaml:4:1: error[RG1010]: YAML syntax error")


def test_unknown_target_language_in_the_project_file(tmp_path, monkeypatch):
    # on the command line it is a usage error (exit 2, tests/unit/test_cli_usage.py); in the
    # project file it is an error in the input
    make_project(tmp_path)
    (tmp_path / "rapidgen.yaml").write_text(
        "targets:\n  - name: s\n    idl: [idl/*.idl]\n    lang: [cobol]\n    out: gen/s\n")
    monkeypatch.chdir(tmp_path)
    res = rapidgen("check", "--fix")
    assert res.code == 1 and "unknown or unavailable target 'cobol'" in res.err
    assert not (tmp_path / "gen").exists()


def test_generating_a_second_language_keeps_the_first(tmp_path, monkeypatch):
    make_project(tmp_path)
    monkeypatch.chdir(tmp_path)
    assert rapidgen("generate", "idl/s.idl", "--lang", "python", "-o", "out").code == 0
    before = sorted(p.relative_to(tmp_path) for p in (tmp_path / "out" / "python").rglob("*.py"))
    res = rapidgen("generate", "idl/s.idl", "--lang", "qos", "-o", "out")
    assert res.code == 0 and "removed" not in res.out
    assert sorted(p.relative_to(tmp_path) for p in (tmp_path / "out" / "python").rglob("*.py")) == before
    assert (tmp_path / "out" / "qos" / "topics.json").is_file()


def test_targets_sharing_an_output_folder_are_refused(tmp_path, monkeypatch):
    make_project(tmp_path)
    (tmp_path / "rapidgen.yaml").write_text(
        "targets:\n  - name: a\n    idl: [idl/*.idl]\n    lang: [python]\n    out: gen/s\n"
        "  - name: b\n    idl: [idl/*.idl]\n    lang: [qos]\n    out: gen/s/inner\n"
        "  - name: a\n    idl: [idl/*.idl]\n    lang: [qos]\n    out: gen/t\n")
    monkeypatch.chdir(tmp_path)
    res = rapidgen("check")
    assert res.code == 1
    assert "error[RG0814]: two targets are named 'a'" in res.err
    assert "targets 'a' and 'b' write into the same folder" in res.err


def test_unwritable_output_is_a_diagnostic(tmp_path, monkeypatch):
    make_project(tmp_path)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a_file").write_text("not a folder\n")
    res = rapidgen("generate", "idl/s.idl", "-o", "a_file")
    assert res.code == 1 and "error[RG0803]: cannot write" in res.err and "Traceback" not in res.err
    assert rapidgen("generate", "idl/s.idl", "--lang", "", "-o", "out").code == 2


def test_headers_name_sources_relative_and_printable(tmp_path, monkeypatch):
    make_project(tmp_path)
    monkeypatch.chdir(tmp_path)
    weird = tmp_path / 'we"ird\nname.idl'
    weird.write_text(IDL)
    assert rapidgen("generate", str(weird), "-o", "out").code == 0
    text = "".join(p.read_text() for p in (tmp_path / "out" / "python").rglob("*.py"))
    assert str(tmp_path) not in text
    assert "we_ird_name.idl" in text


def test_project_schema_errors_point_at_the_value(tmp_path, monkeypatch):
    (tmp_path / "rapidgen.yaml").write_text("targets:\n  - name: s\n    idl: [a.idl]\n    lang: python\n    out: gen\n")
    monkeypatch.chdir(tmp_path)
    res = rapidgen("check")
    assert res.code == 1
    assert res.err.startswith("rapidgen.yaml:4:11: error[RG0812]: project file: at targets/0/lang: 'python' is not of type 'array'")
