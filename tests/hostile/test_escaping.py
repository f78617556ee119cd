"""Issue 8, items 1 and 3: every input string reaches generated files escaped for their format.

The escape functions (rapidgen/backends/escape.py) are checked against the parsers of
their formats; then arbitrary text is fed into IDL file names, identifiers, string
constants and annotation values, and into every string field of a descriptor: generation
either stops with a located diagnostic or writes files that all parse, whose constants
hold the input exactly, and whose import has no side effect.
"""
from __future__ import annotations

import ast
import atexit
import copy
import dataclasses
import json
import os
import re
import shutil
import tempfile
import tomllib
import xml.dom.minidom
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from rapidgen import backends
from rapidgen.asset.describe import describe
from rapidgen.backends import escape
from rapidgen.backends.base import Options, UnwritableCharacter
from rapidgen.diagnostics import DiagnosticSink
from rapidgen.qos.spec import default_library
from tests.helpers import rapidgen
from tests.hostile.limits import run_python

ROOT = Path(__file__).resolve().parents[2]
RAPID = str(ROOT / "specs" / "rapid")
FAST = settings(max_examples=300, deadline=None)
GENERATE = settings(max_examples=100, deadline=None, suppress_health_check=list(HealthCheck))
PAYLOAD = '""";open("pwned","w");"""'

# Text with what breaks each format: quotes, backslashes, newlines, comment/CDATA/markup
# ends, template syntax, control characters, surrogates, noncharacters, non-BMP.
tricky = st.sampled_from(['"""', "'''", '"', "'", "\\", "\n", "\r", "\r\n", "]]>", "</", "-->", "--", "${",
                          "{{", "#", "\x00", "\x1b[31m", "\x7f", "\x85", "\u2028", "\ud800", "\udfff",
                          "\ufffe", "\uffff", "\U0001f600", "coding:utf-16", PAYLOAD, "&amp;", "<![CDATA["])
texts = st.lists(st.one_of(st.text(max_size=8), tricky), max_size=6).map("".join)
# What descriptor loaders accept (no controls, surrogates, noncharacters), still hostile.
printable = st.lists(st.one_of(st.text(st.characters(blacklist_categories=("Cc", "Cs", "Cn")), max_size=8),
                               st.sampled_from(['"""', "'", "\\", "]]>", "</", "-->", "${", "{{", "#", PAYLOAD,
                                                "\U0001f600", "coding:utf-16", "&amp;", "<![CDATA["])),
                     min_size=1, max_size=6).map("".join)


# -- the escape functions against their formats' parsers ------------------------------------
@FAST
@given(texts)
def test_python_literals_and_docstrings_round_trip(text):
    assert ast.literal_eval(escape.py_str(text)) == text
    assert escape.py_str(text).isascii()
    doc = escape.py_docstring(text)
    assert ast.literal_eval(f'"""{doc}"""') == text
    module = ast.parse(f'"""{doc}"""\n'.encode("utf-8", "surrogatepass"))
    assert len(module.body) == 1


@FAST
@given(texts)
def test_comments_stay_one_comment(text):
    line = escape.line_comment(text)
    assert line.isprintable() and not re.search(r"coding[:=]", line)
    # Line 1, where a `coding:` comment would name the encoding; parsed as bytes.
    module = ast.parse(f"# {line}\nx = 1\n".encode("utf-8"))
    assert [type(n) for n in module.body] == [ast.Assign]
    tomllib.loads(f"# {line}\nx = 1\n")
    xml.dom.minidom.parseString(f"<a><!-- {escape.xml_comment(text)} --></a>".encode("utf-8"))


@FAST
@given(texts)
def test_toml_strings_round_trip(text):
    if escape.UNENCODABLE.search(text):  # lone surrogates: TOML has no form; check_output refuses them
        return
    assert tomllib.loads(f"k = {escape.toml_str(text)}\n")["k"] == text


# -- the last line of defence: characters a format cannot carry -----------------------------
@pytest.fixture(scope="module")
def k10():
    from rapidgen.asset import load_asset

    sink = DiagnosticSink()
    loaded = load_asset(str(ROOT / "specs" / "assets" / "k10.yaml"), sink)
    assert loaded is not None and not sink.has_errors
    return loaded


def _with(loaded, **fields):
    return dataclasses.replace(loaded, spec=dataclasses.replace(loaded.spec, **fields))


@pytest.mark.parametrize("bad", ["\x01", "\x1b", "\ud800", "\ufffe", "\uffff"])
def test_xml_writer_refuses_forbidden_characters_with_a_located_diagnostic(k10, bad):
    """The loader refuses these first (RG1014); the back end refuses them again if they get by."""
    asset = _with(k10, partition=f"K10{bad}Red")
    options = Options(source="k10.yaml", qos_library=default_library())
    with pytest.raises(UnwritableCharacter) as info:
        backends.get("qos").generate(asset.model, asset, options)
    sink = DiagnosticSink()
    info.value.report(sink)
    [diag] = sink.errors
    assert diag.code == "RG0830" and f"U+{ord(bad):04X}" in diag.message
    assert diag.loc.file.endswith("k10.yaml") and diag.loc.line >= 1  # the descriptor's partition field
    assert diag.loc == k10.spec.at("partition")


def test_xml_writer_keeps_what_xml_allows(k10):
    asset = _with(k10, partition='K10 <"Red"> & \t \U0001f600 \x85 ]]> --')
    files = backends.get("qos").generate(asset.model, asset, Options("k10.yaml", qos_library=default_library()))
    for f in files:
        if f.path.endswith(".xml"):
            xml.dom.minidom.parseString(f.content.encode("utf-8"))
    names = xml.dom.minidom.parseString(next(f for f in files if f.path.startswith("fastdds")).content.encode())
    assert {n.firstChild.data for n in names.getElementsByTagName("name") if n.parentNode.tagName == "names"} \
        == {asset.spec.partition}


def test_describe_escapes_terminal_control_sequences(k10):
    asset = _with(k10, name="K10\x1b[2J\x1b]0;owned\x07", description="line one\rover\x9b")
    text = describe(asset)
    assert "\x1b" not in text and "\r" not in text and "\x07" not in text and "\x9b" not in text
    assert "K10\\x1b[2J\\x1b]0;owned\\x07" in text and "line one\\rover\\u009b" in text


# -- generation from arbitrary input --------------------------------------------------------
WORK = Path(tempfile.mkdtemp(prefix="rapidgen-escaping-"))
atexit.register(shutil.rmtree, WORK, True)
GENERATED: list[tuple[Path, str]] = []  # (python folder, package) of every successful example


def _idl_literal(value: str) -> str:
    """value as an IDL wide string literal (escapes the front end decodes)."""
    return 'L"' + "".join(ch if " " <= ch < "\x7f" and ch not in '"\\' else
                          f"\\u{ord(ch):04x}" if ord(ch) <= 0xFFFF else ch for ch in value) + '"'


def _run(*args: str) -> tuple[int, str]:
    res = rapidgen(*args)
    if res.code != 0:  # a clean, located diagnostic: no traceback, no internal error
        assert res.code == 1, res.err
        assert "Traceback" not in res.err and "internal error" not in res.err
        assert re.search(r":\d+:\d+: error\[RG\d{4}\]", res.err), res.err
    return res.code, res.err


def _check_files(out: Path) -> dict[str, object]:
    """Parse every generated file; returns each module-level constant of the _idl modules."""
    consts: dict[str, object] = {}
    for p in out.rglob("*"):
        if not p.is_file() or p.name == ".rapidgen-manifest.json":
            continue
        data = p.read_bytes()
        if p.suffix == ".py":
            tree = ast.parse(data, filename=str(p))
            if "_idl" in p.parts:
                for node in tree.body:
                    if isinstance(node, ast.Assign) and isinstance(node.value, ast.Constant):
                        consts[node.targets[0].id] = node.value.value
        elif p.suffix == ".toml":
            tomllib.loads(data.decode("utf-8"))
        elif p.suffix == ".xml":
            xml.dom.minidom.parseString(data)
        elif p.suffix == ".json":
            json.loads(data)
        else:
            raise AssertionError(f"unexpected generated file {p}")
    return consts


def _folder() -> Path:
    return Path(tempfile.mkdtemp(dir=WORK))


file_names = (st.one_of(texts, st.just(f"x{PAYLOAD}y"))
              .filter(lambda n: "/" not in n and "\x00" not in n and n not in ("", ".", ".."))
              .filter(lambda n: _encodable(n) and len(os.fsencode(n)) < 200))
identifiers = st.one_of(st.from_regex(r"\A_?[A-Za-z][A-Za-z0-9_]{0,8}\Z"), texts,
                        st.sampled_from(["class", "None", "qos", "_support", "__init__", "rapid", "self"]))


def _encodable(name: str) -> bool:
    try:
        os.fsencode(name)
    except UnicodeError:
        return False
    return True


@GENERATE
@given(file_name=file_names, module=identifiers, member=identifiers, value=texts, hashid=texts)
@example(file_name=f"x{PAYLOAD}y", module="m", member="a", value=PAYLOAD, hashid=PAYLOAD)
@example(file_name="coding:utf-16", module="m", member="a", value="\ud800\U0001f600\x00]]>", hashid="")
def test_arbitrary_idl_text_generates_safe_code(file_name, module, member, value, hashid):
    folder = _folder()
    idl = folder / f"{file_name}.idl"
    idl.write_text(f"module {module} {{\n  const wstring GREETING = {_idl_literal(value)};\n"
                   f"  struct S {{ @hashid({_idl_literal(hashid)[1:]}) long {member}; }};\n}};\n",
                   encoding="utf-8", errors="surrogatepass")
    code, _ = _run("generate", str(idl), "--lang", "python,qos", "-o", str(folder / "out"))
    if code != 0:
        return
    consts = _check_files(folder / "out")
    assert consts["GREETING"] == value  # the constant holds the input exactly
    GENERATED.append((folder / "out" / "python", "rapid_types"))


def _descriptor() -> dict:
    """A small descriptor using most fields: a command type, agent and position values,
    native passthrough, access control."""
    return {
        "version": 1,
        "asset": {"name": "Fuzzy", "kind": "rover", "description": "a rover", "tags": ["rover"]},
        "dds": {"domain": 3, "partition": "FuzzyPart"},
        "idl": {"rapid": RAPID},
        "subsystem_types": [{"name": "Cam", "extends": "ImageSensor", "description": "a camera", "commands": [
            {"name": "shoot", "description": "take one", "parameters": [
                {"name": "mode", "type": "RAPID_STRING", "allowed": ["left", "right"], "default": "left",
                 "description": "which"},
                {"name": "pan", "type": "RAPID_FLOAT", "unit": "rad", "range": [-1, 1], "default": 0}]}]}],
        "subsystems": [{"name": "Admin"}, {"name": "Mobility"}, {"name": "Eye", "type": "Cam",
                                                                 "description": "the eye"}],
        "telemetry": [
            {"kind": "position", "rate": 1, "frame": "site", "subsystem": "Mobility",
             "values": [{"key": "speed", "type": "RAPID_FLOAT", "unit": "m/s", "description": "how fast"}]},
            {"kind": "agent", "rate": 1, "values": [
                {"key": "mode", "type": "RAPID_STRING", "allowed": ["idle", "busy"], "default": "idle"}]},
            {"kind": "image", "suffix": "eyeLeft", "subsystem": "Eye", "sensor": "EyeLeft",
             "sensor_type": "mono", "mime": "image/png"},
            {"kind": "text", "categories": ["system"]}],
        "native": {"subsystem": "Native", "command": "nativeCommand", "parameter": "text",
                   "description": "as-is"},
        "access_control": {"default": "deny", "sources": [{"source": "Ground", "allow": ["*"],
                                                           "description": "operators"}]},
    }


def _string_paths(node, path=()) -> list[tuple]:
    if isinstance(node, str):
        return [path] if path != ("idl", "rapid") else []
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else []
    return [p for k, v in items for p in _string_paths(v, path + (k,))]


DESCRIPTOR_PATHS = _string_paths(_descriptor())


def test_the_base_descriptor_generates():
    folder = _folder()
    (folder / "d.yaml").write_text(yaml.safe_dump(_descriptor()))
    assert _run("generate", str(folder / "d.yaml"), "--lang", "python,qos", "-o", str(folder / "out"))[0] == 0
    assert len(DESCRIPTOR_PATHS) > 30


@GENERATE
@given(edits=st.lists(st.tuples(st.sampled_from(DESCRIPTOR_PATHS), st.one_of(printable, printable, texts)),
                      min_size=1, max_size=3))
@example(edits=[(("asset", "name"), f"x{PAYLOAD}"), (("dds", "partition"), "a]]></name>--<b>")])
@example(edits=[(("asset", "description"), "\x1b[2J\r\n\"\"\"")])
def test_arbitrary_descriptor_text_generates_safe_files(edits):
    data = copy.deepcopy(_descriptor())
    for path, text in edits:
        node = data
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = text
    folder = _folder()
    (folder / "d.yaml").write_text(yaml.safe_dump(data, allow_unicode=True), encoding="utf-8")
    code, _ = _run("generate", str(folder / "d.yaml"), "--lang", "python,qos", "-o", str(folder / "out"))
    if code != 0:
        return
    _check_files(folder / "out")
    topics = json.loads((folder / "out" / "qos" / "topics.json").read_text(encoding="utf-8"))
    assert topics["asset"] == data["asset"]["name"]
    package = next(p.name for p in (folder / "out" / "python").iterdir() if p.is_dir() and p.name.startswith("rapid_"))
    GENERATED.append((folder / "out" / "python", package))


def test_every_generated_package_imports_without_side_effects():
    """Runs after the generation tests above (file order): one child imports them all."""
    if not GENERATED:
        pytest.skip("run with the generation tests")
    sandbox = _folder()
    code = ("import importlib, pkgutil, sys\n"
            f"for folder, package in {[(str(f), p) for f, p in GENERATED]!r}:\n"
            "    sys.path.insert(0, folder)\n"
            "    pkg = importlib.import_module(package)\n"
            "    for m in pkgutil.walk_packages(pkg.__path__, package + '.'):\n"
            "        importlib.import_module(m.name)\n"
            "    for name in [n for n in sys.modules if n == package or n.startswith(package + '.')]:\n"
            "        del sys.modules[name]\n"
            "    sys.path.pop(0)\n"
            "print('imported', len(sys.argv))\n")
    res = run_python(code, cwd=sandbox, cpu_s=120)
    assert res.code == 0, res.err
    assert res.out == "imported 1\n"  # nothing else printed
    assert list(sandbox.iterdir()) == []  # nothing created
    assert all(not (f / "pwned").exists() for f, _ in GENERATED)
