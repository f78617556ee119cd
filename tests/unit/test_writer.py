"""The writer: write-if-changed, atomic staging, manifest, stale removal, user-owned files."""
import json
import os

import pytest

from rapidgen import writer
from rapidgen.backends.base import GeneratedFile as F


def read(p):
    return p.read_text(encoding="utf-8")


def test_writes_then_leaves_unchanged_files_alone(tmp_path):
    files = [F("a/x.py", "x = 1\n"), F("b.txt", "b\n")]
    first = writer.write_tree(str(tmp_path), files)
    assert sorted(first.written) == ["a/x.py", "b.txt"]
    mtime = os.stat(tmp_path / "a" / "x.py").st_mtime_ns
    second = writer.write_tree(str(tmp_path), files)
    assert second.written == [] and sorted(second.unchanged) == ["a/x.py", "b.txt"]
    assert os.stat(tmp_path / "a" / "x.py").st_mtime_ns == mtime


def test_manifest_lists_generated_files_with_digests(tmp_path):
    writer.write_tree(str(tmp_path), [F("x.py", "1\n"), F("user.py", "edit me\n", user_owned=True)])
    manifest = json.loads(read(tmp_path / writer.MANIFEST))
    assert manifest["files"] == {"x.py": writer.digest("1\n")}


def test_user_owned_files_are_never_overwritten(tmp_path):
    writer.write_tree(str(tmp_path), [F("handlers.py", "template\n", user_owned=True)])
    (tmp_path / "handlers.py").write_text("my code\n")
    report = writer.write_tree(str(tmp_path), [F("handlers.py", "new template\n", user_owned=True)])
    assert report.kept_user == ["handlers.py"]
    assert read(tmp_path / "handlers.py") == "my code\n"


def test_files_no_longer_generated_are_removed_unless_edited(tmp_path):
    writer.write_tree(str(tmp_path), [F("keep.py", "k\n"), F("old.py", "o\n"), F("edited.py", "e\n")])
    (tmp_path / "edited.py").write_text("changed by hand\n")
    report = writer.write_tree(str(tmp_path), [F("keep.py", "k\n")])
    assert report.removed == ["old.py"] and report.kept_edited == ["edited.py"]
    assert not (tmp_path / "old.py").exists() and (tmp_path / "edited.py").exists()


def test_interrupted_run_leaves_previous_output_intact(tmp_path, monkeypatch):
    writer.write_tree(str(tmp_path), [F("a.py", "old a\n"), F("b.py", "old b\n")])
    real_write = writer._write_new
    calls = []

    def failing_write(path, data, mode):
        calls.append(path)
        if len(calls) == 2:
            raise KeyboardInterrupt  # interrupted while staging the second file
        return real_write(path, data, mode)

    monkeypatch.setattr(writer, "_write_new", failing_write)
    with pytest.raises(KeyboardInterrupt):
        writer.write_tree(str(tmp_path), [F("a.py", "new a\n"), F("b.py", "new b\n")])
    assert read(tmp_path / "a.py") == "old a\n" and read(tmp_path / "b.py") == "old b\n"
    assert sorted(os.listdir(tmp_path)) == [writer.MANIFEST, "a.py", "b.py"]


def test_compare_tree_reports_missing_differing_and_extra(tmp_path):
    writer.write_tree(str(tmp_path), [F("same.py", "s\n"), F("diff.py", "d\n"), F("gone.py", "g\n")])
    report = writer.compare_tree(str(tmp_path), [F("same.py", "s\n"), F("diff.py", "D\n"), F("new.py", "n\n")])
    assert report.missing == ["new.py"]
    assert report.differs == ["diff.py", writer.MANIFEST]
    assert report.extra == ["gone.py"]
    assert report.stale
    clean = writer.compare_tree(str(tmp_path), [F("same.py", "s\n"), F("diff.py", "d\n"), F("gone.py", "g\n")])
    assert not clean.stale


def test_write_text_atomic_keeps_mode_and_skips_identical(tmp_path):
    p = tmp_path / "run.sh"
    assert writer.write_text_atomic(str(p), "echo 1\n")
    os.chmod(p, 0o755)
    assert not writer.write_text_atomic(str(p), "echo 1\n")
    assert writer.write_text_atomic(str(p), "echo 2\n")
    assert os.stat(p).st_mode & 0o777 == 0o755


def test_what_the_next_run_relies_on_is_fsynced_before_the_commit(tmp_path, monkeypatch):
    """Before the journal's rename: the journal, the manifest, a user's file created once and
    the staging folder's entry are durable; a generated file need not be (test below)."""
    synced: list[str] = []
    at_commit: dict = {}
    real_fsync, real_replace = os.fsync, os.replace

    def fsync(fd):
        synced.append(os.readlink(f"/proc/self/fd/{fd}"))
        real_fsync(fd)

    def replace(a, b):
        if os.path.basename(a) == "journal.tmp":
            at_commit["synced"] = list(synced)
            at_commit["renames"] = dict(json.loads(open(a, encoding="utf-8").read())["renames"])
        real_replace(a, b)
    monkeypatch.setattr(os, "fsync", fsync)
    monkeypatch.setattr(os, "replace", replace)
    writer.write_tree(str(tmp_path), [F("gen.py", "g\n"), F("handlers.py", "edit me\n", user_owned=True)])
    staging = str(tmp_path / writer.STAGING)
    staged = at_commit["renames"]  # path -> its staged name
    assert set(staged) == {"gen.py", "handlers.py", writer.MANIFEST}
    before = set(at_commit["synced"])
    assert {os.path.join(staging, staged["handlers.py"]), os.path.join(staging, staged[writer.MANIFEST]),
            os.path.join(staging, "journal.tmp"), str(tmp_path)} <= before
    assert os.path.join(staging, staged["gen.py"]) not in before
    assert read(tmp_path / "gen.py") == "g\n" and not os.path.exists(staging)


def test_a_generated_file_a_power_cut_left_short_is_rewritten(tmp_path):
    files = [F("a/x.py", "x = 1\n"), F("b.txt", "b\n")]
    writer.write_tree(str(tmp_path), files)
    (tmp_path / "a" / "x.py").write_bytes(b"")  # its data never reached the disk
    assert writer.compare_tree(str(tmp_path), files).differs == ["a/x.py"]
    report = writer.write_tree(str(tmp_path), files)
    assert report.written == ["a/x.py"] and not report.problems
    assert read(tmp_path / "a" / "x.py") == "x = 1\n"
