"""`rapidgen monitor --replay FILE` (not yet)."""
from __future__ import annotations

from rapidgen.monitor.state import Hub


class ReplayError(Exception):
    """The recording cannot be played (said without a traceback)."""


class ReplaySource:
    mode = "replay"
    hub: Hub

    def __init__(self, path: str, bindings: list, hints) -> None:
        raise ReplayError("--replay is not available yet")

    def info(self) -> dict:
        return {}

    def handle(self, msg: dict) -> dict | None:
        return None

    def close(self) -> None:
        pass
