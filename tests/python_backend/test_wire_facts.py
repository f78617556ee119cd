"""The generated Python classes and the reference codec read the same resolved facts
(member ids, enum and union defaults) from the model, so they agree on the wire and on
the values an older writer's data leaves out (issue 9, defects 1 and 2)."""
from __future__ import annotations

import itertools
import sys
from pathlib import Path

import pytest
from cyclonedds.idl._support import Endianness

from rapidgen.backends import python
from rapidgen.backends.base import Options
from rapidgen.cdr import Codec
from rapidgen.diagnostics import DiagnosticSink
from rapidgen.idl.load import load_idl
from tests.cdr.cyclone_bridge import CycloneTypes, generated_classes

_PACKAGES = itertools.count()


def _bindings(tmp_path: Path, source: str):
    """The model of `source` and its generated classes (by IDL scoped name), imported."""
    (tmp_path / "w.idl").write_text(source, encoding="utf-8")
    sink = DiagnosticSink()
    model, _ = load_idl([str(tmp_path / "w.idl")], [str(tmp_path)], sink)
    assert model is not None, [str(d) for d in sink.diagnostics]
    package = f"wire_facts_{next(_PACKAGES)}"  # a fresh name: one import per test
    out = tmp_path / "out"
    for f in python.generate(model, None, Options(source="w.idl", package=package)):
        path = out / f.path
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(f.content, encoding="utf-8")
    try:
        return model, generated_classes(str(out), package)
    finally:
        sys.path.remove(str(out))


HASHED_BASE = """
module h {
  @mutable @autoid(HASH) struct B { long a; };
  @mutable struct D : B { long b; };
  @mutable @autoid(HASH) struct E : D { long c; @id(7) long d; long e; };
};
"""


@pytest.mark.parametrize("version", [1, 2])
@pytest.mark.parametrize("little", [True, False])
def test_flattened_members_of_a_hashed_base_keep_their_hash_ids(tmp_path, version, little):
    """Defect 1: D's class wrote sequential ids for B's members; the codec hash ids."""
    model, classes = _bindings(tmp_path, HASHED_BASE)
    codec = Codec(model)
    values = {"h::D": {"a": 1, "b": 2}, "h::E": {"a": 1, "b": 2, "c": 3, "d": 4, "e": 5}}
    for name, value in values.items():
        obj = classes[name](**value)
        theirs = obj.serialize(use_version_2=version == 2,
                               endianness=Endianness.Little if little else Endianness.Big)
        ours = codec.encode(name, value, version=version, little=little)
        assert ours.hex(" ", 4) == theirs.hex(" ", 4), name
        assert codec.decode(name, theirs) == value
        assert type(obj).deserialize(ours) == obj


def test_member_ids_are_resolved_once_per_declaring_type(tmp_path):
    """The model holds each member's effective id; sequential ids go on from the last one."""
    from rapidgen.idl.facts import name_hash

    assert name_hash("a") == 0x0975C10C  # md5("a") = 0cc17509..., little-endian, 28 bits
    model, _ = _bindings(tmp_path, HASHED_BASE)
    ids = {m.name: m.member_id for m in model.all_members(model.get("h::E"))}
    assert ids == {"a": name_hash("a"), "b": name_hash("a") + 1, "c": name_hash("c"), "d": 7, "e": name_hash("e")}


DEFAULTS = """
module w {
  enum Color { RED, @default_literal GREEN, BLUE };
  union ByColor switch (Color) { case RED: long r; case GREEN: string g; };
  union ByLong switch (long) { case 1: long one; case 0: double zero; default: short other; };
  union Free switch (long) { case 1: long one; default: short other; };
  union NoBranch switch (short) { case 1: long one; case 2: long two; };
  @appendable struct Old { long x; };
  @appendable struct New { long x; Color c; ByColor bc; ByLong bl; Free f; NoBranch nb; };
  @mutable struct MOld { long x; };
  @mutable struct MNew { long x; Color c; ByColor bc; ByLong bl; Free f; NoBranch nb; };
};
"""


@pytest.mark.parametrize("old,new", [("w::Old", "w::New"), ("w::MOld", "w::MNew")])
def test_absent_members_decode_to_the_bindings_defaults(tmp_path, old, new):
    """Defect 2: the decoder filled an absent enum with its first enumerator (not the
    @default_literal one) and an absent union with its first labelled case."""
    model, classes = _bindings(tmp_path, DEFAULTS)
    codec = Codec(model)
    cy = CycloneTypes(model, classes)
    data = codec.encode(old, {"x": 5}, version=2)
    decoded = codec.decode(new, data)
    bindings = cy.from_obj(codec.types.type_of(new), classes[new](x=5))
    assert decoded == bindings
    assert decoded["c"] == "GREEN"
    assert decoded["bc"] == {"discriminator": "GREEN", "value": ""}
    assert decoded["bl"] == {"discriminator": 0, "value": 0.0}
    assert decoded["f"] == {"discriminator": 0, "value": 0}
    assert decoded["nb"] == {"discriminator": 0}


def test_default_values_are_facts_of_the_model(tmp_path):
    model, _ = _bindings(tmp_path, DEFAULTS)
    assert model.get("w::Color").default == "GREEN"
    by_color = model.get("w::ByColor")
    assert by_color.default_discriminator.name == "GREEN" and by_color.default_member.name == "g"
    assert model.get("w::Free").default_member.name == "other"
    assert model.get("w::NoBranch").default_member is None
