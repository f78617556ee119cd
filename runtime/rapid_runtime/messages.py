"""Plain data <-> the generated cyclonedds classes. `rapid` is the generated package's
`rapid` module (the asset's own types: the runtime brings none)."""
from __future__ import annotations

import time

from rapid_runtime.command import Cmd
from rapid_runtime.values import MEMBER, coerce


def now_us() -> int:
    """Header.timeStamp: microseconds since 1970-01-01 UTC."""
    return time.time_ns() // 1000


def header(rapid, src: str, asset: str, serial: int, status: int = 0, stamp: int | None = None):
    return rapid.Header(srcName=src, assetName=asset, timeStamp=now_us() if stamp is None else stamp,
                        statusCode=status, serial=serial)


def union(rapid, dtype: str, value: object):
    return rapid.ParameterUnion(discriminator=rapid.DataType[dtype], value=coerce(dtype, value))


def _enum_name(value: object) -> str:
    return getattr(value, "name", None) or str(value)


def union_value(u) -> tuple[str, object]:
    """(DataType name, value) of a ParameterUnion as received."""
    value = u.value
    if isinstance(value, (tuple, list)):
        value = list(value)
    return _enum_name(u.discriminator), value


def command_in(sample) -> Cmd:
    """A received rapid::Command as Cmd."""
    return Cmd(cmd_id=sample.cmdId, cmd_src=sample.cmdSrc, subsystem=sample.subsysName, name=sample.cmdName,
               args=tuple(union_value(a) for a in sample.arguments), action=_enum_name(sample.cmdAction),
               target=sample.targetCmdId, src_name=sample.hdr.srcName, asset_name=sample.hdr.assetName,
               serial=sample.hdr.serial, raw=sample)


def command_out(rapid, cmd: Cmd, stamp: int | None = None):
    """A rapid::Command to send (the commander's side)."""
    return rapid.Command(hdr=header(rapid, cmd.src_name, cmd.asset_name, cmd.serial, stamp=stamp),
                         cmdName=cmd.name, cmdId=cmd.cmd_id, cmdSrc=cmd.cmd_src, subsysName=cmd.subsystem,
                         arguments=[union(rapid, t, v) for t, v in cmd.args],
                         cmdAction=rapid.QueueAction[cmd.action], targetCmdId=cmd.target)


def ack(rapid, cmd: Cmd, status: str, completed: str, message: str):
    """The Ack copies the command's header (soraCore), timestamp refreshed."""
    hdr = header(rapid, cmd.src_name, cmd.asset_name, cmd.serial)
    return rapid.Ack(hdr=hdr, cmdId=cmd.cmd_id, status=rapid.AckStatus[status],
                     completedStatus=rapid.AckCompletedStatus[completed], message=message)


def ack_fields(sample) -> tuple[str, str, str, str]:
    """(cmdId, status, completedStatus, message) of a received Ack."""
    return sample.cmdId, _enum_name(sample.status), _enum_name(sample.completedStatus), sample.message


def _triples(rapid, keys: list) -> list:
    return [rapid.KeyTypeValueTriple(key=k["key"], padding=k.get("padding", 0),
                                     value=union(rapid, k["value"]["discriminator"], k["value"]["value"]))
            for k in keys]


def config(rapid, type_name: str, value: dict, hdr):
    """A computed config (asset_tables.CONFIGS value) as the generated class."""
    if type_name == "rapid::CommandConfig":
        types_ = [rapid.SubsystemType(name=t["name"], commands=[
            rapid.CommandDef(name=c["name"], abortable=c["abortable"], suspendable=c["suspendable"],
                             parameters=[rapid.KeyTypePair(key=p["key"], type=rapid.DataType[p["type"]])
                                         for p in c["parameters"]])
            for c in t["commands"]]) for t in value["availableSubsystemTypes"]]
        subs = [rapid.Subsystem(name=s["name"], subsystemTypeName=s["subsystemTypeName"])
                for s in value["availableSubsystems"]]
        return rapid.CommandConfig(hdr=hdr, availableSubsystemTypes=types_, availableSubsystems=subs)
    if type_name == "rapid::AgentConfig":
        return rapid.AgentConfig(hdr=hdr, agentTags=list(value["agentTags"]), topics=list(value["topics"]),
                                 valueKeys=_triples(rapid, value["valueKeys"]))
    if type_name == "rapid::PositionConfig":
        return rapid.PositionConfig(hdr=hdr, frameName=value["frameName"],
                                    poseEncoding=rapid.RotationEncoding[value["poseEncoding"]],
                                    velocityEncoding=rapid.RotationEncoding[value["velocityEncoding"]],
                                    valueKeys=_triples(rapid, value["valueKeys"]))
    if type_name == "rapid::JointConfig":
        return rapid.JointConfig(hdr=hdr, jointGroupName=value["jointGroupName"],
                                 jointDefinitions=[rapid.JointDef(frameName=j["frameName"], dof=j["dof"])
                                                   for j in value["jointDefinitions"]])
    raise KeyError(f"no builder for config type {type_name}")


def config_plain(sample) -> dict:
    """A received CommandConfig as the tables' plain form (the commander reads it)."""
    return {"availableSubsystemTypes": [
        {"name": t.name, "commands": [
            {"name": c.name, "abortable": c.abortable, "suspendable": c.suspendable,
             "parameters": [{"key": p.key, "type": _enum_name(p.type)} for p in c.parameters]}
            for c in t.commands]} for t in sample.availableSubsystemTypes],
        "availableSubsystems": [{"name": s.name, "subsystemTypeName": s.subsystemTypeName}
                                for s in sample.availableSubsystems]}


def queue_state(rapid, hdr, pending: list, active: list, completed: list):
    def records(items):
        return rapid.SingleQueue(records=[
            rapid.CommandRecord(cmd=c.raw if c.raw is not None else command_out(rapid, c),
                                trResult=rapid.ResultType[res], trStatus=rapid.StatusType[st])
            for c, res, st in items])
    return rapid.QueueState(hdr=hdr, pending=records(pending), active=records(active),
                            completed=records(completed), sent=rapid.SingleQueue())


def access_state(rapid, hdr, controller: str, requestors: list[str]):
    return rapid.AccessControlState(hdr=hdr, controller=controller, requestors=list(requestors))


__all__ = ["MEMBER", "ack", "ack_fields", "access_state", "command_in", "command_out", "config", "config_plain",
           "header", "now_us", "queue_state", "union", "union_value"]
