"""The web side (aiohttp): the page and its static files, the latest pictures, and one
WebSocket per page that carries the hub's deltas out and the operator's commands (or a
replay's seek/play/pause) in.

The page is served with a strict Content-Security-Policy (scripts and styles from this
server only, no inline script): data from the network is put into the page as text by the
scripts, and even markup that got in could run nothing.

Another web site open in the operator's browser must not reach the robots through the
page: every request's Host must be a loopback name (localhost, 127.0.0.1, [::1]) or the
--bind address, with the port served (421 otherwise: a name that a rebinding attacker
pointed at 127.0.0.1 is refused); the WebSocket needs an Origin equal to the page's own
(403 otherwise, also when it is missing) and the per-page token the served page carries
(403 otherwise; an HMAC of a random nonce with a key made at start, so tokens need no
table and die with the process)."""
from __future__ import annotations

import asyncio
import hashlib
import hmac
import ipaddress
import json
import secrets
import weakref
from pathlib import Path
from typing import Any, Protocol

from aiohttp import WSMsgType, web

from rapidgen.monitor.state import Hub

STATIC = Path(__file__).parent / "static"
FILES = {"monitor.js": "text/javascript", "plot.js": "text/javascript", "monitor.css": "text/css"}
PICTURE_TYPES = ("image/jpeg", "image/png", "image/gif", "image/bmp")  # what a browser shows
CSP = ("default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self'; connect-src 'self'; "
       "base-uri 'none'; form-action 'none'; frame-ancestors 'none'")
MAX_MESSAGE = 64 << 10  # bytes of one message from a page
LOOPBACK_NAMES = ("localhost", "127.0.0.1", "[::1]")
TOKEN_META = b'<meta name="monitor-token" content="">'


class Source(Protocol):
    """Where the hub's data comes from: the live feed or a recording."""
    hub: Hub
    mode: str  # live | replay

    def info(self) -> dict: ...
    def handle(self, msg: dict) -> dict | None: ...  # a page's message -> the answer (or None)
    def close(self) -> None: ...


class Gate:
    """Which Host names the server answers to, and the per-page WebSocket tokens."""

    def __init__(self, bind: str = "127.0.0.1") -> None:
        self.key = secrets.token_bytes(32)
        try:
            ip = ipaddress.ip_address(bind)
        except ValueError:
            ip = None
        # a wildcard bind is reached by any of the machine's addresses: an IP literal in Host
        # cannot be rebound (rebinding needs a DNS name), so any IP literal is accepted then
        self.any_ip = ip is not None and ip.is_unspecified
        self.names = set(LOOPBACK_NAMES) | {f"[{ip.compressed}]" if ip is not None and ip.version == 6
                                            else (ip.compressed if ip is not None else bind.lower())}

    def host_ok(self, host: str | None, port: int | None) -> bool:
        """Host (the raw header) names this server: an allowed name with the port served."""
        if not host or port is None:
            return False
        host = host.strip().lower()
        if host.startswith("["):
            name, _, rest = host.partition("]")
            name += "]"
            given = rest[1:] if rest.startswith(":") else ("" if not rest else None)
        else:
            name, _, given = host.partition(":") if host.count(":") == 1 else (host, "", "")
        if given is None or (given and not given.isdigit()):
            return False
        if (int(given) if given else 80) != port:
            return False
        if name in self.names:
            return True
        if self.any_ip:
            try:
                ipaddress.ip_address(name.strip("[]"))
                return True
            except ValueError:
                return False
        return False

    def token(self) -> str:
        nonce = secrets.token_hex(16)
        return nonce + "." + hmac.new(self.key, nonce.encode(), hashlib.sha256).hexdigest()

    def token_ok(self, token: str | None) -> bool:
        if not token or token.count(".") != 1 or len(token) > 200:
            return False
        nonce, mac = token.split(".")
        want = hmac.new(self.key, nonce.encode("utf-8", "replace"), hashlib.sha256).hexdigest()
        return hmac.compare_digest(mac.encode("utf-8", "replace"), want.encode())  # (bytes: any text compares)


def _served_port(request: web.Request) -> int | None:
    sock = request.transport.get_extra_info("sockname") if request.transport is not None else None
    return sock[1] if isinstance(sock, tuple) and len(sock) >= 2 else None


@web.middleware
async def _headers(request: web.Request, handler) -> web.StreamResponse:
    gate: Gate = request.app["gate"]
    if not gate.host_ok(request.headers.get("Host"), _served_port(request)):
        resp: web.StreamResponse = web.Response(
            status=421, text="this monitor answers to localhost, 127.0.0.1, [::1] and its --bind address only, "
            "with the port it serves (a foreign Host name is refused: DNS rebinding)")
    else:
        resp = await handler(request)
    resp.headers["Content-Security-Policy"] = CSP
    resp.headers["X-Content-Type-Options"] = "nosniff"
    resp.headers["Referrer-Policy"] = "no-referrer"
    resp.headers["Cache-Control"] = "no-store"
    return resp


async def json_objects(ws):
    """The JSON objects a client sends on a WebSocket (text frames that parse as an object;
    anything else is ignored): the monitor's page and Foxglove clients alike."""
    async for m in ws:
        if m.type != WSMsgType.TEXT:
            continue
        try:
            msg = json.loads(m.data)
        except ValueError:
            continue
        if isinstance(msg, dict):
            yield msg


def make_app(source: Source, tick: float = 0.1, bind: str = "127.0.0.1") -> web.Application:
    app = web.Application(middlewares=[_headers], client_max_size=MAX_MESSAGE)
    gate = app["gate"] = Gate(bind)
    sockets: weakref.WeakSet = weakref.WeakSet()

    async def index(request: web.Request) -> web.Response:
        page = (STATIC / "index.html").read_bytes().replace(
            TOKEN_META, b'<meta name="monitor-token" content="' + gate.token().encode() + b'">')
        return web.Response(body=page, content_type="text/html", charset="utf-8")

    async def static(request: web.Request) -> web.Response:
        name = request.match_info["name"]
        if name not in FILES:
            raise web.HTTPNotFound()
        return web.Response(body=(STATIC / name).read_bytes(), content_type=FILES[name], charset="utf-8")

    async def picture(request: web.Request) -> web.Response:
        got = source.hub.picture(request.match_info["partition"], request.match_info["sensor"])
        if got is None:
            raise web.HTTPNotFound()
        mime, data = got
        if mime.lower() not in PICTURE_TYPES:  # never let the network choose another type (text/html)
            raise web.HTTPUnsupportedMediaType(text=f"pictures of this type are not shown")
        return web.Response(body=data, content_type=mime.lower())

    async def socket(request: web.Request) -> web.WebSocketResponse:
        origin = request.headers.get("Origin")
        if origin is None:
            raise web.HTTPForbidden(text="a WebSocket without an Origin is refused")
        if origin != f"{request.scheme}://{request.headers.get('Host', '')}":
            raise web.HTTPForbidden(text="cross-origin WebSocket refused")
        if not gate.token_ok(request.query.get("token")):
            raise web.HTTPForbidden(text="the page's token is missing or wrong: reload the page")
        ws = web.WebSocketResponse(heartbeat=20, max_msg_size=MAX_MESSAGE)
        await ws.prepare(request)
        sockets.add(ws)
        await ws.send_json({"type": "hello", "mode": source.mode, **source.info()})
        pusher = asyncio.create_task(_push(ws, source, tick))
        try:
            async for msg in json_objects(ws):
                answer = await asyncio.get_running_loop().run_in_executor(None, source.handle, msg)
                if answer is not None:
                    await ws.send_json(answer)
        finally:
            pusher.cancel()
        return ws

    async def closing(app: web.Application) -> None:
        for ws in list(sockets):
            await ws.close()

    app.router.add_get("/", index)
    app.router.add_get("/static/{name}", static)
    app.router.add_get("/picture/{partition}/{sensor}", picture)
    app.router.add_get("/ws", socket)
    app.on_shutdown.append(closing)
    return app


async def _push(ws: web.WebSocketResponse, source: Source, tick: float) -> None:
    """Every tick: what changed since this page's cursor (all of it for a new page)."""
    cursor, generation = 0, None
    try:
        while not ws.closed:
            hub = source.hub
            if generation is not hub:  # a replay seek builds a new hub: the page starts over
                if generation is not None:
                    await ws.send_json({"type": "reset"})
                cursor, generation = 0, hub
            cursor, assets = hub.delta(cursor)
            msg: dict[str, Any] = {"type": "delta", "now": hub.clock(), "stale": hub.stale(), "notes": hub.all_notes()}
            if assets:
                msg["assets"] = assets
            extra = source.info() if source.mode == "replay" else None
            if extra:
                msg["replay"] = extra
            await ws.send_str(json.dumps(msg, allow_nan=False, default=str))
            await asyncio.sleep(tick)
    except (ConnectionResetError, asyncio.CancelledError):
        pass
