"""A RAPID type as one self-contained OMG IDL text, as the MCAP registry's `omgidl` schema
encoding asks (every type it needs, in dependency order, no #include).

RAPID's valuetypes (`valuetype AgentState : Message`) are written as structs with their base
members first: the wire layout is the same, and IDL readers (Foxglove, Lichtblick) know no
valuetypes. Typedefs are kept by name, not resolved: Cyclone matches a reader to a writer
by XTypes type information, in which a typedef differs from the type it names, so a type
generated from this text must keep them (docs/record.md). Extensibility is written out
(`@final`): IDL 4.2's default is appendable, rapidgen's and RAPID's is final.
"""
from __future__ import annotations

from rapidgen.model import ir


def _refs(t: ir.Type) -> list[str]:
    """Scoped names a type expression uses."""
    if isinstance(t, ir.TypeRef):
        return [t.name]
    if isinstance(t, (ir.Sequence, ir.Array)):
        return _refs(t.element)
    if isinstance(t, ir.Map):
        return _refs(t.key) + _refs(t.value)
    return []


def _needs(model: ir.Model, d: ir.Declaration) -> list[str]:
    if isinstance(d, ir.Struct):
        return [n for m in model.all_members(d) for n in _refs(m.type)]
    if isinstance(d, ir.Union):
        return _refs(d.discriminator) + [n for c in d.cases for n in _refs(c.member.type)]
    if isinstance(d, (ir.Typedef, ir.Const)):
        return _refs(d.type)
    if isinstance(d, ir.Bitset) and d.base:
        return [d.base]
    return []


def closure(model: ir.Model, scoped: str) -> list[ir.Declaration]:
    """`scoped` and every declaration it needs, in the model's (dependency) order."""
    seen: set[str] = set()
    todo = [scoped]
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        d = model.get(name)
        if d is None:
            raise KeyError(f"{scoped} needs {name}, which the model does not declare")
        seen.add(name)
        todo.extend(_needs(model, d))
    return [d for d in model.declarations if d.scoped_name in seen]


def _type(t: ir.Type) -> str:
    if isinstance(t, ir.Sequence):
        inner = _type(t.element)
        return f"sequence<{inner}, {t.bound}>" if t.bound else f"sequence<{inner}>"
    if isinstance(t, ir.Map):
        inner = f"{_type(t.key)}, {_type(t.value)}" + (f", {t.bound}" if t.bound else "")
        return f"map<{inner}>"
    if isinstance(t, ir.Array):  # only inside a sequence or map (a member's array is a declarator)
        raise ValueError("an anonymous array type inside a template type cannot be written in IDL")
    return str(t)  # primitives, strings, fixed, scoped names


def _declarator(t: ir.Type, name: str) -> str:
    if isinstance(t, ir.Array):
        return f"{_type(t.element)} {name}" + "".join(f"[{n}]" for n in t.dims)
    return f"{_type(t)} {name}"


def _label(label: ir.Label, scope: str) -> str:
    if isinstance(label, ir.EnumValue):  # scoped by the enum: Foxglove looks labels up in it
        return f"{label.enum}::{label.name}"
    if isinstance(label, bool):
        return "TRUE" if label else "FALSE"
    if isinstance(label, str):
        return "'" + label.replace("\\", "\\\\").replace("'", "\\'") + "'"
    return str(label)


def _member(m: ir.Member, key: bool = False) -> str:
    notes = "".join(f"@{a} " for a in (("key",) if key or m.key else ()) + (("optional",) if m.optional else ())
                    + (("external",) if m.external else ()))
    if m.id is not None:
        notes += f"@id({m.id}) "
    return f"{notes}{_declarator(m.type, m.name)};"


def _body(model: ir.Model, d: ir.Declaration) -> list[str]:
    if isinstance(d, ir.Struct):
        own_keys = {k.split(".")[0] for k in d.keys}
        members = [_member(m, m.name in own_keys) for m in model.all_members(d)]
        head = f"@{d.extensibility}\nstruct {d.name} {{"
        return [head] + [f"    {m}" for m in members] + ["};"]
    if isinstance(d, ir.Union):
        disc = ("@key " if d.discriminator_key else "") + _type(d.discriminator)
        out = [f"@{d.extensibility}\nunion {d.name} switch ({disc}) {{"]
        for c in d.cases:
            labels = [f"    case {_label(lb, d.scoped_name)}:" for lb in c.labels]
            if c.is_default:
                labels.append("    default:")
            out += labels + [f"        {_member(c.member)}"]
        return out + ["};"]
    if isinstance(d, ir.Enum):
        values = []
        for i, e in enumerate(d.enumerators):
            values.append(f"    @value({e.value}) {e.name}" if e.value != i else f"    {e.name}")
        bound = f"@bit_bound({d.bit_bound})\n" if d.bit_bound != 32 else ""
        return [f"{bound}enum {d.name} {{", ",\n".join(values), "};"]
    if isinstance(d, ir.Typedef):
        return [f"typedef {_declarator(d.type, d.name)};"]
    if isinstance(d, ir.Bitmask):
        bits = ",\n".join(f"    @position({v.position}) {v.name}" for v in d.values)
        return [f"@bit_bound({d.bit_bound})\nbitmask {d.name} {{", bits, "};"]
    raise ValueError(f"{d.scoped_name}: a {d.kind} cannot be written in an MCAP schema")


def idl_text(model: ir.Model, scoped: str) -> str:
    """The self-contained IDL of `scoped` (e.g. rapid::AgentState): modules reopened as the
    dependency order needs. Raises KeyError (unknown type) or ValueError (unwritable)."""
    lines = [f"// {scoped}: written by rapidgen record (valuetypes flattened, base members first)"]
    open_path: list[str] = []
    for d in closure(model, scoped):
        path = d.scoped_name.split("::")[:-1]
        common = 0
        while common < min(len(path), len(open_path)) and path[common] == open_path[common]:
            common += 1
        for depth in range(len(open_path), common, -1):
            lines.append("    " * (depth - 1) + "};")
        for depth in range(common, len(path)):
            lines.append("    " * depth + f"module {path[depth]} {{")
        open_path = path
        pad = "    " * len(path)
        for chunk in _body(model, d):
            lines += [pad + line if line else line for line in chunk.split("\n")]
    for depth in range(len(open_path), 0, -1):
        lines.append("    " * (depth - 1) + "};")
    return "\n".join(lines) + "\n"
