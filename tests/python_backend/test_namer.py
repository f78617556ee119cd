"""The Python Namer: keyword escaping, no shadowing, collision-free scopes."""
import pytest

from rapidgen.backends.python import namer


@pytest.mark.parametrize("name, expected", [
    ("class", "class_"), ("from", "from_"), ("None", "None_"), ("lambda", "lambda_"),
    ("types", "types_"), ("annotate", "annotate_"), ("field", "field_"), ("dataclass", "dataclass_"),
    ("idl", "idl_"), ("Optional", "Optional_"), ("IdlStruct", "IdlStruct_"), ("str", "str_"),
    ("list", "list_"), ("range", "range_"),
    ("Command", "Command"), ("hdr", "hdr"), ("type", "type"), ("id", "id"), ("match", "match"),
])
def test_module_level_escaping(name, expected):
    assert namer.escape(name, namer.MODULE_RESERVED) == expected


def test_members_keep_harmless_builtin_names():
    reserved = namer.member_reserved("struct", set())
    assert namer.escape("type", reserved) == "type"  # KeyTypePair.type stays `type`
    assert namer.escape("range", reserved) == "range"  # NamedFloatRangeValue.range too
    assert namer.escape("serialize", reserved) == "serialize_"  # would hide IdlStruct.serialize
    assert namer.escape("str", reserved) == "str_"  # a class body may use `str`


def test_members_avoid_names_the_class_body_uses():
    reserved = namer.member_reserved("struct", {"Header", "types"})
    assert namer.escape("Header", reserved) == "Header_"
    assert namer.escape("hdr", reserved) == "hdr"


def test_union_members_avoid_union_attributes():
    reserved = namer.member_reserved("union", set())
    assert [namer.escape(n, reserved) for n in ("value", "discriminator", "get", "set", "b")] == \
        ["value_", "discriminator_", "get_", "set_", "b"]


def test_enumerators_avoid_enum_reserved_names():
    reserved = namer.enumerator_reserved()
    assert [namer.escape(n, reserved) for n in ("mro", "name", "value", "RAPID_BOOL", "in")] == \
        ["mro_", "name_", "value_", "RAPID_BOOL", "in_"]


def test_scope_never_gives_one_name_twice():
    scope = namer.Scope("test", namer.MODULE_RESERVED)
    assert scope.claim("class_", "m::class_") == "class_"
    assert scope.claim("class", "m::class") == "class__"  # class_ is taken
    assert scope.claim("class", "m::class") == "class__"  # same owner, same name
    assert scope.claim("Foo", "a::Foo") == "Foo"
    assert scope.claim("Foo", "b::Foo") == "Foo_"
    scope.check()


def test_scope_take_refuses_a_collision():
    scope = namer.Scope("test")
    scope.take("Foo", "a::Foo")
    with pytest.raises(namer.NameCollision):
        scope.take("Foo", "b::Foo")


def test_scope_check_refuses_a_keyword():
    scope = namer.Scope("test")
    scope.take("class", "x")
    with pytest.raises(namer.NameCollision):
        scope.check()


@pytest.mark.parametrize("text, expected", [
    ("BaseTypes", "BaseTypes"), ("my-file.v2", "my_file_v2"), ("2d", "_2d"), ("__init__", "init__"),
    ("", "idl"), ("é", "idl"),
])
def test_identifier(text, expected):
    assert namer.identifier(text) == expected


def test_dunder_and_sunder_names_are_escaped():
    assert namer.escape("_x_", frozenset()) == "_x__"
    assert namer.escape("__x__", frozenset()) != "__x__"


@pytest.mark.parametrize("asset, package", [
    ("K10Red", "rapid_k10red"), ("ATHLETE", "rapid_athlete"), ("EVA Suit-A", "rapid_eva_suit_a"),
    ("", "rapid_asset"),
])
def test_package_name(asset, package):
    assert namer.package_name(asset) == package


def test_file_names_stay_apart_on_case_insensitive_file_systems():
    scope = namer.Scope("files", fold_case=True)
    assert scope.claim("Ack", "a/Ack.idl") == "Ack"
    assert scope.claim("ack", "b/ack.idl") == "ack_"
