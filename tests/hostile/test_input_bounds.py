"""Hostile descriptors, project files, QoS libraries and IDL end as located diagnostics
(exit 1, code and file:line:col, no traceback) inside a bounded child process: issue 8,
items 3 (loader), 7, 8 and 12. Every hostile input is made here."""
from __future__ import annotations

import json
import re

import pytest

from tests.hostile.limits import run_python, run_rapidgen

MEM, CPU = 1024, 20  # MiB of address space, CPU seconds: a fence, never a timing assertion

DESCRIPTOR = """version: 1
asset:
  name: Bot
  kind: rover
  description: {description}
dds:
  domain: 0
  partition: {partition}
"""


def located(res, file: str, code: str) -> re.Match:
    """The run ended with a located error of `code` in `file`, cleanly."""
    assert not res.killed, f"killed by signal {-res.code}: {res.err[-500:]}"
    assert res.code == 1, res.err[-2000:]
    assert "Traceback" not in res.err and "internal error" not in res.err
    m = re.search(rf"^{re.escape(file)}:(\d+):(\d+): error\[{code}\]: (.*)$", res.err, re.M)
    assert m, res.err[-2000:]
    return m


def descriptor(tmp_path, partition: str, description: str = "a rover") -> str:
    # json.dumps writes a YAML double-quoted scalar with the \\uXXXX escapes the attack uses
    text = DESCRIPTOR.format(partition=json.dumps(partition), description=json.dumps(description))
    (tmp_path / "bot.yaml").write_text(text, encoding="utf-8", errors="surrogatepass")
    return "bot.yaml"


# -- 3: control characters, noncharacters and surrogates -----------------------------------

@pytest.mark.parametrize("partition", ["\0", "\x01a\x01", "a\ufffeb", "\ud800", "\x7f", "x\x85",
                                       "\ufdd0", "\U0010ffff", "a\tb", "a\nb"])
def test_bad_characters_in_a_value_are_refused_at_the_scalar(tmp_path, partition):
    name = descriptor(tmp_path, partition)
    res = run_rapidgen("generate", name, "--lang", "qos", "-o", "out", cwd=tmp_path, mem_mib=MEM, cpu_s=CPU)
    m = located(res, name, "RG1014")
    assert (m[1], m[2]) == ("8", "14")  # the partition's scalar
    assert m[3].startswith("dds.partition holds ")
    assert "= hint:" in res.err or "^ " in res.err  # a hint is printed
    assert not (tmp_path / "out").exists()


def test_tabs_and_line_breaks_are_text_in_descriptions_only(tmp_path):
    ok = descriptor(tmp_path, "Bot", description="two\tcolumns\nand lines")
    assert run_rapidgen("validate", ok, cwd=tmp_path, mem_mib=MEM, cpu_s=CPU).code == 0
    bad = descriptor(tmp_path, "Bot", description="bell\x07")
    located(run_rapidgen("validate", bad, cwd=tmp_path, mem_mib=MEM, cpu_s=CPU), bad, "RG1014")


def test_bad_characters_in_a_key_are_refused(tmp_path):
    (tmp_path / "bot.yaml").write_text(DESCRIPTOR.format(partition="Bot", description="x")
                                       + '  "\\x1b[2J": 1\n')
    res = run_rapidgen("validate", "bot.yaml", cwd=tmp_path, mem_mib=MEM, cpu_s=CPU)
    m = located(res, "bot.yaml", "RG1014")
    assert (m[1], m[2]) == ("9", "3") and m[3].startswith("a key in dds holds a control character (U+001B)")


def test_the_qos_library_loader_refuses_them_too(tmp_path):
    (tmp_path / "q.yaml").write_text('version: 1\nlibrary: site\npartition: "a\\ud800"\n')
    res = run_python("from rapidgen.diagnostics import DiagnosticSink\n"
                     "from rapidgen.qos import load_qos\n"
                     "sink = DiagnosticSink()\n"
                     "assert load_qos('q.yaml', sink) is None\n"
                     "print('\\n'.join(f'{d.loc.file}:{d.loc.line}:{d.loc.col}: {d.code}' for d in sink.errors))\n",
                     cwd=tmp_path, mem_mib=MEM, cpu_s=CPU)
    assert res.code == 0, res.err
    assert "q.yaml:3:12: RG1014" in res.out.splitlines()


def test_the_project_file_refuses_them_too(tmp_path):
    (tmp_path / "rapidgen.yaml").write_text(
        'targets:\n  - name: "s\\0"\n    idl: [a.idl]\n    lang: [python]\n    out: gen\n')
    m = located(run_rapidgen("check", cwd=tmp_path, mem_mib=MEM, cpu_s=CPU), "rapidgen.yaml", "RG1014")
    assert (m[1], m[2]) == ("2", "11")


# -- 7: the project file: alias bombs, floods of schema errors --------------------------------

def test_project_file_alias_bomb_is_a_located_error(tmp_path):
    # 9 lines expanding to 10^8 values (2 GB and 1 GB of error text before the fix)
    lines = ["a: &a [x, x, x, x, x, x, x, x, x, x]"]
    for prev, name in zip("abcdefg", "bcdefgh"):
        lines.append(f"{name}: &{name} [" + ", ".join([f"*{prev}"] * 10) + "]")
    lines.append("targets: [*h]")
    (tmp_path / "rapidgen.yaml").write_text("\n".join(lines) + "\n")
    res = run_rapidgen("check", cwd=tmp_path, mem_mib=MEM, cpu_s=CPU)
    m = located(res, "rapidgen.yaml", "RG1012")
    assert "expands to more than 200000 values" in m[3]
    assert len(res.err) < 2000


def test_project_file_schema_errors_are_capped(tmp_path):
    (tmp_path / "rapidgen.yaml").write_text("targets:\n" + "  - 1\n" * 20000)
    res = run_rapidgen("check", cwd=tmp_path, mem_mib=MEM, cpu_s=CPU)
    m = located(res, "rapidgen.yaml", "RG0812")
    assert (m[1], m[2]) == ("2", "5")  # document order: the first item first
    assert res.err.count("error[RG0812]") == 50
    assert re.search(r"^rapidgen\.yaml:\d+:\d+: note\[RG0812\]: 39950 more schema errors not shown$",
                     res.err, re.M)
    assert len(res.err) < 20_000


def test_descriptor_schema_errors_are_capped(tmp_path):
    keys = "".join(f"k{i}{'x' * 200}: 1\n" for i in range(5000))
    (tmp_path / "bot.yaml").write_text(DESCRIPTOR.format(partition="Bot", description="x") + keys)
    res = run_rapidgen("validate", "bot.yaml", cwd=tmp_path, mem_mib=MEM, cpu_s=CPU)
    located(res, "bot.yaml", "RG1021")
    assert res.err.count("error[RG1021]") == 50 and "note[RG1027]: 4950 more schema errors not shown" in res.err
    assert "x" * 60 not in res.err.split("\n", 1)[0]  # long keys are cut in messages


# -- 8: a large descriptor without aliases ------------------------------------------------------

def test_large_descriptor_stops_while_parsing_and_says_why(tmp_path):
    # 8 MiB less a little: a flat list of 4 million numbers (155 s and 2.6 GB before the fix)
    n = (8 * 1024 * 1024 - 64) // 2
    (tmp_path / "big.yaml").write_text("version: 1\nx: [" + "0," * n + "0]\n")
    res = run_rapidgen("validate", "big.yaml", cwd=tmp_path, mem_mib=MEM, cpu_s=CPU)
    m = located(res, "big.yaml", "RG1012")
    assert m[3] == "the document has more than 200000 YAML values"
    assert "alias" not in res.err


def test_deep_nesting_stops_while_parsing(tmp_path):
    (tmp_path / "deep.yaml").write_text("version: 1\nx: " + "[" * 100_000 + "]" * 100_000 + "\n")
    res = run_rapidgen("validate", "deep.yaml", cwd=tmp_path, mem_mib=MEM, cpu_s=CPU)
    m = located(res, "deep.yaml", "RG1012")
    assert m[3] == "YAML nesting deeper than 64 levels"


# -- 12: vectors of a string bounded to 2^32 - 1 ---------------------------------------------

def test_vectors_refuse_a_huge_string_bound_at_the_member(tmp_path):
    (tmp_path / "s.idl").write_text("module m {\n  struct S {\n    long id;\n    string<4294967295> text;\n  };\n};\n")
    res = run_rapidgen("vectors", "s.idl", "-o", "v.json", cwd=tmp_path, mem_mib=MEM, cpu_s=CPU)
    m = located(res, "s.idl", "RG0903")
    assert (m[1], m[2]) == ("4", "24") and "string bounded to 4294967295 characters" in m[3]
    assert not (tmp_path / "v.json").exists()


def test_vectors_refuse_many_copies_of_a_large_string(tmp_path):
    (tmp_path / "s.idl").write_text("struct S { string<65536> names[1024]; };\n")
    res = run_rapidgen("vectors", "s.idl", "-o", "v.json", cwd=tmp_path, mem_mib=MEM, cpu_s=CPU)
    m = located(res, "s.idl", "RG0903")
    assert "(1024 of them in an array)" in m[3]
