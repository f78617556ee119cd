"""Speed without a change of output (issue 26): the precompiled templates hold exactly the code
Jinja2 generates from today's sources, a template edited since is compiled from its source,
and `generate`/`check` spread over two processes write what one process writes."""
from __future__ import annotations

import os
import time
import warnings
from pathlib import Path

import pytest

from rapidgen import generate
from rapidgen.backends import templating
from tests.helpers import rapidgen

REPO = Path(__file__).resolve().parents[2]


def test_every_fresh_precompiled_module_is_what_jinja_generates_now():
    behind, extra = templating.stale()
    checked = 0
    for target, name, path in templating._templates():
        if f"{target}/{name}" in behind:
            continue
        module = templating.PRECOMPILED_DIR / f"{templating.module_name(target, name)}.py"
        assert module.read_text(encoding="utf-8") == templating.module_text(target, name, path.read_text("utf-8"))
        checked += 1
    assert checked > 0 and extra == []
    if behind:  # slower, never wrong: the loader compiles these from source
        warnings.warn(f"stale precompiled templates (python -m rapidgen.backends.templating --write): {behind}")


def test_a_changed_source_is_not_taken_from_its_module():
    source = (templating.TEMPLATE_ROOT / "python" / "qos.py.j2").read_text(encoding="utf-8")
    if templating.precompiled_code("python", "qos.py.j2", source) is None:
        pytest.skip("the module is stale here")
    assert templating.precompiled_code("python", "qos.py.j2", source + "{# edited #}") is None
    assert templating.precompiled_code("python", "no-such.j2", source) is None


def test_render_is_the_same_from_source_and_from_the_module(monkeypatch):
    # k10's python and rust files through the modules, then through Jinja2's compiler alone
    root = REPO / "specs" / "assets" / "k10.yaml"
    monkeypatch.chdir(REPO)
    sink = generate.DiagnosticSink()
    inputs = generate.load_inputs([str(root.relative_to(REPO))], [], sink)
    assert inputs is not None
    fast = generate.render(inputs, ["python", "rust", "qos"], sink)
    templating.environment.cache_clear()
    monkeypatch.setattr(templating, "precompiled_code", lambda *a: None)
    try:
        slow = generate.render(inputs, ["python", "rust", "qos"], sink)
    finally:
        templating.environment.cache_clear()
    assert fast == slow and fast


def test_the_module_writer_round_trips(tmp_path):
    root = tmp_path / "templates" / "demo"
    root.mkdir(parents=True)
    (root / "a.txt.j2").write_text("{% for x in xs %}{{ x }}\n{% endfor %}", encoding="utf-8")
    out = tmp_path / "precompiled"
    assert templating.write(tmp_path / "templates", out) == ["demo__a_txt_j2.py"]
    assert templating.stale(tmp_path / "templates", out) == ([], [])
    assert templating.write(tmp_path / "templates", out) == []  # unchanged: nothing written
    (root / "a.txt.j2").write_text("changed", encoding="utf-8")
    assert templating.stale(tmp_path / "templates", out) == (["demo/a.txt.j2"], [])


def _tree(folder: Path) -> dict[str, bytes]:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.mark.skipif(generate.jobs() < 2, reason="one process here (one CPU, no fork, or threads running)")
def test_shared_work_runs_in_two_processes_and_keeps_order():
    def work(i: int) -> tuple[int, int]:
        time.sleep(0.05)  # long enough for both processes to take jobs
        return i * i, os.getpid()

    got = generate._share(6, work)
    assert [v for v, _ in got] == [0, 1, 4, 9, 16, 25]
    assert len({pid for _, pid in got}) == 2 and os.getpid() in {pid for _, pid in got}
    dealt = generate._share(5, work, alternate=True)  # generate's targets: in turn
    assert [v for v, _ in dealt] == [0, 1, 4, 9, 16]
    assert [pid == os.getpid() for _, pid in dealt] == [True, False, True, False, True]


def test_an_error_in_shared_work_reaches_the_caller():
    def work(i: int) -> int:
        if i == 3:
            raise ValueError("job 3")
        return i

    for alternate in (False, True):
        with pytest.raises(ValueError, match="job 3"):
            generate._share(5, work, alternate)


def test_one_process_and_two_write_the_same_files(tmp_path, monkeypatch):
    monkeypatch.chdir(REPO)
    for jobs in ("1", "2"):
        monkeypatch.setenv("RAPIDGEN_JOBS", jobs)
        res = rapidgen("generate", "specs/assets/k10.yaml", "--lang", "python,cpp,rust,qos",
                       "-o", str(tmp_path / jobs))
        assert res.code == 0, res.err
    assert _tree(tmp_path / "1") == _tree(tmp_path / "2") and _tree(tmp_path / "1")
