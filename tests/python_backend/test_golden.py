"""Golden files of the Python back end, and the generated code actually working.

Each case under golden/<case>/ holds input/ (IDL files; input/files.txt lists the ones to
pass when not all of them) and expected/ (the whole generated tree). The case is run
from its folder, so headers name `input/...`. `pytest --update-golden` rewrites expected/;
a failure prints a unified diff per file.

Every expected package is then imported in a fresh interpreter: each struct is built
with its defaults, serialized and read back, and its XTypes type information is built
(what a DDS topic needs).
"""
from __future__ import annotations

import difflib
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from rapidgen.backends.base import Options
from rapidgen.diagnostics import DiagnosticSink
from rapidgen.idl.load import load_idl
from rapidgen.generate import source_name

HERE = Path(__file__).parent
CASES = sorted(p for p in (HERE / "golden").iterdir() if (p / "input").is_dir())


def case_inputs(case: Path) -> list[str]:
    listing = case / "input" / "files.txt"
    if listing.is_file():
        return [f"input/{line.strip()}" for line in listing.read_text().splitlines() if line.strip()]
    return sorted(f"input/{p.name}" for p in (case / "input").glob("*.idl"))


def generate_case(case: Path) -> dict[str, str]:
    from rapidgen.backends import python

    cwd = os.getcwd()
    os.chdir(case)
    try:
        sink = DiagnosticSink()
        inputs = case_inputs(case)
        model, _ = load_idl(inputs, ["input"], sink)
        assert model is not None, [f"{d.loc}: {d.message}" for d in sink.diagnostics]
        files = python.generate(model, None, Options(source=source_name(inputs)))
    finally:
        os.chdir(cwd)
    return {f.path: f.content for f in files}


def read_tree(root: Path) -> dict[str, str]:
    if not root.is_dir():
        return {}
    return {p.relative_to(root).as_posix(): p.read_text(encoding="utf-8")
            for p in sorted(root.rglob("*")) if p.is_file() and "__pycache__" not in p.parts}


def write_tree(root: Path, files: dict[str, str]) -> None:
    if root.exists():
        shutil.rmtree(root)
    for rel, text in files.items():
        path = root / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8", newline="\n")


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_golden(case: Path, update_golden: bool):
    actual = generate_case(case)
    expected_root = case / "expected"
    if update_golden:
        write_tree(expected_root, actual)
    assert expected_root.is_dir(), f"{expected_root} is missing: run pytest --update-golden and review it"
    expected = read_tree(expected_root)
    problems = [f"missing (generated but not expected): {p}" for p in sorted(actual.keys() - expected.keys())]
    problems += [f"no longer generated: {p}" for p in sorted(expected.keys() - actual.keys())]
    for path in sorted(actual.keys() & expected.keys()):
        if actual[path] != expected[path]:
            problems.append("".join(difflib.unified_diff(
                expected[path].splitlines(True), actual[path].splitlines(True),
                f"expected/{path}", f"actual/{path}")))
    if problems:
        pytest.fail(f"{case.name}: generated code differs from the golden files "
                    f"(pytest --update-golden rewrites them):\n" + "\n".join(problems))


SMOKE = r'''
import importlib, inspect, pkgutil, sys
import cyclonedds.idl as idl
root = importlib.import_module(sys.argv[1])
structs = unions = enums = 0
names = [m.name for m in pkgutil.walk_packages(root.__path__, sys.argv[1] + ".")]
for name in names:
    mod = importlib.import_module(name)
    for obj in vars(mod).values():
        if not inspect.isclass(obj) or obj.__module__ != mod.__name__:
            continue
        if issubclass(obj, idl.IdlStruct):
            value = obj()
            assert obj.deserialize(value.serialize()) == value, obj
            obj.__idl__.fill_type_data()
            structs += 1
        elif issubclass(obj, idl.IdlUnion):
            obj.__idl__.populate()
            unions += 1
        elif issubclass(obj, idl.IdlEnum):
            assert list(obj), obj
            enums += 1
print(structs, unions, enums)
'''


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_golden_output_imports_and_round_trips(case: Path, tmp_path: Path):
    """The expected package imports and every struct round-trips (no DDS needed)."""
    tree = read_tree(case / "expected")
    assert tree, "no golden output yet: run pytest --update-golden"
    write_tree(tmp_path, tree)
    package = next(p.split("/")[0] for p in tree if p.count("/") == 1 and p.endswith("/__init__.py"))
    env = dict(os.environ, PYTHONPATH=str(tmp_path), PYTHONDONTWRITEBYTECODE="1")
    env.pop("CYCLONEDDS_URI", None)
    res = subprocess.run([sys.executable, "-c", SMOKE, package], capture_output=True, text=True,
                         env=env, timeout=120, cwd=tmp_path)
    assert res.returncode == 0, res.stderr[-4000:]
    structs, _, _ = map(int, res.stdout.split())
    assert structs > 0
