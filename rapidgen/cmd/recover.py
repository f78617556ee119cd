"""A command lost in a restarting bridge, sent again (docs/runtime.md, "The ground's part").

The command topic is volatile: a command still in a killed bridge's DDS reader, never
journaled, is gone, and the restarted bridge's ack history (rewritten from its journal)
has nothing of it. So while `rapidgen cmd` waits it watches which participants answer as
the asset (a command reader matched to its writer and an ack writer matched to its
reader, in the same participant: a tool that only reads commands is not the asset). When
a new one appears and the command still has no final ack some seconds later (time for the
new ack writer's history to arrive), it is sent again with the same cmdId, at most
MAX_RESENDS times. That is safe: a bridge drops a cmdId its journal knows as a repeat
and answers it from the rewritten history.

The same resend covers a command lost at first contact: the writer matched the asset's
reader, but the asset had not yet discovered the writer, and a volatile reader that
matches late starts after what was written before (seen across the lunar link, where one
discovery message lost costs seconds). A RAPID asset answers a command at once (QUEUED,
EXECUTING or COMPLETED), so no ack at all UNANSWERED s + 2 round trips after the send
means the command never arrived; a repeat that did arrive is dropped by the bridge."""
from __future__ import annotations

from rapidgen.cmd.timing import allow

MAX_RESENDS = 3
SETTLE = 3.0  # s on loopback after the asset came back, before its history is taken as complete
UNANSWERED = 5.0  # s on loopback with no ack at all, before the command is taken as never received
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

    def __init__(self, commander, rtt: float, now: float) -> None:
        self.commander, self.settle, self.unanswered = commander, allow(SETTLE, rtt), allow(UNANSWERED, rtt)
        self.known = self._asset()
        self.back_at: float | None = None
        self.sent_at = now
        self.resends = 0
        self.why = ""

    def _asset(self) -> set:
        c = self.commander
        try:
            readers = _participants(c.writer.get_matched_subscriptions, c.writer.get_matched_subscription_data)
            writers = _participants(c.ack_reader.get_matched_publications,
                                    c.ack_reader.get_matched_publication_data)
        except Exception:  # DDS closing: nothing to learn
            return set()
        return readers & writers

    def due(self, now: float, answered: bool) -> bool:
        """True when the command should be sent again now (call while it has no final ack;
        `answered`: some ack of it came). self.why then says why. Silence counts only while
        the asset is there and no comeback is being waited for (that wait resends itself)."""
        if self.resends >= MAX_RESENDS:
            return False
        current = self._asset()
        new = current - self.known
        if new:
            self.known |= new
            self.back_at = now  # a later newcomer restarts the wait: its history must arrive too
        if self.back_at is not None and now - self.back_at >= self.settle:
            self.why = f"came back (a new participant) and has not answered within {self.settle:g} s: " \
                       "the command was lost in the old one"
        elif self.back_at is None and not answered and now - self.sent_at >= self.unanswered and current:
            self.why = f"has not answered within {self.unanswered:g} s: the command did not reach it"
        else:
            return False
        self.back_at, self.sent_at = None, now
        self.resends += 1
        return True
