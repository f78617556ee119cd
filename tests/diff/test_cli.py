"""`rapidgen diff` on the command line: output, exit status, ignores, waivers, --against."""
from __future__ import annotations

import json
import os
import shutil
import subprocess

import pytest

from rapidgen.cli import main
from tests.diff.conftest import REPO, idl_pair, write

S = "@final struct S {{ @key long id; {} }};"


def run(capsys, *argv):
    code = main(["diff", *argv])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture
def breaking(tmp_path):
    """A WIRE change (member added to @final) and a SOURCE change (constant)."""
    return idl_pair(tmp_path, S.format("long a;") + " const long N = 1;", S.format("long a; long b;") + " const long N = 2;")


def test_text_output_is_located_on_both_sides(capsys, breaking):
    old, new = breaking
    code, out, _ = run(capsys, old, new)
    assert code == 0  # no --fail-on: a report only
    first = out.splitlines()[0]
    assert first.startswith(f"{new}:2:") and "wire[WIRE-MEMBER-02]" in first and "'t::S.b'" in first
    assert f"  {old}:2:" in out and "note: in OLD" in out
    assert "= member added to a @final type: OMG DDS-XTypes 1.3" in out
    assert out.rstrip().endswith("rapidgen diff: 1 WIRE, 0 PROTOCOL, 1 SOURCE changes")


def test_fail_on_decides_the_exit_status(capsys, breaking):
    assert run(capsys, *breaking, "--fail-on", "WIRE")[0] == 1
    assert run(capsys, *breaking, "--fail-on", "PROTOCOL")[0] == 0
    assert run(capsys, *breaking, "--fail-on", "wire,protocol")[0] == 1
    assert run(capsys, *breaking, "--fail-on", "SOURCE", "--ignore", "SRC-CONST-01")[0] == 0


def test_json(capsys, breaking):
    old, new = breaking
    code, out, _ = run(capsys, old, new, "--json", "--ignore", "SRC-CONST-01")
    doc = json.loads(out)
    assert code == 0 and doc["counts"] == {"WIRE": 1, "PROTOCOL": 0, "SOURCE": 0} and doc["waived"] == 1
    (f,) = doc["findings"]
    assert f["rule"] == "WIRE-MEMBER-02" and f["category"] == "WIRE" and f["subject"] == "t::S.b"
    assert f["old"]["file"] == old and f["new"] == {"file": new, "line": 2, "col": f["new"]["col"]}
    assert f["explanation"]


def test_waiver_file(capsys, tmp_path, breaking):
    w = write(tmp_path, "waivers.yaml", "waivers:\n  - {rule: WIRE-MEMBER-02, type: 't::S', reason: not deployed}\n"
              "  - {rule: SRC-CONST-01, type: 't::OTHER', reason: another constant}\n")
    code, out, _ = run(capsys, *breaking, "--waivers", w, "--fail-on", "WIRE,SOURCE")
    assert code == 1 and "WIRE-MEMBER-02" not in out and "SRC-CONST-01" in out and "(1 waived)" in out


def test_bad_waiver_file_is_a_located_input_error(capsys, tmp_path, breaking):
    w = write(tmp_path, "waivers.yaml", "waivers:\n  - {rule: WIRE-MEMBR-02, reason: typo}\n")
    code, out, err = run(capsys, *breaking, "--waivers", w)
    assert code == 1 and out == ""
    assert f"{w}:2:" in err and "error[RG1804]" in err and "did you mean 'WIRE-MEMBER-02'" in err


@pytest.mark.parametrize("argv, says", [
    (["one.idl"], "give OLD and NEW"),
    (["a.idl", "b.idl", "c.idl"], "give OLD and NEW"),
    (["a.idl", "b.idl", "--fail-on", "WIRES"], "unknown category 'WIRES'"),
    (["a.idl", "b.idl", "--ignore", "WIRE-MEMBER-2"], "unknown rule id 'WIRE-MEMBER-2'"),
    (["--against", "HEAD", "a.idl", "b.idl"], "with --against REV give one path"),
])
def test_usage_errors_exit_2(capsys, argv, says):
    code, _, err = run(capsys, *argv)
    assert code == 2 and says in err


def test_kinds_must_agree(capsys, tmp_path):
    old, _ = idl_pair(tmp_path, "const long N = 1;", "const long N = 1;")
    assert run(capsys, old, os.path.join(REPO, "specs", "assets", "k10.yaml"))[0] == 2


def test_input_errors_exit_1_with_diagnostics(capsys, tmp_path):
    old, new = idl_pair(tmp_path, S.format("long a;"), S.format("Mising a;"))
    code, out, err = run(capsys, old, new)
    assert code == 1 and out == "" and f"{new}:2:" in err and "error[RG" in err
    code, _, err = run(capsys, old, str(tmp_path / "nowhere.idl"))
    assert code == 1 and "error[RG1801]" in err


def test_shipped_rapid_set_against_itself(capsys):
    rapid = os.path.join(REPO, "specs", "rapid")
    code, out, _ = run(capsys, rapid, rapid, "--fail-on", "WIRE,PROTOCOL,SOURCE")
    assert code == 0 and out.strip() == "rapidgen diff: 0 WIRE, 0 PROTOCOL, 0 SOURCE changes"
    k10 = os.path.join(REPO, "specs", "assets", "k10.yaml")
    assert run(capsys, k10, k10, "--fail-on", "WIRE,PROTOCOL")[0] == 0


def _git(repo, *args):
    subprocess.run(["git", "-C", str(repo), "-c", "user.name=t", "-c", "user.email=t@t", *args],
                   check=True, capture_output=True)


@pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")
def test_against_a_revision(capsys, tmp_path, monkeypatch):
    """OLD read from a commit (no checkout), includes and the descriptor's `idl.rapid`
    resolved in that revision's tree; locations in OLD name `REV:path`."""
    repo = tmp_path / "repo"
    shutil.copytree(os.path.join(REPO, "specs", "rapid"), repo / "specs" / "rapid")
    write(repo / "specs" / "assets" / "idl", "Ext.idl", '#include "Message.idl"\nmodule rapid { module ext {\n'
          "  valuetype Gps : Message { public double lat; public double lon; };\n}; };\n")
    asset = ("version: 1\nasset: {name: Probe, kind: rover}\nidl: {rapid: ../rapid, files: [idl/Ext.idl]}\n"
             "subsystems: [{name: Admin}]\ntelemetry:\n"
             "  - {kind: agent, values: [{key: a, type: RAPID_FLOAT}, {key: b, type: RAPID_INT}]}\n")
    write(repo / "specs" / "assets", "probe.yaml", asset)
    _git(repo, "init", "-q")
    _git(repo, "add", "-A")
    _git(repo, "commit", "-q", "-m", "one")
    monkeypatch.chdir(repo)
    assert run(capsys, "--against", "HEAD", "specs/assets/probe.yaml", "--fail-on", "WIRE,PROTOCOL")[0] == 0
    # the working tree changes: a member retyped (WIRE), a value key removed (PROTOCOL),
    # and the RAPID set itself: the revision's copy, not the working tree's, is OLD
    write(repo / "specs" / "assets" / "idl", "Ext.idl", '#include "Message.idl"\nmodule rapid { module ext {\n'
          "  valuetype Gps : Message { public double lat; public float lon; };\n}; };\n")
    write(repo / "specs" / "assets", "probe.yaml", asset.replace("{key: a, type: RAPID_FLOAT}, ", ""))
    code, out, err = run(capsys, "--against", "HEAD", "specs/assets/probe.yaml", "--fail-on", "PROTOCOL")
    assert code == 1, err
    assert "wire[WIRE-MEMBER-06]" in out and "'rapid::ext::Gps.lon' was double, is now float" in out
    assert "HEAD:specs/assets/idl/Ext.idl:3:" in out and "protocol[PROTO-VALUE-01]" in out
    assert "HEAD:specs/assets/probe.yaml:6:" in out
    code, _, err = run(capsys, "--against", "no-such-rev", "specs/assets/probe.yaml")
    assert code == 1 and "error[RG1802]" in err and "no-such-rev" in err
    write(repo / "specs", "new.idl", "module n { const long K = 1; };\n")
    code, _, err = run(capsys, "--against", "HEAD", "specs/new.idl")
    assert code == 1 and "'specs/new.idl' does not exist at revision 'HEAD'" in err


def test_long_chain_of_renamed_types_is_bounded(tmp_path):
    """Regression: 3,000 structs each holding the previous, all renamed, once overflowed
    Python's recursion comparing nested fingerprints (an internal error)."""
    from tests.hostile.limits import run_rapidgen

    def chain(prefix: str) -> str:
        decls = [f"struct {prefix}0 {{ long a; }};"]
        decls += [f"struct {prefix}{i} {{ {prefix}{i - 1} a; }};" for i in range(1, 3000)]
        return "module t {\n" + "\n".join(decls) + "\n};\n"

    old, new = write(tmp_path, "old.idl", chain("A")), write(tmp_path, "new.idl", chain("B"))
    r = run_rapidgen("diff", old, new, "--json", mem_mib=1024, cpu_s=30)
    assert r.code == 0, r.err[-2000:]
    doc = json.loads(r.out)
    assert doc["counts"]["WIRE"] == 3000 and {f["rule"] for f in doc["findings"]} == {"WIRE-TYPE-02"}
