"""The door between the command reader and the manager: a flood from one participant must
neither grow the bridge without bound nor lock an operator out.

    intake = Intake(manager, log)      # a worker thread runs the manager
    intake.offer(cmd, writer)          # the reader thread: every decoded Command, never blocks

- One FIFO per writer (the DDS writer the sample came from), served round-robin: a writer
  sending 15 000 commands a second gets its turn like an operator sending one, so the
  operator's command waits for at most one command of each other writer.
- Control commands go first: among the writers, one whose next command is a control command
  (stopAllMotion, AccessControl, Queue cancelAll) is served before the others. A writer's own
  commands keep their order (requestControl then a command is never swapped).
- Each writer holds at most PER_WRITER commands waiting; past that its commands are shed at
  the door: answered COMPLETED/EXEC_FAILED "bridge busy" without being run. The answers
  themselves wait in a bounded list (SHED_ANSWERS) served between commands; when that is
  full too, further commands are dropped unanswered, counted and logged per writer.
- inline=True (the bridge): a command read alone and offered while nothing waits at the door
  and no batch is with the manager is handed to the manager on the offering thread itself (the bridge's
  own command reader thread, not a DDS thread): the same order and answers, one thread
  hand-off less a command (bench/README.md: ~15-30 us and a wake on a 2-core machine).
  Anything offered meanwhile waits at the door as before, for the intake thread.
"""
from __future__ import annotations

import collections
import threading

from rapid_runtime import texts
from rapid_runtime.command import Cmd

PER_WRITER = 256  # commands of one writer waiting for the manager
MAX_WRITERS = 256  # writers with a FIFO of their own; past that they share one
SHED_ANSWERS = 4096  # "busy" answers waiting to be written
BATCH = 32  # commands handed to the manager at once (journal.py: one sync per batch)
CONTROL = {("Mobility", "stopAllMotion"), ("Queue", "cancelAll")}


class Intake:
    def __init__(self, manager, log, per_writer: int = PER_WRITER, shed_answers: int = SHED_ANSWERS,
                 inline: bool = False) -> None:
        self.manager, self.log, self.inline = manager, log, inline
        self.busy = False  # a batch (or an inline command) is with the manager
        self.per_writer, self.shed_limit = per_writer, shed_answers
        self.cond = threading.Condition()
        self.fifos: collections.OrderedDict[int, collections.deque[Cmd]] = collections.OrderedDict()
        self.shed: collections.deque[Cmd] = collections.deque()
        self.unanswered: collections.Counter[int] = collections.Counter()
        self.shed_count: collections.Counter[int] = collections.Counter()
        self.stopping = False
        self._shed_turn = False
        self.thread = threading.Thread(target=self._run, daemon=True, name="rapid-intake")

    def start(self) -> "Intake":
        self.thread.start()
        return self

    def stop(self) -> None:
        with self.cond:
            self.stopping = True
            self.cond.notify_all()
        if self.thread.is_alive() and threading.current_thread() is not self.thread:
            self.thread.join(timeout=5)  # never started for an asset without commands

    # ---- the reader thread -----------------------------------------------------------------
    def offer(self, cmd: Cmd, writer: int, alone: bool = True) -> None:
        """alone=False: more commands were read with this one; it waits at the door with them
        (one batch for the intake thread: one journal sync), never handled inline."""
        with self.cond:
            # (commands offered before start() wait for the intake thread, as at a C++ Intake)
            if self.inline and alone and self.thread.ident is not None and not self.busy and not self.fifos \
                    and not self.shed and not self.stopping:
                self.busy = True  # the intake thread waits; anything offered meanwhile queues
            else:
                self._queue(cmd, writer)
                return
        try:
            self._handle([(cmd, False)])
        finally:
            with self.cond:
                self.busy = False
                if self.fifos or self.shed:
                    self.cond.notify()

    def _queue(self, cmd: Cmd, writer: int) -> None:
        """Under the lock: to the writer's FIFO, else shed, else dropped."""
        if writer not in self.fifos and len(self.fifos) >= MAX_WRITERS:
            writer = 0  # the shared FIFO of writers past MAX_WRITERS
        fifo = self.fifos.setdefault(writer, collections.deque())
        if len(fifo) < self.per_writer:
            fifo.append(cmd)
        elif len(self.shed) < self.shed_limit:
            self.shed.append(cmd)
            self.shed_count[writer] += 1
            if self.shed_count[writer] == 1:
                self.log(f"writer {writer:#x} floods: {self.per_writer} commands waiting; "
                         f"answering its next ones 'bridge busy' (counted, not logged)")
        else:
            self.unanswered[writer] += 1
            if self.unanswered[writer] == 1:
                self.log(f"writer {writer:#x} floods past {self.shed_limit} busy answers: "
                         f"dropping its commands unanswered (counted, not logged)")
        self.cond.notify()

    def waiting(self) -> int:
        with self.cond:
            return sum(len(f) for f in self.fifos.values()) + len(self.shed)

    # ---- the worker ------------------------------------------------------------------------
    def _next(self) -> tuple[Cmd, bool] | None:
        """(command, shed?) to handle next, or None when stopping. Under the lock."""
        while not self.stopping:
            if self.busy:  # an inline command is with the manager: after it
                self.cond.wait()
                continue
            writer = self._control_writer()
            if writer is None:
                if self.shed and (self._shed_turn or not self.fifos):
                    self._shed_turn = False  # busy answers take turns with real commands
                    return self.shed.popleft(), True
                writer = next(iter(self.fifos), None)
            if writer is not None:
                self._shed_turn = True
                fifo = self.fifos.pop(writer)
                cmd = fifo.popleft()
                if fifo:
                    self.fifos[writer] = fifo  # to the back of the round
                return cmd, False
            self.cond.wait()
        return None

    def _control_writer(self) -> int | None:
        for writer, fifo in self.fifos.items():
            if is_control(self.manager.tables, fifo[0]):
                return writer
        return None

    def _run(self) -> None:
        while True:
            with self.cond:
                got = self._next()
                if got is None:
                    return
                batch = [got]  # what is waiting already goes in one manager batch: one journal sync
                while len(batch) < BATCH and (self.fifos or self.shed):
                    more = self._next()
                    if more is None:
                        break
                    batch.append(more)
                self.busy = True
            try:
                self._handle(batch)
            finally:
                with self.cond:
                    self.busy = False

    def _handle(self, batch: list[tuple[Cmd, bool]]) -> None:
        with self.manager.batch():
            for cmd, shed in batch:
                try:
                    if shed:
                        self.manager.refuse(cmd, texts.bridge_busy(self.per_writer))
                    else:
                        self.manager.receive(cmd)
                except Exception as exc:  # a bad command must not stop intake
                    self.log(f"command {cmd.cmd_id!r} not handled: {type(exc).__name__}: {exc}")


def is_control(tables, cmd: Cmd) -> bool:
    kind = tables.type_of(cmd.subsystem)
    return kind == "AccessControl" or (kind, cmd.name) in CONTROL
