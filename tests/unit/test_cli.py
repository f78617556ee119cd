"""Command-line behaviour: exit codes, output file, diagnostics rendering."""
import json
import subprocess
import sys

from tests.helpers import rapidgen


def test_usage_errors_exit_2():
    assert rapidgen().code == 2
    assert rapidgen("ir").code == 2
    assert rapidgen("frobnicate").code == 2
    assert rapidgen("ir", "--no-such-flag", "x.idl").code == 2


def test_missing_file_is_a_located_error(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = rapidgen("ir", "nope.idl")
    assert res.code == 1
    assert res.err.startswith("nope.idl:1:1: error[RG0001]: cannot read 'nope.idl'")
    assert res.err.rstrip().endswith("rapidgen: 1 error")


def test_output_file_and_stdout_match(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a.idl").write_text("module m { struct S { long x; }; };\n")
    out = rapidgen("ir", "a.idl")
    to_file = rapidgen("ir", "a.idl", "-o", "ir.json")
    assert out.code == to_file.code == 0 and to_file.out == ""
    assert (tmp_path / "ir.json").read_text() == out.out
    assert json.loads(out.out)["declarations"][0]["loc"] == "a.idl:1:19"


def test_all_errors_are_reported_sorted_with_count(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a.idl").write_text("struct A { Unknown1 x; };\nstruct B { Unknown2 y; };\n")
    res = rapidgen("ir", "a.idl")
    lines = [ln for ln in res.err.splitlines() if ": error[" in ln]
    assert [ln.split(":")[1] for ln in lines] == ["1", "2"]
    assert "rapidgen: 2 errors" in res.err


def test_console_script_runs_as_a_module(tmp_path):
    (tmp_path / "a.idl").write_text("module m { const long X = 1; };\n")
    proc = subprocess.run([sys.executable, "-m", "rapidgen", "ir", str(tmp_path / "a.idl")],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0 and '"m::X"' in proc.stdout and proc.stderr == ""


def test_version():
    res = rapidgen("--version")
    assert res.code == 0 and res.out.startswith("rapidgen ")


def test_out_of_range_float_and_missing_include_folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a.idl").write_text("const double X = 1e400;\n")
    res = rapidgen("ir", "a.idl", "-I", "nowhere")
    assert res.code == 1
    assert "a.idl:1:18: error[RG0402]: floating-point literal 1e400 is out of range" in res.err
    assert "<command line>: warning[RG0112]: include folder 'nowhere' does not exist" in res.err


def test_device_files_are_bounded(monkeypatch):
    res = rapidgen("ir", "/dev/zero")
    assert res.code == 1 and "error[RG0005]: '/dev/zero' is larger than 16 MiB" in res.err


def test_vectors_refuse_huge_arrays(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a.idl").write_text("typedef long Row[100000];\nstruct A { Row x[100000]; };\n")
    res = rapidgen("vectors", "a.idl", "-o", "v.json")
    assert res.code == 1 and "error[RG0903]" in res.err and not (tmp_path / "v.json").exists()


def test_output_paths_that_cannot_be_written(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a.idl").write_text("@frobnicate struct S { long x; };\n")
    (tmp_path / "out").mkdir()
    for command in ("ir", "vectors"):
        res = rapidgen(command, "a.idl", "-o", "out")
        assert res.code == 1, command
        assert "out: error[RG0803]: cannot write 'out'" in res.err and "Traceback" not in res.err
        assert res.err.count("warning[RG0501]") == 1, "earlier diagnostics must not be printed twice"
