"""The parser keeps no state between calls (issue 9, defect 6): each parse has its own
syntax-tree builder, so parses nest and run in threads, and a finished parse leaves
nothing of its input reachable from the module."""
from __future__ import annotations

import gc
import sys
import threading
import weakref

from rapidgen.diagnostics import DiagnosticSink
from rapidgen.idl import parse as parse_mod
from rapidgen.idl.parse import parse
from rapidgen.idl.preprocess import preprocess

HUGE = "1" * 60  # an integer literal over 40 digits: the builder reports RG0402 while it reduces


def _pre(tmp_path, name: str, body: str):
    path = tmp_path / name
    path.write_text(body, encoding="utf-8")
    sink = DiagnosticSink()
    pre = preprocess([str(path)], [], sink)
    assert not sink.diagnostics
    return pre


def _files(spec) -> set[str]:
    return {d.loc.file.rsplit("/", 1)[-1] for d in spec.definitions}


def test_a_parse_nested_in_another_keeps_each_its_own_file_and_sink(tmp_path):
    outer = _pre(tmp_path, "outer.idl", f"const long long A = {HUGE};\nstruct Outer {{ long x; }};\n"
                                        "struct Outer2 { long y; };\n")
    inner = _pre(tmp_path, "inner.idl", f"struct Inner {{ long z; }};\nconst long long B = {HUGE};\n")
    inner_sink = DiagnosticSink()
    nested: list = []

    class NestingSink(DiagnosticSink):
        """Starts a second parse from inside the first one's builder (at the RG0402 of A)."""

        def error(self, code, message, loc, hint=None):
            super().error(code, message, loc, hint)
            if not nested:
                nested.append(parse(inner, inner_sink))

    outer_sink = NestingSink()
    spec = parse(outer, outer_sink)
    assert spec is not None and nested[0] is not None
    assert _files(spec) == {"outer.idl"} and _files(nested[0]) == {"inner.idl"}
    assert [d.name for d in spec.definitions] == ["A", "Outer", "Outer2"]
    # each literal error in the sink of its own parse, at its own file
    assert [(d.code, d.loc.file.rsplit("/", 1)[-1], d.loc.line) for d in outer_sink.diagnostics] == \
        [("RG0402", "outer.idl", 1)]
    assert [(d.code, d.loc.file.rsplit("/", 1)[-1], d.loc.line) for d in inner_sink.diagnostics] == \
        [("RG0402", "inner.idl", 2)]


def test_parses_in_threads_get_their_own_results(tmp_path):
    old = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)  # switch threads as often as possible, inside parses
    try:
        inputs = []
        for t in range(4):
            body = "".join(f"struct S{t}_{i} {{ long a; //@key\n double b; }};\n" for i in range(150))
            inputs.append(_pre(tmp_path, f"t{t}.idl", body + f"const long long Big{t} = {HUGE};\n"))
        results: dict[int, tuple] = {}

        def work(t: int) -> None:
            for _ in range(3):
                sink = DiagnosticSink()
                spec = parse(inputs[t], sink)
                results[t] = (spec, sink)

        threads = [threading.Thread(target=work, args=(t,)) for t in range(4)]
        for th in threads:
            th.start()
        for th in threads:
            th.join()
    finally:
        sys.setswitchinterval(old)
    for t, (spec, sink) in results.items():
        assert _files(spec) == {f"t{t}.idl"}
        structs = [d for d in spec.definitions if d.name.startswith("S")]
        assert [d.name for d in structs] == [f"S{t}_{i}" for i in range(150)]
        # //@key marks the first member: the key comments of this input, not another's
        assert all(d.members[0].key_comment and not d.members[1].key_comment for d in structs)
        assert [(d.code, d.loc.file.rsplit("/", 1)[-1]) for d in sink.diagnostics] == [("RG0402", f"t{t}.idl")]


def test_a_finished_parse_leaves_nothing_of_its_input_alive(tmp_path):
    pre = _pre(tmp_path, "gone.idl", f"const long long A = {HUGE};\nstruct Gone {{ long x; }};\n")
    sink = DiagnosticSink()
    spec = parse(pre, sink)
    assert spec is not None and sink.has_errors
    refs = [weakref.ref(sink), weakref.ref(pre)]
    del pre, sink, spec
    gc.collect()
    assert [r() for r in refs] == [None, None]
    # and the cached parser objects hold no builder of a parse
    held = gc.get_referents(parse_mod._lean()) + gc.get_referents(parse_mod._lean().rules)
    assert not any(isinstance(o, parse_mod._ToAst) for o in held)


def test_the_builder_has_no_terminal_callbacks():
    """The lean driver calls rule callbacks only; a method named after a terminal would be skipped."""
    terminals = {t.name for t in parse_mod.grammar.lark_parser().terminals}
    assert terminals and not terminals & set(dir(parse_mod._ToAst))
