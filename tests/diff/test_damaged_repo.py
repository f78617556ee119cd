"""`rapidgen diff --against REV` on a damaged or crafted repository (issue 19): every case
is a located error (exit 1, `file: error[RG18xx]: ...` with a hint), never an internal
error (exit 3), with nothing on stdout and nothing left in the temporary folder. Each
repository is built with real git in tmp_path: objects deleted or rewritten on disk,
trees crafted with `git mktree` or written raw with `git hash-object --literally`."""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import tempfile
import zlib

import pytest

from rapidgen.cli import main
from rapidgen.diff import gitread

pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")

T_IDL = "module m { @final struct T { long a; }; };\n"
U_IDL = "module m { @final struct U { long b; }; };\n"
ENV = {"GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@t", "GIT_COMMITTER_NAME": "t", "GIT_COMMITTER_EMAIL": "t@t",
       "GIT_CONFIG_NOSYSTEM": "1", "HOME": os.devnull}


def git(repo, *args: str, data: bytes | None = None) -> str:
    done = subprocess.run(["git", "-C", str(repo), *args], input=data, capture_output=True, check=True,
                          env={**os.environ, **ENV})
    return done.stdout.decode().strip()


@pytest.fixture
def repo(tmp_path, monkeypatch):
    """A repository with specs/t.idl and specs/u.idl committed; the working tree is the
    current directory; temporary folders go to tmp_path/tmp (checked empty afterwards)."""
    root = tmp_path / "repo"
    (root / "specs").mkdir(parents=True)
    (root / "specs" / "t.idl").write_text(T_IDL)
    (root / "specs" / "u.idl").write_text(U_IDL)
    git(root, "init", "-q")
    git(root, "add", "-A")
    git(root, "commit", "-q", "-m", "one")
    monkeypatch.chdir(root)
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(tmp))
    yield root
    assert [n for n in os.listdir(tmp) if n.startswith("rapidgen-diff-")] == []  # gone, whatever happened


def diff(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(["diff", *argv])
    out, err = capsys.readouterr()
    return code, out, err


def located(capsys, code_: str, where: str, *argv: str) -> str:
    """Run diff; it must fail with one located error of that code at `where`, and a hint."""
    code, out, err = diff(capsys, *argv)
    assert code == 1, err
    assert out == ""  # no report, not even a partial one
    assert "internal error" not in err and "Traceback" not in err
    assert err.startswith(f"{where}: error[{code_}]: "), err
    assert "\n  = hint: " in err and err.rstrip().endswith("rapidgen: 1 error")
    return err


def object_file(repo, oid: str):
    path = repo / ".git" / "objects" / oid[:2] / oid[2:]
    assert path.exists()  # loose: a fresh repository packs nothing
    os.chmod(path, 0o644)
    return path


def raw_tree(repo, *entries: tuple[str, bytes, str]) -> str:
    """A tree object written as given (no sorting, no checks), as a broken tool might."""
    body = b"".join(mode.encode() + b" " + name + b"\0" + bytes.fromhex(oid) for mode, name, oid in entries)
    return git(repo, "hash-object", "-t", "tree", "-w", "--stdin", "--literally", data=body)


def mktree(repo, *lines: str) -> str:
    return git(repo, "mktree", "--missing", data="".join(f"{ln}\n" for ln in lines).encode())


def branch(repo, tree: str, name: str = "bad") -> str:
    git(repo, "update-ref", f"refs/heads/{name}", git(repo, "commit-tree", tree, "-m", "crafted"))
    return name


# --- the two cases of the issue -------------------------------------------------------


def test_missing_blob(capsys, repo):
    oid = git(repo, "rev-parse", "HEAD:specs/t.idl")
    os.remove(object_file(repo, oid))
    err = located(capsys, "RG1805", "HEAD:specs/t.idl", "--against", "HEAD", "specs/t.idl")
    assert f"the object of 'specs/t.idl' ({oid}) is missing or corrupt" in err and "git fsck" in err
    # the whole folder, and a file next to it whose own object is fine: the same error
    located(capsys, "RG1805", "HEAD:specs/t.idl", "--against", "HEAD", "specs")
    located(capsys, "RG1805", "HEAD:specs/t.idl", "--against", "HEAD", "specs/u.idl")


@pytest.mark.parametrize("shadow", ["specs", "a"])
def test_name_both_a_file_and_a_folder(capsys, repo, shadow):
    """`specs` as a blob and as a tree in one folder (the path's own folder, or an
    unrelated `a` blob next to `a/b.idl`): no checkout can hold it."""
    blob = git(repo, "rev-parse", "HEAD:specs/t.idl")
    specs = git(repo, "rev-parse", "HEAD:specs")
    lines = [f"040000 tree {specs}\tspecs", f"100644 blob {blob}\t{shadow}"]
    if shadow != "specs":
        lines.append(f"040000 tree {mktree(repo, f'100644 blob {blob}{chr(9)}b.idl')}\t{shadow}")
    rev = branch(repo, mktree(repo, *lines))
    err = located(capsys, "RG1805", f"bad:{shadow}", "--against", rev, "specs/t.idl")
    assert f"'{shadow}' is both a file and a folder in revision 'bad'" in err and "duplicateEntries" in err
    located(capsys, "RG1805", f"bad:{shadow}", "--against", rev, "specs")


# --- other damage ----------------------------------------------------------------------


def test_file_listed_twice(capsys, repo):
    blob = git(repo, "rev-parse", "HEAD:specs/t.idl")
    specs = raw_tree(repo, ("100644", b"t.idl", blob), ("100644", b"t.idl", blob))
    rev = branch(repo, raw_tree(repo, ("40000", b"specs", specs)))
    err = located(capsys, "RG1805", "bad:specs/t.idl", "--against", rev, "specs/t.idl")
    assert "'specs/t.idl' is a file listed twice" in err


def test_file_entry_whose_object_is_a_tree(capsys, repo):
    specs = git(repo, "rev-parse", "HEAD:specs")
    inner = raw_tree(repo, ("100644", b"t.idl", specs))
    rev = branch(repo, raw_tree(repo, ("40000", b"specs", inner)))
    err = located(capsys, "RG1805", "bad:specs/t.idl", "--against", rev, "specs/t.idl")
    assert f"'specs/t.idl' is listed as a file, but its object ({specs}) is a tree" in err


def test_loose_object_rewritten_on_disk(capsys, repo):
    """git reads a loose object whose content no longer matches its name without a word:
    the content is hashed again."""
    oid = git(repo, "rev-parse", "HEAD:specs/t.idl")
    forged = T_IDL.replace("long a", "long z").encode()
    object_file(repo, oid).write_bytes(zlib.compress(b"blob %d\0" % len(forged) + forged))
    err = located(capsys, "RG1805", "HEAD:specs/t.idl", "--against", "HEAD", "specs/t.idl")
    assert "is corrupt: its content does not match its name" in err


def test_loose_object_truncated(capsys, repo):
    """The header inflates, the content does not: git stops in the middle of its output."""
    oid = git(repo, "rev-parse", "HEAD:specs/t.idl")
    path = object_file(repo, oid)
    path.write_bytes(zlib.compress(b"blob %d\0" % len(T_IDL) + T_IDL.encode())[:14])
    err = located(capsys, "RG1805", "HEAD:specs/t.idl", "--against", "HEAD", "specs")
    assert f"the object of 'specs/t.idl' ({oid}) cannot be read" in err


def test_loose_object_garbage(capsys, repo):
    oid = git(repo, "rev-parse", "HEAD:specs/u.idl")
    object_file(repo, oid).write_bytes(b"not zlib at all")
    located(capsys, "RG1805", "HEAD:specs/u.idl", "--against", "HEAD", "specs")


@pytest.mark.parametrize("damage", ["missing", "garbage"])
@pytest.mark.parametrize("what", ["HEAD^{tree}", "HEAD:specs"])
def test_tree_missing_or_corrupt(capsys, repo, what, damage):
    path = object_file(repo, git(repo, "rev-parse", what))
    os.remove(path) if damage == "missing" else path.write_bytes(b"garbage")
    err = located(capsys, "RG1805", "specs/t.idl", "--against", "HEAD", "specs/t.idl")
    assert "the files of revision 'HEAD'" in err and "cannot be listed" in err


@pytest.mark.parametrize("damage", ["missing", "garbage"])
def test_commit_missing_or_corrupt(capsys, repo, damage):
    oid = git(repo, "rev-parse", "HEAD")
    path = object_file(repo, oid)
    os.remove(path) if damage == "missing" else path.write_bytes(b"garbage")
    err = located(capsys, "RG1805", "specs/t.idl", "--against", "HEAD", "specs/t.idl")
    assert f"revision 'HEAD' (object {oid}) cannot be read" in err


@pytest.mark.parametrize("rev, says", [
    ("HEAD:specs/t.idl", "revision 'HEAD:specs/t.idl' names a blob, not a commit"),
    ("HEAD^{tree}", "names a tree, not a commit"),
    ("blobtag", "revision 'blobtag' names a blob, not a commit"),
    ("--output=x", "'--output=x' is not a revision name"),
    ("no-such-rev", "cannot read revision 'no-such-rev': no such commit, branch or tag"),
])
def test_revision_that_is_not_a_commit(capsys, repo, rev, says):
    git(repo, "tag", "-a", "-m", "a tag on a blob", "blobtag", git(repo, "rev-parse", "HEAD:specs/t.idl"))
    err = located(capsys, "RG1802", "specs/t.idl", f"--against={rev}", "specs/t.idl")
    assert says in err
    assert not (repo / "x").exists()


# --- links and submodules: never followed, never written ------------------------------


def test_symbolic_links_in_the_revision_are_not_followed(capsys, repo, tmp_path):
    outside = tmp_path / "outside.idl"
    outside.write_text("module outside { @final struct Secret { long s; }; };\n")
    os.symlink(str(outside), repo / "specs" / "evil.idl")
    os.symlink("specs", repo / "idl")
    git(repo, "add", "-A")
    git(repo, "commit", "-q", "-m", "links")
    # the working tree drops the link to the file outside; the revision's is ignored
    os.remove(repo / "specs" / "evil.idl")
    code, out, err = diff(capsys, "--against", "HEAD", "specs", "--fail-on", "WIRE")
    assert code == 0 and "Secret" not in out + err, out + err
    # a path that is a link at the revision, or lies under one
    (repo / "specs" / "evil.idl").write_text(T_IDL)
    err = located(capsys, "RG1802", "specs/evil.idl", "--against", "HEAD", "specs/evil.idl")
    assert "'specs/evil.idl' is a symbolic link at revision 'HEAD'" in err and "not followed" in err
    os.remove(repo / "idl")
    (repo / "idl").mkdir()
    (repo / "idl" / "t.idl").write_text(T_IDL)
    err = located(capsys, "RG1802", "idl/t.idl", "--against", "HEAD", "idl/t.idl")
    assert "'idl' is a symbolic link at revision 'HEAD'" in err


def test_submodule_entry(capsys, repo):
    git(repo, "update-index", "--add", "--cacheinfo", f"160000,{git(repo, 'rev-parse', 'HEAD')},vendor")
    git(repo, "commit", "-q", "-m", "a gitlink")
    (repo / "vendor").mkdir(exist_ok=True)
    (repo / "vendor" / "v.idl").write_text(T_IDL)
    err = located(capsys, "RG1802", "vendor/v.idl", "--against", "HEAD", "vendor/v.idl")
    assert "'vendor' is a submodule at revision 'HEAD'" in err and "another repository" in err
    code, _, err = diff(capsys, "--against", "HEAD", "specs")  # elsewhere, the gitlink is no matter
    assert code == 0, err


# --- limits, and names that are legal but unusual ------------------------------------


def located_no_hint(capsys, code_: str, *argv: str) -> str:
    code, out, err = diff(capsys, *argv)
    assert code == 1 and out == "" and f"error[{code_}]" in err and "internal error" not in err, err
    return err


def test_limits(capsys, repo, monkeypatch):
    monkeypatch.setattr(gitread, "MAX_BYTES", 50)
    err = located_no_hint(capsys, "RG1803", "--against", "HEAD", "specs")
    assert err.startswith("specs: error[RG1803]: revision 'HEAD' has 86 bytes of spec files, more than 50")
    monkeypatch.setattr(gitread, "MAX_BYTES", 1 << 20)
    monkeypatch.setattr(gitread, "MAX_ENTRIES", 2)
    err = located_no_hint(capsys, "RG1803", "--against", "HEAD", "specs")
    assert "has more than 2 entries" in err


def test_huge_blob_is_never_read(capsys, repo, monkeypatch):
    """Sizes are checked before any content is read."""
    monkeypatch.setattr(gitread, "MAX_BYTES", 1000)
    (repo / "specs" / "huge.idl").write_bytes(b"// " + b"x" * 5000 + b"\n")
    git(repo, "add", "-A")
    git(repo, "commit", "-q", "-m", "huge")
    read: list[tuple[str, ...]] = []
    real = gitread._git

    def spy(top: str, *args: str, data: bytes | None = None) -> bytes:
        read.append(args)
        return real(top, *args, data=data)

    monkeypatch.setattr(gitread, "_git", spy)
    err = located_no_hint(capsys, "RG1803", "--against", "HEAD", "specs")
    assert "more than 1000" in err and not any("--batch" in a for a in read)


def test_deep_tree(capsys, repo):
    """A spec file 100 folders down is compared; 101 is refused (removing the temporary
    tree recurses once per folder: 1,200 folders was an internal error)."""
    folders = ["specs", *["d"] * 99]
    os.makedirs(repo / os.path.join(*folders))
    (repo / os.path.join(*folders, "t.idl")).write_text(T_IDL)
    git(repo, "add", "-A")
    git(repo, "commit", "-q", "-m", "deep")
    code, out, err = diff(capsys, "--against", "HEAD", os.path.join(*folders, "t.idl"), "--fail-on", "WIRE")
    assert code == 0 and err == "", err
    os.mkdir(repo / os.path.join(*folders, "e"))
    (repo / os.path.join(*folders, "e", "t.idl")).write_text(T_IDL)
    git(repo, "add", "-A")
    git(repo, "commit", "-q", "-m", "deeper")
    err = located_no_hint(capsys, "RG1803", "--against", "HEAD", os.path.join(*folders, "t.idl"))
    assert "has a spec file 101 folders deep, more than 100" in err


def test_names_with_control_characters_or_not_utf8_are_shown_escaped(capsys, repo):
    """Such files are compared like any other; their names never reach the output raw."""
    evil = "t\x1b]0;owned\x07\x9b.idl"
    latin = os.fsdecode(b"caf\xe9.idl")
    (repo / "specs" / evil).write_text("module e { @final struct E { long e; }; };\n")
    (repo / "specs" / latin).write_text("module l { @final struct L { long l; }; };\n")
    git(repo, "add", "-A")
    git(repo, "commit", "-q", "-m", "names")
    os.remove(repo / "specs" / evil)
    os.remove(repo / "specs" / latin)
    code, out, err = diff(capsys, "--against", "HEAD", "specs", "--fail-on", "WIRE")
    assert code == 1 and out.count("wire[WIRE-TYPE-01]") == 2, out + err
    assert "HEAD:specs/t\\x1b]0;owned\\x07\\x9b.idl:1:" in out and "HEAD:specs/caf\\udce9.idl:1:" in out
    code, out, err = diff(capsys, "--against", "HEAD", "specs", "--json")
    doc = json.loads(out)
    files = sorted(f["old"]["file"] for f in doc["findings"])
    assert files == ["HEAD:specs/caf\\xe9.idl", f"HEAD:specs/{evil}"]
    for text in (out, err):
        assert not re.search("[\x00-\x09\x0b-\x1f\x7f-\x9f]", text)
