"""The configs the descriptor implies, as samples of the generated types (the asset
tables hold them as plain data with IDL member names).

Deliberately a second computation: the runtimes build the same samples
(rapid_runtime/messages.py config(), the C++ runtime's generated configs), and the
conformance runner judges them, so it must not share their bugs. This is the one place an
asset fact is computed again outside rapidgen/asset/resolved.py (docs/architecture.md)."""
from __future__ import annotations


def _union(r, u: dict):
    dtype, value = u["discriminator"], u["value"]
    if dtype in ("RAPID_FLOAT", "RAPID_DOUBLE"):
        value = float(value)
    elif dtype in ("RAPID_VEC3d", "RAPID_MAT33f"):
        value = [float(x) for x in value]
    return r.ParameterUnion(discriminator=r.DataType[dtype], value=value)


def _triples(r, keys: list) -> list:
    return [r.KeyTypeValueTriple(key=k["key"], padding=k.get("padding", 0), value=_union(r, k["value"])) for k in keys]


def config_sample(bindings, topic: str, hdr):
    r = bindings.rapid
    type_name, v = bindings.tables["CONFIGS"][topic]["type"], bindings.tables["CONFIGS"][topic]["value"]
    if type_name == "rapid::CommandConfig":
        types_ = [r.SubsystemType(name=t["name"], commands=[
            r.CommandDef(name=c["name"], abortable=c["abortable"], suspendable=c["suspendable"],
                         parameters=[r.KeyTypePair(key=p["key"], type=r.DataType[p["type"]]) for p in c["parameters"]])
            for c in t["commands"]]) for t in v["availableSubsystemTypes"]]
        subs = [r.Subsystem(name=x["name"], subsystemTypeName=x["subsystemTypeName"]) for x in v["availableSubsystems"]]
        return r.CommandConfig(hdr=hdr, availableSubsystemTypes=types_, availableSubsystems=subs)
    if type_name == "rapid::AgentConfig":
        return r.AgentConfig(hdr=hdr, agentTags=list(v["agentTags"]), topics=list(v["topics"]),
                             valueKeys=_triples(r, v["valueKeys"]))
    if type_name == "rapid::PositionConfig":
        return r.PositionConfig(hdr=hdr, frameName=v["frameName"], poseEncoding=r.RotationEncoding[v["poseEncoding"]],
                                velocityEncoding=r.RotationEncoding[v["velocityEncoding"]],
                                valueKeys=_triples(r, v["valueKeys"]))
    if type_name == "rapid::JointConfig":
        return r.JointConfig(hdr=hdr, jointGroupName=v["jointGroupName"],
                             jointDefinitions=[r.JointDef(frameName=j["frameName"], dof=j["dof"])
                                               for j in v["jointDefinitions"]])
    raise KeyError(f"no expected form for config type {type_name}")
