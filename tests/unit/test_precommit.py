"""The pre-commit hooks (.pre-commit-hooks.yaml) run as pre-commit runs them, in a scratch git
repository: a fresh tree passes, stale generated code fails `rapidgen-check`, a breaking IDL
change fails `rapidgen-diff` (issue 26). Also `--format github` (docs/ci.md)."""
from __future__ import annotations

import os
import shlex
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from rapidgen import github_annotations
from rapidgen.diagnostics import Diagnostic, Severity, SourceLoc

ROOT = Path(__file__).resolve().parents[2]
IDL = "module m {\n  struct Pose {\n    @key long id;\n    double x;\n  };\n};\n"
PROJECT = "targets:\n  - name: m\n    idl: [idl/*.idl]\n    lang: [python, qos]\n    out: generated/m\n"


def hooks() -> dict[str, dict]:
    return {h["id"]: h for h in yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text(encoding="utf-8"))}


def git(repo: Path, *args: str) -> str:
    return subprocess.run(["git", *args], cwd=repo, check=True, capture_output=True, text=True).stdout


def run_hook(repo: Path, hook_id: str, args: list[str] | None = None) -> subprocess.CompletedProcess:
    """The hook's entry and args, no file names (pass_filenames: false), the way pre-commit
    runs it; `rapidgen` is this interpreter's (pre-commit would install the package)."""
    hook = hooks()[hook_id]
    argv = shlex.split(hook["entry"]) + list(hook.get("args", [])) + (args or [])
    assert argv[0] == "rapidgen"
    return subprocess.run([sys.executable, "-m", "rapidgen", *argv[1:]], cwd=repo, capture_output=True, text=True,
                          env={k: v for k, v in os.environ.items() if k != "RAPIDGEN_JOBS"})


@pytest.fixture
def repo(tmp_path: Path) -> Path:
    (tmp_path / "idl").mkdir()
    (tmp_path / "idl" / "pose.idl").write_text(IDL, encoding="utf-8")
    (tmp_path / "rapidgen.yaml").write_text(PROJECT, encoding="utf-8")
    git(tmp_path, "init", "-q")
    git(tmp_path, "config", "user.email", "ci@example.invalid")
    git(tmp_path, "config", "user.name", "ci")
    fixed = subprocess.run([sys.executable, "-m", "rapidgen", "check", "--fix"], cwd=tmp_path, capture_output=True,
                           text=True)
    assert fixed.returncode == 0, fixed.stderr
    git(tmp_path, "add", "-A")
    git(tmp_path, "commit", "-q", "-m", "generated")
    return tmp_path


def test_the_hooks_file_declares_both_hooks_for_pre_commit():
    h = hooks()
    assert set(h) == {"rapidgen-check", "rapidgen-diff"}
    for hook in h.values():
        assert hook["language"] == "python" and hook["pass_filenames"] is False and hook["name"]
    assert "--against HEAD" in h["rapidgen-diff"]["entry"] and "--fail-on WIRE,PROTOCOL" in h["rapidgen-diff"]["entry"]


def test_check_hook_passes_on_a_fresh_tree_and_fails_on_stale_output(repo):
    assert run_hook(repo, "rapidgen-check").returncode == 0
    generated = next((repo / "generated" / "m" / "python").rglob("*.py"))
    original = generated.read_text(encoding="utf-8")
    generated.write_text(original + "# edited by hand\n", encoding="utf-8")
    stale = run_hook(repo, "rapidgen-check")
    assert stale.returncode == 1 and "m: stale" in stale.stdout and "differs:" in stale.stdout
    generated.write_text(original, encoding="utf-8")
    assert run_hook(repo, "rapidgen-check").returncode == 0
    # an IDL edit committed without regenerating
    (repo / "idl" / "pose.idl").write_text(IDL.replace("double x;", "double x;\n    double y;"), encoding="utf-8")
    assert run_hook(repo, "rapidgen-check").returncode == 1


def test_diff_hook_passes_an_addition_and_fails_a_wire_break(repo):
    added = IDL.replace("};\n};", "};\n  struct Extra { long n; };\n};")
    (repo / "idl" / "pose.idl").write_text(added, encoding="utf-8")
    ok = run_hook(repo, "rapidgen-diff", ["idl/pose.idl"])
    assert ok.returncode == 0, ok.stdout + ok.stderr
    (repo / "idl" / "pose.idl").write_text(IDL.replace("double x;", "float x;"), encoding="utf-8")
    broken = run_hook(repo, "rapidgen-diff", ["idl/pose.idl"])
    assert broken.returncode == 1 and "WIRE-MEMBER-06" in broken.stdout, broken.stdout + broken.stderr
    assert run_hook(repo, "rapidgen-diff").returncode == 2  # no path given: a usage error


def test_check_and_diff_speak_github_annotations(repo):
    generated = next((repo / "generated" / "m" / "python").rglob("*.py"))
    generated.write_text("edited\n", encoding="utf-8")
    res = subprocess.run([sys.executable, "-m", "rapidgen", "check", "--format", "github"], cwd=repo,
                         capture_output=True, text=True)
    rel = generated.relative_to(repo).as_posix()
    assert res.returncode == 1 and f"::error file={rel},title=rapidgen check%3A m::differs" in res.stdout
    (repo / "idl" / "pose.idl").write_text(IDL.replace("double x;", "float x;"), encoding="utf-8")
    res = subprocess.run([sys.executable, "-m", "rapidgen", "diff", "--against", "HEAD", "idl/pose.idl",
                          "--fail-on", "WIRE", "--format", "github"], cwd=repo, capture_output=True, text=True)
    assert res.returncode == 1
    assert "::error file=idl/pose.idl,line=4,col=11,title=wire[WIRE-MEMBER-06]%3A member type changed::" in res.stdout
    (repo / "idl" / "pose.idl").write_text(IDL.replace("long id;", "Mesage id;"), encoding="utf-8")
    res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", "idl/pose.idl", "-o", "out",
                          "--format", "github"], cwd=repo, capture_output=True, text=True)
    assert res.returncode == 1 and res.stdout.startswith("::error file=idl/pose.idl,line=3,")
    assert "title=error[RG0203]::unknown type 'Mesage'" in res.stdout and "rapidgen: 1 error" in res.stderr


def test_annotation_values_cannot_forge_a_second_command():
    d = Diagnostic(Severity.WARNING, "RG0501", "50% done\n::error::forged", SourceLoc("a,b:c.idl", 3, 7), "x\ry")
    line = github_annotations.of_diagnostic(d)
    assert "\n" not in line and "\r" not in line
    assert line == ("::warning file=a%2Cb%3Ac.idl,line=3,col=7,title=warning[RG0501]::"
                    "50%25 done\\n::error::forged (hint: x\\ry)")  # escaped() spells controls out
    assert github_annotations.command("notice", "m", SourceLoc("<command line>", 0, 0)) == "::notice::m"
    assert github_annotations.command("error", "m", SourceLoc("f.idl", 0, 0)) == "::error file=f.idl::m"
