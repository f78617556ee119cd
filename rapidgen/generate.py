"""Fan one parsed input out to the requested back ends, and write or check the result.

Inputs are either one asset descriptor (YAML; it names its IDL) or IDL files (types
alone). Each target's files go to `<out>/<lang>/`, which has its own manifest: generating
one language never touches another's files.
"""
from __future__ import annotations

import contextlib
import io
import os
import sys
from dataclasses import dataclass
from typing import TYPE_CHECKING

from rapidgen import backends
from rapidgen.backends.base import QOS_LIBRARY, GeneratedFile, GenerationError, Options, printable
from rapidgen.diagnostics import Diagnostic, DiagnosticSink, SourceLoc
from rapidgen.model.ir import Model

if TYPE_CHECKING:  # the asset package is loaded only for descriptors
    from rapidgen.asset import LoadedAsset


@dataclass
class Inputs:
    model: Model
    asset: LoadedAsset | None
    source: str  # how headers name the source


def is_asset(path: str) -> bool:
    return path.endswith((".yaml", ".yml"))


def source_name(paths: list[str]) -> str:
    """Stable, machine-independent name of the inputs for file headers.

    Relative to the working folder when inside it (absolute paths would differ between
    machines); printable characters only, since back ends embed it in comments/strings.
    """
    shown = []
    for p in paths:
        rel = os.path.relpath(p) if os.path.isabs(p) else os.path.normpath(p)
        shown.append((os.path.basename(p) if rel.startswith("..") and os.path.isabs(p) else rel)
                     .replace(os.sep, "/"))
    if len(shown) > 3:
        folders = sorted({os.path.dirname(p) or "." for p in shown})
        text = ", ".join(f"{f}/*.idl" for f in folders)
    else:
        text = ", ".join(shown)
    return printable(text)


def load_inputs(paths: list[str], include: list[str], sink: DiagnosticSink,
                defines: dict[str, str] | None = None) -> Inputs | None:
    assets = [p for p in paths if is_asset(p)]
    if assets:
        if len(paths) != 1:
            sink.error("RG0801", "give one asset descriptor, or IDL files, not both", SourceLoc(paths[0], 1, 1),
                       "an asset descriptor names its own IDL files")
            return None
        from rapidgen.asset import load_asset

        loaded = load_asset(assets[0], sink)
        if loaded is None or loaded.model is None or sink.has_errors:
            return None
        return Inputs(loaded.model, loaded, source_name(assets))
    from rapidgen.idl.load import load_idl

    model, _ = load_idl(paths, include, sink, defines)
    if model is None:
        return None
    return Inputs(model, None, source_name(paths))


def render(inputs: Inputs, langs: list[str], sink: DiagnosticSink,
           package: str | None = None) -> dict[str, list[GeneratedFile]] | None:
    """Every requested target's files, by target, paths relative to `<out>/<lang>/`.

    Each back end declares what it needs (backends.base.Backend): the inputs read here, in
    the driver (back ends never read files), and the targets whose files it embeds."""
    langs, problem = backends.parse_langs(langs)
    if problem:
        sink.error("RG0802", problem, SourceLoc("<command line>", 0, 0), "name targets with --lang a,b")
        return None
    renderer = Renderer(inputs, package)
    try:
        return {lang: renderer.target(lang) for lang in langs}
    except GenerationError as exc:
        exc.report(sink)
        return None


class Renderer:
    """Renders targets on demand, each at most once, a target's companions before it: the
    unit of work that render() runs in order and generate/check spread over two processes."""

    def __init__(self, inputs: Inputs, package: str | None) -> None:
        self.inputs, self.package = inputs, package
        self.raw: dict[str, list[GeneratedFile]] = {}  # generate()'s files, before embedding
        self._library: object | None = None

    def _options(self, needs: frozenset[str]) -> Options:
        if QOS_LIBRARY in needs and self._library is None:
            from rapidgen.qos.spec import default_library
            self._library = default_library()
        return Options(source=self.inputs.source, package=self.package,
                       qos_library=self._library if QOS_LIBRARY in needs else None)

    def _generate(self, lang: str) -> list[GeneratedFile]:
        if lang not in self.raw:
            backend, asset = backends.get(lang), self.inputs.asset
            self.raw[lang] = backend.generate(self.inputs.model, asset, self._options(backend.needs(asset)))
        return self.raw[lang]

    def target(self, lang: str) -> list[GeneratedFile]:
        """The target's files with its companions' embedded (raises GenerationError)."""
        backend, asset = backends.get(lang), self.inputs.asset
        files = self._generate(lang)
        return backend.embed(files, {c: self._generate(c) for c in backend.companions(asset)})


def write_outputs(out_dir: str, per_lang: dict[str, list[GeneratedFile]], sink: DiagnosticSink) -> bool:
    """Write each target into out_dir/<lang>; print a line per target. False on a write error."""
    return all(write_lang(out_dir, lang, files, sink) for lang, files in per_lang.items())


def write_lang(out_dir: str, lang: str, files: list[GeneratedFile], sink: DiagnosticSink) -> bool:
    """One target's folder, out_dir/<lang> (its own manifest and lock); prints its line."""
    from rapidgen.writer import write_tree

    folder = os.path.join(out_dir, lang)
    report = _call_writer(write_tree, folder, files, sink)
    if report is None:
        return False
    sink.extend(report.problems)
    if report.failed:
        return False
    if report.recovered:
        print(f"{folder}: completed a run that was interrupted")
    print(f"{folder}: {len(report.written)} written, {len(report.unchanged)} unchanged"
          + (f", {len(report.removed)} removed" if report.removed else "")
          + (f", {len(report.kept_user)} user files kept" if report.kept_user else ""))
    for rel in report.kept_edited:
        print(f"  kept {rel}: no longer generated, but edited by hand", file=sys.stderr)
    return True


def _call_writer(function, folder: str, files: list[GeneratedFile], sink: DiagnosticSink):
    """function(folder, files), its exceptions turned into diagnostics (then None)."""
    from rapidgen.writer import LOCK_WAIT_S, LockBusy, UnsafeJournal

    try:
        return function(folder, files)
    except LockBusy:
        sink.error("RG0824", f"another rapidgen run kept '{folder}' locked for {LOCK_WAIT_S:g} s",
                   SourceLoc(folder, 0, 0), "wait for it to end, or stop it (a killed run's lock is freed)")
    except UnsafeJournal as exc:
        sink.error("RG0822", f"an interrupted run cannot be completed: '{exc.path}' is now a link or in the way",
                   SourceLoc(exc.path, 0, 0), "move it away and run again")
    except OSError as exc:
        where = exc.filename or folder
        sink.error("RG0803", f"cannot write '{where}': {exc.strerror or exc}", SourceLoc(str(where), 0, 0),
                   "check that the output folder is a writable directory")
    return None


def generate_command(paths: list[str], include: list[str], defines: dict[str, str], langs: list[str],
                     out_dir: str, package: str | None, sink: DiagnosticSink) -> bool:
    """Several targets go over two processes (rapidgen.fork_ahead): by the worker forked ahead
    of the front end, or for a large model (large files: no worker forked at all), by this
    process and a child."""
    from rapidgen import fork_ahead

    wanted, problem = backends.parse_langs(langs)
    two = not problem and len(wanted) >= 2 and fork_ahead.jobs() >= 2
    ahead_too = two and fork_ahead.Ahead.likely(paths)
    with _no_cyclic_gc(), (fork_ahead.Ahead(wanted) if ahead_too else contextlib.nullcontext()) as ahead:
        inputs = load_inputs(paths, include, sink, defines)
        if inputs is None:
            return False
        if problem:
            sink.error("RG0802", problem, SourceLoc("<command line>", 0, 0), "name targets with --lang a,b")
            return False
        if not two:
            per_lang = render(inputs, wanted, sink, package)
            return per_lang is not None and write_outputs(out_dir, per_lang, sink)
        if ahead is not None and ahead.worth(inputs):
            done = ahead.hand_over(inputs, package, out_dir, sink)
            if done is not None:
                return done
        return fork_ahead.generate_in_two(Renderer(inputs, package), wanted, out_dir, sink)


@contextlib.contextmanager
def _no_cyclic_gc():
    """The cyclic garbage collector paused for one command: the model and the views hold
    (almost) no cycles (a view pass leaves a few dozen cyclic objects at 1000 structs), and
    its collections over the growing heap only cost time: its first pass after the front
    end alone walked the whole model (0.2 s at 1000 structs). Anything cyclic is collected
    afterwards."""
    import gc
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            gc.enable()


def check_command(project: str, fix: bool, sink: DiagnosticSink, annotate: bool = False) -> int:
    """Regenerate every target of the project file in memory; report (or fix) what is stale.
    The targets are spread over two processes (_share); what each prints comes out in the
    project file's order."""
    from rapidgen.project import load_project

    targets = load_project(project, sink)
    if targets is None:
        return 1

    def one(i: int) -> tuple[bool, str, str, list[Diagnostic]]:
        local = DiagnosticSink(silenced=sink.silenced, warnings_as_errors=sink.warnings_as_errors)
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            stale = _check_target(targets[i], fix, local, annotate)
        return stale, out.getvalue(), err.getvalue(), list(local.diagnostics)

    stale = 0
    with _no_cyclic_gc():
        from rapidgen import fork_ahead
        done = fork_ahead.share(len(targets), one)
    for is_stale, out, err, diags in done:
        sys.stdout.write(out)
        sys.stderr.write(err)
        sink.extend(diags)
        stale += is_stale
    if sink.has_errors:
        return 1
    if stale:
        print(f"rapidgen check: {stale} target{'s' * (stale != 1)} stale; run `rapidgen check --fix`",
              file=sys.stderr)
        return 1
    return 0


def _check_target(t, fix: bool, sink: DiagnosticSink, annotate: bool = False) -> bool:
    """One project target: compare (or rewrite) its output; prints what it finds (annotate:
    each stale file as a GitHub Actions annotation too). True when stale."""
    from rapidgen.writer import compare_tree

    inputs = load_inputs(list(t.inputs), list(t.include), sink)
    if inputs is not None:
        inputs.source = t.source
    per_lang = render(inputs, list(t.lang), sink, t.package) if inputs else None
    if per_lang is None:
        return False
    if fix:
        write_outputs(t.out, per_lang, sink)
        return False
    lines, count = [], 0
    for lang, files in per_lang.items():
        diff = _call_writer(compare_tree, os.path.join(t.out, lang), files, sink)
        if diff is None:
            continue
        sink.extend(diff.problems)
        count += len(files)
        for label, items in (("missing", diff.missing), ("differs", diff.differs),
                             ("no longer generated", diff.extra), ("interrupted run", diff.interrupted)):
            lines += [f"  {label}: {lang}/{item}" for item in items]
    if lines:
        print(f"{t.name}: stale ({t.out})")
        print("\n".join(lines))
        if annotate:
            from rapidgen.github_annotations import command
            for line in lines:
                label, _, rel = line.strip().partition(": ")
                print(command("error", f"{label}: generated output is stale; run `rapidgen check --fix` and commit it",
                              SourceLoc(f"{t.out}/{rel}", 0, 0), f"rapidgen check: {t.name}"))
        return True
    print(f"{t.name}: up to date ({count} files)")
    return False
