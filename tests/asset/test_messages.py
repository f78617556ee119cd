"""Diagnostics that must lead the user to the fix, not to a second error (issue 9).

Each case writes its own descriptor and checks what the message and hint say: plain
words for indentation with both lines named, one error for one mistake, hints listing
the real choices, and a hint that, when followed, makes the descriptor valid.
"""
from __future__ import annotations

import re

import pytest

from rapidgen.asset import load_asset
from rapidgen.asset.facts import STATIC_SHAPES
from rapidgen.yamlread import parse_yaml
from rapidgen.diagnostics import DiagnosticSink

HEAD = "version: 1\nasset: {name: Probe, kind: rover}\n"


def diagnose(tmp_path, text: str) -> list:
    path = tmp_path / "asset.yaml"
    path.write_text(text, encoding="utf-8")
    sink = DiagnosticSink()
    load_asset(str(path), sink)
    return sink.diagnostics


def command(params: str, subsystems: str = "[{name: Arm1, type: Arm}]") -> str:
    return (HEAD + "subsystem_types:\n  - name: Arm\n    commands:\n      - name: move\n"
            f"        parameters:\n{params}subsystems: {subsystems}\n")


# -- 1. indentation ----------------------------------------------------------------------
# (text, line where the block starts or the line above, offending line)
INDENTS = {
    "deeper than the key above": ("a:\n  name: Probe\n   kind: rover\n", 2, 3),
    "between two levels": ("version: 1\nasset:\n  name: Probe\n kind: rover\n", 1, 4),
    "inside a nested mapping": ("a:\n  b:\n    c: 1\n   d: 2\n", 2, 4),
    "list item out of line": ("a:\n  - x: 1\n    y: 2\n   - z: 3\n", 2, 4),
    "key at the dash of a list": ("types:\n  - name: Arm\n  commands:\n    - move\n", 2, 3),
    "list item among keys": ("a:\n  b: 1\n  - c\n", 2, 3),
    "after a comment": ("a:\n  b: 1\n  # note\n   c: 2\n", 2, 4),
}


@pytest.mark.parametrize("name", INDENTS)
def test_indentation_error_says_so_and_names_both_lines(name):
    text, block, bad = INDENTS[name]
    sink = DiagnosticSink()
    assert parse_yaml(text, "x.yaml", sink) is None
    [d] = sink.diagnostics
    said = f"{d.message} {d.hint}"
    assert d.code == "RG1010" and "indentation" in d.message
    assert d.loc.line == bad and re.search(rf"\bline {block}\b", said) and re.search(rf"\bline {bad}\b", said)
    assert "<block" not in said and "not allowed here" not in said  # no parser jargon
    # the caret is at the first character of the offending line
    assert d.loc.col == len(text.splitlines()[bad - 1]) - len(text.splitlines()[bad - 1].lstrip()) + 1


@pytest.mark.parametrize("text", ["a: b: c\n", "a: {b: 1\nc: 2\n"])
def test_other_syntax_errors_do_not_blame_indentation(text):
    sink = DiagnosticSink()
    assert parse_yaml(text, "x.yaml", sink) is None
    [d] = sink.diagnostics
    assert d.code == "RG1010" and "indentation" not in d.message


# -- 2. reversed range -------------------------------------------------------------------
def test_reversed_range_is_one_error_not_also_default_and_threshold(tmp_path):
    diags = diagnose(tmp_path, command(
        "          - {name: angle, type: RAPID_FLOAT, range: [90, -90], default: 0}\n")
        + "telemetry:\n  - kind: agent\n    values:\n"
        "      - {key: temp, type: RAPID_FLOAT, min: 80, max: -40, default: 20,"
        " warning: {above: 60, below: 10}}\n")
    assert [d.code for d in diags] == ["RG1203", "RG1203"], diags


def test_default_outside_a_proper_range_is_still_reported(tmp_path):
    diags = diagnose(tmp_path, command("          - {name: angle, type: RAPID_FLOAT, range: [-90, 90], default: 100}\n"))
    assert [d.code for d in diags] == ["RG1204"], diags


# -- 3. unknown DataType -----------------------------------------------------------------
@pytest.mark.parametrize("written, close", [("RAPID_VEC3", "RAPID_VEC3d"), ("quaternion", None)])
def test_unknown_datatype_lists_every_datatype(tmp_path, written, close):
    [d] = diagnose(tmp_path, command(f"          - {{name: p, type: {written}}}\n"))
    assert d.code == "RG1201"
    if close:
        assert d.hint.startswith(f"did you mean '{close}'?")
    for name in STATIC_SHAPES:
        assert name in d.hint


# -- 4. allowed on a number --------------------------------------------------------------
def test_numeric_allowed_list_is_not_told_to_quote(tmp_path):
    diags = diagnose(tmp_path, command("          - {name: gear, type: RAPID_INT, allowed: [1, 2]}\n"))
    assert diags and all(d.code == "RG1022" for d in diags)
    for d in diags:
        assert "quote" not in d.hint and "range" in d.hint and "RAPID_STRING" in d.hint
    # what "quote it" would have led to: a second error
    quoted = diagnose(tmp_path, command("          - {name: gear, type: RAPID_INT, allowed: ['1', '2']}\n"))
    assert [d.code for d in quoted] == ["RG1205"]


def test_string_allowed_list_is_still_told_to_quote(tmp_path):
    [d] = diagnose(tmp_path, command("          - {name: mode, type: RAPID_STRING, allowed: [eco, 3]}\n"))
    assert d.hint == "quote it: '3'"


# -- 5. comma in a flow mapping ----------------------------------------------------------
def test_comma_in_flow_value_hints_quoting_and_the_hint_works(tmp_path):
    text = HEAD + ("subsystem_types:\n  - name: Pump\n    commands:\n"
                   "      - {name: prime, description: two modules, 12 nozzles}\n"
                   "subsystems: [{name: Pump1, type: Pump}]\n")
    [d] = diagnose(tmp_path, text)
    assert d.code == "RG1021" and "comma" in d.hint and "quote" in d.hint and "'description'" in d.hint
    fix = re.search(r'\((description: "[^"]*")\)', d.hint).group(1)
    assert diagnose(tmp_path, text.replace("description: two modules, 12 nozzles", fix)) == []


@pytest.mark.parametrize("entry, hint", [
    ("{name: flush, descripton: all}", "did you mean 'description'?"),  # a typo, not a comma
    ("{name: '1', abortible}", "did you mean 'abortable'?"),
])
def test_other_unknown_flow_keys_keep_their_hint(tmp_path, entry, hint):
    [d] = diagnose(tmp_path, HEAD + f"subsystem_types:\n  - name: Pump\n    commands:\n      - {entry}\n"
                   "subsystems: [{name: Pump1, type: Pump}]\n")
    assert d.code == "RG1021" and d.hint == hint


# -- 6. subsystem lists in descriptor order ----------------------------------------------
def test_subsystem_hints_follow_the_descriptor_order(tmp_path):
    diags = diagnose(tmp_path, HEAD + (
        "subsystem_types:\n  - name: Arm\n    commands: [{name: move}]\n"
        "subsystems: [{name: Zeta, type: Arm}, {name: Alpha, type: Arm}, {name: Mid, type: Arm}]\n"
        "telemetry:\n  - {kind: text, subsystem: Wheel}\n"
        "access_control:\n  sources:\n    - {source: Cockpit, allow: ['Wheel/*']}\n"))
    assert [d.code for d in diags] == ["RG1103", "RG1103"]
    assert [d.hint for d in diags] == ["subsystems: Zeta, Alpha, Mid"] * 2
