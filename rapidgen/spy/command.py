"""`rapidgen spy`: the command line. Loads the RAPID types (the shipped IDL, through a
minimal descriptor) and each --asset's (its extension types, roles, rates), joins the
domain, watches, prints. Exit 0; 1 when cyclonedds is missing, a descriptor has errors,
or (--strict) a diagnosis fired; 2 usage; Ctrl-C in the live view exits 0."""
from __future__ import annotations

import os
import signal
import sys
import tempfile
import time
from rapidgen.argtypes import domain_id
from rapidgen.live.dds import add_enclave_argument

BASE_DESCRIPTOR = """version: 1
asset: {name: RapidSpy, kind: other}
dds: {domain: 0}
subsystems: []
telemetry: []
"""


def add_parser(sub) -> None:
    p = sub.add_parser("spy", help="watch a live RAPID network and diagnose it (needs cyclonedds)",
                       description="Discover participants, writers and readers per asset (partition), with role, "
                       "QoS profile, rate and latest configs, and diagnose known faults (docs/spy.md). "
                       "`rapidgen spy echo TOPIC` prints a topic's samples.")
    p.add_argument("echo", nargs="*", metavar="echo TOPIC", help="print TOPIC's samples instead of the overview")
    p.add_argument("--domain", type=domain_id, metavar="N", help="DDS domain (default: the first --asset's, else 0)")
    p.add_argument("--transport", choices=("local", "lan", "wan"),
                   help="Cyclone transport (default: CYCLONEDDS_URI if set, else local: loopback only)")
    add_enclave_argument(p)
    p.add_argument("--partition", action="append", default=[], metavar="P", help="watch only partition P (repeatable)")
    p.add_argument("--asset", action="append", default=[], metavar="FILE",
                   help="an asset descriptor: its extension types, roles, rates and config pairs (repeatable)")
    p.add_argument("--seconds", type=float, metavar="S", help="watch S seconds (overview default 3; echo: until Ctrl-C)")
    p.add_argument("--once", action="store_true", help="print one snapshot after --seconds and exit")
    p.add_argument("--json", action="store_true", help="JSON (the snapshot; echo: one JSON object per line)")
    p.add_argument("--count", type=int, metavar="N", help="echo: stop after N samples")
    p.add_argument("--strict", action="store_true", help="exit 1 when a diagnosis fires")


def run_spy(args, sink, report) -> int:
    echo_topic = None
    if args.echo:
        if len(args.echo) != 2 or args.echo[0] != "echo":
            print("rapidgen spy: expected `rapidgen spy [options]` or `rapidgen spy echo TOPIC`", file=sys.stderr)
            return 2
        echo_topic = args.echo[1]
    if args.seconds is not None and args.seconds <= 0 or args.count is not None and args.count <= 0:
        print("rapidgen spy: --seconds and --count must be positive", file=sys.stderr)
        return 2
    from rapidgen.live.dds import dds_missing, use_transport
    if dds_missing("spy"):
        return 1
    try:
        import rapid_runtime  # noqa: F401  (samples are shown in the runtime's plain form)
    except ImportError:
        print("rapidgen spy: needs rapid_runtime, which is not installed; install it with: pip install ./runtime",
              file=sys.stderr)
        return 1
    bindings = _bindings(args.asset, sink)
    report(sink)
    if bindings is None:
        return 1
    use_transport(bindings[0].transport_file(args.transport or "local"), keep_environment=args.transport is None,
                  enclave=args.enclave)
    from rapidgen.spy.collect import Declared
    from rapidgen.spy.watch import Watcher
    assets = [b.tables for b in bindings[1:]]
    domain = args.domain if args.domain is not None else (assets[0]["ASSET"].get("domain", 0) if assets else 0)
    w = Watcher(domain, bindings[1:] + bindings[:1], args.partition,
                declared=[a["ASSET"].get("partition", a["ASSET"]["name"]) for a in assets],
                topics={echo_topic} if echo_topic is not None else None)
    declared = Declared(assets)
    try:
        if echo_topic is not None:
            from rapidgen.spy.echo import echo
            echo(w, echo_topic, args.json, args.seconds, args.count)
            return 0
        return _overview(w, declared, args)
    except KeyboardInterrupt:
        return 0
    finally:
        w.close()


def _bindings(files: list[str], sink):
    """[base bindings, one per --asset]; None after diagnostics."""
    from rapidgen.live.bindings import load_bindings
    with tempfile.TemporaryDirectory(prefix="rapidgen-spy-") as tmp:
        path = os.path.join(tmp, "rapid-spy.yaml")
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(BASE_DESCRIPTOR)
        base = load_bindings(path, sink, prefix="rapidspy_base")
    out = [base]
    for i, f in enumerate(files):
        out.append(load_bindings(f, sink, prefix=f"rapidspy{i}"))
    return None if any(b is None for b in out) else out


def _overview(w, declared, args) -> int:
    from rapidgen.spy import render
    from rapidgen.spy.collect import snapshot
    seconds = 3.0 if args.seconds is None else args.seconds
    live = not args.once and not args.json and sys.stdout.isatty()
    if not live:
        w.run_for(seconds)
        snap = snapshot(w, declared)
        sys.stdout.write(render.as_json(snap) if args.json else render.text(snap))
        return 1 if args.strict and snap.findings else 0
    # Ctrl-C works even when the shell started us with SIGINT ignored, and ends the process at
    # once: the DDS objects are not torn down one by one (with other participants' traffic
    # arriving, that teardown could keep a terminal waiting).
    signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        while True:  # until Ctrl-C
            w.run_for(1.0)
            sys.stdout.write(render.live_frame(snapshot(w, declared)))
            sys.stdout.flush()
            time.sleep(0)
    except KeyboardInterrupt:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(0)
