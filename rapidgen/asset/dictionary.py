"""The asset's effective command dictionary: types after `extends`, used types, native.

Shared by the checks, the CommandConfig computation and `describe`, so all three agree on
which types exist and in which order they are published.
"""
from __future__ import annotations

from dataclasses import replace

from rapidgen.asset.spec import (AssetSpec, CommandSpec, Parameter, SubsystemSpec,
                                 SubsystemTypeSpec)
from rapidgen.asset.standard import STANDARD_TYPES


def effective_types(spec: AssetSpec) -> dict[str, SubsystemTypeSpec]:
    """Every type a subsystem may name: the descriptor's (with inherited commands first),
    then the standard ones it does not redefine. First definition wins on duplicates."""
    out: dict[str, SubsystemTypeSpec] = {}
    for t in spec.subsystem_types:
        if t.name in out or t.name in STANDARD_TYPES:
            continue
        base = STANDARD_TYPES.get(t.extends) if t.extends else None
        if base is not None:
            t = replace(t, commands=base.commands + t.commands)
        out[t.name] = t
    for name, t in STANDARD_TYPES.items():
        out.setdefault(name, t)
    nat = native_type(spec)
    if nat is not None:
        out.setdefault(nat.name, nat)
    return out


def native_type(spec: AssetSpec) -> SubsystemTypeSpec | None:
    """Native passthrough as one subsystem type with one RAPID_STRING command."""
    n = spec.native
    if n is None:
        return None
    param = Parameter(name=n.parameter, type="RAPID_STRING", loc=n.at("parameter"),
                      description="native command text, passed to the asset unchanged")
    cmd = CommandSpec(name=n.command, description=n.description or "native command passthrough",
                      abortable=False, suspendable=False, parameters=(param,), loc=n.at("command"))
    return SubsystemTypeSpec(name=n.subsystem, description="native command passthrough",
                             commands=(cmd,), loc=n.at("subsystem"))


def all_subsystems(spec: AssetSpec) -> tuple[SubsystemSpec, ...]:
    """The descriptor's subsystems, then the native passthrough subsystem."""
    subs = spec.subsystems
    if spec.native is not None:
        n = spec.native
        subs += (SubsystemSpec(name=n.subsystem, type=n.subsystem, description="native command passthrough",
                               loc=n.at("subsystem")),)
    return subs


def used_types(spec: AssetSpec) -> list[SubsystemTypeSpec]:
    """Types in the order their first subsystem names them (CommandConfig order)."""
    types = effective_types(spec)
    out: list[SubsystemTypeSpec] = []
    for s in all_subsystems(spec):
        t = types.get(s.type)
        if t is not None and t not in out:
            out.append(t)
    return out


def commands_of(spec: AssetSpec, subsystem: str) -> tuple[CommandSpec, ...] | None:
    by_name = {s.name: s for s in reversed(all_subsystems(spec))}
    sub = by_name.get(subsystem)
    t = effective_types(spec).get(sub.type) if sub else None
    return t.commands if t else None
