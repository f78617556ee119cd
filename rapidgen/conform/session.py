"""One conformance run: the asset's bindings, our participant, discovery, the client,
and the steps several checks share (finding the asset, taking control, sending a
command and waiting for its final ack)."""
from __future__ import annotations

import re
import time

from rapidgen.textsafe import visible
from rapidgen.conform.asset import AssetFacts, Cmd, valid_args
from rapidgen.conform.client import UNKNOWN, Client, enum_name
from rapidgen.conform.model import Blocked, Fail, Unsupported

COMPLETED, OK = "ACK_COMPLETED", "ACK_COMPLETED_OK"
ACCESS_TOPIC = "rapid_accesscontrol_state"
NO_CONTROLLER = ("", "No Controller")  # soraCore / Astrobee (rapid-protocol.md 5b)
COOKIE = re.compile(r"^[0-9a-fA-F]{16}$")
MAX_LISTED = 32  # strangers listed one by one in a report
# An ack for a cmdId nobody sent arrived after ours was sent, and none carries ours this long
# after it: the asset does not answer with the cmdIds it was sent (CMD-12's finding).
GRACE = 1.0
PROBE = 2.0  # s without any ack for a command before a probe asks whether it was lost (Session.run)
HAND_BACK_WAIT = 3.0  # s for each AccessControl answer when control is handed back at the end


class Session:
    def __init__(self, bindings, domain: int, timeout: float = 10.0, participants: tuple[str, ...] = (),
                 rtt: float = 0.0, motion: dict[str, list] | None = None, allow_motion: bool = False,
                 secured_as: str | None = None) -> None:
        """secured_as: the source whose enclave the runner joined a secured domain with: the
        asset binds cmdSrc to that certificate (docs/secure.md), so the runner speaks as it
        and as no other source."""
        from cyclonedds.builtin import BuiltinDataReader, BuiltinTopicDcpsParticipant
        from cyclonedds.domain import DomainParticipant

        from rapidgen.live.discovery import Discovery
        from rapidgen.live.teardown import delete_participant
        self.b = bindings
        self.facts = AssetFacts(bindings.tables)
        self.asset = self.facts.name
        self.domain = domain
        self.rtt = rtt  # the link's round trip (--rtt): every wait allows for it (allow())
        self.timeout = self.allow(timeout)
        self.participant = DomainParticipant(domain)
        try:
            self.discovery = Discovery(self.participant)
            self._births_reader = BuiltinDataReader(self.participant, BuiltinTopicDcpsParticipant)
            self.client = Client(bindings, self.participant, self.asset)
        except BaseException:  # e.g. DDS Security refusing the command writer: no half-made participant left
            delete_participant(self.participant)
            raise
        self.births: dict[str, int] = {}  # participant GUID -> its announced creation time (ns)
        self.secured_as = secured_as
        self.source = secured_as or self.facts.runner_source()
        self.asset_participants: set[str] = set()
        self.chosen = tuple(_hex(p) for p in participants)  # --participant: GUID prefixes (hex)
        self.identification = ""  # how the asset's participant was chosen (for the report)
        self.started = time.monotonic()
        self.memo: dict = {}  # results of shared steps, by name
        # cmdIds the runner waited for an answer to, in order (CMD-12: were they answered?)
        self.awaited: dict[str, None] = {}
        # Who holds control, from the acks the runner got (grabControl answered OK: its sender;
        # releaseControl answered OK: nobody known); None when not known. AccessControlState
        # is the asset's word, and a check judges it: taking control never relies on it.
        self.holder: str | None = None
        # What the runner may send that moves the asset: "Subsystem/command" -> the arguments
        # (the descriptor's conformance section); allow_motion (--allow-motion): any motion
        # command, with the runner's own arguments (AssetFacts.long_running).
        self.motion: dict[str, list] = dict(motion or {})
        self.allow_motion = allow_motion
        self.before: str | None = None  # AccessControlState's controller before the first check (None: no state)
        self.control = ""  # what hand_back() did, for the report
        # Accounting (CMD-16): every command sent gets a final COMPLETED ack. Not accounted: those
        # sent to get no answer (another asset's: CMD-09), and those whose silence the check that
        # sent them judged itself (CMD-02's valid command, CMD-14's probe: their own rule).
        self.unanswerable: set[str] = set()
        self.owned: set[str] = set()

    def begin(self, check_id: str) -> None:
        """The runner starts a check: the commands sent from now on are its (accounting)."""
        self.client.sender = check_id

    # ---- motion --------------------------------------------------------------------------------
    @staticmethod
    def refusal(cmd: Cmd) -> str:
        return (f"sends {cmd.subsystem}/{cmd.name}: allow it in the descriptor's conformance section or "
                f"with --allow-motion")

    def motion_args(self, cmd: Cmd, default: list) -> list:
        """The arguments the runner may send motion command cmd with: the descriptor's, else
        (--allow-motion) default; Unsupported with the reason when neither allows it."""
        key = f"{cmd.subsystem}/{cmd.name}"
        if key in self.motion:
            return list(self.motion[key])
        if self.allow_motion:
            return default
        raise Unsupported(self.refusal(cmd))

    def long_running(self) -> tuple[Cmd, list] | None:
        """A long drive the runner may send, with its arguments; None when the asset has none;
        Unsupported (why) when it has one the runner may not send."""
        refused: Unsupported | None = None
        for c, default in self.facts.long_running():
            try:
                return c, self.motion_args(c, default)
            except Unsupported as u:
                refused = refused or u
        if refused is not None:
            raise refused
        return None

    def with_params(self) -> Cmd | None:
        """AssetFacts.with_params, a motion command only with --allow-motion (the checks that use
        it send wrong or odd arguments, never the descriptor's); Unsupported (why) when only a
        motion command would do."""
        c = self.facts.with_params(motion=self.allow_motion)
        if c is None and (moving := self.facts.with_params(motion=True)) is not None:
            raise Unsupported(self.refusal(moving))
        return c

    # ---- the asset on the network ------------------------------------------------------------
    def topics(self) -> dict[str, str]:
        """Every topic the asset publishes (name -> type), from the descriptor."""
        return {p["topic"]: p["type"] for p in self.facts.publications}

    def expected(self) -> set[tuple[str, str]]:
        """The (kind, topic) endpoints the descriptor says the asset has."""
        want = {("writer", p["topic"]) for p in self.facts.publications}
        if self.facts.subsystems:
            want.add(("reader", "rapid_command"))
        return want

    def candidates(self) -> dict[str, int]:
        """Participants with an endpoint of the asset's topics in its partition, each with how
        many of the descriptor's endpoints it has there (discovery order)."""
        names = set(self.topics()) | {"rapid_command"}
        want = self.expected()
        found: dict[str, set] = {}
        for e in self.discovery.endpoints.values():
            if e.topic in names and self.facts.partition in e.partitions:
                found.setdefault(e.participant, set()).add((e.kind, e.topic))
        return {p: len(got & want) for p, got in found.items()}

    def allow(self, seconds: float, trips: float = 2.0) -> float:
        """A wait of `seconds` on loopback, over a link of round trip rtt: an answer costs one
        round trip and a lost packet's repair another, so a check judges the asset, not the
        link's delay."""
        return seconds + trips * self.rtt

    def pause(self, seconds: float) -> None:
        """Sleep while an answer that should not come would have come (QUIET checks)."""
        time.sleep(self.allow(seconds))

    def find_asset(self, timeout: float = 15.0, settle: float = 0.5, most: float = 3.0) -> bool:
        """Find the asset's participant, then start our readers (so every config we read is as
        a late joiner). Any participant in the partition may write the asset's topics; only
        one is judged:
        - with --participant, the candidates whose GUID starts with one of the given prefixes;
        - else the candidate with the most of the descriptor's endpoints (a writer per
          publication, the command reader) in the partition; of equals, the oldest (the
          earliest creation time its discovery data announced), and the report says the
          choice was ambiguous.
        Candidates are participants with an endpoint of the asset's topics in its partition;
        the choice is made once the candidates stop changing for `settle` s (at most `most` s
        after the first). Every other participant is a stranger: reported, never judged.
        Over a link (rtt) discovery takes a few round trips, and a lost announcement one more."""
        timeout, settle, most = self.allow(timeout, 6), self.allow(settle, 1), self.allow(most, 4)
        if not self.discovery.wait_until(lambda d: bool(self.candidates()), timeout):
            self.client.start(self.topics())
            return False
        first = last_change = time.monotonic()
        seen = self.candidates()
        while time.monotonic() - last_change < settle and time.monotonic() - first < most:
            time.sleep(0.05)
            self.discovery.poll()
            now = self.candidates()
            if now != seen:
                seen, last_change = now, time.monotonic()
        ok = self._choose(seen)
        self.client.asset_participants = set(self.asset_participants)
        self.client.start(self.topics())
        return ok

    def _choose(self, cands: dict[str, int]) -> bool:
        want = len(self.expected())
        if self.chosen:
            self.asset_participants = {p for p in cands if _hex(p).startswith(self.chosen)}
            self.identification = (f"--participant {', '.join(self.chosen)}: {len(self.asset_participants)} of "
                                   f"{len(cands)} candidate(s)")
            return bool(self.asset_participants)
        best = max(cands.values())
        self._read_births()
        tied = sorted((p for p, n in cands.items() if n == best), key=lambda p: self.births.get(p, 1 << 63))
        self.asset_participants = {tied[0]}
        self.identification = (f"participant {tied[0]}: {best} of the {want} endpoints the descriptor implies, "
                               f"the most of {len(cands)} candidate(s) in partition {self.facts.partition}")
        if len(tied) > 1:
            self.identification += (f"; ambiguous: {len(tied) - 1} other(s) have as many ({', '.join(tied[1:4])}), "
                                    f"the oldest participant is judged (choose with --participant)")
        return True

    def _read_births(self) -> None:
        """Each participant's creation time as it announced it (the source timestamp of its
        discovery sample): of participants that look equally like the asset, the one that was
        there first is judged. Taken one at a time: a sample cyclonedds cannot convert is lost
        alone."""
        for _ in range(4096):
            try:
                got = self._births_reader.take(N=1)
            except Exception:  # an unreadable discovery sample (Discovery reports those)
                continue
            if not got:
                return
            info = getattr(got[0], "sample_info", None)
            stamp = getattr(info, "source_timestamp", None)
            if isinstance(stamp, int) and len(self.births) < 4096:
                self.births.setdefault(str(got[0].key), stamp)

    def endpoints(self, kind: str | None = None, topic: str | None = None):
        """The asset's endpoints (any partition: a wrong one is a finding, not invisible)."""
        return [e for e in self.discovery.find(kind, topic) if e.participant in self.asset_participants]

    def wait_endpoint(self, kind: str, topic: str, timeout: float = 3.0):
        end = time.monotonic() + self.allow(timeout)
        while True:
            found = self.endpoints(kind, topic)
            if found or time.monotonic() > end:
                return found
            time.sleep(0.05)

    def latest(self, topic: str, timeout: float = 0.0):
        got = self.client.wait_sample(topic, self.allow(timeout)) if timeout else self.client.samples(topic)
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
        end = time.monotonic() + self.allow(timeout)
        while time.monotonic() < end:
            if self.client.matched_asset(w, reader=False) and self.client.matched_asset(r, reader=True):
                return True
            time.sleep(0.02)
        return False

    def run(self, cmd: Cmd | tuple[str, str], args=None, source: str | None = None, timeout: float | None = None,
            final: bool = True, **kw) -> list:
        """Send and wait for the final ack; returns the acks of that cmdId. BLOCKED at once
        when an earlier command showed the asset's answers cannot be judged (answers()).
        final: BLOCKED when no final ack came within the timeout (the check cannot judge its
        rule; the missing answer is CMD-16's finding, named with this check); False: the
        acks as they are (a check that judges the silence itself, or does not need it)."""
        self.answers()
        sub, name = (cmd.subsystem, cmd.name) if isinstance(cmd, Cmd) else cmd
        if args is None:
            args = valid_args(cmd) if isinstance(cmd, Cmd) else []
        source = self.source if source is None else source
        cid = self.client.send(sub, name, args, source=source, **kw)
        acks = self.wait_acks(cid, (COMPLETED,), timeout, probe=True)
        f = self.final(acks)
        if sub == "AccessControl" and f is not None and f.completed == OK:
            if name == "grabControl":
                self.holder = source
            elif name in ("releaseControl", "transferControl"):
                self.holder = None
        if final:
            self.require_final(cid, acks)
        return acks

    # ---- accounting: every command sent is followed to its final ack (CMD-16) ------------------
    def require_final(self, cmd_id: str, acks: list | None = None) -> list:
        """The cmdId's acks when they hold its final COMPLETED; else BLOCKED: the check that
        needs the answer cannot judge its rule, and the missing answer is CMD-16's finding."""
        acks = self.client.acks_of(cmd_id) if acks is None else acks
        if self.final(acks) is None:
            raise Blocked(self.silence(cmd_id) + " (CMD-16)")
        return acks

    def silence(self, cmd_id: str) -> str:
        """'cmdId X (Sub/cmd, ACTION) sent by CHECK got no final ack within T s' (the acks it got)."""
        c = self.client
        with c.lock:
            cmd, origin, at = c.sent.get(cmd_id), c.origin.get(cmd_id, ""), c.sent_at.get(cmd_id)
        what = ""
        if cmd is not None:
            action = enum_name(cmd.cmdAction)
            what = f" ({visible(cmd.subsysName)[:32]}/{visible(cmd.cmdName)[:40]}" + \
                   ("" if action == "QUEUE_BYPASS" else f", {action}") + ")"
        waited = (time.monotonic() - at) if at is not None else self.timeout
        acks = c.acks_of(cmd_id)
        got = f" (its acks: {describe(acks)})" if acks else ""
        return (f"cmdId {visible(cmd_id)[:60]!r}{what} sent by {origin or 'the runner'} got no final ack within "
                f"{waited:.0f} s{got}")

    def accountable(self, cmd_id: str) -> bool:
        """A command of the runner's that must get a final COMPLETED ack: not one sent to get no
        answer or whose silence its own check judged, not one with an empty cmdId (nothing
        to answer with), not a queued action on an asset without a queue (soraCore drops
        those: rapid-protocol.md 5b), and sent by a check (not the hand-back at the end)."""
        c = self.client
        with c.lock:
            cmd, origin = c.sent.get(cmd_id), c.origin.get(cmd_id, "")
        if not cmd_id or cmd is None or not origin or cmd_id in self.unanswerable or cmd_id in self.owned:
            return False
        return enum_name(cmd.cmdAction) == "QUEUE_BYPASS" or self.facts.has_type("Queue")

    def _probe(self) -> str | None:
        """Send the harmless command (BYPASS) to see whether the asset answers commands sent
        after one that got no ack at all; None when the asset has none."""
        c = self.facts.harmless()
        if c is None or self.client.command_writer is None:
            return None
        return self.client.send(c.subsystem, c.name, valid_args(c), source=self.source)

    def wait_acks(self, cmd_id: str, statuses: tuple[str, ...] = (COMPLETED,), timeout: float | None = None,
                  probe: bool = False) -> list:
        """The cmdId's acks once one has a status in statuses, or at the timeout. Ends sooner,
        BLOCKED, once acks for cmdIds nobody sent (not the runner, no commander seen on
        rapid_command) have come since the command was sent and, GRACE s later, still none
        that answers it: the asset mangles cmdIds, CMD-12 says so, and waiting out every
        timeout would only repeat it."""
        c = self.client
        self.awaited.setdefault(cmd_id, None)
        end = time.monotonic() + (self.timeout if timeout is None else self.allow(timeout))
        since = c.sent_at.get(cmd_id, time.monotonic())
        probe_id: str | None = None
        with c.lock:
            while True:
                acks = [a for a in c.acks if a.cmd_id == cmd_id]
                now = time.monotonic()
                if any(a.status in statuses for a in acks) or now >= end:
                    return acks
                # probe: no ack at all PROBE s after sending: a command sent behind it tells a lost
                # command (the probe answered, this one not: the asset answers a commander's commands
                # in order) from a slow asset (neither answered); CMD-16 judges the loss in full
                if probe and not acks and probe_id is None and now - since >= self.allow(PROBE):
                    probe_id = self._probe() or ""
                if probe_id and not acks:
                    answered = next((a for a in c.acks if a.cmd_id == probe_id and a.status == COMPLETED), None)
                    if answered is not None and now - answered.at >= self.allow(GRACE / 2, 1):
                        return acks
                odd = c.unsent(since)
                if odd and now - odd[0].at >= GRACE:
                    why = (f"no ack carries cmdId {visible(cmd_id)!r} {now - since:.1f} s after it was sent; the "
                           f"asset's acks carry cmdIds nobody sent ({_ids(odd)}) (CMD-12)")
                    self.memo.setdefault("answers", why)
                    raise Blocked(why)
                c.lock.wait(min(end - now, 0.1) if odd else end - now)

    def answers(self) -> None:
        """BLOCKED when an earlier command showed that the asset's answers cannot be judged:
        they carry cmdIds nobody sent (CMD-12), or a valid command got no ack at all (CMD-02)."""
        why = self.memo.get("answers")
        if why:
            raise Blocked(why)

    def silent_since(self, since: float) -> None:
        """For a check that judges that no ack came: BLOCKED when acks for cmdIds nobody sent
        came meanwhile (an ack for its command may be among them, under another cmdId)."""
        odd = self.client.unsent(since)
        if odd:
            why = f"the asset's acks carry cmdIds nobody sent ({_ids(odd)}) (CMD-12)"
            self.memo.setdefault("answers", why)
            raise Blocked(why)

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
        end = time.monotonic() + self.allow(timeout)
        while True:
            s = self.latest(ACCESS_TOPIC)
            now = None if s is None else s.controller
            if want is None and now is not None or now == want or time.monotonic() > end:
                return now
            time.sleep(0.02)

    def take_control(self, source: str) -> list:
        """requestControl (soraCore: granted when free); Astrobee publishes a cookie in
        requestors[0] that grabControl(cookie) turns into control. Returns the acks. The
        holder (Session.holder) is the source once the state names it after an OK, or once
        grabControl(cookie) is answered OK."""
        acks = self._run_again(("AccessControl", "requestControl"), source)
        f = self.final(acks)
        if self.controller(1.5, want=source) == source:
            if f is not None and f.completed == OK:
                self.holder = source
            return acks
        s = self.latest(ACCESS_TOPIC)
        grab = self.facts.command("AccessControl", "grabControl")
        if s is not None and s.requestors and COOKIE.match(s.requestors[0]) and grab is not None and grab.params:
            acks = acks + self.run(("AccessControl", "grabControl"), [("RAPID_STRING", s.requestors[0])], source=source)
        return acks

    def grab_control(self, source: str) -> list:
        """Take control whoever holds it: grabControl (soraCore: always succeeds), or with
        Astrobee's cookie (requestControl, then grabControl(cookie)); requestControl when
        grabControl is refused. Its OK ack, not AccessControlState, says that source holds
        control."""
        grab = self.facts.command("AccessControl", "grabControl")
        acks: list = []
        if grab is not None and not grab.params:
            acks = self._run_again(("AccessControl", "grabControl"), source)
            if self.holder == source:
                return acks
        return acks + self.take_control(source)  # no grabControl, or refused: ask

    def _run_again(self, cmd: tuple[str, str], source: str) -> list:
        """An AccessControl command the run cannot go on without, sent once more when the first
        gets no final ack (lost: CMD-16 names it); BLOCKED when the second gets none either."""
        acks = self.run(cmd, [], source=source, final=False)
        return acks if self.final(acks) is not None else self.run(cmd, [], source=source)

    def ensure_control(self) -> None:
        """Our source holds control on an asset with access control (or nothing to do),
        judged from the acks the runner got: an asset whose AccessControlState lags (ACC-04's
        finding) must not make later checks fail for want of control."""
        if not self.facts.has_type("AccessControl") or self.holder == self.source:
            return
        self.grab_control(self.source)

    # ---- control before and after the run -------------------------------------------------------
    def note_controller(self) -> None:
        """Remember who held control before the run (AccessControlState, durable), so that
        hand_back() can restore it."""
        if self.facts.has_type("AccessControl") and self.client.command_writer is not None:
            st = self.latest(ACCESS_TOPIC, timeout=3.0)
            self.before = None if st is None else st.controller

    def hand_back(self) -> str:
        """At the end of the run: the runner's sources give up the control they took. Where
        another source held control before the run, transferControl hands it back (5b: by the
        controller, to any source); where that is refused, releaseControl, and the report says
        the previous holder must request control again. Returns that sentence (also
        Session.control); empty when the asset has no access control or nothing was sent."""
        if not self.facts.has_type("AccessControl") or self.client.command_writer is None:
            return ""
        self.client.sender = ""  # not a check's: its answers are said here, not accounted by CMD-16
        with self.client.lock:
            ours = {str(getattr(c, "cmdSrc", "")) for c in self.client.sent.values()}
        if not ours:
            return ""
        before = self.before
        free = before is None or before in NO_CONTROLLER
        was = "nobody held control before the run" if free else f"{before!r} held control before the run"
        transfer = self.facts.command("AccessControl", "transferControl")
        done: list[str] = []
        refused = False
        try:
            for _ in range(6):  # each release may pass control to a queued requestor (ACC-07's, ours)
                now = self.controller(1.0)
                if now == before or (free and (now is None or now in NO_CONTROLLER)):
                    how = f" ({'; '.join(done)})" if done else ""
                    self.control = (f"control: {'nobody holds it' if free else f'{before!r} holds it'}, as before "
                                    f"the run{how}")
                    return self.control
                if now not in ours:
                    self.control = (f"control: {now!r} holds it (not a source the runner sent as): left as it is; "
                                    f"{was}" + (f" ({'; '.join(done)})" if done else ""))
                    return self.control
                if not free and transfer is not None and len(transfer.params) == 1 and not refused:
                    acks = self._send_final("transferControl", [("RAPID_STRING", before)], now)
                    if self.controller(2.0, want=before) == before:
                        done.append(f"transferControl from {now} to {before}")
                        continue
                    refused = True
                    done.append(f"transferControl from {now} to {before} answered {describe(acks)}")
                acks = self._send_final("releaseControl", [], now)
                done.append(f"releaseControl by {now}: {describe(acks)}")
                if self.final(acks).completed != OK:
                    break  # the asset says it does not hold control: its state is not the asset's word here
                if not self.wait_controller_not(now, 2.0):
                    done.append(f"AccessControlState still names {now!r} (ACC-09)")
                    break
        except Blocked as b:  # the asset's answers cannot be judged (CMD-12): say what is known
            done.append(f"stopped: {b}")
        now = self.controller(0.5)
        again = "" if free or now == before else f"; {before!r} must request control again (requestControl)"
        self.control = (f"control: AccessControlState names {now!r} after the run{again}; {was}"
                        + (f" ({'; '.join(done)})" if done else ""))
        return self.control

    def _send_final(self, name: str, args: list, source: str) -> list:
        """Send an AccessControl command as source and wait for its final ack: HAND_BACK_WAIT s
        (access control answers at once; an asset that crashed in the run must not cost a
        timeout per step). Blocked when none came: the hand-back stops there."""
        cid = self.client.send("AccessControl", name, args, source=source)
        acks = self.wait_acks(cid, (COMPLETED,), timeout=HAND_BACK_WAIT)
        f = self.final(acks)
        if f is None:
            raise Blocked(f"{name} as {source} got no final ack within {self.allow(HAND_BACK_WAIT):g} s "
                          f"({describe(acks)})")
        if f.completed == OK:
            self.holder = None
        return acks

    def wait_controller_not(self, who: str, timeout: float) -> bool:
        end = time.monotonic() + self.allow(timeout)
        while self.controller(0.0) == who and time.monotonic() < end:
            time.sleep(0.02)
        return self.controller(0.0) != who

    def close(self) -> None:
        """Stop taking samples: the reports' counts are final from here (notes() still reads
        discovery)."""
        self.client.stop()

    def delete(self) -> None:
        """Stop, then delete our participant and all in it now (rapidgen/live/teardown.py: left
        to interpreter exit, a secured domain's threads outlived OpenSSL: SIGSEGV at exit).
        Nothing is read after this."""
        from rapidgen.live.teardown import delete_participant
        self.client.stop()
        delete_participant(self.participant)

    # ---- what was not judged ------------------------------------------------------------------
    def participant_text(self, key: str) -> str:
        """'<GUID> (process P, pid N, host H)' from Cyclone's participant properties."""
        if key == UNKNOWN:
            return "unknown (writers that had left when their samples were taken)"
        p = self.discovery.participants.get(key)
        props = p.properties if p is not None else {}
        about = [f"{label} {str(props[k])[:48]}" for k, label in (("__ProcessName", "process"), ("__Pid", "pid"),
                                                                     ("__Hostname", "host")) if k in props]
        return visible(key + (f" ({', '.join(about)})" if about else ""))

    def notes(self) -> dict:
        """The asset's participant(s), strangers in the partition and what was dropped: plain
        data for the reports, every wire string made visible."""
        discovery_notes: list[str] = []
        try:  # the report is written whatever discovery makes of the asset leaving (CMD-14's crash)
            self.discovery.poll()
            discovery_notes += getattr(self.discovery, "notes", lambda: [])()  # what it dropped or left out
        except Exception as exc:
            discovery_notes.append(f"discovery could not be read at the end of the run ({type(exc).__name__}: {exc})")
        part = self.facts.partition
        in_partition: dict[str, set[str]] = {}
        for e in list(self.discovery.endpoints.values()):
            if e.participant not in self.asset_participants and isinstance(e.topic, str) \
                    and (part in e.partitions or "*" in e.partitions):
                in_partition.setdefault(e.participant, set()).add(f"{e.kind} {e.topic}")
        with self.client.lock:
            tallies = {k: (dict(v.samples), v.acks_for_runner) for k, v in self.client.strangers.items()}
        strangers = []
        for key in list(dict.fromkeys([*in_partition, *tallies]))[:MAX_LISTED]:
            samples, answered = tallies.get(key, ({}, 0))
            strangers.append({
                "participant": self.participant_text(key),
                "endpoints": sorted(visible(t)[:120] for t in in_partition.get(key, ()))[:64],
                "samples": {visible(t): {"count": c, "bytes": b, "not_decoded": nd}
                            for t, (c, b, nd) in samples.items()},
                "acks_for_runner": answered})
        more = len(set(in_partition) | set(tallies)) - len(strangers)
        return {"asset_participants": [self.participant_text(p) for p in sorted(self.asset_participants)],
                "identification": visible(self.identification), "control": visible(self.control), "strangers": strangers, "more_strangers": max(0, more),
                "dropped": [visible(line) for line in [*self.client.dropped(), *discovery_notes]]}


def _hex(guid: str) -> str:
    """A GUID or prefix as bare lowercase hex (dashes, colons and dots dropped)."""
    return "".join(ch for ch in guid.lower() if ch in "0123456789abcdef")


def _ids(acks: list, most: int = 3) -> str:
    """The distinct cmdIds of acks, quoted and escaped, the first `most` of them."""
    ids = list(dict.fromkeys(a.cmd_id for a in acks))
    text = ", ".join(repr(visible(i)[:60]) for i in ids[:most])
    return text + (f" and {len(ids) - most} more" if len(ids) > most else "")


def describe(acks: list) -> str:
    if not acks:
        return "no ack"
    return " -> ".join(f"{a.status[4:]}/{a.completed[14:] if a.completed.startswith('ACK_COMPLETED_') else a.completed}"
                       + (f" {a.message[:60]!r}" if a.message else "") for a in acks)
