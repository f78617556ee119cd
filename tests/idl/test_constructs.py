"""Every IDL construct the front end supports, checked through the resolved model."""
import pytest

from tests.helpers import errors_of, ir_of


def decls(tmp_path, src, *extra):
    return {d["name"]: d for d in ir_of(tmp_path, src, "t.idl", *extra)["declarations"]}


def member_types(d):
    return [(m["name"], m["type"]) for m in d["members"]]


@pytest.mark.parametrize("spelling,canonical", [
    ("short", "short"), ("long", "long"), ("long long", "long long"),
    ("unsigned short", "unsigned short"), ("unsigned long", "unsigned long"),
    ("unsigned long long", "unsigned long long"), ("int8", "int8"), ("uint8", "uint8"),
    ("int16", "short"), ("uint16", "unsigned short"), ("int32", "long"), ("uint32", "unsigned long"),
    ("int64", "long long"), ("uint64", "unsigned long long"), ("float", "float"), ("double", "double"),
    ("long double", "long double"), ("char", "char"), ("wchar", "wchar"), ("boolean", "boolean"),
    ("octet", "octet"), ("string", "string"), ("string<7>", "string<7>"), ("wstring", "wstring"),
    ("wstring<3>", "wstring<3>"), ("fixed<9,3>", "fixed<9, 3>"), ("sequence<long>", "sequence<long>"),
    ("sequence<string<4>, 2>", "sequence<string<4>, 2>"), ("map<long, double>", "map<long, double>"),
    ("map<string, sequence<octet>, 4>", "map<string, sequence<octet>, 4>"),
])
def test_base_and_template_types(tmp_path, spelling, canonical):
    d = decls(tmp_path, f"struct S {{ {spelling} v; }};")
    assert member_types(d["S"]) == [("v", canonical)]


def test_array_declarators_and_typedef_arrays(tmp_path):
    d = decls(tmp_path, "module m { typedef double Vec3d[3]; typedef float Mat[3][3];"
                        " struct S { short xyz[3], pair[2][4]; Vec3d v; sequence<Vec3d, 2> vs; }; };")
    assert d["m::Vec3d"]["type"] == "double[3]"
    assert d["m::Mat"]["type"] == "float[3][3]"
    assert member_types(d["m::S"]) == [("xyz", "short[3]"), ("pair", "short[2][4]"), ("v", "m::Vec3d"),
                                       ("vs", "sequence<m::Vec3d, 2>")]


def test_struct_inheritance_keeps_base(tmp_path):
    d = decls(tmp_path, "struct A { @key long id; }; struct B : A { double x; }; struct C : B { char c; };")
    assert d["C"]["base"] == "B" and d["B"]["base"] == "A"
    assert d["C"]["keys"] == ["id"]


def test_union_discriminators(tmp_path):
    src = """
    enum E { E0, E1, E2 };
    union UE switch (E) { case E0: long a; case E1: case E2: double b; };
    union UI switch (short) { case -1: long a; case 0x10: char c; default: string s; };
    union UC switch (char) { case 'x': long a; };
    union UB switch (boolean) { case TRUE: long a; case FALSE: octet o; };
    union UO switch (octet) { case 0: long a; case 255: long b; };
    typedef long Disc; union UT switch (Disc) { case 3: long a; };
    """
    d = decls(tmp_path, src)
    assert [c["labels"] for c in d["UE"]["cases"]] == [
        [{"enum": "E", "name": "E0", "value": 0}],
        [{"enum": "E", "name": "E1", "value": 1}, {"enum": "E", "name": "E2", "value": 2}]]
    assert [(c["labels"], c["default"]) for c in d["UI"]["cases"]] == [([-1], False), ([16], False), ([], True)]
    assert d["UC"]["cases"][0]["labels"] == ["x"]
    assert [c["labels"] for c in d["UB"]["cases"]] == [[True], [False]]
    assert d["UO"]["cases"][1]["labels"] == [255]
    assert d["UT"]["discriminator"] == "Disc"


def test_enums_numbering_forms(tmp_path):
    src = """
    enum Plain { A, B, C };
    enum Rti { ARROW = 0, // comment between
               /* block */ CUBE = 5, SPHERE };
    enum Idl4 { @value(3) X, Y, @value(10) Z };
    """
    d = decls(tmp_path, src)
    values = {n: [(e["name"], e["value"]) for e in d[n]["enumerators"]] for n in ("Plain", "Rti", "Idl4")}
    assert values == {"Plain": [("A", 0), ("B", 1), ("C", 2)],
                      "Rti": [("ARROW", 0), ("CUBE", 5), ("SPHERE", 6)],
                      "Idl4": [("X", 3), ("Y", 4), ("Z", 10)]}


def test_bitmask_and_bitset(tmp_path):
    d = decls(tmp_path, "@bit_bound(16) bitmask M { A, @position(5) B, C };"
                        " bitset BS { bitfield<1> flag; bitfield<4, short> n; bitfield<3>; };"
                        " bitset BD : BS { bitfield<7> more; };")
    assert d["M"]["bit_bound"] == 16
    assert [(v["name"], v["position"]) for v in d["M"]["values"]] == [("A", 0), ("B", 5), ("C", 6)]
    assert [(f["name"], f["width"], f["type"]) for f in d["BS"]["fields"]] == [
        ("flag", 1, "boolean"), ("n", 4, "short"), (None, 3, "uint8")]
    assert d["BD"]["base"] == "BS"


@pytest.mark.parametrize("expr,type_,value", [
    ("1 + 2 * 3", "long", 7), ("(1 + 2) * 3", "long", 9), ("-7 / 2", "long", -3), ("-7 % 3", "long", -1),
    ("1 << 10 >> 2", "long", 256), ("0xF0 | 0x0F ^ 0xFF & 0x3C", "long", 0xF0 | (0x0F ^ (0xFF & 0x3C))),
    ("~0", "unsigned long", 0xFFFFFFFF), ("~0", "long", -1), ("010", "long", 8), ("0x7FFFFFFFFFFFFFFF", "long long", 2**63 - 1),
    ("-128", "int8", -128), ("255", "uint8", 255), ("1.5 * 2", "double", 3.0), ("1 / 4.0", "float", 0.25),
    ("'a'", "char", "a"), ("'\\n'", "char", "\n"), ("'\\x41'", "char", "A"),
    ('"ab" "cd"', "string", "abcd"), ('"tab\\t"', "string<8>", "tab\t"), ("TRUE", "boolean", True),
    ("FALSE", "boolean", False), ("200", "octet", 200),
])
def test_constant_expressions(tmp_path, expr, type_, value):
    d = decls(tmp_path, f"const {type_} K = {expr};")
    assert d["K"]["value"] == value


def test_constants_referring_to_constants_enums_and_typedefs(tmp_path):
    src = """module rapid {
      typedef string<64> String64;
      const String64 TOPIC = "rapid_ack";
      enum DataType { RAPID_BOOL, RAPID_DOUBLE };
      const DataType DT = RAPID_DOUBLE;
      const long BASE = 0x0300;
      const long DERIVED = BASE + 2;
      const fixed F = 1.25d;
    };"""
    d = decls(tmp_path, src)
    assert d["rapid::TOPIC"]["value"] == "rapid_ack" and d["rapid::TOPIC"]["type"] == "rapid::String64"
    assert d["rapid::DT"]["value"] == {"enum": "rapid::DataType", "name": "RAPID_DOUBLE", "value": 1}
    assert d["rapid::DERIVED"]["value"] == 0x0302
    assert d["rapid::F"]["value"] == {"fixed": "1.25"}


def test_scoped_names_relative_absolute_and_reopened_modules(tmp_path):
    src = """
    module a { struct T { long x; }; module b { struct T { double y; }; struct U { T inner; ::a::T outer; a::T rel; }; }; };
    module a { struct V { b::T bt; a::b::U u; }; };
    """
    d = decls(tmp_path, src)
    assert member_types(d["a::b::U"]) == [("inner", "a::b::T"), ("outer", "a::T"), ("rel", "a::T")]
    assert member_types(d["a::V"]) == [("bt", "a::b::T"), ("u", "a::b::U")]


def test_forward_declarations_and_recursion_through_sequences(tmp_path):
    src = """module m {
      struct Node;
      union Tree;
      typedef sequence<Node> NodeSeq;
      struct Node { long v; NodeSeq kids; sequence<Tree, 2> trees; };
      union Tree switch (long) { case 0: Node leaf; case 1: sequence<Tree> more; };
    };"""
    d = decls(tmp_path, src)
    order = list(d)
    assert set(order) == {"m::NodeSeq", "m::Node", "m::Tree"}
    assert order.index("m::NodeSeq") < order.index("m::Node") < order.index("m::Tree")


def test_dependency_order_puts_used_types_first(tmp_path):
    src = "module m { struct B { A a; C c; }; struct A { long x; }; struct C { A a; }; };"
    assert list(decls(tmp_path, src)) == ["m::A", "m::C", "m::B"]


def test_annotations_known_and_checked(tmp_path):
    src = """@mutable @topic(name="T") struct S {
      @key @id(4) long k;
      @optional @default(2) long o;
      @range(min=0, max=5) @unit("rad") double r;
      @external sequence<S> self_ref;
    };
    @extensibility(APPENDABLE) struct X { @min(1) @max(9) short s; };
    @final union U switch (@key long) { case 1: long a; };
    @autoid(HASH) @nested struct N { @hashid("x") long a; };
    @verbatim(language="c++", placement=BEGIN_FILE, text="// hi") struct Vb { long a; };
    """
    d = decls(tmp_path, src)
    assert d["S"]["extensibility"] == "mutable" and d["X"]["extensibility"] == "appendable"
    k, o, r, e = d["S"]["members"]
    assert k["key"] and k["id"] == 4
    assert o["optional"] and o["default"] == 2
    assert {a["name"]: a["params"] for a in r["annotations"]} == {"range": {"min": 0.0, "max": 5.0},
                                                                   "unit": {"value": "rad"}}
    assert e["external"]
    assert d["N"]["nested"] is True


def test_user_declared_annotation_is_accepted(tmp_path):
    res = errors_of(tmp_path, "@annotation Level { long value default 1; }; @Level(2) struct S { long x; };")
    assert res.code == 0 and "RG0501" not in res.err


def test_unknown_annotation_is_a_silencable_warning(tmp_path):
    res = errors_of(tmp_path, "@frobnicate struct S { long x; };")
    assert res.code == 0 and "warning[RG0501]: unknown annotation '@frobnicate' is ignored" in res.err
    quiet = errors_of(tmp_path, "@frobnicate struct S { long x; };", "t.idl", "-W", "no-RG0501")
    assert quiet.code == 0 and quiet.err == ""
    strict = errors_of(tmp_path, "@frobnicate struct S { long x; };", "t.idl", "-W", "error")
    assert strict.code == 1


def test_native_and_keyword_escape(tmp_path):
    d = decls(tmp_path, "native Handle; struct S { long _struct; };")
    assert d["Handle"]["kind"] == "native"
    assert d["S"]["members"][0]["name"] == "struct"


def test_keys_own_inherited_nested_and_keylist(tmp_path):
    src = """module m {
      struct Id { long site; long unit; };
      struct Plain { long a; long b; };
      struct Keyed { @key Id id; @key Plain p; long data; };
      struct Derived : Keyed { @key string<8> extra; };
      struct Listed { Id id; long n; long q; };
      #pragma keylist Listed id.unit n
      struct Outer { @key Keyed k; };
    };"""
    d = decls(tmp_path, src)
    assert d["m::Keyed"]["keys"] == ["id.site", "id.unit", "p.a", "p.b"]
    assert d["m::Derived"]["keys"] == ["id.site", "id.unit", "p.a", "p.b", "extra"]
    assert d["m::Listed"]["keys"] == ["id.unit", "n"]
    assert [m.get("key", False) for m in d["m::Listed"]["members"]] == [True, True, False]
    assert d["m::Outer"]["keys"] == ["k.id.site", "k.id.unit", "k.p.a", "k.p.b"]


def test_case_only_member_difference_is_a_warning(tmp_path):
    res = errors_of(tmp_path, "struct S { long value; long Value; };")
    assert res.code == 0 and "warning[RG0312]" in res.err
