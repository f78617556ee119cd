"""`rapidgen diff`: load both sides, compare, waive, print, and decide the exit status.

Exit status: 0 no finding of a `--fail-on` category, 1 such a finding or an input error
(diagnostics on stderr), 2 usage errors.
"""
from __future__ import annotations

import os
import sys
import tempfile
from dataclasses import replace
from typing import TYPE_CHECKING, Callable, overload

from rapidgen.diagnostics import Diagnostic, DiagnosticSink, SourceLoc, did_you_mean
from rapidgen.diff.render import as_json, github, text
from rapidgen.diff.rules import CATEGORIES, RULES, Finding
from rapidgen.diff.sides import Side, kind_of, load_side

if TYPE_CHECKING:  # imported when --waivers is given
    from rapidgen.diff.waivers import Waiver


def _usage(msg: str) -> int:
    print(f"rapidgen diff: {msg}", file=sys.stderr)
    return 2


def compare(old: Side, new: Side) -> list[Finding]:
    """Every finding, wire rules first, in a stable order."""
    from rapidgen.diff.protocol import protocol_diff
    from rapidgen.diff.wire import wire_diff

    found = wire_diff(old.model, new.model)
    if old.asset is not None and new.asset is not None:
        found += protocol_diff(old.asset, new.asset)
    return found


class _Remap:
    """Locations under the temporary tree of `--against REV` shown as `REV:path`."""

    def __init__(self, root: str | None, rev: str | None) -> None:
        self.root = os.path.realpath(root) + os.sep if root else None
        self.rev = rev

    @overload
    def loc(self, loc: SourceLoc) -> SourceLoc: ...
    @overload
    def loc(self, loc: None) -> None: ...

    def loc(self, loc: SourceLoc | None) -> SourceLoc | None:
        if loc is None or self.root is None:
            return loc
        full = os.path.realpath(os.path.abspath(loc.file))
        if full.startswith(self.root):
            return loc._replace(file=f"{self.rev}:{full[len(self.root):].replace(os.sep, '/')}")
        return loc

    def diag(self, d: Diagnostic) -> Diagnostic:
        return replace(d, loc=self.loc(d.loc))


def run_diff(args, sink: DiagnosticSink, report: Callable[[DiagnosticSink], None]) -> int:
    """args: paths, against, include, define, json, fail_on, ignore, waivers."""
    fail_on = {c.strip().upper() for c in (args.fail_on or "").split(",") if c.strip()}
    if fail_on - set(CATEGORIES):
        bad = sorted(fail_on - set(CATEGORIES))[0]
        return _usage(f"--fail-on: unknown category '{bad}'; categories: {','.join(CATEGORIES)}")
    for rid in args.ignore:
        if rid not in RULES:
            hint = did_you_mean(rid, RULES)
            return _usage(f"--ignore: unknown rule id '{rid}'" + (f"; {hint}" if hint else ""))
    if args.against is None and len(args.paths) != 2:
        return _usage("give OLD and NEW (two paths), or --against REV and one path")
    if args.against is not None and len(args.paths) != 1:
        return _usage("with --against REV give one path (its NEW version; OLD is read from REV)")
    new_path = args.paths[-1]
    defines = dict(d.partition("=")[::2] for d in args.define)
    waivers: list[Waiver] = []
    if args.waivers:
        from rapidgen.diff.waivers import load_waivers
        loaded = load_waivers(args.waivers, sink)
        if loaded is None:
            report(sink)
            return 1
        waivers = loaded
    with tempfile.TemporaryDirectory(prefix="rapidgen-diff-") as tmp:
        remap = _Remap(None, None)
        include = list(args.include)
        if args.against is not None:
            from rapidgen.diff.gitread import materialize
            mapped = materialize(args.against, [new_path, *include], tmp, sink)
            if mapped is None:
                report(sink)
                return 1
            old_path, old_include = mapped[0], mapped[1:]
            remap = _Remap(tmp, args.against)
        else:
            old_path, old_include = args.paths[0], include
        if kind_of(old_path) != kind_of(new_path) or os.path.isdir(old_path) != os.path.isdir(new_path):
            return _usage("OLD and NEW must be of the same kind (two IDL files, two folders or two descriptors)")
        old_sink = DiagnosticSink(silenced=sink.silenced, warnings_as_errors=sink.warnings_as_errors)
        old = load_side(old_path, old_include, defines, old_sink)
        for d in old_sink.diagnostics:
            sink.diagnostics.append(remap.diag(d))
        new_sink = DiagnosticSink(silenced=sink.silenced, warnings_as_errors=sink.warnings_as_errors)
        new = load_side(new_path, include, defines, new_sink) if old is not None else None
        sink.diagnostics.extend(new_sink.diagnostics)
        report(sink)
        if old is None or new is None:
            return 1
        found = [replace(f, old=remap.loc(f.old)) for f in compare(old, new)]
    kept = [f for f in found if f.rule.id not in args.ignore and not any(w.covers(f) for w in waivers)]
    waived = len(found) - len(kept)
    if args.json:
        out = as_json(kept, waived)
    elif getattr(args, "format", "text") == "github":
        out = github(kept, waived, fail_on, args.against)
    else:
        out = text(kept, waived)
    sys.stdout.write(out)
    return 1 if any(f.rule.category in fail_on for f in kept) else 0
