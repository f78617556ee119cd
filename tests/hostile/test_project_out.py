"""A project file comes from a repository: `rapidgen check --fix` must not write outside it."""
import os

import pytest

from tests.helpers import rapidgen

IDL = "module m { struct S { long a; }; };\n"


@pytest.mark.parametrize("out", ["../escaped", "/tmp/rapidgen-escaped-abs", "gen/../../escaped", "link/out"])
def test_output_folder_outside_the_project_is_refused(tmp_path, monkeypatch, out):
    project = tmp_path / "project"
    (project / "idl").mkdir(parents=True)
    (project / "idl" / "s.idl").write_text(IDL)
    os.symlink(tmp_path, project / "link")  # a link inside the project that leads out of it
    (project / "rapidgen.yaml").write_text(
        f"targets:\n  - name: s\n    idl: [idl/*.idl]\n    lang: [python]\n    out: {out}\n")
    monkeypatch.chdir(project)
    res = rapidgen("check", "--fix")
    assert res.code == 1
    assert "rapidgen.yaml:5:10: error[RG0815]" in res.err and "outside the project" in res.err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["project"]
    assert not os.path.exists("/tmp/rapidgen-escaped-abs")


def test_output_folder_inside_the_project_is_written(tmp_path, monkeypatch):
    (tmp_path / "idl").mkdir()
    (tmp_path / "idl" / "s.idl").write_text(IDL)
    (tmp_path / "rapidgen.yaml").write_text(
        "targets:\n  - name: s\n    idl: [idl/*.idl]\n    lang: [python]\n    out: gen/./s\n")
    monkeypatch.chdir(tmp_path)
    assert rapidgen("check", "--fix").code == 0
    assert (tmp_path / "gen" / "s" / "python" / ".rapidgen-manifest.json").is_file()
