"""A command request from the page, checked before anything is sent: a source chosen, the
subsystem and command in the asset's dictionary, each argument parsed by its DataType and
held to its range and allowed values (as `rapidgen cmd` does), defaults filled."""
from __future__ import annotations

from dataclasses import dataclass
from types import SimpleNamespace

ACTIONS = ("BYPASS", "APPEND", "INSERT", "REPLACE", "DELETE")
TARGETED = ("INSERT", "REPLACE", "DELETE")  # act on a queued command: its cmdId is the targetCmdId
MAX_SOURCE = 31  # Command.cmdSrc is a String32
MAX_TARGET = 63  # Command.targetCmdId is a String64


class Refused(ValueError):
    """Why a request is not sent (shown to the operator)."""


@dataclass(frozen=True)
class Request:
    partition: str
    asset: str  # hdr.assetName
    subsystem: str
    command: str
    args: tuple  # ((DataType, value), ...)
    source: str
    action: str  # QUEUE_BYPASS | QUEUE_APPEND | QUEUE_INSERT | QUEUE_REPLACE | QUEUE_DELETE
    target: str = ""  # targetCmdId: INSERT after it, REPLACE or DELETE it


def check(msg: dict, commands: dict, asset_name: str) -> Request:
    """The page's {partition, subsystem, command, args: {name: text}, source, action, target}
    as a Request, or Refused with the reason. A DELETE carries its target's subsystem and
    command, and no arguments (the asset checks it as its sender sending the target)."""
    from rapid_runtime.values import coerce, limit_error, parse_text, shape_error

    source = msg.get("source")
    if not isinstance(source, str) or not source.strip():
        raise Refused("choose a command source (cmdSrc) first")
    if len(source.encode("utf-8")) > MAX_SOURCE or not source.isprintable():
        raise Refused(f"the source must be printable and at most {MAX_SOURCE} bytes")
    action = msg.get("action", "BYPASS")
    if action not in ACTIONS:
        raise Refused(f"unknown queue action {str(action)[:20]!r}")
    target = msg.get("target") or ""
    if not isinstance(target, str):
        raise Refused("the target must be a cmdId")
    if action in TARGETED and not target.strip():
        raise Refused(f"{action} acts on a queued command: choose it in the queue first")
    if action not in TARGETED and target:
        raise Refused(f"{action} takes no target")
    if len(target.encode("utf-8")) > MAX_TARGET or not target.isprintable():
        raise Refused(f"the target cmdId must be printable and at most {MAX_TARGET} bytes")
    sub, name = msg.get("subsystem"), msg.get("command")
    if not isinstance(sub, str) or not isinstance(name, str):
        raise Refused("a command needs a subsystem and a name")
    params = None
    for s in commands.get("subsystems", ()):
        if s["subsystem"] == sub:
            params = next((c["parameters"] for c in s["commands"] if c["name"] == name), None)
    if params is None:
        raise Refused(f"{sub}/{name} is not in the asset's command dictionary")
    given = msg.get("args") or {}
    if not isinstance(given, dict):
        raise Refused("arguments must be an object")
    out = []
    for p in params if action != "DELETE" else ():
        text = given.get(p["name"])
        if text is None or (isinstance(text, str) and text.strip() == "" and p["type"] != "RAPID_STRING"):
            if not p["has_default"]:
                raise Refused(f"{p['name']}: a value is needed ({p['type']})")
            value = coerce(p["type"], p["default"])
        else:
            try:
                value = coerce(p["type"], parse_text(p["type"], str(text)))
            except ValueError:
                raise Refused(f"{p['name']}: {str(text)[:40]!r} is not a {p['type']}") from None
        why = shape_error(p["type"], value) or limit_error(SimpleNamespace(**p), value)
        if why:
            raise Refused(f"{p['name']}: {why}")
        out.append((p["type"], value))
    return Request(msg.get("partition", ""), asset_name, sub, name, tuple(out), source.strip(), "QUEUE_" + action,
                   target)
