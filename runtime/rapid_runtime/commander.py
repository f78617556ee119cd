"""The ground side: send commands into an asset's partition and follow their acks
(`rapidgen cmd` and the tests use it). Acks are correlated by cmdId alone and read with
KEEP_ALL history so no intermediate ack is lost; repeated acks are kept as received.

Anyone in the partition can write acks: only the acks of commands this commander sent (or
was asked to follow) are kept, at most ACKS_PER_COMMAND each; the others are counted in
`strangers` and dropped, so an ack flood for cmdIds nobody sent does not grow the commander.
`writers[cmdId]` holds the writers that acked a command: more than one means someone else
answers for the asset (without DDS Security, nothing stops them: docs/security.md)."""
from __future__ import annotations

import itertools
import os
import threading
import time
from collections.abc import Iterable

from rapid_runtime import messages as M
from rapid_runtime.acks import BYPASS, COMPLETED
from rapid_runtime.command import Cmd
from rapid_runtime.dds import Node, ReaderThread

COMMAND_TOPIC, ACK_TOPIC, COMMAND_CONFIG_TOPIC = "rapid_command", "rapid_ack", "rapid_command_config"
FOLLOW_LOOK = 32  # followed commands looked for in an ack's bytes before decoding it
ACKS_PER_COMMAND = 64  # a command's acks kept (QUEUED, EXECUTING, progress, REQUEUED, COMPLETED ...)
WRITE_BLOCKING = 10.0  # s a command write may wait for room in the writer's history


class Commander:
    def __init__(self, rapid, qos, asset: str, source: str, domain: int, follow: Iterable[str] = ()) -> None:
        """follow: cmdIds whose acks to keep from the start. A late joiner reading the ack
        history must name them here: history that arrives before a later follow() is dropped
        (seen: a joiner's first 23 of 60 finals lost when the reader took them first)."""
        self.rapid, self.asset, self.source = rapid, asset, source
        self.node = Node(rapid, qos, domain)
        try:
            self._start(rapid, follow)
        except BaseException:  # e.g. DDS Security refusing the command topic: no participant left running
            self.node.close()
            raise

    def _start(self, rapid, follow: Iterable[str]) -> None:
        # a burst of commands over a slow link fills the writer's history until the asset
        # acknowledges (a round trip): the profile's 100 ms then failed a write with TIMEOUT
        # (200 rounds across the lunar link); it waits for room instead, as the C++ client
        self.writer = self.node.writer(COMMAND_TOPIC, rapid.Command, blocking=WRITE_BLOCKING)
        self.acks: dict[str, list[tuple[str, str, str]]] = {}  # followed cmdId -> its acks
        self.writers: dict[str, set[int]] = {}  # followed cmdId -> the writers that acked it
        self.strangers = 0  # acks for cmdIds not followed, dropped
        self.cond = threading.Condition()
        self._ids = itertools.count(1)
        self.ack_reader = self.node.reader(ACK_TOPIC, rapid.Ack, keep_all=True)
        self.dropped: list[str] = []  # what the ack reader dropped (undecodable), one line per writer
        self._followed: list[bytes] = []  # their encodings, to skip others' acks undecoded
        for cmd_id in follow:  # before the reader thread takes anything
            self.follow(cmd_id)
        self._reader = ReaderThread(self.node, self.ack_reader, rapid.Ack, self._on_ack, "rapid-acks",
                                    log=self.dropped.append, wanted=self._wanted, batch=256).start()

    def _wanted(self, data: bytes) -> bool:
        """Might this ack be for a followed command? (its cmdId's bytes are in the encoding).
        Past FOLLOW_LOOK followed commands (a test driving hundreds) every ack is decoded."""
        followed = self._followed
        return len(followed) > FOLLOW_LOOK or any(cid in data for cid in followed)

    def follow(self, cmd_id: str) -> None:
        """Keep the acks of cmd_id (send() follows what it sends; DELETE's target too)."""
        with self.cond:
            if cmd_id not in self.acks:
                self._followed = [*self._followed, cmd_id.encode()]  # replaced whole: read unlocked
            self.acks.setdefault(cmd_id, [])
            self.writers.setdefault(cmd_id, set())

    def _on_ack(self, sample) -> None:
        cmd_id, status, completed, message = M.ack_fields(sample)
        with self.cond:
            kept = self.acks.get(cmd_id)
            if kept is None:
                self.strangers += 1
                return
            if len(kept) < ACKS_PER_COMMAND:
                kept.append((status, completed, message))
            self.writers[cmd_id].add(sample.sample_info.publication_handle)
            self.cond.notify_all()

    def wait_for_asset(self, timeout: float) -> bool:
        """True once an asset's command reader matched our writer (Astrobee waits likewise)
        and its ack writer our reader."""
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if self.writer.get_matched_subscriptions() and self.ack_reader.get_matched_publications():
                return True
            time.sleep(0.02)
        return False

    def new_id(self) -> str:
        """Unique: counter, source, process and time (rapid-protocol.md section 5)."""
        return f"{next(self._ids)}-{self.source}-{os.getpid()}-{time.time_ns() // 1_000_000}"

    def send(self, subsystem: str, name: str, args=(), action: str = BYPASS, target: str = "",
             cmd_id: str | None = None, source: str | None = None, asset: str | None = None) -> str:
        cmd = Cmd(cmd_id=self.new_id() if cmd_id is None else cmd_id, cmd_src=self.source if source is None else source,
                  subsystem=subsystem, name=name, args=tuple(args), action=action, target=target,
                  src_name=self.source, asset_name=self.asset if asset is None else asset)
        self.follow(cmd.cmd_id)
        self.writer.write(M.command_out(self.rapid, cmd))
        return cmd.cmd_id

    def wait_final(self, cmd_id: str, timeout: float) -> list[tuple[str, str, str]]:
        """The acks of cmd_id up to its COMPLETED (or what came within timeout)."""
        end = time.monotonic() + timeout
        with self.cond:
            while not any(a[0] == COMPLETED for a in self.acks.get(cmd_id, ())):
                left = end - time.monotonic()
                if left <= 0:
                    break
                self.cond.wait(left)
            return list(self.acks.get(cmd_id, ()))

    def wait_acks(self, cmd_id: str, seconds: float) -> list[tuple[str, str, str]]:
        """Whatever acks cmd_id got within `seconds` (to show that none came)."""
        time.sleep(seconds)
        with self.cond:
            return list(self.acks.get(cmd_id, ()))

    def close(self) -> None:
        """Stop reading acks and delete the participant (dds.Node.close()): nothing is used after."""
        self._reader.stop()
        self.node.close()
