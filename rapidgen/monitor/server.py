"""The web side (aiohttp): the page and its static files, the latest pictures, and one
WebSocket per page that carries the hub's deltas out and the operator's commands (or a
replay's seek/play/pause) in.

The page is served with a strict Content-Security-Policy (scripts and styles from this
server only, no inline script): data from the network is put into the page as text by the
scripts, and even markup that got in could run nothing. A WebSocket whose Origin is not
this server is refused, so another web site open in the operator's browser cannot command
the robots through it."""
from __future__ import annotations

import asyncio
import json
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


class Source(Protocol):
    """Where the hub's data comes from: the live feed or a recording."""
    hub: Hub
    mode: str  # live | replay

    def info(self) -> dict: ...
    def handle(self, msg: dict) -> dict | None: ...  # a page's message -> the answer (or None)
    def close(self) -> None: ...


@web.middleware
async def _headers(request: web.Request, handler) -> web.StreamResponse:
    resp = await handler(request)
    resp.headers["Content-Security-Policy"] = CSP
    resp.headers["X-Content-Type-Options"] = "nosniff"
    resp.headers["Referrer-Policy"] = "no-referrer"
    resp.headers["Cache-Control"] = "no-store"
    return resp


def make_app(source: Source, tick: float = 0.1) -> web.Application:
    app = web.Application(middlewares=[_headers], client_max_size=MAX_MESSAGE)
    sockets: weakref.WeakSet = weakref.WeakSet()

    async def index(request: web.Request) -> web.Response:
        return web.Response(body=(STATIC / "index.html").read_bytes(), content_type="text/html", charset="utf-8")

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
        if origin is not None and origin != f"{request.scheme}://{request.host}":
            raise web.HTTPForbidden(text="cross-origin WebSocket refused")
        ws = web.WebSocketResponse(heartbeat=20, max_msg_size=MAX_MESSAGE)
        await ws.prepare(request)
        sockets.add(ws)
        await ws.send_json({"type": "hello", "mode": source.mode, **source.info()})
        pusher = asyncio.create_task(_push(ws, source, tick))
        try:
            async for m in ws:
                if m.type != WSMsgType.TEXT:
                    continue
                try:
                    msg = json.loads(m.data)
                except ValueError:
                    continue
                if isinstance(msg, dict):
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
            msg: dict[str, Any] = {"type": "delta", "now": hub.clock(), "stale": hub.stale(), "notes": hub.notes}
            if assets:
                msg["assets"] = assets
            extra = source.info() if source.mode == "replay" else None
            if extra:
                msg["replay"] = extra
            await ws.send_str(json.dumps(msg, allow_nan=False, default=str))
            await asyncio.sleep(tick)
    except (ConnectionResetError, asyncio.CancelledError):
        pass
