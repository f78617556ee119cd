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
    renderer = _Renderer(inputs, package)
    try:
        return {lang: renderer.target(lang) for lang in langs}
    except GenerationError as exc:
        exc.report(sink)
        return None


class _Renderer:
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


# -- two processes ----------------------------------------------------------------------------
# `generate` with several targets and `check` with several project targets spread their work
# over two processes: the back ends are pure functions of the parsed input, so a forked child
# renders some targets (it inherits the parsed model) and hands the files back, pickled. The
# output is the same as in one process; RAPIDGEN_JOBS=1 keeps everything in one.

def jobs() -> int:
    """How many processes to use: 2 where fork exists, the process may run on two CPUs or
    more and runs no other Python thread (a forked child would get only this one), else 1."""
    text = os.environ.get("RAPIDGEN_JOBS", "").strip()
    if text.isdigit() and int(text) <= 1:
        return 1
    if not hasattr(os, "fork"):
        return 1
    try:
        cpus = len(os.sched_getaffinity(0))
    except AttributeError:  # not Linux
        cpus = os.cpu_count() or 1
    import threading
    return 2 if cpus >= 2 and threading.active_count() == 1 else 1


class _Queue:
    """Job numbers 0..n-1 handed out first come, first served to the two processes: one
    byte each in a pipe, read one at a time (a pipe read of one byte is atomic)."""

    def __init__(self, n: int) -> None:
        self.read, write = os.pipe()
        os.write(write, bytes(range(n)))  # n <= 255, far below a pipe's buffer
        os.close(write)

    def take(self) -> int | None:
        got = os.read(self.read, 1)
        return got[0] if got else None

    def close(self) -> None:
        os.close(self.read)


class _Alternate:
    """Jobs dealt in turn: this process the even ones, the child the odd ones (`generate`:
    a few targets of known order, where the first come, first served queue would hand the
    last target to whoever is done first, though it may be the one to start early)."""

    def __init__(self, n: int) -> None:
        self.n, self.next = n, 0

    def child(self) -> None:
        self.next = 1

    def take(self) -> int | None:
        i, self.next = self.next, self.next + 2
        return i if i < self.n else None

    def close(self) -> None:
        pass


def _share(count: int, work, alternate: bool = False) -> list:
    """work(i) for every i < count, over two processes when jobs() says so; the results
    in order. The jobs go first come, first served (or, alternate, in turn). Results (and
    exceptions) of the child's jobs come back pickled."""
    import pickle

    if count < 2 or count > 255 or jobs() < 2:
        return [work(i) for i in range(count)]
    queue: _Queue | _Alternate = _Alternate(count) if alternate else _Queue(count)
    sys.stdout.flush()
    sys.stderr.flush()
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: never returns into the caller
        code = 0
        try:
            os.close(read)
            if isinstance(queue, _Alternate):
                queue.child()
            done = []
            while (i := queue.take()) is not None:
                try:
                    done.append((i, True, work(i)))
                except Exception as exc:  # noqa: BLE001 (raised again in the parent)
                    done.append((i, False, _portable(exc)))
                    break
            with os.fdopen(write, "wb") as out:
                pickle.dump(done, out, protocol=pickle.HIGHEST_PROTOCOL)
        except BaseException:  # noqa: BLE001 (the parent reports a child that sent nothing)
            code = 70
        finally:
            _child_exit(code)
    os.close(write)
    results: dict[int, object] = {}
    try:
        error: BaseException | None = None
        while error is None and (i := queue.take()) is not None:
            try:
                results[i] = work(i)
            except Exception as exc:  # noqa: BLE001 (raised below, once the child is reaped)
                error = exc
        with os.fdopen(read, "rb") as got:
            data = got.read()
        _, status = os.waitpid(pid, 0)
        pid = 0
    finally:
        queue.close()
        if pid:  # interrupted: stop the child we started, then reap it
            import signal
            os.kill(pid, signal.SIGTERM)
            os.waitpid(pid, 0)
    if error is not None:
        raise error
    if not data:
        raise RuntimeError(f"a rapidgen worker process ended without its results "
                           f"(exit status {os.waitstatus_to_exitcode(status)})")
    for i, ok, value in pickle.loads(data):
        if not ok:
            raise value
        results[i] = value
    return [results[i] for i in range(count)]


def _child_exit(code: int) -> None:
    """End a forked worker: what it compiled of the back ends' classes is saved too."""
    try:
        from rapidgen import codecache
        codecache.save()
    finally:
        os._exit(code)


def _portable(exc: Exception) -> Exception:
    """exc if it survives pickling, else a RuntimeError saying what it was."""
    import pickle
    try:
        pickle.loads(pickle.dumps(exc))
        return exc
    except Exception:  # noqa: BLE001
        return RuntimeError(f"{type(exc).__name__}: {exc}")


def _render_shared(inputs: Inputs, langs: list[str], sink: DiagnosticSink,
                   package: str | None) -> dict[str, list[GeneratedFile]] | None:
    """render(), its targets spread over two processes."""
    langs, problem = backends.parse_langs(langs)
    if problem:
        sink.error("RG0802", problem, SourceLoc("<command line>", 0, 0), "name targets with --lang a,b")
        return None
    renderer = _Renderer(inputs, package)

    def one(i: int) -> tuple[list[GeneratedFile] | None, list[Diagnostic]]:
        local = DiagnosticSink()
        try:
            return renderer.target(langs[i]), []
        except GenerationError as exc:
            exc.report(local)
            return None, list(local.diagnostics)

    done = _share(len(langs), one, alternate=True)
    out = {}
    for lang, (files, diags) in zip(langs, done):
        sink.extend(diags)
        if files is None:
            return None  # as render(): the first target that fails stops the run
        out[lang] = files
    return out


def write_outputs(out_dir: str, per_lang: dict[str, list[GeneratedFile]], sink: DiagnosticSink) -> bool:
    """Write each target into out_dir/<lang>; print a line per target. False on a write error."""
    return all(_write_lang(out_dir, lang, files, sink) for lang, files in per_lang.items())


def _write_lang(out_dir: str, lang: str, files: list[GeneratedFile], sink: DiagnosticSink) -> bool:
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
    with _no_cyclic_gc():
        inputs = load_inputs(paths, include, sink, defines)
        if inputs is None:
            return False
        langs, problem = backends.parse_langs(langs)
        if problem:
            sink.error("RG0802", problem, SourceLoc("<command line>", 0, 0), "name targets with --lang a,b")
            return False
        if len(langs) < 2 or jobs() < 2:
            per_lang = render(inputs, langs, sink, package)
            return per_lang is not None and write_outputs(out_dir, per_lang, sink)
        return _generate_in_two(_Renderer(inputs, package), langs, out_dir, sink)


def _generate_in_two(renderer: "_Renderer", langs: list[str], out_dir: str, sink: DiagnosticSink) -> bool:
    """render() then write_outputs(), the targets dealt in turn to this process and a forked
    child, each rendering and writing its own (each target has its own folder, manifest and
    lock; no process holds the other's files). Both render before either writes: a target
    the back end refuses stops the run with nothing written, as in one process. The child's
    diagnostics and printed lines come back pickled and everything is printed in target
    order, up to the first target whose folder could not be written, as in one process."""
    import pickle
    import signal

    ours, theirs = list(range(0, len(langs), 2)), list(range(1, len(langs), 2))
    files: dict[int, list[GeneratedFile]] = {}

    def render_some(indexes: list[int]) -> list[tuple[int, list[Diagnostic]]]:
        """[(i, diagnostics)] of the first target that fails; [] when all rendered."""
        for i in indexes:
            local = DiagnosticSink(silenced=sink.silenced, warnings_as_errors=sink.warnings_as_errors)
            try:
                files[i] = renderer.target(langs[i])
            except GenerationError as exc:
                exc.report(local)
                return [(i, list(local.diagnostics))]
        return []

    def write_some(indexes: list[int]) -> list[tuple[int, bool, str, str, list[Diagnostic]]]:
        done = []
        for i in indexes:
            local = DiagnosticSink(silenced=sink.silenced, warnings_as_errors=sink.warnings_as_errors)
            out, err = io.StringIO(), io.StringIO()
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                ok = _write_lang(out_dir, langs[i], files.pop(i), local)
            done.append((i, ok, out.getvalue(), err.getvalue(), list(local.diagnostics)))
        return done

    # Jinja2 (through the template loader) once, before the fork, not once in each process.
    import rapidgen.backends.templating  # noqa: F401

    sys.stdout.flush()
    sys.stderr.flush()
    up_r, up_w = os.pipe()  # child -> parent: pickled results
    down_r, down_w = os.pipe()  # parent -> child: b"w" write, b"" stop
    pid = os.fork()
    if pid == 0:  # the child: never returns into the caller
        code = 0
        try:
            os.close(up_r)
            os.close(down_w)
            with os.fdopen(up_w, "wb") as to_parent:
                try:
                    pickle.dump(("rendered", render_some(theirs)), to_parent, protocol=pickle.HIGHEST_PROTOCOL)
                    to_parent.flush()
                    if os.read(down_r, 1) == b"w":
                        pickle.dump(("written", write_some(theirs)), to_parent, protocol=pickle.HIGHEST_PROTOCOL)
                except Exception as exc:  # noqa: BLE001 (raised again in the parent)
                    pickle.dump(("error", _portable(exc)), to_parent, protocol=pickle.HIGHEST_PROTOCOL)
        except BaseException:  # noqa: BLE001 (the parent reports a child that sent nothing)
            code = 70
        finally:
            _child_exit(code)
    os.close(up_w)
    os.close(down_r)
    up = os.fdopen(up_r, "rb")
    finished = False  # the child was told what to do and has answered: it is ending by itself
    try:
        failed = render_some(ours)
        kind, value = _receive(up, pickle)
        failed += value
        if failed:  # the first refused target in order, as render() reports it
            os.close(down_w)
            down_w = -1
            i, diags = min(failed, key=lambda f: f[0])
            sink.extend(diags)
            finished = True
            return False
        os.write(down_w, b"w")
        os.close(down_w)
        down_w = -1
        written = write_some(ours)
        kind, value = _receive(up, pickle)
        written += value
        finished = True
        for i, ok, out, err, diags in sorted(written, key=lambda w: w[0]):
            sys.stdout.write(out)
            sys.stderr.write(err)
            sink.extend(diags)
            if not ok:
                return False
        return True
    finally:
        if down_w >= 0:
            os.close(down_w)
        up.close()
        if not finished:  # leaving early (an exception, an interrupt): stop the child we started
            try:
                os.kill(pid, signal.SIGTERM)
            except ProcessLookupError:
                pass
        os.waitpid(pid, 0)


def _receive(up, pickle) -> tuple[str, list]:
    """The child's next message; raises what it raised, or when it sent nothing."""
    try:
        kind, value = pickle.load(up)
    except EOFError:
        raise RuntimeError("a rapidgen worker process ended without its results") from None
    if kind == "error":
        raise value
    return kind, value


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
        done = _share(len(targets), one)
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
            from rapidgen.annotations import command
            for line in lines:
                label, _, rel = line.strip().partition(": ")
                print(command("error", f"{label}: generated output is stale; run `rapidgen check --fix` and commit it",
                              SourceLoc(f"{t.out}/{rel}", 0, 0), f"rapidgen check: {t.name}"))
        return True
    print(f"{t.name}: up to date ({count} files)")
    return False
