"""rapidgen.packagedata.read_text: a file shipped in a package, read beside its modules,
else through importlib.resources."""
import sys
import types
from pathlib import Path

import pytest

from rapidgen.packagedata import read_text

REPO = Path(__file__).resolve().parents[2]


def test_read_beside_the_package():
    assert read_text("rapidgen.idl", "grammar.lark") == (REPO / "rapidgen/idl/grammar.lark").read_text(encoding="utf-8")


def test_through_importlib_resources_when_not_beside(monkeypatch, tmp_path):
    # a package whose __file__ names a folder without the file: importlib.resources is asked
    pkg = types.ModuleType("rg_pkgdata_probe")
    pkg.__file__ = str(tmp_path / "elsewhere" / "__init__.py")
    monkeypatch.setitem(sys.modules, "rg_pkgdata_probe", pkg)
    asked = []

    class Files:
        def __init__(self, package):
            asked.append(package)

        def joinpath(self, name):
            return types.SimpleNamespace(read_text=lambda encoding: f"{name} via resources")

    import importlib.resources
    monkeypatch.setattr(importlib.resources, "files", Files)
    assert read_text("rg_pkgdata_probe", "data.txt") == "data.txt via resources"
    assert asked == ["rg_pkgdata_probe"]


def test_a_missing_file_is_an_error():
    with pytest.raises(FileNotFoundError):
        read_text("rapidgen.idl", "no-such-file.txt")
