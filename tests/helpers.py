"""Shared test helpers: run the CLI in-process and capture what it prints."""
from __future__ import annotations

import contextlib
import difflib
import io
from dataclasses import dataclass
from pathlib import Path

import pytest

from rapidgen.cli import main


@dataclass
class Result:
    code: int
    out: str
    err: str


def rapidgen(*args: str) -> Result:
    """Run `rapidgen ARGS` in this process (relative paths are against the current folder)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(list(args))
        except SystemExit as exc:  # argparse usage errors
            code = exc.code if isinstance(exc.code, int) else 2
    return Result(code, out.getvalue(), err.getvalue())


def ir_of(tmp_path, source: str, name: str = "t.idl", *extra: str) -> dict:
    """Write one IDL file, resolve it and return the IR JSON as a dict (asserts success)."""
    import json
    import os

    path = tmp_path / name
    path.write_text(source, encoding="utf-8")
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        res = rapidgen("ir", "--no-loc", name, *extra)
    finally:
        os.chdir(cwd)
    assert res.code == 0, res.err
    return json.loads(res.out)


def errors_of(tmp_path, source: str, name: str = "t.idl", *extra: str) -> Result:
    """Write one IDL file, run `rapidgen ir` expecting failure; returns the result."""
    import os

    path = tmp_path / name
    path.write_bytes(source.encode("utf-8") if isinstance(source, str) else source)
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        res = rapidgen("ir", name, *extra)
    finally:
        os.chdir(cwd)
    return res


def assert_golden(path: Path, actual: str, update: bool, what: str = "output") -> None:
    """Compare actual with the golden file (byte for byte); `pytest --update-golden` rewrites it.

    A missing golden file fails (it is never silently created), a mismatch shows a diff.
    """
    if update:
        path.parent.mkdir(parents=True, exist_ok=True)
        with open(path, "w", encoding="utf-8", newline="") as fh:
            fh.write(actual)
        return
    assert path.exists(), f"{path} is missing: run pytest --update-golden and review it"
    with open(path, encoding="utf-8", newline="") as fh:
        expected = fh.read()
    if actual != expected:
        diff = "".join(difflib.unified_diff(expected.splitlines(True), actual.splitlines(True), path.name, "actual"))
        pytest.fail(f"{what} differs from {path.name} (pytest --update-golden rewrites it):\n{diff}", pytrace=False)
