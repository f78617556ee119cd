"""`rapidgen replay FILE`: republish a recording (docs/record.md). Exit 0; 1 when cyclonedds
or mcap is missing, the file is not a readable recording or a descriptor has errors; 2 usage."""
from __future__ import annotations

import functools
import signal
import sys
import threading
import time

from rapidgen.argtypes import domain_id, positive_factor, seconds_from_start
from rapidgen.live.dds import add_enclave_argument
from rapidgen.textsafe import visible


def add_parser(sub) -> None:
    p = sub.add_parser("replay", help="republish a recording (MCAP) onto a DDS domain (needs cyclonedds and mcap)",
                       description="Publish a recording made by `rapidgen record`: configs first, then every "
                       "message at its recorded time (or --rate times faster), the recorded bytes, each channel "
                       "with its recorded reliability and durability. docs/record.md.")
    p.add_argument("files", nargs="+", metavar="FILE.mcap", help="a recording, or the files of a rotated one in order")
    p.add_argument("--domain", type=domain_id, metavar="N", help="DDS domain (default: the recording's)")
    p.add_argument("--partition", metavar="P", help="publish every channel in partition P (default: its recorded one)")
    p.add_argument("--rate", type=positive_factor, default=1.0, metavar="X", help="play X times as fast (default 1)")
    p.add_argument("--topics", metavar="T1,T2", help="replay only these topics (comma-separated)")
    p.add_argument("--from", dest="start", type=seconds_from_start, default=0.0, metavar="S",
                   help="start S seconds after the recording's first message")
    p.add_argument("--to", dest="stop", type=seconds_from_start, metavar="S",
                   help="stop S seconds after the recording's first message")
    p.add_argument("--asset", action="append", default=[], metavar="FILE",
                   help="an asset descriptor whose extension types the recording holds (repeatable)")
    p.add_argument("--transport", choices=("local", "lan", "wan"),
                   help="Cyclone transport (default: CYCLONEDDS_URI if set, else local: loopback only)")
    add_enclave_argument(p)
    p.add_argument("--linger", type=float, default=1.0, metavar="S",
                   help="keep the writers S seconds after the last message (default 1), for readers to catch up")
    p.add_argument("--quiet", action="store_true", help="no progress line")


def run(args) -> int:
    if args.stop is not None and args.stop <= args.start:
        print("rapidgen replay: --to must be after --from", file=sys.stderr)
        return 2
    if args.linger < 0:
        print("rapidgen replay: --linger must be 0 or more seconds", file=sys.stderr)
        return 2
    from rapidgen.live.dds import dds_missing, use_transport
    from rapidgen.record.command import _mcap_missing, load_types
    if dds_missing("replay") or _mcap_missing("replay"):
        return 1
    from rapidgen.record.mcapfile import RecordingError
    from rapidgen.record.replay import Plan
    try:
        recs, configs, start = _first_pass(args.files)
    except RecordingError as exc:
        print(f"rapidgen replay: {exc}", file=sys.stderr)
        return 1
    if start is None:
        print(f"rapidgen replay: {', '.join(args.files)}: no messages", file=sys.stderr)
        return 1
    from rapidgen.reporting import report
    from rapidgen.diagnostics import DiagnosticSink
    sink = DiagnosticSink()
    loaded = load_types(args.asset, sink)
    report(sink)
    if loaded is None:
        return 1
    bindings, _models = loaded
    from rapidgen.live.bindings import find_type_class
    find = functools.partial(find_type_class, bindings)
    schemas: dict[str, bytes] = {}  # the recording's own IDL, for the types no bindings know
    for rec in recs:
        for ch in rec.channels.values():
            schema = rec.schemas.get(ch.schema_id)
            t = ch.metadata.get("dds_type", "")
            if schema is not None and schema.encoding == "omgidl" and schema.name == t and find(t) is None:
                schemas.setdefault(t, schema.data)
    from rapidgen.record.schema_types import classes_from_schemas
    extra, refused, keep = classes_from_schemas(schemas) if schemas else ({}, {}, None)
    for type_name, why in sorted(refused.items()):
        print(f"rapidgen replay: no bindings for {visible(type_name)}: {why}", file=sys.stderr)
    use_transport(bindings[0].transport_file(args.transport or "local"), keep_environment=args.transport is None,
                  enclave=args.enclave)
    recorded = recs[0].metadata.get("rapidgen", {}).get("domain", "0")
    domain = args.domain if args.domain is not None else (int(recorded) if recorded.isdigit() else 0)
    topics = {t.strip() for t in args.topics.split(",") if t.strip()} if args.topics else None
    plan = Plan(start, start + int(args.start * 1e9), None if args.stop is None else start + int(args.stop * 1e9),
                topics, args.rate, args.partition)
    try:
        return _replay(args, recs, configs, lambda t: find(t) or extra.get(t.replace(".", "::")), domain, plan)
    finally:
        if keep is not None:
            keep.cleanup()


def _first_pass(files: list[str]):
    """(the recordings, their configs in publish order, the first log time of the other
    messages). A config carried into each file of a series (same sequence) counts once.
    The configs are held until the replay starts: at most MAX_CONFIG_BYTES, counting
    PER_CONFIG bytes for each besides its own (LimitError past it)."""
    from rapidgen.record.mcapfile import LimitError, open_recording
    from rapidgen.record.replay import MAX_CONFIG_BYTES, PER_CONFIG, is_config
    recs: list = []
    configs: dict[tuple, tuple] = {}
    held = 0
    start = first_config = None
    for path in files:
        rec, messages = open_recording(path)
        recs.append(rec)
        for _schema, channel, msg in messages:
            if is_config(channel):
                key = (channel.topic, channel.metadata.get("partition", ""), msg.sequence, msg.data)
                if key not in configs:
                    held += len(msg.data) + PER_CONFIG
                    if held > MAX_CONFIG_BYTES:
                        messages.close()
                        raise LimitError(f"{path}: its config messages take more than {MAX_CONFIG_BYTES >> 20} "
                                         f"MiB (counting {PER_CONFIG} bytes for each), the most replay holds to "
                                         "send them first: refused (a robot publishes a few configs; this file holds over "
                                         f"{len(configs)})")
                    configs[key] = (channel, msg)
                first_config = msg.log_time if first_config is None else min(first_config, msg.log_time)
            else:
                start = msg.log_time if start is None else min(start, msg.log_time)
    ordered = sorted(configs.values(), key=lambda cm: cm[1].publish_time)
    return recs, ordered, start if start is not None else first_config


def _messages(files: list[str]):
    """The files' messages, one file after the other (a file that cannot be read again ends it)."""
    from rapidgen.record.mcapfile import RecordingError, open_recording
    for path in files:
        try:
            _, messages = open_recording(path)
            yield from messages
        except RecordingError as exc:  # (a cap the first pass met already)
            print(f"rapidgen replay: {exc}", file=sys.stderr)
            return


def _replay(args, recs, configs, type_class, domain: int, plan) -> int:
    from rapidgen.record.replay import Replayer, in_window, is_config, pace
    stop = threading.Event()
    old = {s: signal.signal(s, lambda *_: stop.set()) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        rp = Replayer(domain, type_class, plan)
    except Exception as exc:  # Cyclone refused to start (a bad CYCLONEDDS_URI, no interface)
        for s, h in old.items():
            signal.signal(s, h)
        print(f"rapidgen replay: cannot join domain {domain}: {visible(str(exc))[:300]}", file=sys.stderr)
        return 1
    print(f"rapidgen replay: {visible(', '.join(args.files))} into domain {domain}"
          + (f", partition {visible(plan.partition)}" if plan.partition is not None else "")
          + (f", {args.rate:g}x" if args.rate != 1 else ""), file=sys.stderr)
    sent = 0
    try:
        for channel, msg in configs:  # the configs of the whole window, first
            if plan.end is None or msg.log_time <= plan.end:
                out = rp.out(channel)
                if out is not None and rp.send(out, msg.data):
                    sent += 1
        wall = time.monotonic()
        shown = wall
        for _schema, channel, msg in _messages(args.files):
            if stop.is_set() or (plan.end is not None and msg.log_time > plan.end):
                break
            if is_config(channel) or not in_window(plan, msg.log_time):
                continue
            out = rp.out(channel)
            if out is None:
                continue
            if not pace(plan, wall, msg.log_time, stop):
                break
            if rp.send(out, msg.data):
                sent += 1
            now = time.monotonic()
            if not args.quiet and now - shown >= 5.0:
                shown = now
                print(f"replaying {(msg.log_time - plan.start) / 1e9:7.1f} s  {sent} messages sent", file=sys.stderr)
        if not stop.is_set():
            stop.wait(args.linger)
    finally:
        for s, h in old.items():
            signal.signal(s, h)
        outs = [o for o in plan.outs.values() if o is not None]
        rp.close()
    for where, why in sorted(plan.not_replayed.items()):
        print(f"rapidgen replay: not replayed: {where}: {why}", file=sys.stderr)
    for o in outs:
        if o.skipped:
            print(f"rapidgen replay: {o.skipped} message(s) of [{visible(o.partition)}] {visible(o.topic)} skipped "
                  f"({o.first_error})", file=sys.stderr)
    for rec in recs:
        if rec.cut_reason or not rec.complete:
            print(f"rapidgen replay: {visible(rec.path)} is cut; replayed up to its last whole chunk "
                  f"({visible(rec.cut_reason or 'no summary')})", file=sys.stderr)
    print(f"rapidgen replay: {sent} messages sent on {len(outs)} channel(s)", file=sys.stderr)
    return 0
