"""The rule registry: every change `rapidgen diff` reports, with a stable id and category.

Categories: WIRE (peers built on OLD and NEW no longer match or no longer understand each
other's samples), PROTOCOL (the bytes still decode, but the asset's commands, telemetry
or QoS contract changed under its peers), SOURCE (the wire is the same; code written
against OLD no longer compiles or means something else). Ids never change meaning; a
retired rule keeps its id reserved. docs/diff.md lists them all (a test checks it).
"""
from __future__ import annotations

from dataclasses import dataclass

from rapidgen.diagnostics import SourceLoc

CATEGORIES = ("WIRE", "PROTOCOL", "SOURCE")


@dataclass(frozen=True, slots=True)
class Rule:
    id: str
    category: str
    title: str
    why: str  # the explanation printed under each finding


@dataclass(frozen=True, slots=True)
class Finding:
    rule: Rule
    subject: str  # what changed: a scoped type name, `Type.member`, `subsystem Arm`, ...
    message: str
    old: SourceLoc | None
    new: SourceLoc | None


_X = "OMG DDS-XTypes 1.3 7.2.4.4"
_RULES = (
    # -- types -------------------------------------------------------------------------
    Rule("WIRE-TYPE-01", "WIRE", "type removed",
         "peers built on OLD still publish or subscribe the type; nothing in NEW matches it"),
    Rule("WIRE-TYPE-02", "WIRE", "type renamed (same definition)",
         "the scoped name is the DDS type name: readers and writers match on it (RAPID's QoS "
         "sends no type information, so the name is all they compare)"),
    Rule("WIRE-TYPE-03", "WIRE", "kind of type changed",
         "a struct, union, enum or bitmask is only assignable from a type of the same kind"),
    Rule("WIRE-TYPE-04", "WIRE", "extensibility changed",
         f"{_X}: both types must have the same extensibility kind; the encodings also differ "
         "(XCDR2 adds a DHEADER to @appendable and @mutable, and EMHEADERs to @mutable)"),
    # -- members of structs and unions -------------------------------------------------
    Rule("WIRE-MEMBER-01", "WIRE", "member removed",
         f"{_X}.8: a @final type keeps every member; an @appendable type may only drop members "
         "at its end; OLD readers misread what follows the gap"),
    Rule("WIRE-MEMBER-02", "WIRE", "member added to a @final type",
         f"{_X}.8: @final types must have the same members; make the type @appendable (append "
         "at the end) or @mutable to grow it"),
    Rule("WIRE-MEMBER-03", "WIRE", "member inserted before the end of an @appendable type",
         f"{_X}.8: an @appendable type is assignable only when one member list is a prefix of "
         "the other; append new members at the end"),
    Rule("WIRE-MEMBER-04", "WIRE", "members reordered",
         "@final and @appendable members are encoded in declaration order with no ids"),
    Rule("WIRE-MEMBER-05", "WIRE", "member renamed",
         f"{_X}.8: members with the same id must have the same name; XTypes peers (Cyclone DDS) "
         "refuse the match. Bytes are unchanged, so peers matching by type name alone "
         "(type_information: false) still decode it"),
    Rule("WIRE-MEMBER-06", "WIRE", "member type changed",
         f"{_X}: a member's type must be assignable; primitives must be identical (no "
         "widening), arrays keep their dimensions, collections their element type"),
    Rule("WIRE-MEMBER-07", "WIRE", "@optional changed",
         "an optional member is encoded with a presence flag (XCDR2) or parameter header "
         "(XCDR1); a mandatory one without"),
    Rule("WIRE-MEMBER-08", "WIRE", "@mutable member id now names another member",
         f"{_X}.8: members with the same id must have the same name and type; with sequential "
         "ids, inserting or removing a member shifts the ids of those after it"),
    Rule("WIRE-MEMBER-09", "WIRE", "@mutable member id changed",
         f"{_X}.8: members with the same name must have the same id; OLD readers find no "
         "value under the id they know"),
    Rule("WIRE-BOUND-01", "WIRE", "bound shrunk",
         "a string, sequence or map holding more than NEW's bound is refused by NEW readers "
         "(XTypes 7.6.3.4: dropped, or no match when bounds are enforced); OLD writers may "
         "legitimately send it. Growing a bound is reported by nothing: keep NEW writers "
         "within OLD's bound until OLD readers are gone"),
    Rule("WIRE-KEY-01", "WIRE", "key members changed",
         "the key decides instance identity (keyhash, dispose, history per instance); OLD and "
         "NEW would disagree which samples belong to one instance"),
    # -- enums, bitmasks ---------------------------------------------------------------
    Rule("WIRE-ENUM-01", "WIRE", "enumerator value changed",
         "enumerators travel as their integer value: OLD and NEW read a different enumerator"),
    Rule("WIRE-ENUM-02", "WIRE", "enumerator removed",
         "OLD writers still send its value; NEW readers have no enumerator for it"),
    Rule("WIRE-ENUM-03", "WIRE", "enumerator added to a @final enum",
         f"{_X}.1: @final enums must have the same enumerators; make it @appendable and add at "
         "the end"),
    Rule("WIRE-ENUM-04", "WIRE", "enumerator renamed",
         f"{_X}.1: enumerators with the same value must have the same name (Cyclone DDS "
         "refuses the match)"),
    Rule("WIRE-ENUM-05", "WIRE", "@bit_bound changed",
         "the bit bound decides the encoded size (1, 2 or 4 bytes in XCDR2)"),
    Rule("WIRE-BITMASK-01", "WIRE", "bitmask flags or bit bound changed",
         "a bitmask travels as an integer; a flag at another position or a new bit bound "
         "changes what the bits mean or how many bytes are sent"),
    # -- unions ------------------------------------------------------------------------
    Rule("WIRE-UNION-01", "WIRE", "discriminator type changed",
         f"{_X}.9: the discriminator types must be identical (same width and sign)"),
    Rule("WIRE-UNION-02", "WIRE", "case labels changed",
         "the label on the wire selects the member: a value now selects another member"),
    Rule("WIRE-UNION-03", "WIRE", "case removed",
         "OLD writers still send its label; NEW readers drop the sample or read no member"),
    Rule("WIRE-UNION-04", "WIRE", "case added to a @final union",
         f"{_X}.9: @final unions must have the same labels; OLD readers cannot read the new one"),
    Rule("WIRE-UNION-05", "WIRE", "default case changed",
         "values no label names select the default member: they now decode as another member"),
    # -- typedefs, constants -----------------------------------------------------------
    Rule("WIRE-TYPEDEF-01", "WIRE", "typedef now names another wire type",
         "every member declared with the typedef changes type on the wire"),
    Rule("WIRE-TOPIC-01", "WIRE", "topic name changed",
         "a `*_TOPIC` constant names a DDS topic: readers and writers meet only on the same name"),
    # -- source ------------------------------------------------------------------------
    Rule("SRC-TYPE-01", "SOURCE", "type spelled differently, same wire form",
         "a typedef replaced by what it names (or the reverse), or a nested type renamed with "
         "the same definition: XTypes resolves aliases, the bytes are the same, code using the "
         "old spelling breaks. (Cyclone DDS 11 has been seen to refuse such a match when the "
         "typedef sits inside a nested type: prefer keeping the spelling)"),
    Rule("SRC-MEMBER-01", "SOURCE", "trailing member removed from an @appendable type",
         f"{_X}.8: still assignable (a prefix); OLD readers see the member's default value and "
         "code reading it breaks"),
    Rule("SRC-MEMBER-02", "SOURCE", "member removed from a @mutable type",
         "still assignable (members are found by id); OLD readers see its default value and "
         "code reading it breaks"),
    Rule("SRC-TYPEDEF-01", "SOURCE", "typedef removed",
         "nothing on the wire names a typedef; code using it breaks"),
    Rule("SRC-CONST-01", "SOURCE", "constant value changed",
         "constants are not on the wire, but code and peers that compare against them now "
         "disagree"),
    Rule("SRC-CONST-02", "SOURCE", "constant removed", "code using the constant breaks"),
    # -- protocol (asset descriptor) ---------------------------------------------------
    Rule("PROTO-SUBSYS-01", "PROTOCOL", "subsystem removed",
         "operators and scripts address commands to it; CommandConfig no longer lists it"),
    Rule("PROTO-SUBSYS-02", "PROTOCOL", "subsystem type changed",
         "CommandConfig publishes the subsystem's type name; tools pick command sets by it"),
    Rule("PROTO-CMD-01", "PROTOCOL", "command removed",
         "commanders built on OLD still send it; NEW answers it as unknown"),
    Rule("PROTO-CMD-02", "PROTOCOL", "command no longer abortable or suspendable",
         "commanders built on OLD may abort or suspend it; NEW refuses"),
    Rule("PROTO-PARAM-01", "PROTOCOL", "parameter removed",
         "parameters are positional in Command.args: OLD commanders send one too many"),
    Rule("PROTO-PARAM-02", "PROTOCOL", "parameter added",
         "parameters are positional in Command.args: OLD commanders send one too few"),
    Rule("PROTO-PARAM-03", "PROTOCOL", "parameter DataType changed",
         "the ParameterUnion member OLD commanders fill is not the one NEW reads"),
    Rule("PROTO-PARAM-04", "PROTOCOL", "parameters reordered",
         "parameters are positional: OLD commanders' values land in other parameters"),
    Rule("PROTO-PARAM-05", "PROTOCOL", "parameter range narrowed",
         "values OLD commanders may send are now refused"),
    Rule("PROTO-PARAM-06", "PROTOCOL", "allowed values reduced",
         "values OLD commanders may send are now refused"),
    Rule("PROTO-PARAM-07", "PROTOCOL", "parameter unit changed",
         "the number means something else (rad vs deg): silently wrong motion"),
    Rule("PROTO-VALUE-01", "PROTOCOL", "telemetry value key removed",
         "values are positional, aligned with the config's valueKeys: readers built on OLD "
         "look for it"),
    Rule("PROTO-VALUE-02", "PROTOCOL", "telemetry value key moved",
         "values are positional, aligned with valueKeys: readers that index by position read "
         "another value"),
    Rule("PROTO-VALUE-03", "PROTOCOL", "telemetry value DataType changed",
         "the ParameterUnion member readers expect is not the one sent"),
    Rule("PROTO-VALUE-04", "PROTOCOL", "telemetry value unit changed",
         "the number means something else to displays and monitors"),
    Rule("PROTO-JOINT-01", "PROTOCOL", "joint removed or moved",
         "JointSample arrays are positional, aligned with JointConfig's joint list"),
    Rule("PROTO-TOPIC-01", "PROTOCOL", "published topic removed",
         "subscribers built on OLD wait on a topic nobody writes"),
    Rule("PROTO-TOPIC-02", "PROTOCOL", "topic message type changed",
         "readers of the topic expect the OLD message type"),
    Rule("PROTO-QOS-01", "PROTOCOL", "reliability made incompatible",
         "DDS request/offered: a reliable reader does not match a best-effort writer"),
    Rule("PROTO-QOS-02", "PROTOCOL", "durability made incompatible",
         "DDS request/offered: a transient-local reader does not match a volatile writer, and "
         "late joiners lose the last config or state"),
    Rule("PROTO-DOMAIN-01", "PROTOCOL", "DDS domain changed",
         "participants in different domains never discover each other"),
    Rule("PROTO-PART-01", "PROTOCOL", "partition changed",
         "readers and writers match only within a common partition"),
    Rule("PROTO-ACCESS-01", "PROTOCOL", "access widened: a source may now send a command it could not",
         "a source the OLD access_control refused is obeyed; under DDS Security the keystore's permissions "
         "must be regenerated (rapidgen secure) for the wider grant to take effect, and reviewed"),
)

RULES: dict[str, Rule] = {r.id: r for r in _RULES}
assert len(RULES) == len(_RULES), "duplicate rule id"


def rule(rule_id: str) -> Rule:
    return RULES[rule_id]
