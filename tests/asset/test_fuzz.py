"""Robustness: random text, random YAML and mutated seed descriptors give only diagnostics.

Every diagnostic must be located (a line >= 1 in the descriptor or an IDL file); any
exception is a bug.
"""
import atexit
import copy
import shutil
import tempfile
from pathlib import Path

import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rapidgen.asset import load_asset
from rapidgen.asset.describe import describe
from rapidgen.diagnostics import DiagnosticSink
from tests.asset.conftest import ASSETS, ROOT, SEEDS

RAPID = str(ROOT / "specs" / "rapid")
WORK = Path(tempfile.mkdtemp(prefix="rapidgen-asset-fuzz-"))
shutil.copytree(ASSETS / "idl", WORK / "idl")
atexit.register(shutil.rmtree, WORK, True)
SEED_DATA = {s: yaml.safe_load((ASSETS / f"{s}.yaml").read_text()) for s in SEEDS}
FUZZ = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])

scalars = st.one_of(st.none(), st.booleans(), st.integers(-2**70, 2**70), st.integers(-10**400, 10**400),
                    st.floats(allow_nan=False, allow_infinity=False),
                    st.text(max_size=40), st.sampled_from(["RAPID_FLOAT", "Admin", "position", "*", "a/b", ""]))
values = st.recursive(scalars, lambda inner: st.one_of(
    st.lists(inner, max_size=4), st.dictionaries(st.text(max_size=12), inner, max_size=4)), max_leaves=12)


def run(data: bytes | str) -> None:
    path = WORK / "fuzz.yaml"
    path.write_bytes(data.encode("utf-8", "surrogatepass") if isinstance(data, str) else data)
    sink = DiagnosticSink()
    loaded = load_asset(str(path), sink, RAPID)
    for d in sink.diagnostics:
        assert d.loc.line >= 1 and d.message, d
    if loaded is not None and not sink.has_errors:
        describe(loaded)  # a valid descriptor must also describe and publish cleanly
        loaded.configs


@FUZZ
@given(st.binary(max_size=300))
def test_random_bytes(data):
    run(data)


@FUZZ
@given(st.text(alphabet=st.sampled_from(list("abc: -[]{}\n\t'\"&*!#?|>%@`,.0123456789\\")), max_size=200))
def test_random_yaml_like_text(text):
    run(text)


@FUZZ
@given(values)
def test_random_yaml_documents(value):
    run(yaml.safe_dump(value))


def _paths(node, prefix=()):
    yield prefix
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _paths(v, prefix + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _paths(v, prefix + (i,))


@FUZZ
@given(st.sampled_from(SEEDS), st.data())
def test_mutated_seeds(name, data):
    doc = copy.deepcopy(SEED_DATA[name])
    for _ in range(data.draw(st.integers(1, 4))):
        paths = [p for p in _paths(doc) if p]
        path = data.draw(st.sampled_from(paths))
        parent = doc
        for part in path[:-1]:
            parent = parent[part]
        action = data.draw(st.sampled_from(["replace", "delete", "duplicate", "rename"]))
        key = path[-1]
        if action == "replace":
            parent[key] = data.draw(values)
        elif action == "delete":
            del parent[key]
        elif action == "duplicate" and isinstance(parent, list):
            parent.append(copy.deepcopy(parent[key]))
        elif action == "rename" and isinstance(parent, dict):
            parent[data.draw(st.text(max_size=8))] = parent.pop(key)
    run(yaml.safe_dump(doc, sort_keys=False, allow_unicode=True))
