"""The writer against a hostile output folder, kills and concurrent runs (issue 8, items 2 and 4).

Every hostile manifest, link and file is made by the test. The kill test forks a child
that runs a real regeneration and exits hard just before its i-th filesystem mutation,
for every i; the folder must then hold exactly the old or exactly the new output.
"""
from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from rapidgen import writer
from rapidgen.backends.base import GeneratedFile as F
from rapidgen.diagnostics import DiagnosticSink
from rapidgen.generate import load_inputs, render, write_outputs
from tests.hostile.limits import run_rapidgen

ROOT = Path(__file__).resolve().parents[2]
K10 = str(ROOT / "specs" / "assets" / "k10.yaml")
IDL = "module demo {\n  struct Pose { double x; double y; };\n  struct Note { string text; };\n};\n"
PKG = "rapid_types"


def sha(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def codes(text: str) -> list[str]:
    return sorted({"RG" + part.split("]")[0] for part in text.split("[RG")[1:]})


def snapshot(root: Path) -> dict[str, bytes | None]:
    """Every entry below root: files with their bytes, folders as None, links as their target."""
    out: dict[str, bytes | None] = {}
    for folder, dirs, files in os.walk(root):
        for name in dirs + files:
            p = Path(folder, name)
            rel = str(p.relative_to(root))
            out[rel] = (b"->" + os.readlink(p).encode()) if p.is_symlink() else (None if p.is_dir() else p.read_bytes())
    return out


def manifest_matches(root: Path) -> bool:
    files = json.loads((root / writer.MANIFEST).read_text())["files"]
    return all(sha((root / rel).read_bytes()) == digest for rel, digest in files.items())


@pytest.fixture
def demo(tmp_path):
    """A small IDL input generated once into out/python; returns (workdir, output folder)."""
    (tmp_path / "demo.idl").write_text(IDL)
    res = run_rapidgen("generate", "demo.idl", "-o", "out", cwd=tmp_path)
    assert res.code == 0, res.err
    return tmp_path, tmp_path / "out" / "python"


def add_manifest_entry(out: Path, key: str, digest: str) -> None:
    m = json.loads((out / writer.MANIFEST).read_text())
    m["files"][key] = digest
    (out / writer.MANIFEST).write_text(json.dumps(m))


# --- item 2: the manifest and the folder are input -------------------------------------

@pytest.mark.parametrize("absolute", [False, True])
def test_manifest_key_outside_the_folder_is_never_deleted(demo, absolute):
    work, out = demo
    readme = work / "README.md"
    readme.write_bytes(b"the user's readme\n")
    key = str(readme) if absolute else "../../README.md"
    (work / "rapidgen.yaml").write_text(
        "targets:\n  - name: demo\n    idl: [demo.idl]\n    lang: [python]\n    out: out\n")
    for args in (("generate", "demo.idl", "-o", "out"), ("check", "--fix")):
        add_manifest_entry(out, key, sha(readme.read_bytes()))
        res = run_rapidgen(*args, cwd=work)
        assert res.code == 0, res.err
        assert readme.read_bytes() == b"the user's readme\n"
        assert codes(res.err) == ["RG0821"] and "README.md' ignored" in res.err
        assert key not in json.loads((out / writer.MANIFEST).read_text())["files"]


def test_hostile_manifest_entries_are_ignored_and_counted(tmp_path):
    writer.write_tree(str(tmp_path / "out"), [F("a.py", "a\n")])
    (tmp_path / "victim").write_text("v\n")
    bad = {"x" * 300: "0" * 64, "a.py": 5, "../victim": sha(b"v\n"), "": "0" * 64,
           **{f"../v{i}": "0" * 64 for i in range(20)}}
    (tmp_path / "out" / writer.MANIFEST).write_text(json.dumps({"files": bad}))
    report = writer.write_tree(str(tmp_path / "out"), [F("a.py", "a\n")])
    assert not report.failed and {d.code for d in report.problems} == {"RG0821"}
    assert len(report.problems) == writer._MAX_LISTED + 1 and "more manifest entries" in report.problems[-1].message
    assert (tmp_path / "victim").read_text() == "v\n" and (tmp_path / "out" / "a.py").read_text() == "a\n"
    (tmp_path / "out" / writer.MANIFEST).write_text("[1, 2")  # not JSON
    report = writer.write_tree(str(tmp_path / "out"), [F("a.py", "a\n")])
    assert [d.code for d in report.problems] == ["RG0821"] and manifest_matches(tmp_path / "out")


def test_check_reports_a_bad_manifest_key_without_touching_anything(demo):
    work, out = demo
    add_manifest_entry(out, "../victim.txt", "0" * 64)
    (work / "victim.txt").write_text("x")
    (work / "rapidgen.yaml").write_text(
        "targets:\n  - name: demo\n    idl: [demo.idl]\n    lang: [python]\n    out: out\n")
    res = run_rapidgen("check", cwd=work)
    assert res.code == 1 and "RG0821" in codes(res.err) and "differs: python/.rapidgen-manifest.json" in res.out
    assert (work / "victim.txt").read_text() == "x"


def test_symlinked_folder_pointing_outside_is_never_written_or_deleted_through(demo):
    work, out = demo
    victim = work / "victim"
    shutil.copytree(out / PKG, victim)  # the link's target holds files with the generated hashes
    before = snapshot(victim)
    shutil.rmtree(out / PKG)
    os.symlink(victim, out / PKG)
    res = run_rapidgen("generate", "demo.idl", "-o", "out", cwd=work)  # wants to write through the link
    assert res.code == 1 and "RG0822" in codes(res.err) and f"{PKG}' is a symbolic link" in res.err
    assert snapshot(victim) == before
    # no longer generated (another package name): the stale entries lie behind the link
    res = run_rapidgen("generate", "demo.idl", "-o", "out", "--package", "other", cwd=work)
    assert res.code == 0, res.err
    assert "RG0822" in codes(res.err) and snapshot(victim) == before and (out / PKG).is_symlink()
    assert (out / "other" / "__init__.py").is_file()


def test_symlinked_file_pointing_outside_is_never_written_or_deleted(demo):
    work, out = demo
    outside = work / "outside.toml"
    outside.write_bytes((out / "pyproject.toml").read_bytes())
    (out / "pyproject.toml").unlink()
    os.symlink(outside, out / "pyproject.toml")
    before = outside.read_bytes()
    res = run_rapidgen("generate", "demo.idl", "-o", "out", "--package", "other", cwd=work)  # pyproject changes
    assert res.code == 1 and "RG0822" in codes(res.err) and "pyproject.toml' is a symbolic link" in res.err
    assert outside.read_bytes() == before and not (out / "other").exists()  # nothing written at all
    # a stale manifest entry that is a link to a file with the listed hash: neither removed
    (out / "pyproject.toml").unlink()
    os.symlink(outside, out / "gone.toml")
    add_manifest_entry(out, "gone.toml", sha(before))
    res = run_rapidgen("generate", "demo.idl", "-o", "out", cwd=work)
    assert res.code == 0 and codes(res.err) == ["RG0822"]
    assert (out / "gone.toml").is_symlink() and outside.read_bytes() == before


def test_user_file_at_a_wanted_path_is_reported_and_untouched(tmp_path):
    (tmp_path / "demo.idl").write_text(IDL)
    out = tmp_path / "out" / "python"
    out.mkdir(parents=True)
    (out / "pyproject.toml").write_text("my own project\n")
    res = run_rapidgen("generate", "demo.idl", "-o", "out", cwd=tmp_path)
    assert res.code == 1 and codes(res.err) == ["RG0823"]
    assert f"{os.path.join('out', 'python', 'pyproject.toml')}: error[RG0823]" in res.err
    assert (out / "pyproject.toml").read_text() == "my own project\n"
    assert sorted(os.listdir(out)) == ["pyproject.toml"]  # all or nothing: nothing else written


def test_generated_file_edited_by_hand_is_ours_and_regenerated(demo):
    work, out = demo
    (out / "pyproject.toml").write_text("edited\n")
    res = run_rapidgen("generate", "demo.idl", "-o", "out", cwd=work)
    assert res.code == 0 and "1 written" in res.out and "edited" not in (out / "pyproject.toml").read_text()


@pytest.mark.parametrize("bad", ["../escape.py", "/tmp/abs.py", "a//b.py", "./a.py", "a\\b.py", writer.MANIFEST])
def test_back_end_paths_are_validated(tmp_path, bad):
    report = writer.write_tree(str(tmp_path / "out"), [F("ok.py", "1\n"), F(bad, "x\n")])
    assert report.failed and [d.code for d in report.problems] == ["RG0820"]
    assert os.listdir(tmp_path / "out") == [] and not (tmp_path / "escape.py").exists()


def test_duplicate_back_end_paths_are_rejected(tmp_path):
    report = writer.write_tree(str(tmp_path), [F("a.py", "1\n"), F("a.py", "2\n")])
    assert report.failed and "listed twice" in report.problems[0].message


# --- issue 9 defect 5: folders emptied by removals go too ----------------------------

def test_renamed_package_leaves_no_empty_folders_but_keeps_user_folders(tmp_path):
    res = run_rapidgen("generate", K10, "--lang", "python", "-o", "out", cwd=tmp_path)
    assert res.code == 0, res.err
    out = tmp_path / "out" / "python"
    (out / "rapid_k10red" / "rapid" / "notes.txt").write_text("mine\n")
    res = run_rapidgen("generate", K10, "--lang", "python", "-o", "out", "--package", "renamed", cwd=tmp_path)
    assert res.code == 0, res.err
    left = sorted(str(p.relative_to(out)) for p in (out / "rapid_k10red").rglob("*"))
    # handlers.py is the user's (written once, user_owned): kept like notes.txt
    assert left == ["rapid_k10red/handlers.py", "rapid_k10red/rapid", "rapid_k10red/rapid/notes.txt"]
    assert sorted(os.listdir(out)) == [writer.MANIFEST, "pyproject.toml", "rapid_k10red", "renamed"]


# --- item 4: all or nothing after a kill at any point ---------------------------------

def _render_k10(package: str | None):
    sink = DiagnosticSink()
    per_lang = render(load_inputs([K10], [], sink), ["python"], sink, package)
    assert per_lang and not sink.has_errors
    return per_lang["python"]


MUTATIONS = ("replace", "rename", "unlink", "rmdir", "mkdir")


def _run_killed_at(folder: Path, files, kill_at: int) -> int:
    """Fork a child that runs write_tree and os._exit(9)s just before mutation kill_at;
    returns the child's number of mutations (when it was not killed) or -1."""
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: never returns into pytest
        code = 1
        try:
            os.close(read)
            count = [0]

            def counting(real):
                def call(*args, **kwargs):
                    if count[0] == kill_at:
                        os._exit(9)
                    count[0] += 1
                    return real(*args, **kwargs)
                return call
            for name in MUTATIONS:
                setattr(os, name, counting(getattr(os, name)))
            os.fsync = lambda fd: None  # guards against power loss, not against a kill; slow
            writer._write_new = counting(writer._write_new)
            writer.write_tree(str(folder), files)
            os.write(write, str(count[0]).encode())
            code = 0
        finally:
            os._exit(code)
    os.close(write)
    with os.fdopen(read) as fh:
        told = fh.read()
    _, status = os.waitpid(pid, 0)
    code = os.waitstatus_to_exitcode(status)
    assert code in (0, 9), code
    return int(told) if code == 0 else -1


def test_kill_at_every_mutation_leaves_exactly_old_or_new_output(tmp_path):
    old_files, new_files = _render_k10(None), _render_k10("renamed")
    base = tmp_path / "base"
    assert not writer.write_tree(str(base), old_files).failed
    (base / "handlers").mkdir()
    (base / "handlers" / "mine.py").write_text("user code\n")  # the user's own files survive
    (base / "rapid_k10red" / "_idl" / "Ack.py").write_text("edited by hand\n")  # stale but edited: kept
    old = snapshot(base)
    done = tmp_path / "done"
    shutil.copytree(base, done, symlinks=True)
    total = _run_killed_at(done, new_files, kill_at=10**9)
    new = snapshot(done)
    assert old[writer.MANIFEST] == writer.manifest_text(old_files).encode()  # Ack.py: the user's edit
    assert new[writer.MANIFEST] == writer.manifest_text(new_files).encode() and manifest_matches(done)
    assert new != old and new["handlers/mine.py"] == b"user code\n"
    assert "rapid_k10red/_idl/Ack.py" in new and "rapid_k10red/rapid" not in new  # emptied folders removed
    outcomes = {"old": 0, "new": 0}
    for i in range(total):
        case = tmp_path / f"k{i}"
        shutil.copytree(base, case, symlinks=True)
        assert _run_killed_at(case, new_files, kill_at=i) == -1
        state = snapshot(case)
        staged = writer.STAGING in state
        committed = f"{writer.STAGING}/{writer.JOURNAL}" in state
        if not committed:  # before the commit the old output is untouched; after it, complete
            assert {k: v for k, v in state.items() if not k.startswith(writer.STAGING)} in (old, new)
        if staged:
            assert writer.compare_tree(str(case), new_files).interrupted  # `check` says so
        assert writer.recover(str(case)) == committed  # what the next run does first
        after = snapshot(case)
        assert after in (old, new), f"killed before mutation {i}: a mix of old and new"
        outcomes["new" if after == new else "old"] += 1
        shutil.rmtree(case)
    assert outcomes["old"] and outcomes["new"]  # kills fell on both sides of the commit


def test_next_generate_completes_an_interrupted_run(tmp_path):
    old_files, new_files = _render_k10(None), _render_k10("renamed")
    out = tmp_path / "out" / "python"
    writer.write_tree(str(out), old_files)
    total = _run_killed_at(tmp_path / "probe", new_files, kill_at=10**9)
    assert _run_killed_at(out, new_files, kill_at=total // 2) == -1  # mid-journal
    (tmp_path / "rapidgen.yaml").write_text(
        f"targets:\n  - name: k10\n    asset: {K10}\n    lang: [python]\n    out: out\n    package: renamed\n")
    res = run_rapidgen("check", cwd=tmp_path)
    assert res.code == 1 and "interrupted run: python/.rapidgen-staging/journal.json" in res.out
    res = run_rapidgen("check", "--fix", cwd=tmp_path)
    assert res.code == 0 and "completed a run that was interrupted" in res.out
    assert run_rapidgen("check", cwd=tmp_path).code == 0
    # the old package's handlers.py is the user's (user_owned): it stays, alone
    assert sorted(os.listdir(out)) == [writer.MANIFEST, "pyproject.toml", "rapid_k10red", "renamed"]
    assert os.listdir(out / "rapid_k10red") == ["handlers.py"] and manifest_matches(out)


# --- item 4: one run at a time -------------------------------------------------------

HOLDER = """
import os, sys, time
from rapidgen import writer
from rapidgen.cli import main
real_apply = writer._apply
def slow_apply(*args):  # hold the lock mid-run until the test says go
    open("in-apply", "w").close()
    for _ in range(600):
        if os.path.exists("go"):
            break
        time.sleep(0.05)
    return real_apply(*args)
writer._apply = slow_apply
sys.exit(main(["generate", "demo.idl", "-o", "out", "--package", "first"]))
"""


def test_concurrent_runs_take_turns(demo):
    work, out = demo
    env = dict(os.environ, PYTHONHASHSEED="0")
    first = subprocess.Popen([sys.executable, "-c", HOLDER], cwd=work, env=env,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    for _ in range(600):
        if (work / "in-apply").exists() or first.poll() is not None:
            break
        time.sleep(0.05)
    assert (work / "in-apply").exists(), first.communicate()
    second = subprocess.Popen([sys.executable, "-m", "rapidgen", "generate", "demo.idl", "-o", "out",
                               "--package", "second"], cwd=work, env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    waiting = second.stderr.readline()  # blocks until the second run reports that it waits
    (work / "go").touch()
    out1, err1 = first.communicate(timeout=120)
    out2, err2 = second.communicate(timeout=120)
    assert "waiting for another run" in waiting
    assert first.returncode == 0 and second.returncode == 0, (err1, waiting + err2)
    fresh = work / "fresh"
    assert run_rapidgen("generate", "demo.idl", "-o", "fresh", "--package", "second", cwd=work).code == 0
    assert snapshot(out) == snapshot(fresh / "python")  # the second run's complete output, nothing else


def test_a_run_that_cannot_get_the_lock_fails_clearly(demo, monkeypatch):
    work, out = demo
    before = snapshot(out)
    monkeypatch.setattr(writer, "LOCK_WAIT_S", 0)
    sink = DiagnosticSink()
    with writer._locked(str(out.resolve()), exclusive=True):
        assert not write_outputs(str(work / "out"), {"python": [F("x.py", "1\n")]}, sink)
    assert [d.code for d in sink.diagnostics] == ["RG0824"] and snapshot(out) == before


def test_output_to_a_device_writes_into_it_and_never_replaces_it(tmp_path):
    # `rapidgen ir -o /dev/null` as root replaced the device with a regular file (then every
    # program's "discarded" output piled up in it); a FIFO stands in for the device here
    import os
    import stat
    import threading

    from tests.helpers import rapidgen as run

    (tmp_path / "t.idl").write_text("module m { struct S { long a; }; };\n")
    fifo = tmp_path / "sink"
    os.mkfifo(fifo)
    got: list[bytes] = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_bytes()))
    reader.start()
    res = run("ir", str(tmp_path / "t.idl"), "-o", str(fifo))
    reader.join(timeout=10)
    assert res.code == 0, res.err
    assert stat.S_ISFIFO(os.stat(fifo).st_mode) and b'"m::S"' in got[0]
