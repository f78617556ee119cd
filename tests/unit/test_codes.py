"""One registry of diagnostic codes (rapidgen/codes.py, issue 9): the source uses exactly
its codes, with the severities it gives them; the docs' code tables say what it says;
`-W` takes only what it can honour."""
from __future__ import annotations

import re
import typing
from pathlib import Path

import pytest

from rapidgen import codes
from rapidgen.cli import build_parser
from rapidgen.diagnostics import DiagnosticSink, SourceLoc
from tests.helpers import rapidgen

ROOT = Path(__file__).resolve().parents[2]
SOURCE = sorted(p for p in (ROOT / "rapidgen").rglob("*.py") if p.name != "codes.py")
DOCS = ["idl-frontend.md", "asset-descriptor.md", "qos.md", "python-backend.md", "cpp-backend.md", "rust-backend.md", "diff.md", "runtime.md", "secure.md"]
ROW = re.compile(r"^\|\s*(RG\d{4}\S*)\s*\|\s*(.*?)\s*\|\s*$", re.M)
LOC = SourceLoc("t.idl", 1, 1)


def _source_text() -> dict[Path, str]:
    return {p: p.read_text(encoding="utf-8") for p in SOURCE}


def test_every_code_the_source_uses_is_registered_and_every_registered_code_is_used():
    used = {c for text in _source_text().values() for c in re.findall(r"RG\d{4}", text)}
    assert sorted(used - set(codes.REGISTRY)) == []  # reported but not registered
    assert sorted(set(codes.REGISTRY) - used) == []  # registered but dead


def test_registry_entries_are_well_formed():
    assert list(codes.REGISTRY) == sorted(codes.REGISTRY)
    for c in codes.REGISTRY.values():
        assert re.fullmatch(r"RG\d{4}", c.code)
        assert c.severity in typing.get_args(codes.Severity) and c.stage in typing.get_args(codes.Stage)
        assert c.summary and "\n" not in c.summary and not c.summary.endswith(".")


# How a call reports a code: (regex over a whole file, severity of the match)
CALLS = [
    (re.compile(r"\.error\(\s*\"(RG\d{4})\""), "error"),
    (re.compile(r"\._fail\(\s*\"(RG\d{4})\""), "error"),  # idl/consts.py: sink.error, then abandon
    (re.compile(r"\.warning\(\s*\"(RG\d{4})\""), "warning"),
    (re.compile(r"\.report\(\s*E,\s*\"(RG\d{4})\""), "error"),  # writer.py: E = Severity.ERROR
    (re.compile(r"\.report\(\s*W,\s*\"(RG\d{4})\""), "warning"),
    (re.compile(r"\byield\s*\(?\s*\"(RG\d{4})\""), "error"),  # schema translators: reported with sink.error
]


def test_every_call_reports_its_code_with_a_registered_severity():
    seen, wrong = 0, []
    for path, text in _source_text().items():
        for pattern, severity in CALLS:
            for m in pattern.finditer(text):
                seen += 1
                entry = codes.REGISTRY.get(m.group(1))
                if entry is None or not entry.allows(severity):
                    line = text.count("\n", 0, m.start()) + 1
                    wrong.append(f"{path.relative_to(ROOT)}:{line}: {m.group(1)} as {severity}")
    assert seen > 200 and wrong == []


def _doc_rows() -> list[tuple[str, str, str]]:
    rows = []
    for name in DOCS:
        for code, text in ROW.findall((ROOT / "docs" / name).read_text(encoding="utf-8")):
            rows.append((name, code, text))
    return rows


def test_docs_rows_are_single_registered_codes_with_the_registry_text():
    rows = _doc_rows()
    assert rows
    bad = [f"{doc}: {code}" for doc, code, _ in rows if code not in codes.REGISTRY]  # also RG0810-RG0813
    assert bad == []
    differ = [f"{doc}: | {code} | {text} | -- registry: {codes.REGISTRY[code].doc_text}"
              for doc, code, text in rows if text != codes.REGISTRY[code].doc_text]
    assert differ == []


def test_every_registered_code_is_in_exactly_one_docs_row():
    count: dict[str, list[str]] = {}
    for doc, code, _ in _doc_rows():
        count.setdefault(code, []).append(doc)
    missing = sorted(set(codes.REGISTRY) - set(count))
    twice = {code: docs for code, docs in count.items() if len(docs) > 1}
    assert missing == [] and twice == {}


# --- checked as reported (RAPIDGEN_CHECK_CODES=1, set by tests/conftest.py) -------------

def test_the_suite_checks_codes_as_they_are_reported():
    assert codes.checking()


@pytest.mark.parametrize("report", [
    lambda s: s.error("RG9999", "no such code", LOC),
    lambda s: s.warning("RG9999", "no such code", LOC),
    lambda s: s.error("RG0501", "a warning code reported as an error", LOC),
    lambda s: s.warning("RG0203", "an error code reported as a warning", LOC),
    lambda s: s.error("RG1027", "a note code reported as an error", LOC),
])
def test_sink_refuses_unregistered_codes_and_wrong_severities(report):
    with pytest.raises(codes.UnregisteredCode):
        report(DiagnosticSink())


def test_sink_accepts_registered_codes_with_their_severity():
    sink = DiagnosticSink(warnings_as_errors=True)
    sink.error("RG0203", "unknown name", LOC)
    sink.warning("RG0501", "unknown annotation", LOC)  # promoted by -W error: still a warning code
    sink.error("RG0822", "link", LOC)
    sink.warning("RG0822", "stale link", LOC)
    assert len(sink.errors) == 4


# --- -W -------------------------------------------------------------------------------

def _with_W() -> dict[str, list[str]]:
    """Each subcommand taking -W, with the fewest arguments that get it as far as its options."""
    sub = next(a for a in build_parser()._actions if a.dest == "command")
    out = {}
    for name, parser in sub.choices.items():
        if not any("-W" in a.option_strings for a in parser._actions):
            continue
        args: list[str] = []
        for a in parser._actions:
            if not a.option_strings and a.nargs in (None, "+"):
                args.append("x")
            elif a.option_strings and a.required:
                args += [a.option_strings[0], "x"]
        out[name] = args
    return out


SUBCOMMANDS = _with_W()


def test_the_front_end_commands_take_W():
    assert {"ir", "summary", "validate", "describe", "generate", "check", "vectors"} <= set(SUBCOMMANDS)


@pytest.mark.parametrize("command", sorted(SUBCOMMANDS))
@pytest.mark.parametrize("value,message", [
    ("no-RG9999", "unknown diagnostic code 'RG9999'"),
    ("foo", "unknown value 'foo'; expected no-CODE"),
    ("no-RG0402", "RG0402 is an error; only warnings can be silenced"),
    ("no-RG1027", "RG1027 is a note; only warnings can be silenced"),
    ("no-", "unknown diagnostic code ''"),
])
def test_bad_W_values_are_usage_errors(command, value, message, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = rapidgen(command, *SUBCOMMANDS[command], "-W", value)
    assert res.code == 2 and message in res.err and f"rapidgen {command}: error: argument -W" in res.err
    assert res.out == "" and list(tmp_path.iterdir()) == []  # nothing read, nothing written


@pytest.mark.parametrize("value", ["no-RG0501", "no-rg0501", "error", "no-RG0822"])
def test_good_W_values_are_accepted(value, tmp_path):
    (tmp_path / "t.idl").write_text("@unknown_thing struct S { long x; };\n", encoding="utf-8")
    res = rapidgen("ir", str(tmp_path / "t.idl"), "-W", value)
    if value == "error":
        assert res.code == 1 and "error[RG0501]" in res.err
    elif value.lower() == "no-rg0501":
        assert res.code == 0 and res.err == ""
    else:
        assert res.code == 0 and "warning[RG0501]" in res.err
