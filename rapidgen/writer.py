"""Writing generated files: only when content changed, atomically, with a manifest.

A run stages every changed file as a temporary file beside its target first and renames
them into place only when all are staged, then writes the manifest; a run interrupted
while staging leaves the previous output untouched (stale temporaries are removed by the
next run). Files listed in the previous manifest but no longer generated are deleted,
unless the user edited them. User-owned files (bridge handlers) are created once and
never overwritten.
"""
from __future__ import annotations

import hashlib
import json
import os
import tempfile
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Iterable

from rapidgen.backends.base import GeneratedFile

if TYPE_CHECKING:
    from rapidgen.diagnostics import DiagnosticSink

MANIFEST = ".rapidgen-manifest.json"
_TMP_PREFIX = ".rapidgen-"


def digest(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def write_text_atomic(path: str, text: str) -> bool:
    """Write text to path unless it already holds exactly that; returns True if written."""
    staged = _stage(path, text)
    if staged is None:
        return False
    os.replace(staged, path)
    return True


def write_output(path: str, text: str, sink: "DiagnosticSink") -> bool | None:
    """write_text_atomic for a command's output file: True written, False unchanged, None on
    failure, reported in sink as RG0803 (a directory, a missing folder, no permission)."""
    from rapidgen.diagnostics import SourceLoc

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
        _unlink(tmp)
        raise
    return tmp


def _unlink(path: str) -> None:
    try:
        os.unlink(path)
    except OSError:
        pass


@dataclass
class WriteReport:
    written: list[str] = field(default_factory=list)
    unchanged: list[str] = field(default_factory=list)
    removed: list[str] = field(default_factory=list)
    kept_user: list[str] = field(default_factory=list)  # user-owned files that already existed
    kept_edited: list[str] = field(default_factory=list)  # stale files not removed: edited by hand


def read_manifest(out_dir: str) -> dict[str, str]:
    try:
        with open(os.path.join(out_dir, MANIFEST), encoding="utf-8") as fh:
            data = json.load(fh)
        files = data.get("files", {})
        return {str(k): str(v) for k, v in files.items()} if isinstance(files, dict) else {}
    except (OSError, ValueError):
        return {}


def manifest_text(files: Iterable[GeneratedFile]) -> str:
    entries = {f.path: digest(f.content) for f in sorted(files, key=lambda f: f.path) if not f.user_owned}
    return json.dumps({"generator": "rapidgen", "files": entries}, indent=1, sort_keys=True) + "\n"


def _remove_stale_temporaries(out_dir: str) -> None:
    for root, _dirs, names in os.walk(out_dir):
        for name in names:
            if name.startswith(_TMP_PREFIX) and name.endswith(".tmp"):
                _unlink(os.path.join(root, name))


def write_tree(out_dir: str, files: list[GeneratedFile]) -> WriteReport:
    report = WriteReport()
    os.makedirs(out_dir, exist_ok=True)
    _remove_stale_temporaries(out_dir)
    previous = read_manifest(out_dir)
    staged: list[tuple[str, str, str]] = []  # (temp, target, relative path)
    try:
        for f in sorted(files, key=lambda f: f.path):
            target = os.path.join(out_dir, *f.path.split("/"))
            if f.user_owned and os.path.exists(target):
                report.kept_user.append(f.path)
                continue
            tmp = _stage(target, f.content)
            if tmp is None:
                report.unchanged.append(f.path)
            else:
                staged.append((tmp, target, f.path))
    except BaseException:
        for tmp, _target, _rel in staged:
            _unlink(tmp)
        raise
    for tmp, target, rel in staged:
        os.replace(tmp, target)
        report.written.append(rel)
    current = {f.path for f in files}
    for rel, old_digest in sorted(previous.items()):
        if rel in current:
            continue
        target = os.path.join(out_dir, *rel.split("/"))
        try:
            with open(target, encoding="utf-8") as fh:
                edited = digest(fh.read()) != old_digest
        except (OSError, UnicodeDecodeError):
            continue
        if edited:
            report.kept_edited.append(rel)
        else:
            _unlink(target)
            report.removed.append(rel)
    write_text_atomic(os.path.join(out_dir, MANIFEST), manifest_text(files))
    return report


@dataclass
class StaleReport:
    missing: list[str] = field(default_factory=list)
    differs: list[str] = field(default_factory=list)
    extra: list[str] = field(default_factory=list)  # in the manifest on disk, no longer generated

    @property
    def stale(self) -> bool:
        return bool(self.missing or self.differs or self.extra)


def compare_tree(out_dir: str, files: list[GeneratedFile]) -> StaleReport:
    """What `write_tree` would change, without writing anything."""
    report = StaleReport()
    for f in sorted(files, key=lambda f: f.path):
        target = os.path.join(out_dir, *f.path.split("/"))
        try:
            with open(target, "rb") as fh:
                data = fh.read()
        except OSError:
            report.missing.append(f.path)
            continue
        if not f.user_owned and data != f.content.encode("utf-8"):
            report.differs.append(f.path)
    current = {f.path for f in files}
    report.extra = sorted(p for p in read_manifest(out_dir) if p not in current)
    manifest = os.path.join(out_dir, MANIFEST)
    try:
        with open(manifest, encoding="utf-8") as fh:
            if fh.read() != manifest_text(files):
                if MANIFEST not in report.differs:
                    report.differs.append(MANIFEST)
    except OSError:
        report.missing.append(MANIFEST)
    return report
