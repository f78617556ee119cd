"""The `rapidgen cmd` run: load the asset (rapidgen.live.bindings), check the command, send
it once the asset listens, print its acks."""
from __future__ import annotations

import importlib
import sys
import time

from rapidgen.argtypes import domain_id
from rapidgen.live.dds import add_enclave_argument, security_refusal, use_enclave
from rapidgen.cmd.arguments import complete
from rapidgen.cmd.dictionary import live_config, merged_tables
from rapidgen.cmd.line import CMDLINE, CmdLine, did_you_mean, report
from rapidgen.cmd.recover import MAX_RESENDS, POLL, AssetWatch
from rapidgen.cmd.timing import DISCOVERY_TRIPS, allow, round_trip
from rapidgen.diagnostics import DiagnosticSink, SourceLoc
from rapidgen.textsafe import visible

ACTIONS = ("BYPASS", "APPEND", "INSERT", "REPLACE", "DELETE")
TARGETED = ("INSERT", "REPLACE", "DELETE")


def add_parser(sub) -> None:
    p = sub.add_parser("cmd", help="send a command to a live asset and print its acks (needs cyclonedds)",
                       description="Send SUBSYSTEM COMMAND to a live asset, arguments by name, checked against "
                       "its command dictionary first; print the acks. Exit 0 on COMPLETED/OK, else 1.")
    p.add_argument("asset", metavar="ASSET", help="asset descriptor (ASSET.yaml) or installed asset package")
    p.add_argument("subsystem", metavar="SUBSYSTEM")
    p.add_argument("command_name", metavar="COMMAND")
    p.add_argument("arguments", nargs="*", metavar="key=value", help="parameters by name; defaults fill the rest")
    p.add_argument("--action", default="BYPASS", metavar="ACTION",
                   help="queue action: BYPASS (default), APPEND, INSERT, REPLACE, DELETE")
    p.add_argument("--target", metavar="CMDID", help="the queued command INSERT, REPLACE or DELETE acts on")
    p.add_argument("--id", metavar="CMDID", help="this command's cmdId (default: a fresh unique one)")
    p.add_argument("--source", default="rapidgen", metavar="NAME", help="cmdSrc and srcName (default rapidgen)")
    p.add_argument("--domain", type=domain_id, metavar="N", help="DDS domain (default: the asset's)")
    p.add_argument("--transport", choices=("local", "lan", "wan"), help="Cyclone transport of the asset's QoS "
                   "files (default: local, loopback only, unless CYCLONEDDS_URI is set)")
    add_enclave_argument(p)
    p.add_argument("--timeout", type=float, default=30.0, metavar="S",
                   help="seconds to wait for the asset, then for completion (default 30)")
    p.add_argument("--discover", type=float, default=2.0, metavar="S",
                   help="seconds to wait for the live CommandConfig before using the descriptor's (default 2)")
    p.add_argument("--rtt", type=round_trip, default=0.0, metavar="SECONDS",
                   help="the link's round trip (e.g. 2.6 for the Moon): each wait above grows by what the link "
                        "costs (discovery 6 round trips, an answer 2; docs/field.md). Default 0: a LAN")
    p.add_argument("--from-descriptor", action="store_true", help="use the descriptor's dictionary, not the live one")
    p.add_argument("--no-check", action="store_true",
                   help="send values outside their range or allowed values (the asset answers BAD_SYNTAX)")
    p.add_argument("--no-wait", action="store_true", help="return after the first ack")


def _runtime_missing(sink: DiagnosticSink, what: str) -> None:
    sink.error("RG1909", f"`rapidgen cmd` needs {what}, which is not installed", SourceLoc(CMDLINE, 0, 0),
               "pip install cyclonedds==11.0.1 ./runtime  (the robot-side runtime, rapid_runtime)")


def load_asset(asset: str, line: CmdLine, sink: DiagnosticSink):
    """The asset's bindings (rapidgen.live.bindings), or None after diagnostics."""
    from rapidgen.live.bindings import import_bindings, load_bindings

    if asset.endswith((".yaml", ".yml")):
        return load_bindings(asset, sink, prefix="rapidgen_cmd")
    try:
        return import_bindings(asset)
    except ModuleNotFoundError as exc:
        if exc.name and exc.name.split(".")[0] == "cyclonedds":
            raise
        sink.error("RG1901", f"'{asset}' is neither an asset descriptor nor an installed asset package",
                   line.at(0), "give ASSET.yaml, or the name of a generated package (pip install out/python)")
    except Exception as exc:  # the package's RapidQosError: its QoS files are damaged
        if type(exc).__name__ != "RapidQosError":
            raise
        sink.error("RG1908", f"the asset's QoS files cannot be used: {exc}", SourceLoc(CMDLINE, 0, 0),
                   "regenerate the asset's package")
    return None


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
        report(sink, line)
        return 1
    return _run(args, line, sink)


def _run(args, line: CmdLine, sink: DiagnosticSink) -> int:
    from cyclonedds.core import DDSException
    from rapid_runtime.acks import COMPLETED, OK
    from rapid_runtime.commander import Commander
    from rapid_runtime.dds import use_transport
    from rapid_runtime.tables import Tables

    asset = load_asset(args.asset, line, sink)
    if asset is None:
        report(sink, line)
        return 1
    tables = Tables(asset.tables)
    action = args.action.upper().removeprefix("QUEUE_")
    if action not in ACTIONS:
        sink.error("RG1907", f"unknown queue action '{args.action}'", SourceLoc(CMDLINE, 0, 0),
                   did_you_mean(action, ACTIONS))
    elif (action in TARGETED) != bool(args.target):
        sink.error("RG1907", f"--action {action} " + ("needs --target CMDID" if action in TARGETED else
                                                      "takes no --target"), SourceLoc(CMDLINE, 0, 0),
                   "INSERT, REPLACE and DELETE name the queued command they act on; BYPASS and APPEND do not")
    if sink.has_errors:
        report(sink, line)
        return 1
    from rapidgen.live.cyclone_log import quiet_warnings
    quiet_warnings()  # a C++ bridge's retired acks: a Cyclone warning each (rapidgen/live/cyclone_log.py)
    try:
        use_transport(asset.qos, args.transport)
        if args.enclave:
            use_enclave(args.enclave)
        qos = asset.qos_module.RapidQos()
    except asset.qos_module.RapidQosError as exc:
        sink.error("RG1908", f"the asset's QoS files cannot be used: {exc}", SourceLoc(CMDLINE, 0, 0),
                   "regenerate the asset's package")
        report(sink, line)
        return 1
    domain = tables.domain if args.domain is None else args.domain
    # a DELETE/INSERT/REPLACE target's acks kept from the start (its history comes on match)
    try:  # (a refused Commander has deleted its participant itself)
        commander = Commander(asset.rapid, qos, tables.name, args.source, domain,
                              follow=(args.target,) if args.target else ())
    except DDSException as exc:  # what DDS Security refused, said plainly
        refused = security_refusal("cmd", "command", args.enclave, exc,
                                   "it writes the asset's commands and reads their acks", "command")
        if refused is None:
            raise
        print(refused, file=sys.stderr)
        return 1
    try:
        origin = "descriptor"
        if not args.from_descriptor:
            config = live_config(commander, asset.rapid, tables.name, allow(args.discover, args.rtt, DISCOVERY_TRIPS))
            if config is not None:
                tables, origin = Tables(merged_tables(asset.tables, config)), "live CommandConfig"
            else:
                print(f"cmd: no CommandConfig from {tables.name} within {allow(args.discover, args.rtt, DISCOVERY_TRIPS):g} s "
                      f"(domain {domain}); using the descriptor's dictionary", file=sys.stderr)
        payload = _checked(tables, action, args, line, sink, origin)
        if payload is None:
            report(sink, line)
            return 1
        if not commander.wait_for_asset(allow(args.timeout, args.rtt, DISCOVERY_TRIPS)):
            sink.error("RG1908", f"no asset {tables.name} reads commands on domain {domain}, partition "
                       f"'{tables.partition}' (waited {allow(args.timeout, args.rtt, DISCOVERY_TRIPS):g} s)", SourceLoc(CMDLINE, 0, 0),
                       "start its bridge (python -m <package>.bridge), or check --domain and --transport")
            report(sink, line)
            return 1
        shown = " ".join(f"{p.name}={_shown(v)}" for p, (_t, v) in zip(payload[0].params, payload[1]))
        watch = AssetWatch(commander, args.rtt, time.monotonic())  # before the send: who the asset is now
        cmd_id = commander.send(args.subsystem, args.command_name, payload[1], action="QUEUE_" + action,
                                target=args.target or "", cmd_id=args.id)

        def again() -> None:  # the same command, the same cmdId (docs/runtime.md, "The ground's part")
            print(f"cmd: {tables.name} {watch.why}; sending it again with the same cmdId "
                  f"({watch.resends} of {MAX_RESENDS})", file=sys.stderr, flush=True)
            commander.send(args.subsystem, args.command_name, payload[1], action="QUEUE_" + action,
                           target=args.target or "", cmd_id=cmd_id)
        print(f"{tables.name} <- {args.subsystem}/{args.command_name}" + (f" {shown}" if shown else "")
              + f"  [cmdId {cmd_id}, QUEUE_{action}" + (f" {args.target}" if args.target else "")
              + f", from {args.source}]", flush=True)
        acks = _follow(commander, cmd_id, allow(args.timeout, args.rtt), stop_at_first=args.no_wait,
                       watch=None if args.no_wait else watch, again=again)
        _warn_strangers(commander, cmd_id)
        if not acks:
            print(f"  no ack within {allow(args.timeout, args.rtt):g} s", flush=True)
            return 1
        # the first COMPLETED decides: acks taken in the same batch after it (a stranger's, on
        # the same cmdId) must not turn an answered command into a failure
        final = next((a for a in acks if a[0] == COMPLETED), acks[-1])
        if action == "DELETE" and final[0] == COMPLETED:
            print(f"target {visible(args.target)}:", flush=True)
            _follow(commander, args.target, allow(3.0, args.rtt))
        if final[0] == COMPLETED and final[1] != OK and "does not have control" in final[2]:
            print(f"  hint: send `rapidgen cmd {args.asset} AccessControl requestControl --source {args.source}` "
                  "first", file=sys.stderr)
        if args.no_wait:
            return 0 if final[0] != COMPLETED or final[1] == OK else 1
        return 0 if final[:2] == (COMPLETED, OK) else 1
    finally:  # reader stopped, participant deleted before the interpreter ends (rapid_runtime/teardown.py)
        commander.close()


def _checked(tables, action: str, args, line: CmdLine, sink: DiagnosticSink, origin: str):
    """(entry, [(DataType, value), ...]) or None with the problems in the sink."""
    if action != "BYPASS" and not tables.has_type("Queue"):
        sink.error("RG1907", f"--action {action}: asset {tables.name} has no command queue",
                   SourceLoc(CMDLINE, 0, 0), "send it as BYPASS (the default)")
        return None
    if tables.type_of(args.subsystem) is None:
        sink.error("RG1902", f"asset {tables.name} has no subsystem '{args.subsystem}' ({origin})", line.at(1),
                   did_you_mean(args.subsystem, tables.subsystems))
        return None
    entry = tables.command(args.subsystem, args.command_name)
    if entry is None:
        names = tables.commands_of_type(tables.type_of(args.subsystem))
        sink.error("RG1903", f"subsystem {args.subsystem} has no command '{args.command_name}' ({origin})",
                   line.at(2), did_you_mean(args.command_name, names))
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


def _follow(commander, cmd_id: str, timeout: float, stop_at_first: bool = False, watch: AssetWatch | None = None,
            again=None) -> list:
    """Print cmd_id's acks as they come, until COMPLETED (or the first, or timeout). With a
    watch: when the asset comes back without answering, again() sends the command again
    (recover.py) and the wait starts over."""
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
            now = time.monotonic()
            if watch is not None and watch.due(now, bool(acks)):
                again()
                end = max(end, now + timeout)  # bounded: MAX_RESENDS
            left = end - now
            if left <= 0:
                return list(acks)
            commander.cond.wait(left if watch is None else min(left, POLL))
