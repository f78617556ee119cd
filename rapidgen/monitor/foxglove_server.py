"""A Foxglove WebSocket protocol server (subprotocol `foxglove.websocket.v1`, docs/foxglove.md):
channels advertised with their schemas, clients subscribe, each message sent as a binary frame
(opcode 1, subscription id u32 LE, timestamp u64 LE ns, payload).

Written on aiohttp rather than with the foxglove-sdk package so that the monitor page's rules
apply (rapidgen.monitor.server.Gate): the Host header must name this server (DNS rebinding),
a browser's Origin must be one given with --foxglove-origin, and every client has a byte budget
of queued messages: a client that falls that far behind is disconnected (a 1008 close saying
why), never waited on, so one slow client costs neither memory nor the others' latency.
A new subscription gets its channel's latest message first (pictures and configs come
seldom), within LATEST_BYTES for all channels together.

Thread-safety: `publish` and `add_channel` may be called from any thread (the DDS reader's);
they hand over to the event loop.
"""
from __future__ import annotations

import asyncio
import collections
import json
import socket
import struct
import sys
import threading
from dataclasses import dataclass, field
from typing import Any

from aiohttp import web

from rapidgen.monitor.server import Gate, json_objects

SUBPROTOCOL = "foxglove.websocket.v1"
CLIENT_BUDGET = 32 << 20  # bytes queued for one client before it is dropped
MAX_CLIENTS = 16
MAX_CHANNELS = 4096
MAX_CLIENT_MESSAGE = 256 << 10  # bytes of one message from a client (subscribe lists)
MAX_SUBSCRIPTIONS = 8192
SOCKET_BUFFER = 256 << 10  # the kernel's send buffer per client (not autotuned to megabytes)
LATEST_BYTES = 64 << 20  # each channel's latest message, sent to a new subscriber first (all channels together)


@dataclass(frozen=True)
class Channel:
    id: int
    topic: str
    encoding: str
    schema_name: str
    schema: str
    schema_encoding: str

    def advert(self) -> dict[str, Any]:
        return {"id": self.id, "topic": self.topic, "encoding": self.encoding, "schemaName": self.schema_name,
                "schema": self.schema, "schemaEncoding": self.schema_encoding}


@dataclass(eq=False)  # hashed by identity: kept in a set
class Client:
    ws: web.WebSocketResponse
    subs: dict[int, int] = field(default_factory=dict)  # subscription id -> channel id
    by_channel: dict[int, set[int]] = field(default_factory=dict)  # channel id -> subscription ids
    queue: collections.deque = field(default_factory=collections.deque)
    queued: int = 0  # bytes in queue
    wake: asyncio.Event = field(default_factory=asyncio.Event)
    dropped: str | None = None
    transport: Any = None
    peer: str = ""
    writer: asyncio.Task | None = None


class FoxgloveServer:
    def __init__(self, bind: str = "127.0.0.1", origins: tuple[str, ...] = (), name: str = "rapidgen",
                 budget: int = CLIENT_BUDGET) -> None:
        self.gate = Gate(bind)
        self.origins = frozenset(o.rstrip("/").lower() for o in origins)
        self.name, self.budget = name, budget
        self.channels: dict[int, Channel] = {}
        self.clients: set[Client] = set()
        self.loop: asyncio.AbstractEventLoop | None = None
        self.dropped = 0  # clients disconnected for being slow
        self.sent = 0
        self._lock = threading.Lock()
        self._next = 1
        self.latest: dict[int, tuple[bytes, bytes]] = {}  # channel id -> (timestamp u64 LE, payload)
        self._latest_bytes = 0

    # -- any thread ----------------------------------------------------------------------
    def add_channel(self, topic: str, encoding: str, schema_name: str, schema: str, schema_encoding: str) -> int | None:
        """A new channel's id (advertised to every client), or None past MAX_CHANNELS."""
        with self._lock:
            if len(self.channels) >= MAX_CHANNELS:
                return None
            ch = Channel(self._next, topic, encoding, schema_name, schema, schema_encoding)
            self._next += 1
            self.channels[ch.id] = ch
        if self.loop is not None:
            self.loop.call_soon_threadsafe(self._advertise, [ch])
        return ch.id

    def publish(self, channel_id: int, timestamp_ns: int, payload: bytes) -> None:
        if self.loop is not None:
            self.loop.call_soon_threadsafe(self._publish, channel_id, timestamp_ns, payload)

    # -- the event loop ------------------------------------------------------------------
    def _advertise(self, channels: list[Channel]) -> None:
        text = json.dumps({"op": "advertise", "channels": [c.advert() for c in channels]}, ensure_ascii=True)
        for c in list(self.clients):
            self._enqueue(c, text)

    def _publish(self, channel_id: int, timestamp_ns: int, payload: bytes) -> None:
        head = struct.pack("<Q", max(0, timestamp_ns))
        old = self.latest.pop(channel_id, None)
        self._latest_bytes -= len(old[1]) if old is not None else 0
        if self._latest_bytes + len(payload) <= LATEST_BYTES:
            self.latest[channel_id] = (head, payload)
            self._latest_bytes += len(payload)
        for c in list(self.clients):
            for sub in c.by_channel.get(channel_id, ()):
                self._enqueue(c, b"\x01" + struct.pack("<I", sub) + head + payload)

    def _enqueue(self, c: Client, item: str | bytes) -> None:
        if c.dropped is not None:
            return
        size = len(item)
        if c.queue and c.queued + size > self.budget:  # (one message alone always goes)
            c.dropped = f"too slow: more than {self.budget} bytes queued for this client"
            c.queue.clear()
            c.queued = 0
            self.dropped += 1
            print(f"monitor: Foxglove client {c.peer} dropped: {c.dropped}", file=sys.stderr, flush=True)
            if c.writer is not None:
                c.writer.cancel()  # it may be blocked on the client's full socket
            asyncio.ensure_future(self._drop(c))
            return
        else:
            c.queue.append(item)
            c.queued += size
        c.wake.set()

    async def _drop(self, c: Client) -> None:
        """Cut a slow client's connection. No close frame: its socket is full, and a clean close
        waits for the buffer to drain, which is what it does not do."""
        if c.transport is not None:
            c.transport.abort()
        try:
            await c.ws.close(code=1008)
        except Exception:  # already cut
            pass

    async def _writer(self, c: Client) -> None:
        try:
            while True:
                await c.wake.wait()
                c.wake.clear()
                while c.queue and c.dropped is None:
                    item = c.queue.popleft()
                    c.queued -= len(item)
                    if isinstance(item, str):
                        await c.ws.send_str(item)
                    else:
                        await c.ws.send_bytes(item)
                        self.sent += 1
        except (ConnectionError, RuntimeError):  # the client went away: its handler ends too
            c.queue.clear()
            c.queued = 0

    def _subscribe(self, c: Client, msg: dict) -> None:
        op = msg.get("op")
        if op == "subscribe" and isinstance(msg.get("subscriptions"), list):
            for s in msg["subscriptions"]:
                if not isinstance(s, dict):
                    continue
                sid, cid = s.get("id"), s.get("channelId")
                if isinstance(sid, int) and isinstance(cid, int) and cid in self.channels and sid not in c.subs \
                        and len(c.subs) < MAX_SUBSCRIPTIONS and 0 <= sid < 2**32:
                    c.subs[sid] = cid
                    c.by_channel.setdefault(cid, set()).add(sid)
                    got = self.latest.get(cid)
                    if got is not None:  # what came before the subscription: a picture, a config
                        self._enqueue(c, b"\x01" + struct.pack("<I", sid) + got[0] + got[1])
        elif op == "unsubscribe" and isinstance(msg.get("subscriptionIds"), list):
            for sid in msg["subscriptionIds"]:
                cid = c.subs.pop(sid, None) if isinstance(sid, int) else None
                if cid is not None:
                    c.by_channel.get(cid, set()).discard(sid)

    def _origin_ok(self, origin: str | None) -> bool:
        """No Origin (Foxglove's desktop app, non-browser clients), or one given with --foxglove-origin."""
        return origin is None or origin.rstrip("/").lower() in self.origins

    async def handle(self, request: web.Request) -> web.StreamResponse:
        sock = request.transport.get_extra_info("sockname") if request.transport is not None else None
        port = sock[1] if isinstance(sock, tuple) and len(sock) >= 2 else None
        if not self.gate.host_ok(request.headers.get("Host"), port):
            return web.Response(status=421, text="this server answers to localhost, 127.0.0.1, [::1] and its bind "
                                "address only, with the port it serves (a foreign Host name is refused: DNS rebinding)")
        if not self._origin_ok(request.headers.get("Origin")):
            return web.Response(status=403, text="this Origin is not allowed (give it with --foxglove-origin)")
        if len(self.clients) >= MAX_CLIENTS:
            return web.Response(status=503, text=f"at most {MAX_CLIENTS} clients")
        ws = web.WebSocketResponse(protocols=(SUBPROTOCOL,), heartbeat=20, max_msg_size=MAX_CLIENT_MESSAGE)
        if not ws.can_prepare(request).ok:
            return web.Response(status=400, text=f"a WebSocket with subprotocol {SUBPROTOCOL} is expected here")
        await ws.prepare(request)
        if ws.ws_protocol != SUBPROTOCOL:
            await ws.close(code=1002, message=f"subprotocol {SUBPROTOCOL} required".encode())
            return ws
        peer = request.transport.get_extra_info("peername") if request.transport is not None else None
        raw = request.transport.get_extra_info("socket") if request.transport is not None else None
        if raw is not None:
            try:
                raw.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, SOCKET_BUFFER)
            except OSError:
                pass
        c = Client(ws, transport=request.transport,
                   peer=f"{peer[0]}:{peer[1]}" if isinstance(peer, tuple) and len(peer) >= 2 else "?")
        self.clients.add(c)
        self._enqueue(c, json.dumps({"op": "serverInfo", "name": self.name, "capabilities": [],
                                     "supportedEncodings": [], "metadata": {}, "sessionId": str(id(self))}))
        self._enqueue(c, json.dumps({"op": "advertise", "channels": [ch.advert() for ch in list(self.channels.values())]},
                                    ensure_ascii=True))
        writer = c.writer = asyncio.create_task(self._writer(c))
        try:
            async for msg in json_objects(ws):
                self._subscribe(c, msg)
        finally:
            self.clients.discard(c)
            writer.cancel()
        return ws

    def app(self) -> web.Application:
        app = web.Application(client_max_size=MAX_CLIENT_MESSAGE)
        app.router.add_get("/", self.handle)
        return app
