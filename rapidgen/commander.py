"""`rapidgen cmd ASSET SUBSYSTEM COMMAND key=value ...`: a command to a live asset.

ASSET is a descriptor (the asset's package is generated into a temporary folder for its
types, QoS and tables) or an importable generated package (`rapid_k10red`). The
dictionary is the asset's live CommandConfig, merged with the descriptor's units, ranges,
allowed values and defaults; `--from-descriptor`, or no config within `--discover`
seconds, uses the descriptor's alone. Arguments are checked before anything is sent; a
bad one is a located error on the command line (exit 1). The acks are printed as they
come; exit 0 on COMPLETED/OK, 1 otherwise. The protocol side is rapid_runtime.commander;
cyclonedds and rapid_runtime are imported here, lazily, so the compiler runs without them.
"""
from __future__ import annotations

import difflib
import importlib
import os
import shlex
import sys
import tempfile
import time
from dataclasses import dataclass
from types import ModuleType

from rapidgen.textsafe import visible
from rapidgen.diagnostics import DiagnosticSink, FileLineCache, SourceLoc, render

CMDLINE = "<command line>"
ACTIONS = ("BYPASS", "APPEND", "INSERT", "REPLACE", "DELETE")
TARGETED = ("INSERT", "REPLACE", "DELETE")
KIND = {"RAPID_BOOL": "a boolean (true/false)", "RAPID_INT": "a 32-bit integer", "RAPID_LONGLONG": "a 64-bit integer",
        "RAPID_FLOAT": "a number", "RAPID_DOUBLE": "a number", "RAPID_STRING": "a string",
        "RAPID_VEC3d": "3 numbers (x,y,z)", "RAPID_MAT33f": "9 numbers (row by row)"}


class CmdLine:
    """The command's words as one line, so a diagnostic can point at a word (column)."""

    def __init__(self, words: list[str]) -> None:
        self.words = words
        self.text = " ".join(shlex.quote(w) for w in words)
        self.cols, col = [], 1
        for w in words:
            self.cols.append(col)
            col += len(shlex.quote(w)) + 1

    def at(self, index: int, offset: int = 0, length: int | None = None) -> SourceLoc:
        col = self.cols[index] + offset
        width = len(shlex.quote(self.words[index])) - offset if length is None else length
        return SourceLoc(CMDLINE, 1, col, 1, col + max(1, width))


def _report(sink: DiagnosticSink, line: CmdLine) -> None:
    lines = FileLineCache()
    lines.add_text(CMDLINE, line.text)
    for d in sink.sorted():
        print(render(d, lines), file=sys.stderr)
    n = len(sink.errors)
    print(f"rapidgen: {n} error{'s' * (n != 1)}", file=sys.stderr)


def _did_you_mean(name: str, choices) -> str:
    close = difflib.get_close_matches(name, list(choices), n=1, cutoff=0.6)
    shown = ", ".join(sorted(choices)) or "none"
    return f"did you mean '{close[0]}'? (known: {shown})" if close else f"known: {shown}"


# -- the asset: types, QoS and tables ---------------------------------------------------------
@dataclass
class Asset:
    rapid: object  # the package's `rapid` module
    qos_mod: ModuleType  # the package's `qos` module
    tables_data: dict  # the asset_tables module's literals


def _runtime_missing(sink: DiagnosticSink, what: str) -> None:
    sink.error("RG1909", f"`rapidgen cmd` needs {what}, which is not installed", SourceLoc(CMDLINE, 0, 0),
               "pip install cyclonedds==11.0.1 ./runtime  (the robot-side runtime, rapid_runtime)")


def _import_package(package: str):
    return (importlib.import_module(f"{package}.rapid"), importlib.import_module(f"{package}.qos"),
            vars(importlib.import_module(f"{package}.asset_tables")))


def load_asset(asset: str, line: CmdLine, sink: DiagnosticSink, tmp: str) -> Asset | None:
    if asset.endswith((".yaml", ".yml")):
        from rapidgen.generate import load_inputs, render as render_targets

        inputs = load_inputs([asset], [], sink)
        per_lang = render_targets(inputs, ["python"], sink, "rapidgen_cmd_asset") if inputs else None
        if per_lang is None:
            return None
        for f in per_lang["python"]:
            path = os.path.join(tmp, *f.path.split("/"))
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(f.content)
        sys.path.insert(0, tmp)
        return Asset(*_import_package("rapidgen_cmd_asset"))
    try:
        return Asset(*_import_package(asset))
    except ModuleNotFoundError as exc:
        if exc.name and exc.name.split(".")[0] == "cyclonedds":
            raise
        sink.error("RG1901", f"'{asset}' is neither an asset descriptor nor an installed asset package",
                   line.at(0), "give ASSET.yaml, or the name of a generated package (pip install out/python)")
        return None


# -- the dictionary ---------------------------------------------------------------------------
def live_config(commander, rapid, asset: str, seconds: float) -> dict | None:
    """The asset's CommandConfig (transient-local: a late reader still gets it), or None."""
    from rapid_runtime import messages as M
    from rapid_runtime.commander import COMMAND_CONFIG_TOPIC

    from rapidgen.live.take import GuardedReader

    guard = GuardedReader(commander.node.reader(COMMAND_CONFIG_TOPIC, rapid.CommandConfig), dedupe=True, batch=4)
    end = time.monotonic() + seconds
    try:
        while time.monotonic() < end:
            for s in guard.take():  # a config that does not decode is someone else's: dropped, said below
                if s.hdr.assetName == asset:
                    return M.config_plain(s)
            time.sleep(0.02)
        return None
    finally:
        for note in guard.summary():
            print(f"cmd: {note}", file=sys.stderr)


def merged_tables(data: dict, config: dict) -> dict:
    """The tables with the live config's subsystems and commands; a parameter keeps the
    descriptor's unit, range, allowed values and default when its name and type agree."""
    known = data["COMMANDS"]
    commands: dict[str, dict] = {}
    for t in config["availableSubsystemTypes"]:
        out = commands[t["name"]] = {}
        for c in t["commands"]:
            mine = known.get(t["name"], {}).get(c["name"], {})
            by_name = {p["name"]: p for p in mine.get("parameters", ())}
            params = []
            for p in c["parameters"]:
                d = by_name.get(p["key"])
                params.append(dict(d) if d and d["type"] == p["type"] else
                               {"name": p["key"], "arg": p["key"], "type": p["type"]})
            out[c["name"]] = {"method": mine.get("method", c["name"]), "abortable": c["abortable"],
                              "suspendable": c["suspendable"], "parameters": params}
    subsystems = {s["name"]: s["subsystemTypeName"] for s in config["availableSubsystems"]}
    return dict(data, SUBSYSTEMS=subsystems, COMMANDS=commands)


# -- arguments --------------------------------------------------------------------------------
def _check_value(p, value, line: CmdLine, index: int, offset: int, sink: DiagnosticSink, limits: bool):
    from rapid_runtime.values import coerce, limit_error, shape_error

    value = coerce(p.type, value)
    why = shape_error(p.type, value) or (limit_error(p, value) if limits else None)
    if why:
        unit = f" [{p.unit}]" if p.unit else ""
        sink.error("RG1905", f"{p.name}: {why}", line.at(index, offset),
                   f"{p.name} is {KIND.get(p.type, p.type)}{unit}" + _limits_text(p))
        return None
    return value


def _limits_text(p) -> str:
    parts = []
    if p.min is not None or p.max is not None:
        parts.append(f"in [{'-inf' if p.min is None else f'{p.min:g}'}, {'inf' if p.max is None else f'{p.max:g}'}]")
    if p.allowed:
        parts.append("one of " + "|".join(map(str, p.allowed)))
    return (", " + ", ".join(parts)) if parts else ""


def complete(entry, words: list[str], first: int, line: CmdLine, sink: DiagnosticSink,
             limits: bool = True) -> list[tuple[str, object]] | None:
    """(DataType, value) per parameter in order: key=value words parsed by type, defaults
    filled, every problem reported at its word. None when any was found."""
    from rapid_runtime.values import parse_text

    by_key = {}
    for p in entry.params:
        by_key[p.name] = p
        by_key.setdefault(p.arg, p)
    given: dict[str, object] = {}
    for i, word in enumerate(words, first):
        key, eq, text = word.partition("=")
        if not eq or not key:
            sink.error("RG1904", f"'{word}' is not key=value", line.at(i),
                       f"{entry.name} takes " + (", ".join(f"{p.name}=..." for p in entry.params) or "no arguments"))
            continue
        p = by_key.get(key)
        if p is None:
            sink.error("RG1904", f"{entry.name} has no parameter '{key}'", line.at(i, 0, len(key)),
                       _did_you_mean(key, [q.name for q in entry.params]))
            continue
        if p.name in given:
            sink.error("RG1904", f"'{p.name}' given twice", line.at(i, 0, len(key)), "give each parameter once")
            continue
        offset = len(key) + 1 + (shlex.quote(word) != word)  # the value's column (after an opening quote)
        try:
            value = parse_text(p.type, text)
        except ValueError:
            sink.error("RG1905", f"{p.name}: '{text}' is not {KIND.get(p.type, p.type)}", line.at(i, offset),
                       f"{p.name} is {p.type}" + (f" [{p.unit}]" if p.unit else "") + _limits_text(p))
            given[p.name] = None
            continue
        given[p.name] = _check_value(p, value, line, i, offset, sink, limits)
    missing = [p for p in entry.params if p.name not in given and not p.has_default]
    if missing:
        sink.error("RG1906", f"{entry.name} needs " + ", ".join(f"{p.name} ({p.type})" for p in missing),
                   line.at(2), "add " + " ".join(f"{p.name}=..." for p in missing))
    if sink.has_errors:
        return None
    from rapid_runtime.values import coerce
    return [(p.type, given[p.name] if p.name in given else coerce(p.type, p.default)) for p in entry.params]


def _shown(value) -> str:
    if isinstance(value, list):
        return ",".join(f"{x:g}" if isinstance(x, float) else str(x) for x in value)
    return repr(value) if isinstance(value, str) else str(value).lower() if isinstance(value, bool) else f"{value}"


def _status(ack: tuple[str, str, str]) -> str:
    status, completed, message = ack
    text = status.removeprefix("ACK_")
    if status == "ACK_COMPLETED" or completed != "ACK_COMPLETED_NOT":
        text += " " + completed.removeprefix("ACK_COMPLETED_")
    return text + (f"  {visible(message)}" if message else "")  # the wire's text: never raw on a terminal


# -- the run ----------------------------------------------------------------------------------
def run_cmd(args, sink: DiagnosticSink) -> int:
    line = CmdLine([args.asset, args.subsystem, args.command_name, *args.arguments])
    try:
        importlib.import_module("cyclonedds")
    except ImportError:
        _runtime_missing(sink, "cyclonedds")
    try:
        importlib.import_module("rapid_runtime")
    except ImportError:
        _runtime_missing(sink, "the runtime (rapid_runtime)")
    if sink.has_errors:
        _report(sink, line)
        return 1
    with tempfile.TemporaryDirectory(prefix="rapidgen-cmd-") as tmp:
        try:
            return _run(args, line, sink, tmp)
        finally:
            if tmp in sys.path:
                sys.path.remove(tmp)


def _run(args, line: CmdLine, sink: DiagnosticSink, tmp: str) -> int:
    from rapid_runtime.acks import COMPLETED, OK
    from rapid_runtime.commander import Commander
    from rapid_runtime.dds import use_transport
    from rapid_runtime.tables import Tables

    asset = load_asset(args.asset, line, sink, tmp)
    if asset is None:
        _report(sink, line)
        return 1
    tables = Tables(asset.tables_data)
    action = args.action.upper().removeprefix("QUEUE_")
    if action not in ACTIONS:
        sink.error("RG1907", f"unknown queue action '{args.action}'", SourceLoc(CMDLINE, 0, 0),
                   _did_you_mean(action, ACTIONS))
    elif (action in TARGETED) != bool(args.target):
        sink.error("RG1907", f"--action {action} " + ("needs --target CMDID" if action in TARGETED else
                                                      "takes no --target"), SourceLoc(CMDLINE, 0, 0),
                   "INSERT, REPLACE and DELETE name the queued command they act on; BYPASS and APPEND do not")
    if sink.has_errors:
        _report(sink, line)
        return 1
    try:
        use_transport(asset.qos_mod.RapidQos(), args.transport)
        qos = asset.qos_mod.RapidQos()
    except asset.qos_mod.RapidQosError as exc:
        sink.error("RG1908", f"the asset's QoS files cannot be used: {exc}", SourceLoc(CMDLINE, 0, 0),
                   "regenerate the asset's package")
        _report(sink, line)
        return 1
    domain = tables.domain if args.domain is None else args.domain
    commander = Commander(asset.rapid, qos, tables.name, args.source, domain)
    try:
        origin = "descriptor"
        if not args.from_descriptor:
            config = live_config(commander, asset.rapid, tables.name, args.discover)
            if config is not None:
                tables, origin = Tables(merged_tables(asset.tables_data, config)), "live CommandConfig"
            else:
                print(f"cmd: no CommandConfig from {tables.name} within {args.discover:g} s "
                      f"(domain {domain}); using the descriptor's dictionary", file=sys.stderr)
        payload = _checked(tables, action, args, line, sink, origin)
        if payload is None:
            _report(sink, line)
            return 1
        if not commander.wait_for_asset(args.timeout):
            sink.error("RG1908", f"no asset {tables.name} reads commands on domain {domain}, partition "
                       f"'{tables.partition}' (waited {args.timeout:g} s)", SourceLoc(CMDLINE, 0, 0),
                       "start its bridge (python -m <package>.bridge), or check --domain and --transport")
            _report(sink, line)
            return 1
        shown = " ".join(f"{p.name}={_shown(v)}" for p, (_t, v) in zip(payload[0].params, payload[1]))
        if args.target:
            commander.follow(args.target)
        cmd_id = commander.send(args.subsystem, args.command_name, payload[1], action="QUEUE_" + action,
                                target=args.target or "", cmd_id=args.id)
        print(f"{tables.name} <- {args.subsystem}/{args.command_name}" + (f" {shown}" if shown else "")
              + f"  [cmdId {cmd_id}, QUEUE_{action}" + (f" {args.target}" if args.target else "")
              + f", from {args.source}]", flush=True)
        acks = _follow(commander, cmd_id, args.timeout, stop_at_first=args.no_wait)
        _warn_strangers(commander, cmd_id)
        if not acks:
            print(f"  no ack within {args.timeout:g} s", flush=True)
            return 1
        final = acks[-1]
        if action == "DELETE" and final[0] == COMPLETED:
            print(f"target {visible(args.target)}:", flush=True)
            _follow(commander, args.target, 3.0)
        if final[0] == COMPLETED and final[1] != OK and "does not have control" in final[2]:
            print(f"  hint: send `rapidgen cmd {args.asset} AccessControl requestControl --source {args.source}` "
                  "first", file=sys.stderr)
        if args.no_wait:
            return 0 if final[0] != COMPLETED or final[1] == OK else 1
        return 0 if final[:2] == (COMPLETED, OK) else 1
    finally:
        commander.close()


def _checked(tables, action: str, args, line: CmdLine, sink: DiagnosticSink, origin: str):
    """(entry, [(DataType, value), ...]) or None with the problems in the sink."""
    if action != "BYPASS" and not tables.has_type("Queue"):
        sink.error("RG1907", f"--action {action}: asset {tables.name} has no command queue",
                   SourceLoc(CMDLINE, 0, 0), "send it as BYPASS (the default)")
        return None
    if tables.type_of(args.subsystem) is None:
        sink.error("RG1902", f"asset {tables.name} has no subsystem '{args.subsystem}' ({origin})", line.at(1),
                   _did_you_mean(args.subsystem, tables.subsystems))
        return None
    entry = tables.command(args.subsystem, args.command_name)
    if entry is None:
        names = tables.commands_of_type(tables.type_of(args.subsystem))
        sink.error("RG1903", f"subsystem {args.subsystem} has no command '{args.command_name}' ({origin})",
                   line.at(2), _did_you_mean(args.command_name, names))
        return None
    values = complete(entry, list(args.arguments), 3, line, sink, limits=not args.no_check)
    return None if values is None else (entry, values)


def _warn_strangers(commander, cmd_id: str) -> None:
    """Say when more than one writer answered, or acks were dropped (docs/security.md). Acks
    for other commanders' commands are normal on a shared partition: counted, not shown."""
    with commander.cond:
        writers, dropped = len(commander.writers.get(cmd_id, ())), list(commander.dropped)
    if writers > 1:
        print(f"cmd: warning: acks of {visible(cmd_id)} came from {writers} writers; only the asset should "
              "answer (a stranger on the domain? DDS Security keeps them out)", file=sys.stderr)
    for line in dropped:
        print(f"cmd: {line}", file=sys.stderr)


def _follow(commander, cmd_id: str, timeout: float, stop_at_first: bool = False) -> list:
    """Print cmd_id's acks as they come, until COMPLETED (or the first, or timeout)."""
    from rapid_runtime.acks import COMPLETED

    end, printed = time.monotonic() + timeout, 0
    with commander.cond:
        while True:
            acks = commander.acks.get(cmd_id, [])
            for ack in acks[printed:]:
                print(f"  {_status(ack)}", flush=True)
            printed = len(acks)
            if acks and (stop_at_first or any(a[0] == COMPLETED for a in acks)):
                return list(acks)
            left = end - time.monotonic()
            if left <= 0:
                return list(acks)
            commander.cond.wait(left)
