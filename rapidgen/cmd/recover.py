"""A command lost in a restarting bridge, sent again (docs/runtime.md, "The ground's part").

The command topic is volatile: a command still in a killed bridge's DDS reader, never
journaled, is gone, and the restarted bridge's ack history (rewritten from its journal)
has nothing of it. So while `rapidgen cmd` waits it watches which participants answer as
the asset (a command reader matched to its writer and an ack writer matched to its
reader, in the same participant: a tool that only reads commands is not the asset). When
a new one appears and the command still has no final ack some seconds later (time for the
new ack writer's history to arrive), it is sent again with the same cmdId, at most
MAX_RESENDS times. That is safe: a bridge drops a cmdId its journal knows as a repeat
and answers it from the rewritten history."""
from __future__ import annotations

from rapidgen.cmd.timing import allow

MAX_RESENDS = 3
SETTLE = 3.0  # s on loopback after the asset came back, before its history is taken as complete
POLL = 0.25  # s between looks at the matched endpoints while no ack comes


def _participants(handles, data) -> set:
    out = set()
    for h in handles():
        try:
            out.add(data(h).participant_key)
        except Exception:  # the endpoint left between the two calls
            continue
    return out


class AssetWatch:
    """Notices an asset participant that was not there when the command was sent."""

    def __init__(self, commander, rtt: float) -> None:
        self.commander, self.settle = commander, allow(SETTLE, rtt)
        self.known = self._asset()
        self.back_at: float | None = None
        self.resends = 0

    def _asset(self) -> set:
        c = self.commander
        try:
            readers = _participants(c.writer.get_matched_subscriptions, c.writer.get_matched_subscription_data)
            writers = _participants(c.ack_reader.get_matched_publications,
                                    c.ack_reader.get_matched_publication_data)
        except Exception:  # DDS closing: nothing to learn
            return set()
        return readers & writers

    def due(self, now: float) -> bool:
        """True when the command should be sent again now (call while it has no final ack)."""
        if self.resends >= MAX_RESENDS:
            return False
        new = self._asset() - self.known
        if new:
            self.known |= new
            self.back_at = now  # a later newcomer restarts the wait: its history must arrive too
        if self.back_at is not None and now - self.back_at >= self.settle:
            self.back_at = None
            self.resends += 1
            return True
        return False
