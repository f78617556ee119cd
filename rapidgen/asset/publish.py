"""The values an asset publishes about itself, computed from its descriptor.

Plain data (dicts, lists, str, numbers, bool) whose keys are the IDL member names, so a
back end or a test can compare or serialize them directly. `hdr` is left out: srcName,
assetName, timeStamp and serial are set at run time. Enumerators are given by name;
a ParameterUnion is {"discriminator": "RAPID_FLOAT", "f": 0.0} (member named as in the IDL).
"""
from __future__ import annotations

from collections.abc import Sequence

from rapidgen.asset.facts import STATIC_SHAPES, Facts
from rapidgen.asset.spec import (AgentTelemetry, AssetSpec, JointTelemetry, PositionTelemetry, SubsystemSpec,
                                 SubsystemTypeSpec, ValueKey)
from rapidgen.asset.topics import Publication


def command_config(types: Sequence[SubsystemTypeSpec], subsystems: Sequence[SubsystemSpec]) -> dict | None:
    """CommandConfig, or None for an asset without subsystems (telemetry only)."""
    if not types:
        return None
    return {
        "availableSubsystemTypes": [
            {"name": t.name, "commands": [
                {"name": c.name, "abortable": c.abortable, "suspendable": c.suspendable,
                 "parameters": [{"key": p.name, "type": p.type} for p in c.parameters]}
                for c in t.commands]}
            for t in types],
        "availableSubsystems": [{"name": s.name, "subsystemTypeName": s.type} for s in subsystems],
    }


def union_value(facts: Facts, data_type: str, value: object = None) -> dict:
    """A ParameterUnion holding value (the type's zero when None), in the codec's value form."""
    shape = facts.shapes.get(data_type) or STATIC_SHAPES[data_type]
    v: bool | int | float | str | list[float]
    if shape.kind == "bool":
        v = bool(value) if value is not None else False
    elif shape.kind == "int":
        v = int(_number(value)) if value is not None else 0
    elif shape.kind == "float":
        v = float(_number(value)) if value is not None else 0.0
    elif shape.kind == "string":
        v = str(value) if value is not None else ""
    else:
        assert value is None or isinstance(value, (list, tuple)), value  # checked: a list of numbers
        v = [float(_number(x)) for x in value] if value is not None else [0.0] * shape.count
    return {"discriminator": data_type, "value": v}


def _number(x: object) -> int | float:
    """A descriptor value the checks (check_values.py) already found to be a number."""
    assert isinstance(x, (int, float)), x
    return x


def value_keys(facts: Facts, values: tuple[ValueKey, ...]) -> list[dict]:
    """KeyTypeValueTriples: the value's type is the discriminator; its value the default."""
    return [{"key": v.name, "padding": 0,
             "value": union_value(facts, v.type, v.default if v.has_default else None)}
            for v in values]


def agent_config(spec: AssetSpec, t: AgentTelemetry, facts: Facts, pubs: Sequence[Publication]) -> dict:
    return {"agentTags": list(spec.tags),
            "topics": [p.topic for p in pubs],
            "valueKeys": value_keys(facts, t.values)}


def position_config(t: PositionTelemetry, facts: Facts) -> dict:
    return {"frameName": t.frame, "poseEncoding": t.pose_encoding,
            "velocityEncoding": t.velocity_encoding, "valueKeys": value_keys(facts, t.values)}


def joint_config(t: JointTelemetry) -> dict:
    return {"jointGroupName": t.group,
            "jointDefinitions": [{"frameName": j.frame, "dof": j.dof} for j in t.joints]}


def configs(spec: AssetSpec, facts: Facts, pubs: Sequence[Publication], types: Sequence[SubsystemTypeSpec],
            subsystems: Sequence[SubsystemSpec]) -> dict[str, tuple[str, dict]]:
    """Every config the asset publishes: topic -> (message type, value), in publication
    order (resolved.LoadedAsset.configs is the one caller)."""
    out: dict[str, tuple[str, dict]] = {}
    for p in pubs:
        if p.role != "config":
            continue
        t = p.source
        if p.type == "rapid::CommandConfig":
            command = command_config(types, subsystems)
            if command is None:
                continue  # no subsystems: nothing to command
            value = command
        elif isinstance(t, AgentTelemetry):
            value = agent_config(spec, t, facts, pubs)
        elif isinstance(t, PositionTelemetry):
            value = position_config(t, facts)
        elif isinstance(t, JointTelemetry):
            value = joint_config(t)
        else:
            continue  # custom configs: their contents are the asset's own business
        out[p.topic] = (p.type, value)
    return out
