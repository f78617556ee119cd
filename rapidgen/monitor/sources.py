"""The live source of the page: the hub the DDS thread fills, and the commands the page sends."""
from __future__ import annotations

from rapidgen.monitor.commanding import Refused, check
from rapidgen.monitor.live import LiveFeed
from rapidgen.monitor.state import Hub


class LiveSource:
    mode = "live"

    def __init__(self, hub: Hub, feed: LiveFeed, domain: int) -> None:
        self.hub, self.feed, self.domain = hub, feed, domain

    def info(self) -> dict:
        return {"domain": self.domain}

    def handle(self, msg: dict) -> dict | None:
        if msg.get("type") != "command":
            return None
        ref = msg.get("ref") if isinstance(msg.get("ref"), (int, str)) else None
        partition = msg.get("partition")
        with self.hub.lock:
            a = self.hub.assets.get(partition) if isinstance(partition, str) else None
            commands: dict | None = a.sections["commands"][1] if a is not None else None  # type: ignore[assignment]
            name = (a.name or a.partition) if a is not None else ""
        try:
            if commands is None:
                raise Refused("no such asset on the domain")
            if commands.get("refused"):
                raise Refused(str(commands["refused"]))
            req = check(msg, commands, name)
        except Refused as exc:
            return {"type": "refused", "partition": partition, "ref": ref, "reason": str(exc)}
        return {"type": "sent", "partition": partition, "ref": ref, "cmdId": self.feed.send(req)}

    def close(self) -> None:
        self.feed.stop()
