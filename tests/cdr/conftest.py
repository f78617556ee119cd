"""Fixtures of the CDR codec tests: the RAPID model (seed assets merged), the test types
of idl/Kitchen.idl, and the committed golden vectors."""
from __future__ import annotations

import glob
import json
import os

import pytest

from rapidgen.diagnostics import DiagnosticSink
from rapidgen.cdr import Codec
from rapidgen.vectors import COMMITTED, load_model

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
KITCHEN = os.path.join(ROOT, "tests", "cdr", "idl", "Kitchen.idl")


def seed_assets() -> list[str]:
    """The inputs of the committed vectors, relative to the repository root."""
    return sorted(os.path.relpath(p, ROOT).replace(os.sep, "/")
                  for p in glob.glob(os.path.join(ROOT, "specs", "assets", "*.yaml")))


def _load(paths: list[str]):
    sink = DiagnosticSink()
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        model = load_model(paths, [], sink)
    finally:
        os.chdir(cwd)
    assert model is not None, [str(d) for d in sink.diagnostics]
    return model


@pytest.fixture(scope="session")
def rapid_model():
    return _load(seed_assets())


@pytest.fixture(scope="session")
def rapid_codec(rapid_model):
    return Codec(rapid_model)


@pytest.fixture(scope="session")
def kitchen_model():
    return _load([os.path.relpath(KITCHEN, ROOT)])


@pytest.fixture(scope="session")
def kt(kitchen_model):
    return Codec(kitchen_model)


@pytest.fixture(scope="session")
def committed():
    with open(os.path.join(ROOT, COMMITTED), encoding="utf-8") as fh:
        return json.load(fh)
