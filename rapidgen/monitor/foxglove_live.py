"""`rapidgen monitor --foxglove PORT` (docs/foxglove.md): every RAPID writer on the domain served
live over Foxglove's WebSocket protocol. The DDS side is `rapidgen record`'s (rapidgen.record.
recorder: the descriptors' topics from the start, every other RAPID writer as discovered, CDR
taken raw) with a sink that sends instead of writing a file: each (partition, topic) is a
channel `/PARTITION/TOPIC` with its omgidl schema and the CDR as it came off the wire, plus the
derived channels of `record --foxglove` (rapidgen.foxglove.derive), named as in a recording."""
from __future__ import annotations

import asyncio
import sys
import threading
import time

from rapidgen.monitor.foxglove_server import FoxgloveServer
from rapidgen.record.mcapfile import MESSAGE_ENCODING, ChannelInfo


class LiveSink:
    """The recorder's sink interface (schema, channel, write) onto a FoxgloveServer."""

    def __init__(self, server: FoxgloveServer) -> None:
        self.server = server
        self._schemas: dict[str, str] = {}
        self._ids: dict[tuple[str, str, str], int | None] = {}
        self.messages = 0

    def schema(self, type_name: str, text: str) -> None:
        self._schemas.setdefault(type_name, text)

    def channel(self, ch: ChannelInfo) -> int | None:
        key = (ch.topic, ch.partition, ch.type_name)
        if key not in self._ids:
            schema_encoding, encoding = ch.encodings
            rapid = encoding == MESSAGE_ENCODING
            topic = f"/{ch.partition}/{ch.topic}" if rapid else ch.topic
            schema = self._schemas.get(ch.type_name, "")
            self._ids[key] = self.server.add_channel(topic, encoding, ch.type_name, schema,
                                                     schema_encoding if schema else "")
        return self._ids[key]

    def write(self, ch: ChannelInfo, log_time: int, publish_time: int, data: bytes, sequence: int = 0) -> None:
        cid = self.channel(ch)
        if cid is not None:
            self.server.publish(cid, log_time, data)
            self.messages += 1


def run_live(args) -> int:
    """Serve until Ctrl-C/SIGTERM or --seconds. Exit 0; 1 when DDS, a descriptor or the port fails."""
    from rapidgen.record.command import _schema_finder, open_assets
    opened = open_assets(args)
    if opened is None:
        return 1
    bindings, models, assets, domain = opened
    server = FoxgloveServer(args.bind, tuple(args.foxglove_origin or ()), budget=args.foxglove_queue)
    live = LiveSink(server)
    stop = threading.Event()
    error: list[str] = []
    ready = threading.Event()

    def pump() -> None:
        from rapidgen.record.derived import DerivedWriter
        from rapidgen.record.recorder import Recorder
        from rapidgen.textsafe import visible
        rec = None
        try:
            roles: dict[str, str] = {}
            rec = Recorder(domain, bindings, None, _schema_finder(models), live, roles)
            rec.derived = DerivedWriter(live, bindings)
            for b in bindings[1:]:
                rec.declared(b.qos, b.tables["ASSET"].get("partition", b.tables["ASSET"]["name"]))
        except Exception as exc:  # Cyclone refused to start
            if rec is not None:  # its participant deleted now (rapidgen/live/teardown.py)
                rec.close()
            error.append(f"cannot join DDS domain {domain}: {visible(str(exc))[:300]}")
            ready.set()
            return
        ready.set()
        last = 0.0
        try:
            while not stop.is_set():
                now = time.monotonic()
                if now - last >= 0.25:
                    rec.discover()
                    last = now
                if rec.take() == 0:
                    time.sleep(0.005)
        finally:
            rec.close()

    try:
        return asyncio.run(_serve(server, args, domain, pump, stop, ready, error))
    finally:
        stop.set()


async def _serve(server: FoxgloveServer, args, domain: int, pump, stop: threading.Event, ready: threading.Event,
                 error: list[str]) -> int:
    import signal

    from aiohttp import web

    from rapidgen.textsafe import visible
    server.loop = asyncio.get_running_loop()
    thread = threading.Thread(target=pump, name="foxglove-dds", daemon=True)
    thread.start()
    await asyncio.get_running_loop().run_in_executor(None, ready.wait, 60)
    if error:
        print(f"rapidgen monitor: {error[0]}", file=sys.stderr)
        return 1
    runner = web.AppRunner(server.app(), access_log=None, handle_signals=False)
    await runner.setup()
    site = web.TCPSite(runner, args.bind, args.foxglove)
    try:
        await site.start()
    except OSError as exc:
        await runner.cleanup()
        stop.set()
        await asyncio.get_running_loop().run_in_executor(None, thread.join, 10)  # the recorder closed (pump)
        print(f"rapidgen monitor: cannot serve on {visible(args.bind)}:{args.foxglove}: {exc.strerror or exc}",
              file=sys.stderr)
        return 1
    host = f"[{args.bind}]" if ":" in args.bind else args.bind
    port = next((a[1] for a in runner.addresses if isinstance(a, tuple) and len(a) >= 2), args.foxglove)
    print(f"monitor: Foxglove WebSocket server for DDS domain {domain} on ws://{host}:{port}/ "
          "(Foxglove: Open connection, Foxglove WebSocket)", file=sys.stderr, flush=True)
    done = asyncio.Event()
    loop = asyncio.get_running_loop()
    for s in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(s, done.set)
    try:
        if args.seconds is not None:
            try:
                await asyncio.wait_for(done.wait(), args.seconds)
            except asyncio.TimeoutError:
                pass
        else:
            await done.wait()
    finally:
        stop.set()
        await runner.cleanup()
        await loop.run_in_executor(None, thread.join, 10)
    print(f"monitor: Foxglove server stopped: {server.sent} messages sent, {server.dropped} slow client(s) dropped",
          file=sys.stderr)
    return 0
