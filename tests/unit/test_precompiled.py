"""Speed without a change of output (issue 26): the precompiled templates hold exactly the code
Jinja2 generates from today's sources, a template edited since is compiled from its source,
and (tests/unit/test_fork_ahead.py) `generate`/`check` spread over processes write what one
process writes."""
from __future__ import annotations

from pathlib import Path

import pytest

from rapidgen import generate
from rapidgen.backends import templating

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
    # (a stale module is slower, never wrong: the loader compiles its template from source; but
    # the modules are committed output, and committed output is kept fresh)
    assert behind == [], f"stale precompiled templates (python -m rapidgen.backends.templating --write): {behind}"


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
