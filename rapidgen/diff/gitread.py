"""`--against REV`: the old side read from git (ls-tree + cat-file), no checkout.

The revision's spec files (IDL, YAML) are written under a temporary folder with the
repository's layout, so includes, `idl.rapid: ../rapid` and `specs/rapid` lookups resolve
within that revision's tree. Paths in messages name them `REV:path`.
"""
from __future__ import annotations

import os
import subprocess

from rapidgen.diagnostics import DiagnosticSink, SourceLoc
from rapidgen.idl.preprocess import display_path

SPEC_SUFFIXES = (".idl", ".pidl", ".yaml", ".yml")
MAX_FILES = 20_000
MAX_BYTES = 64 * 1024 * 1024  # of spec files read from one revision
REGULAR = ("100644", "100755")


class GitError(Exception):
    pass


def _git(top: str, *args: str, data: bytes | None = None) -> bytes:
    try:
        done = subprocess.run(["git", "-C", top, *args], input=data, capture_output=True, timeout=120)
    except (OSError, subprocess.TimeoutExpired) as exc:
        raise GitError(f"cannot run git: {exc}") from exc
    if done.returncode != 0:
        raise GitError(done.stderr.decode("utf-8", "replace").strip().splitlines()[-1:][0]
                       if done.stderr.strip() else f"git {args[0]} failed")
    return done.stdout


def _safe(rel: str) -> bool:
    parts = rel.split("/")
    return bool(rel) and not rel.startswith("/") and ".." not in parts and "" not in parts and "\\" not in rel


def materialize(rev: str, paths: list[str], dest: str, sink: DiagnosticSink) -> list[str] | None:
    """Write the revision's spec files under dest; the given paths as they map there.
    None after a diagnostic (RG1802: not a repository, unknown revision, missing path;
    RG1803: the revision's spec files exceed the limits)."""
    first = os.path.abspath(paths[0])
    where = SourceLoc(display_path(paths[0]), 0, 0)
    try:
        start = first if os.path.isdir(first) else os.path.dirname(first)
        top = _git(start, "rev-parse", "--show-toplevel").decode().strip()
        _git(top, "rev-parse", "--verify", "--quiet", f"{rev}^{{commit}}")
    except GitError as exc:
        sink.error("RG1802", f"cannot read revision '{rev}': {exc}", where,
                   "--against takes a commit, branch or tag of the repository holding the paths")
        return None
    rels = []
    for p in paths:
        rel = os.path.relpath(os.path.realpath(p), os.path.realpath(top)).replace(os.sep, "/")
        if rel.startswith(".."):
            sink.error("RG1802", f"'{display_path(p)}' is outside the repository at '{display_path(top)}'",
                       SourceLoc(display_path(p), 0, 0))
            return None
        rels.append("" if rel == "." else rel)
    listing = _git(top, "ls-tree", "-r", "-z", "--full-tree", rev).split(b"\0")
    wanted: list[tuple[str, str]] = []
    for entry in listing:
        if not entry:
            continue
        meta, _, name_b = entry.partition(b"\t")
        mode, kind, oid = meta.decode().split()
        name = name_b.decode("utf-8", "surrogateescape")
        under = any(r == "" or name == r or name.startswith(r + "/") for r in rels)
        if kind == "blob" and mode in REGULAR and _safe(name) and (name.lower().endswith(SPEC_SUFFIXES) or under):
            wanted.append((oid, name))
    names = {n for _, n in wanted}
    for p, r in zip(paths, rels):
        if r and r not in names and not any(n.startswith(r + "/") for n in names):
            sink.error("RG1802", f"'{r}' does not exist at revision '{rev}'", SourceLoc(display_path(p), 0, 0),
                       "the path must be in that revision's tree (added since?)")
            return None
    if len(wanted) > MAX_FILES:
        sink.error("RG1803", f"revision '{rev}' has {len(wanted)} spec files, more than {MAX_FILES}", where)
        return None
    sizes = _git(top, "cat-file", "--batch-check=%(objectsize)", data="\n".join(o for o, _ in wanted).encode())
    total = sum(int(x) for x in sizes.split())
    if total > MAX_BYTES:
        sink.error("RG1803", f"revision '{rev}' has {total} bytes of spec files, more than {MAX_BYTES}", where)
        return None
    blob = _git(top, "cat-file", "--batch", data="\n".join(o for o, _ in wanted).encode())
    pos = 0
    for _, name in wanted:
        header_end = blob.index(b"\n", pos)
        size = int(blob[pos:header_end].split()[2])
        content = blob[header_end + 1:header_end + 1 + size]
        pos = header_end + 1 + size + 1
        target = os.path.join(dest, *name.split("/"))
        os.makedirs(os.path.dirname(target), exist_ok=True)
        with open(target, "wb") as f:
            f.write(content)
    return [os.path.join(dest, *r.split("/")) if r else dest for r in rels]
