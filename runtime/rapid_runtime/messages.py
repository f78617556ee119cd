"""Plain data <-> the generated cyclonedds classes. `rapid` is the generated package's
`rapid` module (the asset's own types: the runtime brings none)."""
from __future__ import annotations

import time
import typing
from dataclasses import dataclass

from cyclonedds.idl import IdlEnum, IdlStruct, IdlUnion
from cyclonedds.idl import types as T

from rapid_runtime.acks import valid
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


# The names every command carries (its sender, asset, subsystem and command): one str object
# each, however many commands carry them, rather than one decoded copy per command (the
# command window remembers thousands of commands: manager.py, journal.py). Wire text, so not
# sys.intern (interned strings may live for good): a table of at most NAMES_KEPT, emptied when
# full.
NAMES_KEPT = 1024
_names: dict[str, str] = {}


def shared_name(text: str) -> str:
    """text, or an equal str object seen before."""
    got = _names.get(text)
    if got is None:
        if len(_names) >= NAMES_KEPT:
            _names.clear()
        got = _names.setdefault(text, text)
    return got


def command_in(sample) -> Cmd:
    """A received rapid::Command as Cmd (its names shared: shared_name)."""
    hdr = sample.hdr
    return Cmd(cmd_id=sample.cmdId, cmd_src=shared_name(sample.cmdSrc), subsystem=shared_name(sample.subsysName),
               name=shared_name(sample.cmdName), args=tuple(union_value(a) for a in sample.arguments),
               action=_enum_name(sample.cmdAction), target=sample.targetCmdId, src_name=shared_name(hdr.srcName),
               asset_name=shared_name(hdr.assetName), serial=hdr.serial, raw=sample)


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


# ---- images --------------------------------------------------------------------------------

IDENTITY = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]


def image_meta(rapid, sensor: str, sensor_type: str, width: int, height: int, offset=None, extras=()):
    """ImageMetadata; offset (xyz, rot9) of the sensor in the asset's frame (default: at the
    origin, identity rotation); extras as (key, DataType, value) triples."""
    xyz, rot = offset if offset is not None else ([0.0, 0.0, 0.0], IDENTITY)
    return rapid.ImageMetadata(
        sensorName=sensor, sensorType=sensor_type, width=int(width), height=int(height),
        offset=rapid.Transform3D(xyz=[float(x) for x in xyz], rot=[float(x) for x in rot]),
        extras=[rapid.KeyTypeValueTriple(key=k, padding=0, value=union(rapid, t, v)) for k, t, v in extras])


def image_sample(rapid, hdr, meta, mime: str, data: bytes):
    return rapid.ImageSensorSample(hdr=hdr, meta=meta, mimeType=mime, data=list(data))


def image_state(rapid, hdr, meta):
    return rapid.ImageSensorState(hdr=hdr, meta=meta)


# ---- any generated class, by its members (extension types) ---------------------------------------

@dataclass(frozen=True)
class Shape:
    """What an IDL member annotation is: kind struct|enum|union (cls), sequence|array (elem,
    bound: the maximum or exact length), string (bound, None: unbounded), bool, int (bits,
    signed), float (bits), char, optional (elem)."""
    kind: str
    cls: typing.Any = None
    elem: typing.Any = None
    bound: int | None = None
    signed: bool = True


_PRIMITIVE = {"float32": ("float", 32), "float64": ("float", 64), "int8": ("int", 8), "int16": ("int", 16),
              "int32": ("int", 32), "int64": ("int", 64), "uint8": ("uint", 8), "uint16": ("uint", 16),
              "uint32": ("uint", 32), "uint64": ("uint", 64), "byte": ("uint", 8)}


def shape(tp) -> Shape:
    """The Shape of a generated class's member annotation (typedefs see through)."""
    if typing.get_origin(tp) is typing.Annotated:
        base, meta = typing.get_args(tp)[:2]
        found = _meta_shape(meta)
        return found if found is not None else shape(base)
    found = _meta_shape(tp)  # cyclonedds keeps some nested annotations unwrapped (typedef of typedef)
    if found is not None:
        return found
    if typing.get_origin(tp) is typing.Union:
        inner = [a for a in typing.get_args(tp) if a is not type(None)]
        if len(inner) == 1:
            return Shape("optional", elem=inner[0])
    if isinstance(tp, type):
        if issubclass(tp, IdlStruct):
            return Shape("struct", cls=tp)
        if issubclass(tp, IdlUnion):
            return Shape("union", cls=tp)
        if issubclass(tp, IdlEnum):
            return Shape("enum", cls=tp)
        if tp is bool:
            return Shape("bool")
        if tp is int:
            return Shape("int", bound=64)
        if tp is float:
            return Shape("float", bound=64)
        if tp is str:
            return Shape("string")
    raise TypeError(f"no shape for member type {tp!r}")


def _meta_shape(meta) -> Shape | None:
    if isinstance(meta, T.typedef):
        return shape(meta.subtype)
    if isinstance(meta, T.array):
        return Shape("array", elem=meta.subtype, bound=meta.length)
    if isinstance(meta, T.sequence):
        return Shape("sequence", elem=meta.subtype, bound=meta.max_length)
    if isinstance(meta, T.bounded_str):
        return Shape("string", bound=meta.max_length)
    if isinstance(meta, (T.case, T.default)):
        return shape(meta.subtype)
    if isinstance(meta, str):
        if meta in ("char", "wchar"):
            return Shape("char")
        if meta in _PRIMITIVE:
            kind, bits = _PRIMITIVE[meta]
            return Shape("float" if kind == "float" else "int", bound=bits, signed=kind == "int")
    return None


def members(cls) -> dict[str, object]:
    """Member name -> annotation, in declaration order (a union's: its cases)."""
    return typing.get_type_hints(cls, include_extras=True)


def case_labels(cls) -> dict[str, list]:
    """A union's case name -> its discriminator labels ([] for the default case)."""
    out = {}
    for name, tp in members(cls).items():
        meta = typing.get_args(tp)[1] if typing.get_origin(tp) is typing.Annotated else None
        out[name] = list(meta.labels) if isinstance(meta, T.case) else []
    return out


def build(cls, values: dict):
    """An instance of a generated struct from plain data: `values` by member name; nested
    structs as dicts (or instances), enums by enumerator name (or value), a union as
    {case: value}, sequences as lists (octets also as bytes). Members not given keep the
    class's defaults. KeyError for a member the type does not have, TypeError or ValueError
    for a value that does not fit (wrong kind, too long, out of range)."""
    if isinstance(values, cls):
        return values
    if not isinstance(values, dict):
        raise TypeError(f"{cls.__name__}: a dict of members, not {type(values).__name__}")
    known = members(cls)
    unknown = [k for k in values if k not in known]
    if unknown:
        raise KeyError(f"{cls.__name__} has no member {', '.join(map(str, unknown))} "
                       f"(members: {', '.join(known)})")
    return cls(**{k: convert(known[k], v, f"{cls.__name__}.{k}") for k, v in values.items()})


def convert(tp, value, where: str = "value"):
    """Plain data as the member annotation tp wants it (see build)."""
    s = shape(tp)
    if s.kind == "struct":
        return build(s.cls, value)
    if s.kind == "enum":
        if isinstance(value, s.cls):
            return value
        try:
            return s.cls[value] if isinstance(value, str) else s.cls(value)
        except (KeyError, ValueError):
            raise ValueError(f"{where}: {value!r} is not one of {', '.join(e.name for e in s.cls)}") from None
    if s.kind == "union":
        if isinstance(value, s.cls):
            return value
        if not (isinstance(value, dict) and len(value) == 1):
            raise TypeError(f"{where}: a union as {{case: value}}, one of {', '.join(members(s.cls))}")
        (case, v), = value.items()
        cases = members(s.cls)
        if case not in cases:
            raise KeyError(f"{where}: no case {case!r} (cases: {', '.join(cases)})")
        return s.cls(**{case: convert(cases[case], v, f"{where}.{case}")})
    if s.kind in ("sequence", "array"):
        if isinstance(value, (str, dict)) or not hasattr(value, "__len__"):
            raise TypeError(f"{where}: a list, not {type(value).__name__}")
        n = len(value)
        if s.kind == "array" and n != s.bound:
            raise ValueError(f"{where}: {n} elements for an array of {s.bound}")
        if s.kind == "sequence" and s.bound is not None and n > s.bound:
            raise ValueError(f"{where}: {n} elements, at most {s.bound}")
        if isinstance(value, (bytes, bytearray)):
            elem = shape(s.elem)
            if elem.kind != "int" or elem.bound != 8:
                raise TypeError(f"{where}: bytes for a {s.kind} of {elem.kind}")
            return list(value)
        return [convert(s.elem, x, f"{where}[{i}]") for i, x in enumerate(value)]
    if s.kind == "optional":
        return None if value is None else convert(s.elem, value, where)
    if s.kind == "string":
        if not isinstance(value, str):
            raise TypeError(f"{where}: a string, not {type(value).__name__}")
        value = valid(value)  # a lone surrogate or a NUL: U+FFFD (acks.valid), before the bound is checked
        if s.bound is not None and len(value.encode("utf-8")) > s.bound:
            raise ValueError(f"{where}: {len(value.encode('utf-8'))} bytes, at most {s.bound}")
        return value
    if s.kind == "char":
        if not (isinstance(value, str) and len(value) == 1):
            raise TypeError(f"{where}: one character")
        return value
    if s.kind == "bool":
        if not isinstance(value, bool):
            raise TypeError(f"{where}: true or false, not {value!r}")
        return value
    if s.kind == "int":
        if isinstance(value, bool) or not isinstance(value, int):
            raise TypeError(f"{where}: an integer, not {value!r}")
        bits = s.bound or 64
        lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if s.signed else (0, (1 << bits) - 1)
        if not lo <= value <= hi:
            raise ValueError(f"{where}: {value} outside [{lo}, {hi}]")
        return value
    if s.kind == "float":
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise TypeError(f"{where}: a number, not {value!r}")
        return float(value)
    raise TypeError(f"{where}: cannot convert to {s.kind}")  # pragma: no cover


__all__ = ["IDENTITY", "MEMBER", "Shape", "ack", "ack_fields", "access_state", "build", "case_labels",
           "command_in", "command_out", "config", "config_plain", "convert", "header", "image_meta",
           "image_sample", "image_state", "members", "now_us", "queue_state", "shape", "union", "union_value"]
