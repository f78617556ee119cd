"""`rapidgen monitor`: the command line. Loads the RAPID base types and each --asset's
bindings and hints, joins the domain (or reads a recording), and serves the page on
127.0.0.1 unless --bind says otherwise. Exit 0 on Ctrl-C or after --seconds; 1 when
cyclonedds or the runtime is missing, a descriptor has errors, or the port is taken;
2 usage."""
from __future__ import annotations

import asyncio
import ipaddress
import os
import signal
import sys

from typing import TYPE_CHECKING

from rapidgen.argtypes import domain_id
from rapidgen.live.dds import add_enclave_argument
from rapidgen.record.command import size

if TYPE_CHECKING:
    from rapidgen.monitor.server import Source

DEFAULT_PORT = 8765


def add_parser(sub) -> None:
    p = sub.add_parser("monitor", help="a local web page showing and commanding every asset on a domain "
                       "(needs cyclonedds and aiohttp)",
                       description="Serve a web page (http://127.0.0.1:8765/ by default) with every RAPID asset on "
                       "the domain: status, command forms from its live CommandConfig, acks, queue and access "
                       "control, telemetry coloured by the descriptor's thresholds, plots, site map and traverse, "
                       "latest pictures, text log (docs/monitor.md). --replay FILE plays an MCAP recording.")
    p.add_argument("--domain", type=domain_id, metavar="N", help="DDS domain (default: the first --asset's, else 0)")
    p.add_argument("--transport", choices=("local", "lan", "wan"),
                   help="Cyclone transport (default: CYCLONEDDS_URI if set, else local: loopback only)")
    add_enclave_argument(p)
    p.add_argument("--asset", action="append", default=[], metavar="FILE",
                   help="an asset descriptor: units, ranges, defaults and thresholds, extension types (repeatable)")
    p.add_argument("--bind", default="127.0.0.1", metavar="ADDR",
                   help="address the page is served on (default 127.0.0.1: this machine only)")
    p.add_argument("--port", type=int, default=DEFAULT_PORT, metavar="N", help=f"TCP port (default {DEFAULT_PORT}; "
                   "0: any free port)")
    p.add_argument("--replay", metavar="FILE", help="play an MCAP recording (rapidgen record) instead of the domain")
    p.add_argument("--tick", type=float, default=0.1, metavar="S", help="seconds between page updates (default 0.1)")
    p.add_argument("--seconds", type=float, metavar="S", help="stop after S seconds (default: until Ctrl-C)")
    p.add_argument("--foxglove", type=int, metavar="PORT", help="serve the domain over Foxglove's WebSocket "
                   "protocol on PORT (0: any free port) instead of the page (docs/foxglove.md)")
    p.add_argument("--foxglove-origin", action="append", metavar="URL", help="a browser Origin allowed to "
                   "connect to the Foxglove server, e.g. https://app.foxglove.dev (repeatable; default none)")
    p.add_argument("--foxglove-queue", type=size, default=32 << 20, metavar="SIZE", help="bytes queued for one "
                   "Foxglove client before it is dropped as too slow (default 32M)")


def _usage(text: str) -> int:
    print(f"rapidgen monitor: {text}", file=sys.stderr)
    return 2


def _check_args(args) -> int | None:
    if not 0 <= args.port <= 65535:
        return _usage(f"--port {args.port} is outside 0..65535")
    if args.foxglove is not None and not 0 <= args.foxglove <= 65535:
        return _usage(f"--foxglove {args.foxglove} is outside 0..65535")
    if args.foxglove is not None and args.replay is not None:
        return _usage("--foxglove serves the live domain; open a recording in Foxglove itself instead of --replay")
    if not args.tick > 0 or args.tick > 10:
        return _usage("--tick must be in (0, 10] seconds")
    if args.seconds is not None and not args.seconds > 0:
        return _usage("--seconds must be positive")
    try:
        ipaddress.ip_address(args.bind)
    except ValueError:
        if args.bind != "localhost":
            return _usage(f"--bind {args.bind!r} is not an IP address (e.g. 127.0.0.1, 0.0.0.0, ::1)")
    if args.replay is not None and not os.path.isfile(args.replay):
        print(f"rapidgen monitor: cannot read the recording {args.replay!r}: no such file", file=sys.stderr)
        return 1
    return None


def _loopback(bind: str) -> bool:
    return bind == "localhost" or ipaddress.ip_address(bind).is_loopback


def run(args) -> int:
    bad = _check_args(args)
    if bad is not None:
        return bad
    from rapidgen.live.dds import dds_missing
    if dds_missing("monitor"):
        return 1
    try:
        import aiohttp  # noqa: F401
        import rapid_runtime  # noqa: F401
    except ImportError as exc:
        print(f"rapidgen monitor: needs {exc.name}, which is not installed; "
              "install it with: pip install 'rapidgen[monitor]' ./runtime", file=sys.stderr)
        return 1
    if args.foxglove is not None:
        from rapidgen.monitor.foxglove_live import run_live
        return run_live(args)
    from rapidgen.diagnostics import DiagnosticSink
    from rapidgen.monitor.assets import load
    sink = DiagnosticSink()
    loaded = load(args.asset, sink)
    if loaded is None:
        from rapidgen.reporting import report
        report(sink)
        return 1
    bindings, hints = loaded
    from rapidgen.live.dds import use_transport
    use_transport(bindings[-1].transport_file(args.transport or "local"), keep_environment=args.transport is None,
                  enclave=args.enclave)
    from rapidgen.monitor.state import Hub
    source: Source
    if args.replay is not None:
        from rapidgen.monitor.replay import ReplaySource, ReplayError
        try:
            source = ReplaySource(args.replay, bindings, hints)
        except ReplayError as exc:
            print(f"rapidgen monitor: {exc}", file=sys.stderr)
            return 1
        what = f"recording {args.replay}"
    else:
        from rapidgen.monitor.live import LiveFeed
        from rapidgen.monitor.sources import LiveSource
        tables = [b.tables for b in bindings[:-1]]
        domain = args.domain if args.domain is not None else (tables[0]["ASSET"].get("domain", 0) if tables else 0)
        hub = Hub(hints)
        feed = LiveFeed(hub, domain, bindings,
                        [t["ASSET"].get("partition") or t["ASSET"]["name"] for t in tables]).start()
        feed.ready.wait(30)
        if feed.error is not None:
            print(f"rapidgen monitor: cannot join DDS domain {domain}: {feed.error}", file=sys.stderr)
            return 1
        source = LiveSource(hub, feed, domain)
        what = f"DDS domain {domain}"
    try:
        return asyncio.run(_serve(source, args, what))
    finally:
        source.close()


async def _serve(source, args, what: str) -> int:
    from aiohttp import web

    from rapidgen.monitor.server import make_app
    runner = web.AppRunner(make_app(source, args.tick, args.bind), access_log=None, handle_signals=False)
    await runner.setup()
    site = web.TCPSite(runner, args.bind, args.port)
    if not _loopback(args.bind):
        print(f"monitor: warning: the page will be served on {args.bind}: anyone who can reach this machine sees the "
              "assets and can command them from the page (there is no login)", file=sys.stderr, flush=True)
    try:
        await site.start()
    except OSError as exc:
        await runner.cleanup()
        print(f"rapidgen monitor: cannot listen on {args.bind}:{args.port}: {exc.strerror or exc}", file=sys.stderr)
        return 1
    port = runner.addresses[0][1] if runner.addresses else args.port  # the one picked for --port 0
    host = f"[{args.bind}]" if ":" in args.bind else args.bind
    print(f"monitor: {what} on http://{host}:{port}/", flush=True)
    if _loopback(args.bind):
        print(f"monitor: served on {args.bind} only: this machine (--bind ADDR to share it)", flush=True)
    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, stop.set)
    try:
        if args.seconds is None:
            await stop.wait()
        else:
            try:
                await asyncio.wait_for(stop.wait(), args.seconds)
            except asyncio.TimeoutError:
                pass
    finally:
        await runner.cleanup()
    print("monitor: stopped", flush=True)
    return 0
