"""One conformance run: the asset's bindings, our participant, discovery, the client,
and the steps several checks share (finding the asset, taking control, sending a
command and waiting for its final ack)."""
from __future__ import annotations

import re
import time

from rapidgen.conform.asset import AssetFacts, Cmd, valid_args
from rapidgen.conform.client import Client
from rapidgen.conform.model import Fail, Unsupported

COMPLETED, OK = "ACK_COMPLETED", "ACK_COMPLETED_OK"
ACCESS_TOPIC = "rapid_accesscontrol_state"
NO_CONTROLLER = ("", "No Controller")  # soraCore / Astrobee (rapid-protocol.md 5b)
COOKIE = re.compile(r"^[0-9a-fA-F]{16}$")


class Session:
    def __init__(self, bindings, domain: int, timeout: float = 10.0) -> None:
        from cyclonedds.domain import DomainParticipant

        from rapidgen.live.discovery import Discovery
        self.b = bindings
        self.facts = AssetFacts(bindings.tables)
        self.asset = self.facts.name
        self.domain = domain
        self.timeout = timeout
        self.participant = DomainParticipant(domain)
        self.discovery = Discovery(self.participant)
        self.client = Client(bindings, self.participant, self.asset)
        self.source = self.facts.runner_source()
        self.asset_participants: set[str] = set()
        self.started = time.monotonic()
        self.memo: dict = {}  # results of shared steps, by name

    # ---- the asset on the network ------------------------------------------------------------
    def topics(self) -> dict[str, str]:
        """Every topic the asset publishes (name -> type), from the descriptor."""
        return {p["topic"]: p["type"] for p in self.facts.publications}

    def find_asset(self, timeout: float = 15.0) -> bool:
        """Wait until a participant shows any endpoint of the asset's RAPID topics in its
        partition; then start our readers (so every config we read is as a late joiner)."""
        names = set(self.topics()) | {"rapid_command"}

        def seen(d) -> bool:
            eps = [e for e in d.endpoints.values() if e.topic in names]
            self.asset_participants = {e.participant for e in eps if self.facts.partition in e.partitions}
            return bool(self.asset_participants)
        ok = self.discovery.wait_until(seen, timeout)
        if ok:  # let the rest of its endpoints arrive
            self.discovery.wait_until(lambda d: False, 0.5)
            seen(self.discovery)
        self.client.start(self.topics())
        return ok

    def endpoints(self, kind: str | None = None, topic: str | None = None):
        """The asset's endpoints (any partition: a wrong one is a finding, not invisible)."""
        return [e for e in self.discovery.find(kind, topic) if e.participant in self.asset_participants]

    def wait_endpoint(self, kind: str, topic: str, timeout: float = 3.0):
        end = time.monotonic() + timeout
        while True:
            found = self.endpoints(kind, topic)
            if found or time.monotonic() > end:
                return found
            time.sleep(0.05)

    def latest(self, topic: str, timeout: float = 0.0):
        got = self.client.wait_sample(topic, timeout) if timeout else self.client.samples(topic)
        return got[-1].sample if got else None

    # ---- commands ------------------------------------------------------------------------------
    def needs_commands(self) -> None:
        if not self.facts.subsystems or self.client.command_writer is None:
            raise Unsupported("the asset takes no commands (no subsystems)")

    def wait_command_match(self, timeout: float = 10.0) -> bool:
        """Our command writer matched the asset's reader, and our ack reader its writer."""
        w, r = self.client.command_writer, self.client.ack_reader
        if w is None or r is None:  # no subsystems: needs_commands() reports it
            return False
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if w.get_matched_subscriptions() and r.get_matched_publications():
                return True
            time.sleep(0.02)
        return False

    def run(self, cmd: Cmd | tuple[str, str], args=None, source: str | None = None, timeout: float | None = None,
            **kw) -> list:
        """Send and wait for the final ack; returns the acks of that cmdId."""
        sub, name = (cmd.subsystem, cmd.name) if isinstance(cmd, Cmd) else cmd
        if args is None:
            args = valid_args(cmd) if isinstance(cmd, Cmd) else []
        cid = self.client.send(sub, name, args, source=self.source if source is None else source, **kw)
        return self.client.wait_final(cid, self.timeout if timeout is None else timeout)

    @staticmethod
    def final(acks: list):
        return next((a for a in acks if a.status == COMPLETED), None)

    def expect_ok(self, acks: list, what: str) -> None:
        f = self.final(acks)
        if f is None or f.completed != OK:
            raise Fail(f"{what} answered COMPLETED/OK", describe(acks))

    def expect_refused(self, acks: list, what: str) -> None:
        f = self.final(acks)
        if f is None or f.completed in (OK, "ACK_COMPLETED_NOT"):
            raise Fail(f"{what} answered COMPLETED with BAD_SYNTAX or EXEC_FAILED", describe(acks))

    # ---- access control -----------------------------------------------------------------------
    def controller(self, timeout: float = 2.0, want: str | None = None) -> str | None:
        """The latest AccessControlState's controller (waiting up to timeout for `want`)."""
        end = time.monotonic() + timeout
        while True:
            s = self.latest(ACCESS_TOPIC)
            now = None if s is None else s.controller
            if want is None and now is not None or now == want or time.monotonic() > end:
                return now
            time.sleep(0.02)

    def take_control(self, source: str) -> list:
        """requestControl (soraCore: granted when free); Astrobee publishes a cookie in
        requestors[0] that grabControl(cookie) turns into control. Returns the acks."""
        acks = self.run(("AccessControl", "requestControl"), [], source=source)
        if self.controller(1.5, want=source) == source:
            return acks
        s = self.latest(ACCESS_TOPIC)
        grab = self.facts.command("AccessControl", "grabControl")
        if s is not None and s.requestors and COOKIE.match(s.requestors[0]) and grab is not None and grab.params:
            acks = acks + self.run(("AccessControl", "grabControl"), [("RAPID_STRING", s.requestors[0])], source=source)
        return acks

    def ensure_control(self) -> None:
        """Our source holds control on an asset with access control (or nothing to do)."""
        if not self.facts.has_type("AccessControl"):
            return
        if self.controller(0.5) != self.source:
            self.take_control(self.source)

    def close(self) -> None:
        self.client.stop()


def describe(acks: list) -> str:
    if not acks:
        return "no ack"
    return " -> ".join(f"{a.status[4:]}/{a.completed[14:] if a.completed.startswith('ACK_COMPLETED_') else a.completed}"
                       + (f" {a.message[:60]!r}" if a.message else "") for a in acks)
