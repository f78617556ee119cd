"""`rapidgen record`: RAPID traffic on a domain into MCAP (docs/record.md); `rapidgen record
--info FILE` summarises a recording. Exit 0; 1 when cyclonedds or mcap is missing, a
descriptor has errors or a file cannot be written or read; 2 usage."""
from __future__ import annotations

import hashlib
import os
import re
import signal
import sys
import tempfile
import threading
import time

from rapidgen.argtypes import domain_id, positive_seconds
from rapidgen.live.dds import add_enclave_argument

BASE_DESCRIPTOR = """version: 1
asset: {name: RapidRecord, kind: other}
dds: {domain: 0}
subsystems: []
telemetry: []
"""
PROGRESS_SECONDS = 1.0  # on a terminal; a pipe or file gets a line every 5 s
_SIZE = re.compile(r"^\s*(\d+(?:\.\d+)?)\s*([kKmMgG]?)i?[bB]?\s*$")


def size(text: str) -> int:
    """'200M', '1.5G', '4096' -> bytes (a usage error otherwise)."""
    import argparse
    m = _SIZE.match(text)
    if not m or float(m.group(1)) <= 0:
        raise argparse.ArgumentTypeError(f"'{text}' is not a size (e.g. 500M, 2G, 65536)")
    return int(float(m.group(1)) * {"": 1, "k": 1 << 10, "m": 1 << 20, "g": 1 << 30}[m.group(2).lower()])


def add_parser(sub) -> None:
    p = sub.add_parser("record", help="record RAPID traffic into MCAP files (needs cyclonedds and mcap)",
                       description="Discover the RAPID writers on a domain and record every topic they write, "
                       "the CDR bytes as received, into an MCAP file (omgidl schemas, cdr messages; opens in "
                       "Foxglove and Lichtblick). Ctrl-C or SIGTERM closes the file. docs/record.md.")
    p.add_argument("--info", metavar="FILE", help="summarise a recording (complete or cut) and exit")
    p.add_argument("--asset", action="append", default=[], metavar="FILE",
                   help="an asset descriptor: its extension types, and its partition is recorded (repeatable)")
    p.add_argument("--partition", action="append", default=[], metavar="P",
                   help="record partition P (an asset's name; repeatable). Default: the --asset "
                   "descriptors' partitions, or every partition when none is given")
    p.add_argument("--domain", type=domain_id, metavar="N", help="DDS domain (default: the first --asset's, else 0)")
    p.add_argument("--transport", choices=("local", "lan", "wan"),
                   help="Cyclone transport (default: CYCLONEDDS_URI if set, else local: loopback only)")
    add_enclave_argument(p)
    p.add_argument("-o", "--output", metavar="FILE.mcap",
                   help="the file (default rapid-YYYYmmdd-HHMMSS.mcap); with rotation FILE-000.mcap, FILE-001.mcap, ...")
    p.add_argument("--seconds", type=positive_seconds, metavar="S", help="stop after S seconds (default: until Ctrl-C/SIGTERM)")
    p.add_argument("--split-size", type=size, metavar="SIZE", help="start a new file past SIZE (e.g. 500M)")
    p.add_argument("--split-seconds", type=positive_seconds, metavar="S", help="start a new file every S seconds")
    p.add_argument("--foxglove", action="store_true",
                   help="also write derived channels in Foxglove's well-known schemas (FrameTransform, "
                   "PoseInFrame, LocationFix, CompressedImage, Log, JointStates; docs/foxglove.md)")
    p.add_argument("--quiet", action="store_true", help="no progress line")


def open_assets(args):
    """What record and the live Foxglove server start from: the descriptors' bindings and
    models (errors reported), the transport chosen, the asset tables and the domain; None
    when a descriptor could not be loaded."""
    from rapidgen.diagnostics import DiagnosticSink
    from rapidgen.live.dds import use_transport
    from rapidgen.reporting import report
    sink = DiagnosticSink()
    loaded = load_types(args.asset, sink)
    report(sink)
    if loaded is None:
        return None
    bindings, models = loaded
    use_transport(bindings[0].transport_file(args.transport or "local"), keep_environment=args.transport is None,
                  enclave=args.enclave)
    assets = [b.tables["ASSET"] for b in bindings[1:]]
    domain = args.domain if args.domain is not None else (assets[0].get("domain", 0) if assets else 0)
    return bindings, models, assets, domain


def run(args) -> int:
    if args.info is not None:
        from rapidgen.record.info import print_info
        return print_info(args.info)
    from rapidgen.live.dds import dds_missing
    if dds_missing("record") or _mcap_missing("record"):
        return 1
    opened = open_assets(args)
    if opened is None:
        return 1
    bindings, models, assets, domain = opened
    partitions = set(args.partition) | {a.get("partition", a["name"]) for a in assets}
    output = args.output or time.strftime("rapid-%Y%m%d-%H%M%S.mcap")
    try:
        return _record(args, bindings, models, domain, partitions or None, output)
    except OSError as exc:
        print(f"rapidgen record: cannot write {output}: {exc.strerror or exc}", file=sys.stderr)
        return 1


def _mcap_missing(tool: str) -> bool:
    try:
        import mcap  # noqa: F401
    except ImportError:
        print(f"rapidgen {tool}: this command needs the mcap package; install it with: pip install 'rapidgen[dds]'",
              file=sys.stderr)
        return True
    return False


def load_types(files: list[str], sink):
    """([base bindings, one per descriptor], [their models]); None after diagnostics."""
    from rapidgen.generate import load_inputs
    from rapidgen.live.bindings import load_bindings
    with tempfile.TemporaryDirectory(prefix="rapidgen-record-") as tmp:
        base = os.path.join(tmp, "rapid-record.yaml")
        with open(base, "w", encoding="utf-8") as fh:
            fh.write(BASE_DESCRIPTOR)
        bindings, models = [], []
        for i, path in enumerate([base] + files):
            inputs = load_inputs([path], [], sink)
            b = load_bindings(path, sink, prefix="rapidrec_base" if i == 0 else f"rapidrec{i}") \
                if inputs is not None else None
            if inputs is None or b is None:
                return None
            bindings.append(b)
            models.append(inputs.model)
    return bindings, models


def _schema_finder(models):
    from rapidgen.record.schema import idl_text
    cache: dict[str, str | None] = {}

    def schema_of(type_name: str) -> str | None:
        if type_name not in cache:
            cache[type_name] = None
            for model in reversed(models):  # an asset's model holds the base types too
                if model.get(type_name) is not None:
                    try:
                        cache[type_name] = idl_text(model, type_name)
                    except (KeyError, ValueError):
                        pass
                    break
        return cache[type_name]
    return schema_of


def _read(path: str) -> bytes:
    with open(path, "rb") as fh:
        return fh.read()


def _record(args, bindings, models, domain: int, partitions: set[str] | None, output: str) -> int:
    from rapidgen import __version__
    from rapidgen.record.mcapfile import Sink
    from rapidgen.record.recorder import Recorder
    from rapidgen.textsafe import visible
    roles: dict[str, str] = {}
    for b in bindings:
        for t in b.tables.get("PUBLICATIONS", ()) or ():
            if isinstance(t, dict) and "topic" in t and "role" in t:
                roles.setdefault(t["topic"], t["role"])
    descriptors = [(f, _read(f)) for f in args.asset]
    metadata = {
        "rapidgen": {"version": __version__, "domain": str(domain), "started": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
                     "partitions": ",".join(sorted(partitions)) if partitions else "*"},
        "assets": {b.tables["ASSET"]["name"]: b.tables["ASSET"].get("partition", b.tables["ASSET"]["name"])
                   for b in bindings[1:]},
        "descriptors": {os.path.basename(f): hashlib.sha256(data).hexdigest() for f, data in descriptors},
    }
    # the descriptors themselves too (loaded and checked above, so bounded), as attachments
    attachments = tuple((os.path.basename(f), "application/yaml", data) for f, data in descriptors)
    stop = threading.Event()
    old = {s: signal.signal(s, lambda *_: stop.set()) for s in (signal.SIGINT, signal.SIGTERM)}
    sink = Sink(output, metadata, f"rapidgen {__version__}", args.split_size, args.split_seconds, attachments)
    rec = None
    try:
        rec = Recorder(domain, bindings, partitions, _schema_finder(models), sink, roles)
        if getattr(args, "foxglove", False):
            from rapidgen.record.derived import DerivedWriter
            rec.derived = DerivedWriter(sink, bindings)
        for b in bindings[1:]:
            rec.declared(b.qos, b.tables["ASSET"].get("partition", b.tables["ASSET"]["name"]))
    except Exception as exc:  # Cyclone refused to start (a bad CYCLONEDDS_URI, no interface)
        sink.close()
        if rec is not None:  # its participant deleted now (rapidgen/live/teardown.py)
            rec.close()
        for s, h in old.items():
            signal.signal(s, h)
        print(f"rapidgen record: cannot join domain {domain}: {visible(str(exc))[:300]}", file=sys.stderr)
        return 1
    where = ", ".join(sorted(partitions)) if partitions else "every partition"
    print(f"rapidgen record: recording domain {domain} ({visible(where)}) -> {visible(sink.files[0])}",
          file=sys.stderr, flush=True)
    started = last = shown = time.monotonic()
    tty = sys.stderr.isatty()
    try:
        while not stop.is_set():
            now = time.monotonic()
            if args.seconds is not None and now - started >= args.seconds:
                break
            if now - last >= 0.25 or not rec.streams:
                rec.discover()
                last = now
            if rec.take() == 0:
                time.sleep(0.005)
            sink.tick()
            if not args.quiet and now - shown >= (PROGRESS_SECONDS if tty else 5.0):
                _progress(rec, sink, now - started, now - shown, tty)
                shown = now
        rec.take()
    finally:
        for s, h in old.items():
            signal.signal(s, h)
        seen = sorted({st.channel.partition for st in rec.streams.values()})
        channels = len(rec.streams)
        sink.metadata_at_end({"partitions": ",".join(seen), "messages": str(sink.messages)})
        sink.close()
        rec.close()
    if tty and not args.quiet:
        sys.stderr.write("\n")
    for (topic, type_name), why in sorted(rec.skipped.items()):
        print(f"rapidgen record: not recorded: {visible(topic)} ({visible(type_name)}): {why}", file=sys.stderr)
    if rec.derived is not None:
        print(f"rapidgen record: {rec.derived.messages} derived Foxglove messages"
              + (f" ({rec.derived.undecodable} samples did not decode)" if rec.derived.undecodable else ""),
              file=sys.stderr)
    files = ", ".join(sink.files)
    print(f"rapidgen record: {sink.messages} messages, {sink.bytes} bytes on {channels} channel(s) "
          f"in {time.monotonic() - started:.1f} s -> {files}", file=sys.stderr)
    return 0


def _progress(rec, sink, elapsed: float, dt: float, tty: bool) -> None:
    from rapidgen.textsafe import visible
    rates = []
    for st in rec.streams.values():
        st.window = [st.window[1], st.count]
        if dt > 0:
            rates.append((st.count - st.window[0]) / dt)
    per_topic: dict[str, float] = {}
    for st, r in zip(rec.streams.values(), rates):
        per_topic[st.channel.topic] = per_topic.get(st.channel.topic, 0.0) + r
    busiest = sorted(per_topic.items(), key=lambda kv: -kv[1])[:6]
    topics = ", ".join(f"{visible(t)[:40]} {r:.1f}/s" for t, r in busiest)
    line = (f"recording {elapsed:6.1f} s  {sink.messages} msgs  {sink.bytes / 1048576:.2f} MiB  "
            f"{len(rec.streams)} channel(s)  {topics}")
    if tty:
        sys.stderr.write("\r\x1b[K" + line[:200])
    else:
        sys.stderr.write(line + "\n")
    sys.stderr.flush()
