"""Every rule has an (OLD, NEW) pair that triggers exactly it, and safe changes trigger nothing."""
from __future__ import annotations

import pytest

from rapidgen.diff.rules import RULES
from tests.diff.conftest import asset_pair, base, diff_paths, idl_pair

S = "@final struct S {{ @key long id; {} }};"
A = "@appendable struct S {{ @key long id; {} }};"
M = "@mutable struct S {{ @key @id(0) long id; {} }};"
U = "union U switch (long) {{ {} }};"

# rule id -> (OLD IDL, NEW IDL), each inside `module t { ... };`
IDL_PAIRS = {
    "WIRE-TYPE-01": ("struct Gone { long a; }; " + S.format(""), S.format("")),
    "WIRE-TYPE-02": ("struct P { long a; double b; };", "struct Q { long a; double b; };"),
    "WIRE-TYPE-03": ("struct P { long a; };", "union P switch (long) { case 1: long a; };"),
    "WIRE-TYPE-04": (S.format("long a;"), A.format("long a;")),
    "WIRE-MEMBER-01": (S.format("long a; long b;"), S.format("long b;")),
    "WIRE-MEMBER-02": (S.format("long a;"), S.format("long a; long b;")),
    "WIRE-MEMBER-03": (A.format("long a;"), A.format("long z; long a;")),
    "WIRE-MEMBER-04": (S.format("long a; double b;"), S.format("double b; long a;")),
    "WIRE-MEMBER-05": (S.format("long a;"), S.format("long b;")),
    "WIRE-MEMBER-06": (S.format("long a;"), S.format("long long a;")),
    "WIRE-MEMBER-07": (A.format("long a;"), A.format("@optional long a;")),
    "WIRE-MEMBER-08": (M.format("@id(1) long a;"), M.format("@id(1) long c;")),
    "WIRE-MEMBER-09": (M.format("@id(1) long a;"), M.format("@id(7) long a;")),
    "WIRE-BOUND-01": (S.format("string<16> a;"), S.format("string<8> a;")),
    "WIRE-KEY-01": (S.format("long a;"), S.format("@key long a;")),
    "WIRE-ENUM-01": ("enum E { A, B };", "enum E { @value(1) A, @value(0) B };"),
    "WIRE-ENUM-02": ("enum E { A, B };", "enum E { A };"),
    "WIRE-ENUM-03": ("enum E { A, B };", "enum E { A, B, C };"),
    "WIRE-ENUM-04": ("enum E { A, B };", "enum E { A, X };"),
    "WIRE-ENUM-05": ("@bit_bound(16) enum E { A, B };", "@bit_bound(8) enum E { A, B };"),
    "WIRE-BITMASK-01": ("bitmask F { f0, f1 };", "bitmask F { @position(3) f0, f1 };"),
    "WIRE-UNION-01": (U.format("case 1: long a;"), "union U switch (short) { case 1: long a; };"),
    "WIRE-UNION-02": (U.format("case 1: long a; case 2: double b;"), U.format("case 1: long a; case 3: double b;")),
    "WIRE-UNION-03": (U.format("case 1: long a; case 2: double b;"), U.format("case 1: long a;")),
    "WIRE-UNION-04": (U.format("case 1: long a;"), U.format("case 1: long a; case 2: double b;")),
    "WIRE-UNION-05": (U.format("case 1: long a; case 2: double b;"),
                      U.format("case 1: long a; case 2: default: double b;")),
    "WIRE-TYPEDEF-01": ("typedef long N;", "typedef double N;"),
    "WIRE-TOPIC-01": ('const string X_TOPIC = "x";', 'const string X_TOPIC = "y";'),
    "SRC-TYPE-01": ("typedef string<8> N; " + S.format("N a;"), "typedef string<8> N; " + S.format("string<8> a;")),
    "SRC-MEMBER-01": (A.format("long a; long b;"), A.format("long a;")),
    "SRC-MEMBER-02": (M.format("@id(1) long a; @id(2) long b;"), M.format("@id(2) long b;")),
    "SRC-TYPEDEF-01": ("typedef long N; " + S.format("long a;"), S.format("long a;")),
    "SRC-CONST-01": ("const long N = 3;", "const long N = 4;"),
    "SRC-CONST-02": ("const long N = 3; const long K = 1;", "const long K = 1;"),
}


def _asset(change):
    new = base()
    change(new)
    return new


def _param(i, **kv):
    def change(d):
        d["subsystem_types"][0]["commands"][0]["parameters"][i].update(kv)
    return change


def _qos(profile):
    def change(d):
        d["telemetry"][3]["qos"] = {"sample": profile}
    return change


ASSET_CHANGES = {
    "PROTO-SUBSYS-01": lambda d: d["subsystems"].pop(2),
    "PROTO-SUBSYS-02": lambda d: (d["subsystem_types"][0].update(name="Arm2"), d["subsystems"][2].update(type="Arm2")),
    "PROTO-CMD-01": lambda d: d["subsystem_types"][0]["commands"].pop(1),
    "PROTO-CMD-02": lambda d: d["subsystem_types"][0]["commands"][0].update(abortable=False),
    "PROTO-PARAM-01": lambda d: d["subsystem_types"][0]["commands"][0]["parameters"].pop(2),
    "PROTO-PARAM-02": lambda d: d["subsystem_types"][0]["commands"][1]["parameters"].append(
        {"name": "speed", "type": "RAPID_FLOAT"}),
    "PROTO-PARAM-03": _param(0, type="RAPID_DOUBLE"),
    "PROTO-PARAM-04": lambda d: d["subsystem_types"][0]["commands"][0]["parameters"].reverse(),
    "PROTO-PARAM-05": _param(0, range=[-0.5, 1]),
    "PROTO-PARAM-06": _param(2, allowed=["slow"]),
    "PROTO-PARAM-07": _param(0, unit="mm"),
    "PROTO-VALUE-01": lambda d: d["telemetry"][1]["values"].pop(0),
    "PROTO-VALUE-02": lambda d: d["telemetry"][1]["values"].reverse(),
    "PROTO-VALUE-03": lambda d: d["telemetry"][0]["values"][0].update(type="RAPID_DOUBLE"),
    "PROTO-VALUE-04": lambda d: d["telemetry"][0]["values"][0].update(unit="km/h"),
    "PROTO-JOINT-01": lambda d: d["telemetry"][2]["joints"].pop(0),
    "PROTO-TOPIC-01": lambda d: d["telemetry"][3].update(suffix="camera"),
    "PROTO-QOS-01": _qos("RapidBestEffortQos"),
    "PROTO-QOS-02": _qos("RapidReliableDurableQos"),
    "PROTO-DOMAIN-01": lambda d: d["dds"].update(domain=3),
    "PROTO-PART-01": lambda d: d["dds"].update(partition="other"),
}


def _topic_type(old_type, new_type):
    def make(d, t):
        d["telemetry"].append({"kind": "custom", "sample": {"type": t, "topic": "probe_topic"}})
    old, new = base(), base()
    make(old, old_type)
    make(new, new_type)
    return old, new


ASSET_PAIRS = {rid: (base(), _asset(change)) for rid, change in ASSET_CHANGES.items()}
ASSET_PAIRS["PROTO-TOPIC-02"] = _topic_type("rapid::PositionSample", "rapid::JointSample")
ASSET_PAIRS["PROTO-ACCESS-01"] = (  # a new source may command (tests/diff/test_access_rule.py: the others)
    _asset(lambda d: d.update(access_control={"default": "deny", "sources": [{"source": "A", "allow": ["Admin/*"]}]})),
    _asset(lambda d: d.update(access_control={"default": "deny", "sources": [{"source": "A", "allow": ["Admin/*"]},
                                                                             {"source": "B", "allow": ["*"]}]})))


def _ids(findings):
    """The rules found (a pair may trigger its rule more than once: two enumerators swapped)."""
    return sorted({f.rule.id for f in findings})


@pytest.mark.parametrize("rule_id", sorted(IDL_PAIRS))
def test_idl_pair_triggers_exactly_its_rule(tmp_path, rule_id):
    old, new = IDL_PAIRS[rule_id]
    found = diff_paths(*idl_pair(tmp_path, old, new))
    assert _ids(found) == [rule_id], [f.message for f in found]
    f = found[0]
    # located on both sides where both sides have it, in the right files
    assert f.old is not None and "old" in f.old.file and f.old.line > 0
    if f.new is not None:
        assert "new" in f.new.file and f.new.line > 0


@pytest.mark.parametrize("rule_id", sorted(ASSET_PAIRS))
def test_asset_pair_triggers_exactly_its_rule(tmp_path, rule_id):
    old, new = ASSET_PAIRS[rule_id]
    found = diff_paths(*asset_pair(tmp_path, old, new))
    assert _ids(found) == [rule_id], [f.message for f in found]
    f = found[0]
    assert f.new is not None and "new" in f.new.file and f.new.line > 0
    if f.old is not None:
        assert "old" in f.old.file and f.old.line > 0


def test_every_rule_has_a_pair():
    assert set(IDL_PAIRS) | set(ASSET_PAIRS) == set(RULES)
    assert len(RULES) >= 30


SAFE_IDL = {
    "append to @appendable": (A.format("long a;"), A.format("long a; double b; string c;")),
    "grow a string bound": (S.format("string<8> a;"), S.format("string<16> a;")),
    "grow a sequence bound": (A.format("sequence<long, 4> a;"), A.format("sequence<long, 8> a;")),
    "bounded to unbounded": (S.format("string<8> a;"), S.format("string a;")),
    "add a member to @mutable": (M.format("@id(1) long a;"), M.format("@id(5) double z; @id(1) long a;")),
    "add to @appendable enum": ("@appendable enum E { A, B };", "@appendable enum E { A, B, C };"),
    "add a case to @appendable union": ("@appendable " + U.format("case 1: long a;"),
                                        "@appendable " + U.format("case 1: long a; case 2: double b;")),
    "add a flag to a bitmask": ("bitmask F { f0, f1 };", "bitmask F { f0, f1, f2 };"),
    "add a type": (S.format("long a;"), S.format("long a;") + " struct T { long b; };"),
    "add a constant": ("const long N = 3;", "const long N = 3; const long K = 1;"),
    "comments and layout": (S.format("long a;"), "/* c */\n\n" + S.format("long   a; // x\n")),
}


@pytest.mark.parametrize("name", sorted(SAFE_IDL))
def test_safe_idl_change_triggers_nothing(tmp_path, name):
    assert diff_paths(*idl_pair(tmp_path, *SAFE_IDL[name])) == []


def _add_command(d):
    d["subsystem_types"][0]["commands"].append({"name": "wave", "parameters": [{"name": "n", "type": "RAPID_INT"}]})


SAFE_ASSET = {
    "add a command": _add_command,
    "add a subsystem": lambda d: d["subsystems"].append({"name": "LeftArm", "type": "Arm"}),
    "widen a range": _param(0, range=[-2, 2]),
    "allow more values": _param(2, allowed=["slow", "fast", "turbo"]),
    "append a value key": lambda d: d["telemetry"][1]["values"].append({"key": "temp", "type": "RAPID_FLOAT"}),
    "append a joint": lambda d: d["telemetry"][2]["joints"].append({"frame": "Arm/J2", "dof": "roll", "unit": "rad"}),
    "strengthen a writer's QoS": _qos("RapidReliableQos"),
    "add a telemetry topic": lambda d: d["telemetry"].append({"kind": "text", "categories": ["x"]}),
    "gain abortable": lambda d: d["subsystem_types"][0]["commands"][1].update(abortable=True),
}


@pytest.mark.parametrize("name", sorted(SAFE_ASSET))
def test_safe_asset_change_triggers_nothing(tmp_path, name):
    assert diff_paths(*asset_pair(tmp_path, base(), _asset(SAFE_ASSET[name]))) == []
