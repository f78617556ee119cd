"""`generate` and `check` over processes (rapidgen.fork_ahead) write what one process writes:
the worker forked ahead of the front end, the fallback for a large model, and errors,
interrupts and a lost worker on the way. The model handed over (rapidgen.model.pickling)
is the same model.

Run by test_fork_ahead.py in a fresh interpreter: fork_ahead forks only a process that runs
no other thread, and a test run's worker may still hold one another test started."""
from __future__ import annotations

import os
import pickle
import time
from pathlib import Path

import pytest

from rapidgen import fork_ahead
from rapidgen.diagnostics import DiagnosticSink
from rapidgen.generate import generate_command, load_inputs
from rapidgen.model import ir, pickling
from tests.helpers import rapidgen

REPO = Path(__file__).resolve().parents[2]
TWO = pytest.mark.skipif(fork_ahead.jobs() < 2, reason="one process here (one CPU, no fork, or threads running)")
LANGS = ["python", "cpp", "rust", "qos"]


def _tree(folder: Path) -> dict[str, bytes]:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.fixture
def forks(monkeypatch) -> list[int]:
    """The processes this process forks during the test."""
    pids: list[int] = []
    real = os.fork

    def fork() -> int:
        pid = real()
        if pid:
            pids.append(pid)
        return pid
    monkeypatch.setattr(os, "fork", fork)
    return pids


def _all_reaped(pids: list[int]) -> bool:
    for pid in pids:
        try:
            os.waitpid(pid, os.WNOHANG)
        except ChildProcessError:  # reaped already
            continue
        return False
    return True


@pytest.mark.skipif(fork_ahead.jobs() < 2, reason="one process here (one CPU, no fork, or threads running)")
def test_shared_work_runs_in_two_processes_and_keeps_order():
    def work(i: int) -> tuple[int, int]:
        time.sleep(0.05)  # long enough for both processes to take jobs
        return i * i, os.getpid()

    got = fork_ahead.share(6, work)
    assert [v for v, _ in got] == [0, 1, 4, 9, 16, 25]
    assert len({pid for _, pid in got}) == 2 and os.getpid() in {pid for _, pid in got}
    dealt = fork_ahead.share(5, work, alternate=True)  # generate's targets: in turn
    assert [v for v, _ in dealt] == [0, 1, 4, 9, 16]
    assert [pid == os.getpid() for _, pid in dealt] == [True, False, True, False, True]


def test_an_error_in_shared_work_reaches_the_caller():
    def work(i: int) -> int:
        if i == 3:
            raise ValueError("job 3")
        return i

    for alternate in (False, True):
        with pytest.raises(ValueError, match="job 3"):
            fork_ahead.share(5, work, alternate)


def test_one_process_and_two_write_the_same_files(tmp_path, monkeypatch):
    monkeypatch.chdir(REPO)
    for jobs in ("1", "2"):
        monkeypatch.setenv("RAPIDGEN_JOBS", jobs)
        res = rapidgen("generate", "specs/assets/k10.yaml", "--lang", "python,cpp,rust,qos",
                       "-o", str(tmp_path / jobs))
        assert res.code == 0, res.err
    assert _tree(tmp_path / "1") == _tree(tmp_path / "2") and _tree(tmp_path / "1")


@pytest.mark.parametrize("source", ["specs/assets/k10.yaml", "specs/assets/robonaut2.yaml",
                                    "specs/rapid/PositionSample.idl"])
def test_the_handed_over_model_is_the_same_model(source, monkeypatch):
    monkeypatch.chdir(REPO)
    inputs = load_inputs([source], ["specs/rapid"], DiagnosticSink())
    assert inputs is not None
    data = pickling.dumps(inputs)
    back = pickle.loads(data)
    assert back.model == inputs.model and back.source == inputs.source
    assert [type(d) for d in back.model.declarations] == [type(d) for d in inputs.model.declarations]
    assert back.model.get(inputs.model.declarations[-1].scoped_name) is not None  # the lookup rebuilt
    struct = next(d for d in back.model.declarations if isinstance(d, ir.Struct))
    assert struct.kind == "struct" and struct.loc == next(
        d for d in inputs.model.declarations if d.scoped_name == struct.scoped_name).loc
    # each IR object goes as its constructor's call, not through dataclasses' __getstate__
    assert b"_dataclass_setstate" not in data and len(data) < len(pickle.dumps(inputs, protocol=5))


def _generate(paths: list[str], out: Path, langs: list[str] = LANGS) -> tuple[bool, DiagnosticSink]:
    sink = DiagnosticSink()
    ok = generate_command(paths, [], {}, langs, str(out), None, sink)
    return ok, sink


@TWO
def test_a_large_model_is_rendered_here_and_the_worker_ends(tmp_path, monkeypatch, capsys, forks):
    monkeypatch.chdir(REPO)
    handed = []
    real = fork_ahead.Ahead.hand_over
    monkeypatch.setattr(fork_ahead.Ahead, "hand_over", lambda self, *a: handed.append(1) or real(self, *a))
    monkeypatch.setattr(fork_ahead.Ahead, "MAX_DECLARATIONS", 0)  # every model counts as large
    assert _generate(["specs/assets/k10.yaml"], tmp_path / "here")[0]
    assert handed == [] and len(forks) == 2 and _all_reaped(forks)  # the worker (stopped), the child
    monkeypatch.setattr(fork_ahead.Ahead, "MAX_DECLARATIONS", 10_000)
    assert _generate(["specs/assets/k10.yaml"], tmp_path / "worker")[0]
    assert handed == [1] and _all_reaped(forks)
    forked = []
    enter = fork_ahead.Ahead.__enter__
    monkeypatch.setattr(fork_ahead.Ahead, "__enter__", lambda self: forked.append(1) or enter(self))
    monkeypatch.setattr(fork_ahead.Ahead, "MAX_INPUT_BYTES", 10)  # large files: no worker at all
    assert _generate(["specs/assets/k10.yaml"], tmp_path / "none")[0]
    assert forked == [] and handed == [1] and _all_reaped(forks)
    monkeypatch.setenv("RAPIDGEN_JOBS", "1")
    assert _generate(["specs/assets/k10.yaml"], tmp_path / "one")[0]
    one = _tree(tmp_path / "one")
    assert one and _tree(tmp_path / "here") == one and _tree(tmp_path / "worker") == one
    assert _tree(tmp_path / "none") == one
    printed = capsys.readouterr().out.splitlines()
    assert [line.split(": ", 1)[1] for line in printed[:4]] == [line.split(": ", 1)[1] for line in printed[12:]]


@TWO
def test_an_input_error_stops_the_worker_and_writes_nothing(tmp_path, forks):
    bad = tmp_path / "bad.idl"
    bad.write_text("module m { struct S { long x } ; };\n", encoding="utf-8")
    ok, sink = _generate([str(bad)], tmp_path / "out")
    assert not ok and [d.code for d in sink.diagnostics] == ["RG0201"]
    assert sink.diagnostics[0].loc.line == 1
    assert len(forks) == 1 and _all_reaped(forks)  # the worker, stopped
    assert not (tmp_path / "out").exists()


@TWO
def test_a_worker_lost_before_the_hand_over_leaves_the_work_here(tmp_path, monkeypatch, forks):
    monkeypatch.chdir(REPO)
    monkeypatch.setattr(fork_ahead, "prepare", lambda *a, **k: os._exit(9))  # the worker dies at once
    assert _generate(["specs/assets/k10.yaml"], tmp_path / "out")[0]
    monkeypatch.setenv("RAPIDGEN_JOBS", "1")
    assert _generate(["specs/assets/k10.yaml"], tmp_path / "one")[0]
    assert _tree(tmp_path / "out") == _tree(tmp_path / "one") and _all_reaped(forks)


def _in_the_worker_only(monkeypatch, what) -> None:
    """generate_in_two runs `what()` instead in a forked worker; in this process, as it is."""
    here, real = os.getpid(), fork_ahead.generate_in_two

    def patched(*a):
        return what() if os.getpid() != here else real(*a)
    monkeypatch.setattr(fork_ahead, "generate_in_two", patched)


@TWO
def test_a_worker_lost_after_the_hand_over_leaves_the_work_here(tmp_path, monkeypatch, forks):
    monkeypatch.chdir(REPO)
    _in_the_worker_only(monkeypatch, lambda: os._exit(9))  # the worker dies with the inputs
    handed: list = []
    hand_over = fork_ahead.Ahead.hand_over
    monkeypatch.setattr(fork_ahead.Ahead, "hand_over", lambda self, *a: handed.append(hand_over(self, *a)) or handed[-1])
    assert _generate(["specs/assets/k10.yaml"], tmp_path / "out")[0]
    assert handed == [None] and _all_reaped(forks)  # lost: rendered and written here
    monkeypatch.setenv("RAPIDGEN_JOBS", "1")
    assert _generate(["specs/assets/k10.yaml"], tmp_path / "one")[0]
    assert _tree(tmp_path / "out") == _tree(tmp_path / "one") and _tree(tmp_path / "one")


@TWO
def test_an_error_in_the_worker_is_an_internal_error_here(tmp_path, monkeypatch, forks):
    monkeypatch.chdir(REPO)

    def boom():
        raise RuntimeError("boom in the worker")
    _in_the_worker_only(monkeypatch, boom)
    with pytest.raises(RuntimeError, match="boom in the worker"):
        _generate(["specs/assets/k10.yaml"], tmp_path / "out")
    assert not (tmp_path / "out").exists() and _all_reaped(forks)
    res = rapidgen("generate", "specs/assets/k10.yaml", "--lang", "python,cpp", "-o", str(tmp_path / "cli"))
    assert res.code == 3 and "internal error" in res.err and "boom in the worker" in res.err


@TWO
def test_a_refused_target_in_the_worker_is_reported_here(tmp_path, monkeypatch, forks):
    from rapidgen.backends import rust
    from rapidgen.diagnostics import SourceLoc

    monkeypatch.chdir(REPO)

    def refuse(*a, **k):
        raise rust.UnsupportedInput([("no rust today", SourceLoc("specs/assets/k10.yaml", 1, 1))])
    monkeypatch.setattr(rust, "generate", refuse)
    ok, sink = _generate(["specs/assets/k10.yaml"], tmp_path / "out")
    assert not ok and any("no rust today" in d.message for d in sink.diagnostics)
    assert not (tmp_path / "out").exists() and _all_reaped(forks)


def test_prepare_loads_the_templates_until_the_inputs_arrive():
    from rapidgen.backends import templating

    names = templating.names("qos")
    assert "fastdds.xml.j2" in names and all(n.endswith(".j2") for n in names)
    read, write = os.pipe()
    with os.fdopen(read, "rb") as until, os.fdopen(write, "wb") as arrived:
        templating.environment.cache_clear()
        fork_ahead.prepare(["qos"], until=until)
        assert len(templating.environment("qos").cache or {}) == len(names)  # nothing to read: all
        arrived.write(b"x")
        arrived.flush()
        templating.environment.cache_clear()
        fork_ahead.prepare(["qos"], until=until)
        assert len(templating.environment("qos").cache or {}) == 0  # the inputs came first
    templating.environment.cache_clear()
