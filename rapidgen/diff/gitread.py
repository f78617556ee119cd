"""`--against REV`: the old side read from git (ls-tree + cat-file), no checkout.

The revision's spec files (IDL, YAML) are written under a temporary folder with the
repository's layout, so includes, `idl.rapid: ../rapid` and `specs/rapid` lookups resolve
within that revision's tree. Paths in messages name them `REV:path`.

The repository is input like any other: a damaged or crafted one (a missing or corrupt
object, a name that is both a file and a folder, an entry whose object is of another type,
a revision that names a blob) is a located error (RG1805, or RG1802 for what is not a
commit), found before anything is written; links and submodules in the revision are never
followed or written; the listing is read as a stream and bounded (RG1803).
"""
from __future__ import annotations

import hashlib
import os
import subprocess
import tempfile
import threading
from collections.abc import Generator
from contextlib import closing

from rapidgen.diagnostics import DiagnosticSink, SourceLoc
from rapidgen.diagnostics import display_path

SPEC_SUFFIXES = (".idl", ".pidl", ".yaml", ".yml")
MAX_FILES = 20_000
MAX_BYTES = 64 * 1024 * 1024  # of spec files read from one revision
MAX_ENTRIES = 1_000_000  # files, folders, links and submodules in the revision's tree
MAX_NAME = 3_800  # bytes in a path of the revision (PATH_MAX is 4,096 with the temporary folder)
MAX_PART = 255  # bytes in one component (NAME_MAX)
MAX_DEPTH = 100  # folders above a spec file (removing the temporary tree recurses once per folder)
TIMEOUT = 120  # seconds for one git command

REV_HINT = "--against takes a commit, branch or tag of the repository holding the paths"
DAMAGED = ("the repository is damaged: `git fsck` lists what is missing or corrupt; fetch the objects again "
           "(in a partial clone: `git fetch`) or clone the repository anew")
CRAFTED = ("no checkout can hold this tree (`git fsck`: duplicateEntries): it was not made by `git add`; "
           "diff against another revision")


class GitError(Exception):
    def __init__(self, message: str, stdout: bytes = b"") -> None:
        super().__init__(message)
        self.stdout = stdout  # what git wrote before it failed


class _Fail(Exception):
    """A located error: reported by materialize, which then writes nothing more."""

    def __init__(self, code: str, message: str, loc: SourceLoc, hint: str | None = None) -> None:
        super().__init__(message)
        self.code, self.message, self.loc, self.hint = code, message, loc, hint


def _last_line(stderr: bytes, what: str) -> str:
    lines = [ln.strip() for ln in stderr.decode("utf-8", "replace").splitlines() if ln.strip()]
    return lines[-1][:300] if lines else f"git {what} failed"


def _command(top: str, args: tuple[str, ...]) -> list[str]:
    return ["git", "-C", top, "--no-replace-objects", *args]


def _git(top: str, *args: str, data: bytes | None = None) -> bytes:
    try:
        done = subprocess.run(_command(top, args), input=data, capture_output=True, timeout=TIMEOUT,
                              stdin=None if data is not None else subprocess.DEVNULL)
    except subprocess.TimeoutExpired as exc:
        raise GitError(f"git {args[0]} took more than {TIMEOUT} s", exc.stdout or b"") from exc
    except (OSError, ValueError) as exc:
        raise GitError(f"cannot run git: {exc}") from exc
    if done.returncode != 0:
        raise GitError(_last_line(done.stderr, args[0]), done.stdout)
    return done.stdout


def _records(top: str, *args: str, max_record: int) -> Generator[bytes, None, None]:
    """The NUL-terminated records git writes, read as a stream (a huge tree is never held
    whole); a record longer than max_record raises _TooLong."""
    with tempfile.TemporaryFile() as err:
        try:
            proc = subprocess.Popen(_command(top, args), stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=err)
        except (OSError, ValueError) as exc:
            raise GitError(f"cannot run git: {exc}") from exc
        expired = threading.Event()

        def expire() -> None:
            expired.set()
            proc.kill()

        timer = threading.Timer(TIMEOUT, expire)
        timer.start()
        try:
            assert proc.stdout is not None
            rest = b""
            while chunk := proc.stdout.read(1 << 16):
                records = (rest + chunk).split(b"\0")
                rest = records.pop()
                if len(rest) > max_record:
                    raise _TooLong()
                yield from records
            if proc.wait() != 0:
                if expired.is_set():
                    raise GitError(f"git {args[0]} took more than {TIMEOUT} s")
                err.seek(0)
                raise GitError(_last_line(err.read(), args[0]))
            if rest:
                yield rest
        finally:
            timer.cancel()
            if proc.poll() is None:
                proc.kill()
            proc.wait()
            if proc.stdout is not None:
                proc.stdout.close()


class _TooLong(Exception):
    pass


def _shown(name: bytes) -> str:
    return name.decode("utf-8", "backslashreplace")


def _safe(rel: str) -> bool:
    """A path rapidgen writes: relative, no `.`/`..`/empty part, no backslash, within the
    file system's name limits. (Control characters and bytes that are not UTF-8 are
    written: such names are shown escaped, never raw.)"""
    parts = rel.split("/")
    return (bool(rel) and not rel.startswith("/") and "\\" not in rel and "\0" not in rel
            and not any(p in ("", ".", "..") or len(os.fsencode(p)) > MAX_PART for p in parts)
            and len(os.fsencode(rel)) <= MAX_NAME)


def _commit(top: str, rev: str, where: SourceLoc) -> str:
    """The commit REV names, as a full object name (later commands never see REV itself,
    so nothing in it is read as an option)."""
    if not rev or rev.startswith("-") or "\0" in rev:
        raise _Fail("RG1802", f"'{rev}' is not a revision name", where, REV_HINT)
    try:
        return _git(top, "rev-parse", "--verify", "--quiet", f"{rev}^{{commit}}").decode("ascii").strip()
    except (GitError, UnicodeDecodeError):
        pass
    try:
        oid = _git(top, "rev-parse", "--verify", "--quiet", rev).decode("ascii").strip()
    except (GitError, UnicodeDecodeError):
        raise _Fail("RG1802", f"cannot read revision '{rev}': no such commit, branch or tag", where, REV_HINT) from None
    try:
        kind = _git(top, "cat-file", "-t", f"{oid}^{{}}").decode("ascii", "replace").strip()
    except GitError as exc:
        raise _Fail("RG1805", f"revision '{rev}' (object {oid}) cannot be read: {exc}", where, DAMAGED) from None
    if kind != "commit":
        raise _Fail("RG1802", f"revision '{rev}' names a {kind}, not a commit", where,
                    REV_HINT + " (REV:path names a file or folder in a revision: give the path on its own)")
    raise _Fail("RG1805", f"revision '{rev}' (object {oid}) cannot be read as a commit", where, DAMAGED)


def materialize(rev: str, paths: list[str], dest: str, sink: DiagnosticSink) -> list[str] | None:
    """Write the revision's spec files under dest; the given paths as they map there.
    None after a diagnostic (RG1802: not a repository, unknown revision or not a commit,
    missing path; RG1803: the revision exceeds the limits; RG1805: the repository is
    damaged, or the files cannot be written). Every check is made before the first write."""
    try:
        return _materialize(rev, paths, dest)
    except _Fail as f:
        sink.error(f.code, f.message, f.loc, f.hint)
        return None


def _materialize(rev: str, paths: list[str], dest: str) -> list[str]:
    first = os.path.abspath(paths[0])
    where = SourceLoc(display_path(paths[0]), 0, 0)
    try:
        start = first if os.path.isdir(first) else os.path.dirname(first)
        top = os.fsdecode(_git(start, "rev-parse", "--show-toplevel")).rstrip("\n")
    except GitError as exc:
        raise _Fail("RG1802", f"cannot read revision '{rev}': {exc}", where, REV_HINT) from None
    commit = _commit(top, rev, where)
    rels = []
    for p in paths:
        rel = os.path.relpath(os.path.realpath(p), os.path.realpath(top)).replace(os.sep, "/")
        if rel.startswith(".."):
            raise _Fail("RG1802", f"'{display_path(p)}' is outside the repository at '{display_path(top)}'",
                        SourceLoc(display_path(p), 0, 0))
        rels.append("" if rel == "." else rel)
    wanted, links = _listing(top, rev, commit, rels, where)
    names = {n for _, n in wanted}
    for p, r in zip(paths, rels):
        if r and r not in names and not any(n.startswith(r + "/") for n in names):
            message, hint = _absent(r, rev, links)
            raise _Fail("RG1802", message, SourceLoc(display_path(p), 0, 0), hint)
    if len(wanted) > MAX_FILES:
        raise _Fail("RG1803", f"revision '{rev}' has {len(wanted)} spec files, more than {MAX_FILES}", where)
    for _, name in wanted:
        if name.count("/") > MAX_DEPTH:
            raise _Fail("RG1803", f"revision '{rev}' has a spec file {name.count('/')} folders deep, more than "
                        f"{MAX_DEPTH}: '{name[:60]}...'", where)
    contents = _read(top, rev, wanted, where)
    _write(dest, rev, contents)
    return [os.path.join(dest, *r.split("/")) if r else dest for r in rels]


def _listing(top: str, rev: str, commit: str, rels: list[str],
             where: SourceLoc) -> tuple[list[tuple[str, str]], dict[str, str]]:
    """(object, path) of the files to write; the links and submodules by path. Every entry
    of the tree is seen (`ls-tree -r -t`): a name listed twice is a crafted tree."""
    wanted: list[tuple[str, str]] = []
    links: dict[str, str] = {}
    seen: dict[bytes, bool] = {}  # every name in the tree: is it a folder
    records = _records(top, "ls-tree", "-r", "-t", "-z", "--full-tree", commit, max_record=MAX_NAME + 200)
    try:
        with closing(records):
            for count, record in enumerate(records, 1):
                if count > MAX_ENTRIES:
                    raise _Fail("RG1803", f"revision '{rev}' has more than {MAX_ENTRIES} entries "
                                "(files, folders, links)", where)
                meta, tab, name_b = record.partition(b"\t")
                fields = meta.split()
                try:
                    mode = int(fields[0], 8)
                    kind, oid = fields[1].decode("ascii"), fields[2].decode("ascii")
                    bytes.fromhex(oid)
                except (IndexError, ValueError):
                    raise _Fail("RG1805", f"git's listing of revision '{rev}' cannot be read: "
                                f"{_shown(record[:100])!r}", where, DAMAGED) from None
                if not tab or len(fields) != 3 or len(oid) not in (40, 64):
                    raise _Fail("RG1805", f"git's listing of revision '{rev}' cannot be read: "
                                f"{_shown(record[:100])!r}", where, DAMAGED)
                is_tree = kind == "tree"
                if name_b in seen:
                    what = ("both a file and a folder" if seen[name_b] != is_tree
                            else "a folder listed twice" if is_tree else "a file listed twice")
                    raise _Fail("RG1805", f"'{_shown(name_b)}' is {what} in revision '{rev}'",
                                SourceLoc(f"{rev}:{_shown(name_b)}", 0, 0), CRAFTED)
                seen[name_b] = is_tree
                if is_tree:
                    continue
                name = name_b.decode("utf-8", "surrogateescape")  # as os.fsdecode on POSIX
                if kind == "commit":
                    links[name] = "a submodule"
                elif mode & 0o170000 == 0o120000:
                    links[name] = "a symbolic link"
                elif kind == "blob" and mode & 0o170000 == 0o100000 and _safe(name):
                    under = any(r == "" or name == r or name.startswith(r + "/") for r in rels)
                    if name.lower().endswith(SPEC_SUFFIXES) or under:
                        wanted.append((oid, name))
    except _TooLong:
        raise _Fail("RG1803", f"revision '{rev}' holds a path longer than {MAX_NAME} bytes", where) from None
    except GitError as exc:
        raise _Fail("RG1805", f"the files of revision '{rev}' (commit {commit[:12]}) cannot be listed: {exc}",
                    where, DAMAGED) from None
    return wanted, links


def _absent(rel: str, rev: str, links: dict[str, str]) -> tuple[str, str]:
    """Why a path has no file to compare at the revision: (message, hint)."""
    parts = rel.split("/")
    for i in range(len(parts), 0, -1):
        at = "/".join(parts[:i])
        kind = links.get(at)
        if kind == "a submodule":
            return (f"'{at}' is a submodule at revision '{rev}'",
                    "a submodule's files are in another repository: run `rapidgen diff --against` there")
        if kind is not None:
            return (f"'{at}' is a symbolic link at revision '{rev}'",
                    "links stored in a revision are not followed (they may point anywhere, outside "
                    "the repository too): give the path the link points to")
    return (f"'{rel}' does not exist at revision '{rev}'", "the path must be in that revision's tree (added since?)")


def _read(top: str, rev: str, wanted: list[tuple[str, str]], where: SourceLoc) -> list[tuple[str, bytes]]:
    """Each file's bytes, checked: present, a blob, within the limits, and matching its
    object name (a loose object rewritten on disk is read by git without complaint)."""
    oids = "".join(f"{o}\n" for o, _ in wanted).encode()
    try:
        check = _git(top, "cat-file", "--batch-check=%(objectname) %(objecttype) %(objectsize)", data=oids)
    except GitError as exc:
        raise _Fail("RG1805", f"the files of revision '{rev}' cannot be read: {exc}", where, DAMAGED) from None
    lines = check.splitlines()
    total = 0
    sizes = []
    for i, (oid, name) in enumerate(wanted):
        here = SourceLoc(f"{rev}:{name}", 0, 0)
        fields = lines[i].split() if i < len(lines) else []
        if len(fields) == 2 and fields[1] == b"missing" or not fields:
            raise _Fail("RG1805", f"the object of '{name}' ({oid}) is missing or corrupt", here, DAMAGED)
        if len(fields) != 3 or fields[0].decode("ascii", "replace") != oid or not fields[2].isdigit():
            raise _Fail("RG1805", f"the object of '{name}' ({oid}) cannot be read: "
                        f"{_shown(lines[i][:100])!r}", here, DAMAGED)
        if fields[1] != b"blob":
            raise _Fail("RG1805", f"'{name}' is listed as a file, but its object ({oid}) is a "
                        f"{_shown(fields[1][:20])}", here, CRAFTED)
        sizes.append(int(fields[2]))
        total += sizes[-1]
    if total > MAX_BYTES:
        raise _Fail("RG1803", f"revision '{rev}' has {total} bytes of spec files, more than {MAX_BYTES}", where)
    failure = ""
    try:
        blob = _git(top, "cat-file", "--batch", data=oids)
    except GitError as exc:  # git stops at an object it cannot inflate: the ones before it are whole
        blob, failure = exc.stdout, str(exc)
    out = []
    pos = 0
    for (oid, name), size in zip(wanted, sizes):
        here = SourceLoc(f"{rev}:{name}", 0, 0)
        header = f"{oid} blob {size}\n".encode()
        end = pos + len(header) + size
        if blob[pos:pos + len(header)] != header or len(blob) < end + 1 or blob[end:end + 1] != b"\n":
            raise _Fail("RG1805", f"the object of '{name}' ({oid}) cannot be read"
                        + (f": {failure}" if failure else ""), here, DAMAGED)
        content = blob[pos + len(header):end]
        digest = hashlib.new("sha1" if len(oid) == 40 else "sha256", b"blob %d\0" % size)
        digest.update(content)
        if digest.hexdigest() != oid:
            raise _Fail("RG1805", f"the object of '{name}' ({oid}) is corrupt: its content does not match "
                        "its name", here, DAMAGED)
        out.append((name, content))
        pos = end + 1
    return out


def _write(dest: str, rev: str, contents: list[tuple[str, bytes]]) -> None:
    """Each file under dest, folders made one level at a time (no recursion however deep);
    a file is never written twice or through anything already there."""
    made = {dest}
    for name, content in contents:
        parts = name.split("/")
        folder = dest
        try:
            for part in parts[:-1]:
                folder = os.path.join(folder, part)
                if folder not in made:
                    os.mkdir(folder)
                    made.add(folder)
            with open(os.path.join(folder, parts[-1]), "xb") as f:
                f.write(content)
        except OSError as exc:
            raise _Fail("RG1805", f"'{name}' cannot be written to a temporary folder: {exc.strerror or exc}",
                        SourceLoc(f"{rev}:{name}", 0, 0),
                        "two names that differ only in case, on a file system that ignores case? "
                        "or no space left in the temporary folder") from None
