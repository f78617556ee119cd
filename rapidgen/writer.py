"""Writing generated files into an output folder: only what changed, all or nothing, never
outside the folder, never over a file rapidgen did not write.

The unit is one output folder `<out>/<lang>/` (the root) and its manifest
`.rapidgen-manifest.json` (path -> sha256 of each generated file rapidgen wrote there). The
user may keep files of their own in it; user-owned files (bridge handlers: created once,
never overwritten) and files no longer generated but edited by hand are never touched.

Paths (the folder may come from an untrusted checkout, the manifest is input):
- a path is used only if it is relative, '/'-separated, without '', '.' or '..' segments,
  and no existing component of it below the root is a symbolic link (nor, for a parent, a
  non-folder). So nothing is written, read or deleted through a link, and nothing outside
  the root is reached. Manifest keys failing this are ignored and never deleted (warnings
  RG0821, RG0822); back ends' paths failing it stop the write (RG0820, a bug);
- a wanted path that holds a link, a folder, or a file the previous manifest does not
  list and whose content differs, stops the write: errors RG0822/RG0823 at that path.
  Nothing at all is written for a root with an error.

Locking: a run holds flock(LOCK_EX) on the root folder itself (a lock file would be left
in committed trees); `check` holds LOCK_SH. Another run waits up to LOCK_WAIT_S, then
fails with RG0824. The kernel drops the lock of a killed run.

All or nothing, by a write-ahead journal replayed forward:
1. under the lock, replay an interrupted run's journal (step 4), or delete the staging
   folder of a run killed before its commit (the lock proves no live run owns it);
2. stage every new or changed file, the new manifest last, in `<root>/.rapidgen-staging/`,
   and beside them the journal as a temporary file (the files to remove with their
   digests, the renames); fsync the journal, the manifest, the user's files created once
   and the root (the staging folder's entry). The generated files need no fsync: after a
   power cut the next run finds one that came out short by its digest and rewrites it
   (the manifest lists it), as `check` reports it;
3. commit: rename the journal to `journal.json`, fsync the staging folder;
4. apply: remove the stale files that still hold what rapidgen wrote, rename each staged
   file over its target (manifest last), remove the folders emptied by the removals,
   fsync the folders, delete the journal, then the staging folder. Every step is
   idempotent (a staged file already gone was renamed), so a replay after a kill at any
   point finishes the same run.

Guarantee: after a kill at any point the root holds either the old output and manifest
untouched (killed before the journal's rename), or a committed journal, or the complete
new output (killed after the journal's removal); the hidden staging folder may be left.
The next `generate` or `check --fix` into that folder (or recover()) first replays the
journal or removes the staging folder, so the root then holds exactly the old or exactly
the new output with a matching manifest, the user's files intact. Until then `rapidgen
check` reports the folder as stale (interrupted run). Not covered: another local process
racing a run, e.g. swapping a folder for a link between the check and the rename.
"""
from __future__ import annotations

import contextlib
import errno
import fcntl
import hashlib
import json
import os
import re
import shutil
import stat
import sys
import tempfile
import time
from dataclasses import dataclass, field
from typing import Callable, Iterable, Iterator, Protocol

from rapidgen.diagnostics import Diagnostic, DiagnosticSink, Severity, SourceLoc


class GeneratedFile(Protocol):
    """What the writer writes (a back end's rapidgen.backends.base.GeneratedFile has it): the
    writer knows no back end."""

    @property
    def path(self) -> str: ...  # relative to the output folder, '/'-separated

    @property
    def content(self) -> str: ...

    @property
    def user_owned(self) -> bool: ...  # written once if absent, never overwritten

MANIFEST = ".rapidgen-manifest.json"
STAGING = ".rapidgen-staging"
JOURNAL = "journal.json"
_TMP_PREFIX = ".rapidgen-"
LOCK_WAIT_S = 60.0  # a full `check --fix` takes seconds; a longer hold is a stuck run
MAX_MANIFEST_BYTES = 8 * 1024 * 1024  # real manifests are a few KiB; the file is input
_MAX_LISTED = 5  # bad manifest entries reported one by one, then counted
_STAGED_NAME = re.compile(r"[0-9]{1,9}\.tmp")


def digest(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


# --- single files (`ir -o`, `vectors -o`) ---------------------------------------------

def write_text_atomic(path: str, text: str) -> bool:
    """Write text to path unless it already holds exactly that; returns True if written.
    A device or pipe (`-o /dev/null`) is written into, never replaced: renaming a file over
    it would turn /dev/null into a regular file for every process on the machine."""
    try:
        mode = os.stat(path).st_mode
    except OSError:
        mode = 0
    if mode and not stat.S_ISREG(mode) and not stat.S_ISDIR(mode):
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(text)
        return True
    staged = _stage(path, text)
    if staged is None:
        return False
    os.replace(staged, path)
    return True


def write_output(path: str, text: str, sink: DiagnosticSink) -> bool | None:
    """write_text_atomic for a command's output file: True written, False unchanged, None on
    failure, reported in sink as RG0803 (a directory, a missing folder, no permission)."""
    try:
        return write_text_atomic(path, text)
    except OSError as exc:
        sink.error("RG0803", f"cannot write '{path}': {exc.strerror or exc}", SourceLoc(path, 0, 0),
                   "check that the folder exists and is writable, and that the path is not a directory")
        return None


def _stage(path: str, text: str) -> str | None:
    """A temp file holding text next to path, or None when path already holds it."""
    data = text.encode("utf-8")
    try:
        with open(path, "rb") as fh:
            if fh.read() == data:
                return None
    except OSError:
        pass
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=_TMP_PREFIX, suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        st = os.stat(path) if os.path.exists(path) else None
        os.chmod(tmp, (st.st_mode & 0o777) if st else 0o644)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    return tmp


# --- paths ----------------------------------------------------------------------------

def path_problem(rel: object) -> str | None:
    """Why rel is not a safe path below an output folder, or None when it is."""
    if not isinstance(rel, str) or not rel:
        return "empty"
    if rel.startswith("/"):
        return "absolute"
    if "\\" in rel or "\0" in rel:
        return "contains a backslash or NUL"
    parts = rel.split("/")
    if any(p in ("", ".", "..") for p in parts):
        return "has an empty, '.' or '..' segment"
    if parts[0] in (MANIFEST, STAGING):
        return "a name rapidgen reserves"
    return None


def _inspect(root: str, rel: str, gone: frozenset[str] = frozenset()) -> tuple[str, str]:
    """What is at root/rel, without following links: (kind, the component concerned).

    kind: 'missing', 'file', 'dir', 'other' (fifo, device...), 'link' (a component is a
    symbolic link), 'blocked' (a parent is not a folder). A parent that is a file in
    `gone` (about to be removed) counts as missing.
    """
    parts = rel.split("/")
    path = root
    for i, part in enumerate(parts):
        path = os.path.join(path, part)
        prefix = "/".join(parts[:i + 1])
        try:
            mode = os.lstat(path).st_mode
        except OSError as exc:
            if exc.errno in (errno.ENOENT, errno.ENAMETOOLONG):  # a name no file can have
                return "missing", prefix
            raise
        if stat.S_ISLNK(mode):
            return "link", prefix
        if i == len(parts) - 1:
            return ("file" if stat.S_ISREG(mode) else "dir" if stat.S_ISDIR(mode) else "other"), prefix
        if not stat.S_ISDIR(mode):
            return ("missing" if prefix in gone and stat.S_ISREG(mode) else "blocked"), prefix
    raise AssertionError("unreachable")


def _read_limited(path: str, limit: int) -> bytes | None:
    """A regular file's bytes (links not followed), None when it is larger than limit."""
    fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    with os.fdopen(fd, "rb") as fh:
        if not stat.S_ISREG(os.fstat(fh.fileno()).st_mode):
            raise IsADirectoryError(path)
        data = fh.read(limit + 1)
    return None if len(data) > limit else data


def _sha256_of(path: str) -> str:
    fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    with os.fdopen(fd, "rb") as fh:
        return hashlib.file_digest(fh, "sha256").hexdigest()


# --- reports --------------------------------------------------------------------------

@dataclass
class WriteReport:
    written: list[str] = field(default_factory=list)
    unchanged: list[str] = field(default_factory=list)
    removed: list[str] = field(default_factory=list)
    kept_user: list[str] = field(default_factory=list)  # user-owned files that already existed
    kept_edited: list[str] = field(default_factory=list)  # stale files not removed: edited by hand
    problems: list[Diagnostic] = field(default_factory=list)  # RG082x; any error: nothing written
    recovered: bool = False  # an interrupted run's journal was replayed first

    @property
    def failed(self) -> bool:
        return any(d.severity is Severity.ERROR for d in self.problems)


@dataclass
class StaleReport:
    missing: list[str] = field(default_factory=list)
    differs: list[str] = field(default_factory=list)
    extra: list[str] = field(default_factory=list)  # in the manifest on disk, no longer generated
    interrupted: list[str] = field(default_factory=list)  # leftovers of a killed run
    problems: list[Diagnostic] = field(default_factory=list)

    @property
    def stale(self) -> bool:
        return bool(self.missing or self.differs or self.extra or self.interrupted)


class LockBusy(Exception):
    """Another run held the output folder's lock for LOCK_WAIT_S."""

    def __init__(self, folder: str):
        super().__init__(folder)
        self.folder = folder


class UnsafeJournal(Exception):
    """A journal being replayed names a path that is no longer safe to write."""

    def __init__(self, path: str):
        super().__init__(path)
        self.path = path


# --- the plan: what a run would do, found without writing ------------------------------

@dataclass
class _Plan:
    shown: str  # the output folder as the user named it, for messages
    writes: list[tuple[str, bytes]] = field(default_factory=list)  # manifest last
    removes: list[tuple[str, str]] = field(default_factory=list)  # (path, its digest)
    missing: list[str] = field(default_factory=list)
    differs: list[str] = field(default_factory=list)
    extra: list[str] = field(default_factory=list)
    unchanged: list[str] = field(default_factory=list)
    kept_user: list[str] = field(default_factory=list)
    kept_edited: list[str] = field(default_factory=list)
    problems: list[Diagnostic] = field(default_factory=list)

    def report(self, severity: Severity, code: str, message: str, rel: str, hint: str | None = None) -> None:
        loc = SourceLoc(os.path.join(self.shown, *rel.split("/")) if rel else self.shown, 0, 0)
        self.problems.append(Diagnostic(severity, code, message, loc, hint))

    @property
    def failed(self) -> bool:
        return any(d.severity is Severity.ERROR for d in self.problems)


def _shorten(text: str) -> str:
    return text if len(text) <= 120 else text[:117] + "..."


def manifest_text(files: Iterable[GeneratedFile]) -> str:
    entries = {f.path: digest(f.content) for f in sorted(files, key=lambda f: f.path) if not f.user_owned}
    return json.dumps({"generator": "rapidgen", "files": entries}, indent=1, sort_keys=True) + "\n"


def _load_manifest(root: str, plan: _Plan) -> dict[str, str]:
    """The previous manifest's usable entries; what is unusable is reported and ignored."""
    W = Severity.WARNING
    path = os.path.join(root, MANIFEST)
    kind, _ = _inspect(root, MANIFEST)
    if kind == "link":
        plan.report(W, "RG0822", "the manifest is a symbolic link; ignored (it will be replaced by a file)", MANIFEST)
    if kind != "file":
        return {}
    data = _read_limited(path, MAX_MANIFEST_BYTES)
    try:
        files = json.loads(data.decode("utf-8"))["files"] if data is not None else None
    except (ValueError, KeyError, TypeError):
        files = None
    if not isinstance(files, dict):
        plan.report(W, "RG0821", "the manifest is not a rapidgen manifest (or over 8 MiB); ignored", MANIFEST,
                    "files it listed are treated as yours: none is deleted or overwritten")
        return {}
    good: dict[str, str] = {}
    bad = 0
    for key, value in files.items():
        code, why = "RG0821", path_problem(key)
        if why is None and not (isinstance(value, str) and re.fullmatch(r"[0-9a-f]{64}", value)):
            why = "its digest is not a sha256"
        if why is None:
            kind, where = _inspect(root, key)
            if kind == "link":
                code, why = "RG0822", f"'{_shorten(where)}' is a symbolic link"
        if why is None:
            good[key] = value
            continue
        bad += 1
        if bad <= _MAX_LISTED:
            plan.report(W, code, f"manifest entry '{_shorten(str(key))}' ignored: {why}", MANIFEST,
                        "rapidgen removes or replaces only files inside the output folder, never through a link")
    if bad > _MAX_LISTED:
        plan.report(W, "RG0821", f"{bad - _MAX_LISTED} more manifest entries ignored", MANIFEST)
    return good


def _plan(root: str, shown: str, files: list[GeneratedFile]) -> _Plan:
    E = Severity.ERROR
    plan = _Plan(shown)
    wanted: dict[str, GeneratedFile] = {}
    for f in files:
        why = path_problem(f.path) or ("listed twice" if f.path in wanted else None)
        if why:
            plan.report(E, "RG0820", f"a back end produced an unsafe output path '{_shorten(str(f.path))}': {why}",
                        "", "this is a bug in rapidgen; please report it with the input")
        else:
            wanted[f.path] = f
    if plan.failed:
        return plan
    previous = _load_manifest(root, plan)
    for rel, old in sorted(previous.items()):  # stale files first: removing one may free a path
        if rel in wanted:
            continue
        plan.extra.append(rel)
        if _inspect(root, rel)[0] == "file":
            if _sha256_of(os.path.join(root, *rel.split("/"))) == old:
                plan.removes.append((rel, old))
            else:
                plan.kept_edited.append(rel)
    gone = frozenset(rel for rel, _ in plan.removes)
    for rel, f in sorted(wanted.items()):
        data = f.content.encode("utf-8")
        kind, where = _inspect(root, rel, gone)
        if kind == "missing":
            plan.missing.append(rel)
            plan.writes.append((rel, data))
        elif kind == "file" and f.user_owned:
            plan.kept_user.append(rel)
        elif kind == "link":
            plan.report(E, "RG0822", f"'{where}' is a symbolic link; rapidgen does not write through links", where,
                        "replace the link with a real file or folder, or generate into another folder")
        elif kind != "file":
            what = {"dir": "a folder", "other": "not a regular file", "blocked": "a file where a folder is needed"}
            plan.report(E, "RG0823", f"'{where}' is in the way of generated '{rel}': {what[kind]}", where,
                        "move it away; rapidgen never deletes what it did not write")
        elif _read_limited(os.path.join(root, *rel.split("/")), len(data)) == data:
            plan.unchanged.append(rel)
        else:
            plan.differs.append(rel)
            plan.writes.append((rel, data))
            if rel not in previous:
                plan.report(E, "RG0823", f"'{rel}' exists but rapidgen did not write it (it is not in the manifest); "
                            "not overwritten", rel, "move your file away, or delete it to have it generated")
    manifest = manifest_text(files).encode("utf-8")
    kind, _ = _inspect(root, MANIFEST)
    if kind in ("dir", "other"):
        plan.report(E, "RG0823", "the manifest's path is not a regular file", MANIFEST, "move it away")
    elif kind != "file":
        plan.missing.append(MANIFEST)
        plan.writes.append((MANIFEST, manifest))
    elif _read_limited(os.path.join(root, MANIFEST), len(manifest)) != manifest:
        plan.differs.append(MANIFEST)
        plan.writes.append((MANIFEST, manifest))
    return plan


# --- locking, staging, journal ---------------------------------------------------------

@contextlib.contextmanager
def _locked(root: str, exclusive: bool) -> Iterator[None]:
    fd = os.open(root, os.O_RDONLY | os.O_DIRECTORY)
    try:
        op = (fcntl.LOCK_EX if exclusive else fcntl.LOCK_SH) | fcntl.LOCK_NB
        deadline = time.monotonic() + LOCK_WAIT_S
        told = False
        while True:
            try:
                fcntl.flock(fd, op)
                break
            except BlockingIOError:
                if time.monotonic() >= deadline:
                    raise LockBusy(root) from None
                if not told:
                    print(f"rapidgen: waiting for another run writing '{root}'", file=sys.stderr)
                    told = True
                time.sleep(0.05)
        yield
    finally:
        os.close(fd)


def _fsync_dir(path: str) -> None:
    try:
        fd = os.open(path, os.O_RDONLY | os.O_DIRECTORY)
    except OSError:
        return  # removed since (an emptied folder)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _write_new(path: str, data: bytes, mode: int) -> None:
    """A new file; the caller fsyncs it (_fsync_all: many at once)."""
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600)
    with os.fdopen(fd, "wb") as fh:
        fh.write(data)
        fh.flush()
        os.fchmod(fh.fileno(), mode)


SYNC_THREADS = 8  # fsync releases the GIL, and the file system commits concurrent ones together


def _fsync_all(paths: list[str], sync: Callable[[str], None] | None = None) -> None:
    """fsync every path (files or folders), several at a time; the first error is raised
    once all are done."""
    sync = sync or _fsync_path
    if len(paths) < 2:
        for p in paths:
            sync(p)
        return
    import threading

    errors: list[BaseException] = []
    queue = list(reversed(paths))
    lock = threading.Lock()

    def work() -> None:
        while True:
            with lock:
                if not queue or errors:
                    return
                path = queue.pop()
            try:
                sync(path)
            except BaseException as exc:  # noqa: BLE001 (raised below, in the caller's thread)
                with lock:
                    errors.append(exc)

    threads = [threading.Thread(target=work, daemon=True) for _ in range(min(SYNC_THREADS, len(paths)))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    if errors:
        raise errors[0]


def _fsync_path(path: str) -> None:
    fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _commit(root: str, writes: list[tuple[str, bytes]], removes: list[tuple[str, str]],
            once: frozenset[str] = frozenset()) -> None:
    """Stage, commit and apply (steps 2-4 above); `once`: the user's files among the writes."""
    staging = os.path.join(root, STAGING)
    os.mkdir(staging, 0o700)
    renames = []
    try:
        for i, (rel, data) in enumerate(writes):
            target = os.path.join(root, *rel.split("/"))
            try:  # keep an existing file's mode (an executable script stays executable)
                mode = os.lstat(target).st_mode & 0o777
            except FileNotFoundError:
                mode = 0o644
            _write_new(os.path.join(staging, f"{i}.tmp"), data, mode)
            renames.append([rel, f"{i}.tmp"])
        journal = json.dumps({"version": 1, "removes": [list(r) for r in removes],
                              "renames": renames}).encode("utf-8")
        _write_new(os.path.join(staging, "journal.tmp"), journal, 0o600)
        # Durable before the commit (the journal's rename), in one round of concurrent fsyncs:
        # the staging folder's entry, the journal, and the files no later run would rewrite
        # (the manifest, the user's files created once). The other files are checked against
        # the manifest by the next run: one a power cut left short is rewritten.
        lasting = [os.path.join(staging, name) for rel, name in renames if rel == MANIFEST or rel in once]
        _fsync_all([root, *lasting, os.path.join(staging, "journal.tmp")])
        os.replace(os.path.join(staging, "journal.tmp"), os.path.join(staging, JOURNAL))  # the commit
    except BaseException:  # not committed: the old output is untouched, drop what was staged
        shutil.rmtree(staging, ignore_errors=True)
        raise
    _fsync_dir(staging)
    _apply(root, removes, renames)


def _apply(root: str, removes: list, renames: list[list[str]]) -> None:
    """Roll a committed journal forward; safe to run again after a kill at any point."""
    staging = os.path.join(root, STAGING)
    touched = {root}
    gone = frozenset(rel for rel, _ in removes)
    for rel, old in removes:
        path = os.path.join(root, *rel.split("/"))
        if _inspect(root, rel)[0] == "file" and _sha256_of(path) == old:  # still the file we wrote
            os.unlink(path)
            touched.add(os.path.dirname(path))
    for rel, name in renames:
        source = os.path.join(staging, name)
        try:
            if not stat.S_ISREG(os.lstat(source).st_mode):
                raise UnsafeJournal(source)
        except FileNotFoundError:
            continue  # renamed before the kill
        kind, where = _inspect(root, rel, gone)
        if kind not in ("missing", "file"):
            raise UnsafeJournal(os.path.join(root, *where.split("/")))
        target = os.path.join(root, *rel.split("/"))
        os.makedirs(os.path.dirname(target), exist_ok=True)
        os.replace(source, target)
        touched.add(os.path.dirname(target))
    for rel, _ in removes:  # folders emptied by our removals; rmdir never removes anything else
        folder = os.path.dirname(os.path.join(root, *rel.split("/")))
        while folder != root and _inspect(root, os.path.relpath(folder, root))[0] == "dir":
            try:
                os.rmdir(folder)
            except OSError:
                break
            touched.add(os.path.dirname(folder))
            folder = os.path.dirname(folder)
    _fsync_all(sorted(touched), _fsync_dir)
    os.unlink(os.path.join(staging, JOURNAL))
    shutil.rmtree(staging)


def _read_journal(staging: str) -> tuple[list[str], list[list[str]]] | None:
    """A committed journal's (removes, renames), None when absent or not a valid journal."""
    try:
        data = _read_limited(os.path.join(staging, JOURNAL), MAX_MANIFEST_BYTES)
        if data is None:
            return None
        doc = json.loads(data.decode("utf-8"))
        removes, renames = doc["removes"], doc["renames"]
        if doc["version"] != 1:
            return None
    except (OSError, ValueError, KeyError, TypeError):
        return None
    if not (isinstance(removes, list)
            and all(isinstance(r, list) and len(r) == 2 and path_problem(r[0]) is None and isinstance(r[1], str)
                    for r in removes)
            and isinstance(renames, list)
            and all(isinstance(e, list) and len(e) == 2 and isinstance(e[1], str)
                    and (e[0] == MANIFEST or path_problem(e[0]) is None) and _STAGED_NAME.fullmatch(e[1])
                    for e in renames)):
        return None  # not ours (a crafted checkout): discarded like abandoned temporaries
    return removes, renames


def _recover(root: str) -> bool:
    """Under the lock: finish an interrupted run, or drop a dead run's temporaries."""
    staging = os.path.join(root, STAGING)
    try:
        mode = os.lstat(staging).st_mode
    except FileNotFoundError:
        return False
    if not stat.S_ISDIR(mode):  # our reserved name, holding a link or file: drop the name only
        os.unlink(staging)
        return False
    journal = _read_journal(staging)
    if journal is None:
        shutil.rmtree(staging)
        return False
    _apply(root, *journal)
    return True


def _leftovers(root: str) -> list[str]:
    staging = os.path.join(root, STAGING)
    if not os.path.lexists(staging):
        return []
    if os.path.lexists(os.path.join(staging, JOURNAL)):
        return [f"{STAGING}/{JOURNAL}: a killed run's changes, half applied"]
    return [f"{STAGING}: temporaries of a killed run"]


# --- entry points ----------------------------------------------------------------------

def recover(out_dir: str) -> bool:
    """Complete (or clean up after) a run killed while writing out_dir; True if one was completed."""
    root = os.path.realpath(out_dir)
    if not os.path.isdir(root):
        return False
    with _locked(root, exclusive=True):
        return _recover(root)


def read_manifest(out_dir: str) -> dict[str, str]:
    """The usable entries of out_dir's manifest (unsafe ones dropped)."""
    root = os.path.realpath(out_dir)
    return _load_manifest(root, _Plan(out_dir)) if os.path.isdir(root) else {}


def write_tree(out_dir: str, files: list[GeneratedFile]) -> WriteReport:
    """Bring out_dir to exactly `files` (plus the user's files), all or nothing (see above).

    Problems come back in report.problems; with an error among them nothing was written.
    Raises LockBusy, UnsafeJournal, or OSError (permissions, a full disk...).
    """
    root = os.path.realpath(out_dir)
    os.makedirs(root, exist_ok=True)
    with _locked(root, exclusive=True):
        recovered = _recover(root)
        plan = _plan(root, out_dir, files)
        report = WriteReport(unchanged=plan.unchanged, kept_user=plan.kept_user, kept_edited=plan.kept_edited,
                             problems=plan.problems, recovered=recovered)
        if plan.failed or not (plan.writes or plan.removes):
            return report
        _commit(root, plan.writes, plan.removes, frozenset(f.path for f in files if f.user_owned))
    report.written = [rel for rel, _ in plan.writes if rel != MANIFEST]
    report.removed = [rel for rel, _ in plan.removes]
    return report


def compare_tree(out_dir: str, files: list[GeneratedFile]) -> StaleReport:
    """What `write_tree` would change, without writing anything."""
    root = os.path.realpath(out_dir)
    if not os.path.isdir(root):
        return StaleReport(missing=sorted(f.path for f in files) + [MANIFEST])
    with _locked(root, exclusive=False):
        plan = _plan(root, out_dir, files)
        leftovers = _leftovers(root)
    return StaleReport(missing=plan.missing, differs=plan.differs, extra=plan.extra,
                       interrupted=leftovers, problems=plan.problems)
