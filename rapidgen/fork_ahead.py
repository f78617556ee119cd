"""`generate` and `check` over two processes.

The back ends are pure functions of the parsed input, so a forked child renders some
targets (it inherits the parsed model) and hands back what it must (the files, or only what
it printed when it writes them itself), pickled. The output is the same as in one process;
RAPIDGEN_JOBS=1 keeps everything in one.

- `share`: `check`'s project targets, first come, first served over two processes.
- `generate_in_two`: `generate`'s targets dealt in turn to this process and a child, each
  rendering and writing its own.
- `Ahead`: for `generate`, a worker forked before the front end runs, which prepares the
  rendering meanwhile on the other CPU and then runs `generate_in_two` itself.
"""
from __future__ import annotations

import contextlib
import io
import os
import sys
from typing import IO, TYPE_CHECKING

from rapidgen import backends
from rapidgen.backends.base import GeneratedFile, GenerationError
from rapidgen.diagnostics import Diagnostic, DiagnosticSink
from rapidgen.speed_devices import without

if TYPE_CHECKING:
    from rapidgen.generate import Inputs, Renderer


def jobs() -> int:
    """How many processes to use: 2 where fork exists, the process may run on two CPUs or
    more and runs no other Python thread (a forked child would get only this one), else 1."""
    text = os.environ.get("RAPIDGEN_JOBS", "").strip()
    if (text.isdigit() and int(text) <= 1) or without("two-processes"):
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


def share(count: int, work, alternate: bool = False) -> list:
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
                    done.append((i, False, portable(exc)))
                    break
            with os.fdopen(write, "wb") as out:
                pickle.dump(done, out, protocol=pickle.HIGHEST_PROTOCOL)
        except BaseException:  # noqa: BLE001 (the parent reports a child that sent nothing)
            code = 70
        finally:
            child_exit(code)
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
            stop(pid)
            os.waitpid(pid, 0)
    if error is not None:
        raise error
    if not data:
        raise WorkerLost(f"a rapidgen worker process ended without its results "
                         f"(exit status {os.waitstatus_to_exitcode(status)})")
    for i, ok, value in pickle.loads(data):
        if not ok:
            raise value
        results[i] = value
    return [results[i] for i in range(count)]


def child_exit(code: int) -> None:
    """End a forked worker: what it compiled of the back ends' classes is saved too."""
    try:
        from rapidgen import codecache
        codecache.save()
    finally:
        os._exit(code)


def portable(exc: Exception) -> Exception:
    """exc if it survives pickling, else a RuntimeError saying what it was."""
    import pickle
    try:
        pickle.loads(pickle.dumps(exc))
        return exc
    except Exception:  # noqa: BLE001
        return RuntimeError(f"{type(exc).__name__}: {exc}")


class Ahead:
    """`generate`'s worker, forked before the front end runs.

    While this process parses, the worker does on the other CPU what rendering would
    otherwise do first: import Jinja2 and the targets' back ends, load their templates
    (~50 ms of every run). Handed the parsed inputs, it runs generate_in_two itself (it and
    a child of its own render and write the targets) and sends back what was printed; this
    process only waits for it. Handing over costs ~0.07 ms per declaration (pickling the
    model: rapidgen.model.pickling), more than the worker saves from a few hundred on:
    a larger model is rendered here as before (the caller decides: worth()) and the worker
    is stopped; for large input files none is forked (likely()). So is a model the worker
    could not take or did not answer for (killed): the output is the same either way."""

    MAX_DECLARATIONS = 400
    MAX_INPUT_BYTES = 256 * 1024  # given files larger than this make a model over the limit

    def __init__(self, langs: list[str]) -> None:
        self.langs = langs
        self.pid, self.down, self.up = 0, -1, -1

    @classmethod
    def likely(cls, paths: list[str]) -> bool:
        """Whether the inputs may make a model small enough to hand over: no worker is forked
        for large files (its preparing would only take a CPU from this process's parsing)."""
        try:
            return sum(os.path.getsize(p) for p in paths) <= cls.MAX_INPUT_BYTES
        except OSError:  # the front end reports it
            return True

    @classmethod
    def worth(cls, inputs: Inputs) -> bool:
        return len(inputs.model.declarations) <= cls.MAX_DECLARATIONS

    def __enter__(self) -> Ahead:
        sys.stdout.flush()
        sys.stderr.flush()
        down_r, self.down = os.pipe()  # this process -> worker: the pickled inputs (EOF: end)
        self.up, up_w = os.pipe()  # worker -> this process: the outcome, pickled
        pid = os.fork()
        if pid == 0:
            os.close(self.down)
            os.close(self.up)
            _ahead_worker(self.langs, down_r, up_w)  # never returns
        self.pid = pid
        os.close(down_r)
        os.close(up_w)
        return self

    def __exit__(self, kind: object, *_: object) -> None:
        """A worker handed nothing is stopped at once (it holds nothing yet), as is one this
        process leaves on an exception or an interrupt; then reaped."""
        handed = self.down < 0
        for fd in (self.down, self.up):
            if fd >= 0:
                os.close(fd)
        self.down = self.up = -1
        if self.pid:
            if kind is not None or not handed:
                stop(self.pid)
            os.waitpid(self.pid, 0)
            self.pid = 0

    def hand_over(self, inputs: Inputs, package: str | None, out_dir: str, sink: DiagnosticSink) -> bool | None:
        """What generate_in_two returns, the work done by the worker, what it printed printed
        here; None when the inputs do not pickle (then the worker ends with nothing done) or
        the worker is lost before it answers: the caller renders the targets itself. An error
        the worker raised is raised here."""
        from rapidgen.model import pickling
        try:
            data = pickling.dumps((inputs, package, out_dir, sink.silenced, sink.warnings_as_errors))
        except Exception:  # noqa: BLE001 (an asset holding what does not pickle: rendered here)
            return None
        try:
            with os.fdopen(self.down, "wb") as down:
                self.down = -1
                down.write(data)
        except BrokenPipeError:  # the worker is gone (killed): rendered here
            return None
        with os.fdopen(self.up, "rb") as up:
            self.up = -1
            try:
                _, (ok, out, err, diags) = receive(up)
            except WorkerLost:  # killed, or it died, before it answered: rendered here again
                return None  # (the same files; each folder's lock and journal see to a half write)
        sys.stdout.write(out)
        sys.stderr.write(err)
        sink.extend(diags)
        return ok


def _ahead_worker(langs: list[str], down_r: int, up_w: int) -> None:
    import pickle
    import signal

    def idle(signum: int, frame: object) -> None:
        os._exit(0)  # nothing written, no child; nothing saved (an import may be half done)

    def busy(signum: int, frame: object) -> None:
        raise KeyboardInterrupt  # generate_in_two then stops its own child too

    code = 0
    try:
        signal.signal(signal.SIGTERM, idle)
        with os.fdopen(down_r, "rb") as down:
            prepare(langs, until=down)
            try:
                inputs, package, out_dir, silenced, werror = pickle.load(down)
            except EOFError:  # not handed over: this process renders, and keeps the code cache
                os._exit(0)  # (a save here could be cut short by the stop that follows the EOF)
        signal.signal(signal.SIGTERM, busy)
        from rapidgen.generate import Renderer
        with os.fdopen(up_w, "wb") as to_parent:
            local = DiagnosticSink(silenced=silenced, warnings_as_errors=werror)
            out, err = io.StringIO(), io.StringIO()
            message: tuple[str, object]
            try:
                with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                    ok = generate_in_two(Renderer(inputs, package), langs, out_dir, local)
                message = ("done", (ok, out.getvalue(), err.getvalue(), list(local.diagnostics)))
            except Exception as exc:  # noqa: BLE001 (raised again in the parent)
                message = ("error", portable(exc))
            pickle.dump(message, to_parent, protocol=pickle.HIGHEST_PROTOCOL)
    except BaseException:  # noqa: BLE001 (the parent reports a worker that sent nothing)
        code = 70
    finally:
        child_exit(code)


def prepare(langs: list[str], until: IO[bytes] | None = None) -> None:
    """What rendering the targets does first: import their back ends (and Jinja2), load their
    templates (each target's own first, those in subfolders last). The templates stop
    loading once `until` has something to read: the rest load when used, as usual."""
    import select

    from rapidgen.backends import templating
    for lang in langs:
        backends.get(lang)
    for lang in langs:
        for name in sorted(templating.names(lang), key=lambda n: (n.count("/"), n)):
            if until is not None and select.select([until], [], [], 0)[0]:
                return
            templating.environment(lang).get_template(name)


def stop(pid: int) -> None:
    import signal
    try:
        os.kill(pid, signal.SIGTERM)
    except ProcessLookupError:
        pass


def generate_in_two(renderer: Renderer, langs: list[str], out_dir: str, sink: DiagnosticSink) -> bool:
    """render() then write_outputs(), the targets dealt in turn to this process and a forked
    child, each rendering and writing its own (each target has its own folder, manifest and
    lock; no process holds the other's files). Both render before either writes: a target
    the back end refuses stops the run with nothing written, as in one process. The child's
    diagnostics and printed lines come back pickled and everything is printed in target
    order, up to the first target whose folder could not be written, as in one process."""
    import pickle

    from rapidgen.generate import write_lang

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
                ok = write_lang(out_dir, langs[i], files.pop(i), local)
            done.append((i, ok, out.getvalue(), err.getvalue(), list(local.diagnostics)))
        return done

    # Jinja2 (through the template loader) once, before the fork, not once in each process.
    import rapidgen.backends.templating  # noqa: F401 (Ahead's worker has it already)

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
                    pickle.dump(("error", portable(exc)), to_parent, protocol=pickle.HIGHEST_PROTOCOL)
        except BaseException:  # noqa: BLE001 (the parent reports a child that sent nothing)
            code = 70
        finally:
            child_exit(code)
    os.close(up_w)
    os.close(down_r)
    up = os.fdopen(up_r, "rb")
    finished = False  # the child was told what to do and has answered: it is ending by itself
    try:
        failed = render_some(ours)
        kind, value = receive(up)
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
        kind, value = receive(up)
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
            stop(pid)
        os.waitpid(pid, 0)


class WorkerLost(RuntimeError):
    """A worker process ended without sending its results (killed, or it died)."""


def receive(up: IO[bytes]) -> tuple[str, list]:
    """The child's next message; raises what it raised, or WorkerLost when it sent nothing."""
    import pickle
    try:
        kind, value = pickle.load(up)
    except EOFError:
        raise WorkerLost("a rapidgen worker process ended without its results") from None
    if kind == "error":
        raise value
    return kind, value
