"""Issue 8, item 1: a hostile file name must not become code in the generated package.

Each reproduction names an input x + PAYLOAD + y (three quotes, code, three quotes): before the fix the
name closed a module docstring, so importing the package created the file `pwned`.
Every path the name can take is covered: the IDL file on the command line, a
descriptor's idl.files, and the project file's idl:/asset: text (`rapidgen check --fix`).
Each test imports the generated package in a child process and parses every file.
"""
from __future__ import annotations

import ast
import json
import tomllib
import xml.dom.minidom
from pathlib import Path

from tests.hostile.limits import run_python, run_rapidgen

ROOT = Path(__file__).resolve().parents[2]
PAYLOAD = '""";open("pwned","w");"""'
IDL = "module m { struct S { long a; }; const string GREETING = \"hi\"; };\n"


def assert_parses(out: Path) -> int:
    """Every generated file parses in its own format; returns how many were checked."""
    files = [p for p in out.rglob("*") if p.is_file() and p.name != ".rapidgen-manifest.json"]
    for p in files:
        data = p.read_bytes()
        if p.suffix == ".py":
            ast.parse(data, filename=str(p))  # bytes: a PEP 263 coding line would be honoured
        elif p.suffix == ".toml":
            tomllib.loads(data.decode("utf-8"))
        elif p.suffix == ".xml":
            xml.dom.minidom.parseString(data)
        elif p.suffix == ".json":
            json.loads(data)
    return len(files)


def assert_imports_cleanly(python_dir: Path, package: str) -> None:
    """Import the package and every submodule in a child; the payload would create `pwned`."""
    code = ("import importlib, pkgutil, sys\n"
            f"pkg = importlib.import_module({package!r})\n"
            "for m in pkgutil.walk_packages(pkg.__path__, pkg.__name__ + '.'):\n"
            "    importlib.import_module(m.name)\n"
            "print('imported', pkg.__doc__.splitlines()[0])\n")
    res = run_python(code, cwd=python_dir)
    assert res.code == 0, res.err
    assert "imported" in res.out
    assert not (python_dir / "pwned").exists()


def test_hostile_idl_file_name_on_the_command_line(tmp_path):
    name = f"x{PAYLOAD}y.idl"
    (tmp_path / name).write_text(IDL)
    res = run_rapidgen("generate", name, "--lang", "python,qos", "-o", "out", cwd=tmp_path)
    assert res.code == 0, res.err
    assert assert_parses(tmp_path / "out") > 8
    assert_imports_cleanly(tmp_path / "out" / "python", "rapid_types")
    # The docstring names the file exactly: escaped, not mangled.
    doc = ast.get_docstring(ast.parse(next((tmp_path / "out/python/rapid_types/_idl").glob("x*.py")).read_bytes()))
    assert name in doc


def _descriptor(idl_file: str) -> str:
    return (f"version: 1\nasset: {{name: Evil, kind: rover}}\n"
            f"idl:\n  rapid: {json.dumps(str(ROOT / 'specs' / 'rapid'))}\n  files: [{json.dumps(idl_file)}]\n")


def test_hostile_idl_file_name_in_a_descriptor(tmp_path):
    name = f"x{PAYLOAD}y.idl"
    (tmp_path / name).write_text(IDL)
    (tmp_path / "evil.yaml").write_text(_descriptor(name))
    res = run_rapidgen("generate", "evil.yaml", "--lang", "python,qos", "-o", "out", cwd=tmp_path)
    assert res.code == 0, res.err
    assert assert_parses(tmp_path / "out") > 8
    assert_imports_cleanly(tmp_path / "out" / "python", "rapid_evil")


def test_hostile_project_file_text_with_check_fix(tmp_path):
    idl = f"x{PAYLOAD}y.idl"
    asset = f"e{PAYLOAD}v.yaml"
    (tmp_path / idl).write_text(IDL)
    (tmp_path / asset).write_text(_descriptor(idl))
    targets = [{"name": "types", "idl": [f"x{PAYLOAD}*.idl"], "lang": ["python"], "out": "gen/types"},
               {"name": "evil", "asset": asset, "lang": ["python", "qos"], "out": "gen/evil"}]
    (tmp_path / "rapidgen.yaml").write_text(json.dumps({"targets": targets}))  # JSON is YAML
    res = run_rapidgen("check", "--fix", cwd=tmp_path)
    assert res.code == 0, res.err
    for target, package in (("types", "rapid_types"), ("evil", "rapid_evil")):
        out = tmp_path / "gen" / target
        assert assert_parses(out) > 4
        assert_imports_cleanly(out / "python", package)
        project = tomllib.loads((out / "python" / "pyproject.toml").read_text())
        assert PAYLOAD in project["project"]["description"]  # the TOML string holds the name exactly
    assert run_rapidgen("check", cwd=tmp_path).code == 0  # and is stable


def test_coding_declaration_in_a_file_name_does_not_change_the_source_encoding(tmp_path):
    """A header comment `# ... coding:utf-16 ...` on line 1 would make every module unloadable."""
    name = "coding:utf-16.idl"
    (tmp_path / name).write_text(IDL)
    res = run_rapidgen("generate", name, "-o", "out", cwd=tmp_path)
    assert res.code == 0, res.err
    assert_parses(tmp_path / "out")
    assert_imports_cleanly(tmp_path / "out" / "python", "rapid_types")


def test_deserialize_raises_one_documented_error_for_bad_bytes():
    """Issue 8, item 13: cyclonedds raises struct.error, UnicodeDecodeError, ... on bad bytes;
    the generated classes raise _support.DeserializeError (a ValueError) instead."""
    code = """
import random
import rapid_types.rapid as r
from rapid_types._support import DeserializeError
rng = random.Random(8)
causes = set()
for good in (r.Ack(), r.TextMessage(), r.CommandConfig(), r.AgentState(), r.Command(),
             r.ParameterUnion(s="text")):
    cls = type(good)
    assert cls.deserialize(good.serialize()) == good  # good bytes: cyclonedds' answer
    for _ in range(300):
        data = bytearray(good.serialize())
        for _ in range(rng.randint(1, 6)):
            data[rng.randrange(len(data))] = rng.randrange(256)
        data = data[:rng.randint(0, len(data))] if rng.random() < 0.3 else data
        try:
            cls.deserialize(bytes(data))
        except DeserializeError as exc:
            assert isinstance(exc, ValueError) and exc.__cause__ is not None
            causes.add(type(exc.__cause__).__name__)
print(sorted(causes))
"""
    res = run_python(code, cwd=ROOT / "generated" / "rapid" / "python")
    assert res.code == 0, res.err
    assert "error" in res.out and "UnicodeDecodeError" in res.out  # both kinds were provoked, and wrapped
