"""Command intake and the ack lifecycle: the asset's side of rapid_command / rapid_ack.

    manager = CommandManager(tables, handlers, outbox)
    manager.receive(cmd)          # every Command read from the asset's partition

Dropped without an ack (logged): a command for another asset, a repeated cmdId.
Everything else gets exactly one final COMPLETED ack. Acks go out through the outbox
(dds.py writes them; tests collect them), always under the manager's lock so the acks
of one command keep their order. docs/runtime.md lists every answer.

Memory stays bounded on a robot that runs for months: only the last `window` commands are
remembered (duplicates detected among them and among those still pending or running), and
once more than `window` commands have completed, the oldest one's acks are retired
(outbox.retire: the ack writer unregisters the instance, so DDS frees its history).

With a journal (journal.py), every step that an ack promises is on disk before that ack:
acks, queue and access states are held back within a locked operation (batch()) and
written, in order, once the journal is synced; the intake hands over up to 32 commands
in one batch, so a flood costs one sync per batch.
"""
from __future__ import annotations

import collections
import contextlib
import functools
import threading
import time
import traceback
from dataclasses import dataclass, field
from typing import Callable, NamedTuple, Protocol

from rapid_runtime import access, texts
from rapid_runtime.acks import (APPEND, BAD_SYNTAX, BYPASS, CANCELED, COMPLETED, DELETE, EXEC_FAILED, EXECUTING,
                                HEAD, INSERT, NOT, OK, QUEUED, REPLACE, REQUEUED, RESULT_OF_COMPLETION,
                                STATUS_OF_COMPLETION, clip)
from rapid_runtime.cmdqueue import Pending
from rapid_runtime.command import Cmd
from rapid_runtime.handlers import Cancelled, CommandContext, CommandFailed
from rapid_runtime.tables import CommandEntry, Tables
from rapid_runtime.validate import _short, check_command, kwargs_of

# Commands whose state is kept: the last 4096 cmdIds received (duplicate detection) and the
# acks of the last 4096 completed commands (for late-joining ack readers). A cmdId sent
# again after 4096 newer commands is a new command. Bridge(command_window=N) or the
# bridge's --command-window N changes it.
COMMAND_WINDOW = 4096
# What the window costs in Python: per command its cmdId, a slot in the recent ids (_Recent)
# and a _Kept tuple, or with a journal the journal's own Entry of its outcome (one object
# for both); the names a command carries are one str for all (messages.command_in). About
# 200 bytes a command, 285 with the journal (tests/runtime/test_window_memory.py): 0.8 and
# 1.1 MiB for 4096. The ack instances DDS keeps for them cost more (bench/README.md, "the
# Python bridge's memory").
# A flood of commands must not grow the asset without bound either: queued commands wait
# (each held with its sample) and BYPASS ones each run on a thread of their own. Past these,
# a command is answered EXEC_FAILED at once (docs/runtime.md, "Bounded memory").
QUEUE_LIMIT = 1024
BYPASS_LIMIT = 64
COMPLETED_KEEP_S = 20.0  # finished commands stay in QueueState this long (soraCore)
RECORDS = 64  # QueueState's SingleQueue holds at most 64 records
# Every text an ack carries is in texts (generated from runtime/spec/texts.yaml, the C++
# runtime's too). What a command left unfinished by a restart or a stop is answered
# (docs/runtime.md, "Restarts": a command never re-run, since a half-done motion run again
# is not safe), and the handler faults' texts (issue 42; docs/runtime.md, "Handler faults"),
# are also named here for the tests.
RESTARTED_QUEUED = texts.RESTARTED_QUEUED
RESTARTED_RUNNING = texts.RESTARTED_RUNNING
STOP_TIMEOUT_MS = 2000  # a told-to-stop handler's default bound (descriptor: stop_timeout_ms)
SHUTDOWN_TIMEOUT_MS = 5000  # how long a stop waits for the handlers told to stop
DID_NOT_STOP = texts.DID_NOT_STOP
SHUTTING_DOWN = texts.ASSET_SHUTTING_DOWN
NOT_IMPLEMENTED = texts.NOT_IMPLEMENTED  # the generated stub's CommandFailed
NO_HARDWARE_STOP = texts.NO_HARDWARE_STOP


class Outbox(Protocol):
    def ack(self, cmd: Cmd, status: str, completed: str, message: str) -> None: ...
    def queue_state(self, code: int, pending: list, active: list, completed: list) -> None: ...
    def access_state(self, controller: str, requestors: list[str]) -> None: ...
    def retire(self, cmd: Cmd) -> None: ...  # the command's acks need not be kept any longer
    def log(self, text: str) -> None: ...


@dataclass(eq=False)
class Run:
    cmd: Cmd
    entry: CommandEntry
    kwargs: dict = field(default_factory=dict)
    queued: bool = False  # came through the queue (not BYPASS)
    ctx: CommandContext | None = None
    requeue: bool = False  # preempted: goes back to the queue's front when its handler returns
    done: bool = False  # its COMPLETED ack is written: nothing follows it
    record_status: str = "Q_STATUS_INLINE"
    running: bool = False  # its handler method has been called and has not returned
    stop_by: float | None = None  # told to stop: the handler's deadline (time.monotonic)
    stopped: tuple = ()  # stopAllMotion: the motion runs it told to stop


class CommandManager:
    def __init__(self, tables: Tables, handlers: object, outbox: Outbox,
                 on_shutdown: Callable[[], None] | None = None, clock: Callable[[], float] = time.monotonic,
                 window: int = COMMAND_WINDOW, queue_limit: int = QUEUE_LIMIT,
                 bypass_limit: int = BYPASS_LIMIT, journal=None, stop_timeout_ms: int = STOP_TIMEOUT_MS) -> None:
        if window < 1:
            raise ValueError(f"command window {window}: at least 1")
        if queue_limit < 1 or bypass_limit < 1:
            raise ValueError(f"queue limit {queue_limit}, bypass limit {bypass_limit}: at least 1 each")
        if stop_timeout_ms < 1:
            raise ValueError(f"stop timeout {stop_timeout_ms} ms: at least 1")
        self.stop_timeout_ms = stop_timeout_ms
        self.queue_limit, self.bypass_limit = queue_limit, bypass_limit
        self.tables, self.handlers, self.out = tables, handlers, outbox
        self.on_shutdown = on_shutdown
        self.clock = clock
        self.window = window
        self.lock = threading.RLock()
        self.seen = _Recent(window)  # the last `window` cmdIds
        self.acked: collections.deque = collections.deque()  # completed (_Kept or journal.Entry), acks kept; oldest first
        self.pending = Pending()
        self.active: Run | None = None  # the queue's running command
        self.bypass: list[Run] = []  # BYPASS commands running
        self.completed: collections.deque = collections.deque()  # (time, Run, completion)
        self.suspended = False
        self.control = access.Control()
        self.has_queue = tables.has_type("Queue")
        self.has_control = tables.has_type("AccessControl")
        self.idle = threading.Condition(self.lock)
        self.shutdown_after: Run | None = None
        self.journal = journal  # journal.Journal, or None: nothing survives a crash
        self._outgoing: list[Callable[[], None]] = []  # writes held until the journal is synced
        self._depth = 0
        self._sync_failed = False
        # Told-to-stop handlers and their deadlines: one watchdog thread for all (made on first use)
        self._stopping: set[Run] = set()
        self._watch = threading.Condition(self.lock)
        self._watchdog: threading.Thread | None = None
        self.closing = False  # shutting down: nothing starts, nothing is requeued
        self._handlers_running = 0

    # ---- batches: the journal synced before the acks that promise what it holds --------------
    @contextlib.contextmanager
    def batch(self):
        """Hold the lock; acks and states written at the end of the outermost batch, after the
        journal's sync (one sync for everything the batch promised)."""
        with self.lock:
            self._depth += 1
            try:
                yield
            finally:
                self._depth -= 1
                if self._depth == 0:
                    self._flush()

    def _flush(self) -> None:
        if self.journal is not None:
            try:
                self.journal.sync()
                self._sync_failed = False
            except OSError as exc:  # a full or failing disk: answer anyway, say so once
                if not self._sync_failed:
                    self.out.log(f"journal not written ({exc.strerror or exc}): a crash now would leave "
                                 f"commands without an outcome")
                self._sync_failed = True
        out, self._outgoing = self._outgoing, []
        for write in out:
            write()

    def _emit(self, write: Callable[[], None]) -> None:
        if self._depth:
            self._outgoing.append(write)
        else:
            write()

    # ---- intake ---------------------------------------------------------------------------
    def receive(self, cmd: Cmd) -> None:
        with self.batch():
            if cmd.asset_name != self.tables.name:
                self.out.log(f"ignored {cmd.cmd_id!r}: addressed to asset {cmd.asset_name!r}")
                return
            if cmd.cmd_id in self.seen or self._live(cmd.cmd_id):
                final = self.seen.final(cmd.cmd_id) if cmd.cmd_id in self.seen else None
                if final is not None and final.src_name == cmd.src_name and not self._live(cmd.cmd_id):
                    # answered already: nothing runs; the stored final ack is written again
                    self._emit(functools.partial(self._write_ack, _entry_cmd(final), COMPLETED, final.completion,
                                                 final.message))
                    self.out.log(f"{cmd.cmd_id!r} sent again: answered already, its final ack written again")
                else:
                    self.out.log(f"ignored {cmd.cmd_id!r}: repeated cmdId")
                return
            self.seen.add(cmd.cmd_id)
            reason = self._intake(cmd)
            if reason is not None:
                kind, text = reason
                self._ack(cmd, COMPLETED, kind, text)
                self.out.log(f"{cmd.cmd_id}: {kind.removeprefix('ACK_COMPLETED_')}: {text}")

    def refuse(self, cmd: Cmd, why: str) -> None:
        """Answer a command shed at the door (intake.py) COMPLETED/EXEC_FAILED without running
        it or remembering its id (it may be sent again). Not answered: another asset's, an
        empty id, or the id of a command seen or live (its acks are that command's)."""
        with self.batch():
            if cmd.asset_name != self.tables.name or not cmd.cmd_id:
                return
            if cmd.cmd_id in self.seen or self._live(cmd.cmd_id):
                return
            self._ack(cmd, COMPLETED, EXEC_FAILED, why, journal=False)  # not remembered: may come again

    def _intake(self, cmd: Cmd) -> tuple[str, str] | None:
        """Checks then dispatch; (completion, message) when the command ends here."""
        if not cmd.cmd_id:
            return BAD_SYNTAX, texts.EMPTY_CMD_ID
        action, target = cmd.action, cmd.target
        if action not in (BYPASS, APPEND, DELETE, INSERT, REPLACE):
            return BAD_SYNTAX, texts.unknown_queue_action(_short(str(action)))
        if action != BYPASS and not self.has_queue:
            return BAD_SYNTAX, texts.no_queue(action)
        if action in (BYPASS, APPEND) and target:
            return BAD_SYNTAX, texts.target_not_taken(action, _short(target))
        if action in (INSERT, REPLACE, DELETE) and not target:
            return BAD_SYNTAX, texts.target_needed(action)
        if action == DELETE:
            return self._delete(cmd)
        entry, why = check_command(cmd, self.tables)
        if why:
            return BAD_SYNTAX, why
        assert entry is not None  # check_command: an entry when there is no reason
        if action == INSERT and target != HEAD and not self._queued_run(target):
            return BAD_SYNTAX, texts.unknown_insert_target(_short(target))
        if action == REPLACE and not self._queued_run(target):
            return BAD_SYNTAX, texts.unknown_target(_short(target))
        denied = self._authorize(cmd, entry)
        if denied:
            return BAD_SYNTAX, denied
        if action in (APPEND, INSERT) and len(self.pending) >= self.queue_limit:
            return EXEC_FAILED, texts.queue_full(self.queue_limit)
        if action == BYPASS and len(self.bypass) >= self.bypass_limit:
            return EXEC_FAILED, texts.bypass_full(self.bypass_limit)
        if self.closing:  # the bridge is stopping: nothing new starts or waits
            return EXEC_FAILED, SHUTTING_DOWN
        run = Run(cmd, entry, kwargs_of(entry, cmd), queued=action != BYPASS)
        if action == BYPASS:
            self._start(run)
            return None
        if action == REPLACE:
            old = self._queued_run(target)
            assert old is not None  # checked above, under the same lock
            if old is self.active:
                if not self._abortable(old):
                    return EXEC_FAILED, texts.target_not_abortable(_short(target))
                self._cancel(old)
                self.pending.push_front(run)
            else:
                self.pending.replace(target, run)
                self._finish_unstarted(old, texts.replaced_by(_short(cmd.cmd_id)))
        elif action == INSERT:
            if not self.pending.insert_after(target, run):  # the running command: go next
                self.pending.push_front(run)
        else:
            self.pending.append(run)
        self._ack(cmd, QUEUED, NOT, "")
        self._service()
        return None

    def _live(self, cmd_id: str) -> bool:
        """A command of that id is pending or running (however many came after it)."""
        return self._queued_run(cmd_id) is not None or any(r.cmd.cmd_id == cmd_id for r in self.bypass)

    def _queued_run(self, cmd_id: str) -> Run | None:
        if self.active is not None and self.active.cmd.cmd_id == cmd_id:
            return self.active
        return self.pending.find(cmd_id)

    def _authorize(self, cmd: Cmd, entry: CommandEntry) -> str | None:
        """Why the source may not send this command, or None. Allow-list, then control."""
        if access.always_allowed(entry.subsystem_type, entry.name):
            return None
        if not access.allowed(self.tables.access, cmd.cmd_src, cmd.subsystem, entry.name):
            return texts.access_not_allowed(_short(cmd.cmd_src), _short(cmd.subsystem), _short(entry.name))
        if (self.has_control and entry.subsystem_type != "AccessControl" and cmd.cmd_src != self.tables.name
                and not self.control.holds(cmd.cmd_src)):
            return texts.access_no_control(_short(cmd.cmd_src))
        return None

    def _delete(self, cmd: Cmd) -> tuple[str, str] | None:
        target = self._queued_run(cmd.target) or next((r for r in self.bypass if r.cmd.cmd_id == cmd.target), None)
        if target is None:
            return BAD_SYNTAX, texts.unknown_target(_short(cmd.target))
        denied = self._authorize(_as_sender(cmd, target.cmd), target.entry)
        if denied:
            return BAD_SYNTAX, denied
        if target in self.pending.items:
            self.pending.remove(target)
            self._finish_unstarted(target, texts.deleted_by(_short(cmd.cmd_id)))
            said = texts.target_canceled(_short(cmd.target))
        elif not self._abortable(target):
            return EXEC_FAILED, texts.target_not_abortable(_short(cmd.target))
        else:
            self._cancel(target)  # its own final ack follows when its handler returns, or at its stop bound
            said = texts.cancel_requested(_short(cmd.target))
        self._ack(cmd, EXECUTING, NOT, "")
        self._ack(cmd, COMPLETED, OK, said)
        self._service()
        return None

    # ---- running ----------------------------------------------------------------------------
    def _busy(self, subsystem: str) -> bool:
        return any(r.cmd.subsystem == subsystem and not r.done for r in self.bypass)

    def _service(self) -> None:
        """Start the queue's front command when nothing queued runs and the queue is not suspended."""
        while self.active is None and not self.suspended and not self.closing:
            run = self.pending.pop_ready(self._busy)
            if run is None:
                break
            self.active = run
            self._start(run)
        self._publish_queue()

    def _start(self, run: Run) -> None:
        e = run.entry
        builtin = BUILTINS.get((e.subsystem_type, e.name)) if e.standard else None
        if not run.queued:
            self._preempt(run)
        self._ack(run.cmd, EXECUTING, NOT, "")
        run.record_status = "Q_STATUS_INPROCESS"
        if builtin is not None:
            outcome = builtin(self, run)
            if not run.queued and builtin in (_cancel_all, _stop_all_motion):
                self._publish_queue()  # the queue changed (a queued one: _service publishes it)
            if outcome is not None:  # done at once; None: continue with the handler
                self._complete(run, *outcome)
                return
        if not run.queued:
            self.bypass.append(run)
        ctx = run.ctx = CommandContext(run.cmd, e, None)
        ctx._progress = lambda text, r=run, c=ctx: self._progress(r, c, text)
        run.running = True
        # started with the acks, after the journal's sync: a handler never moves hardware for a
        # command whose "running" step a power cut could still erase
        self._emit(threading.Thread(target=self._execute, args=(run,), daemon=True,
                                    name=f"cmd-{run.cmd.cmd_id[:20]}").start)

    def _preempt(self, run: Run) -> None:
        """A BYPASS command takes its subsystem over: a suspendable command running there from
        the queue is requeued, an abortable one canceled; others keep running beside it."""
        if run.entry.standard and (run.entry.subsystem_type, run.entry.name) in BUILTINS:
            return
        for other in [self.active, *self.bypass]:
            if other is None or other.done or other.cmd.subsystem != run.cmd.subsystem or other.ctx is None:
                continue
            if other.queued and other.entry.suspendable:
                self._tell_stop(other)
                other.requeue = True
            elif self._abortable(other):
                self._tell_stop(other)

    def _execute(self, run: Run) -> None:
        method = getattr(self.handlers, run.entry.method, None)
        ctx = run.ctx
        assert ctx is not None  # _start sets it before this thread starts
        with self.lock:
            self._handlers_running += 1
        try:
            if method is None:
                raise CommandFailed(NOT_IMPLEMENTED)
            result = method(ctx, **run.kwargs)
            outcome = (CANCELED, texts.CANCELED) if ctx.cancelled.is_set() else (OK, result if isinstance(result, str) else "")
        except Cancelled:
            outcome = CANCELED, texts.CANCELED
        except CommandFailed as exc:
            outcome = EXEC_FAILED, _text(exc) or texts.FAILED
        except BaseException as exc:  # a handler's bug must not stop the bridge; the commander hears of it
            # (BaseException: a SystemExit or KeyboardInterrupt raised in a handler ends the command, not the bridge)
            outcome = EXEC_FAILED, texts.handler_error(type(exc).__name__, _text(exc))
            self._log_exception(run, exc)
        with self.batch():
            self._handlers_running -= 1
            run.running = False
            self._stopping.discard(run)
            if run in self.bypass:
                self.bypass.remove(run)
            if run.done:  # answered already (its stop bound, the bridge stopping): nothing follows a COMPLETED
                return
            if _is_stop_all_motion(run.entry):
                outcome = self._stop_all_motion_outcome(run, outcome)
            if run.requeue and outcome[0] == CANCELED and not self.closing:
                run.requeue, run.done, run.ctx, run.stop_by = False, False, None, None
                self._ack(run.cmd, REQUEUED, NOT, texts.PREEMPTED)
                run.record_status = "Q_STATUS_PAUSED"
                self.active = None
                self.pending.push_front(run)
            else:
                self._complete(run, *outcome)
            self._service()

    def _progress(self, run: Run, ctx: CommandContext, text: object) -> None:
        """ctx.progress: nothing once the command is done, or from a context of an earlier
        run of a requeued command (a helper thread left behind), whatever the thread."""
        with self.batch():
            if not run.done and run.ctx is ctx and run.running:
                self._ack(run.cmd, EXECUTING, NOT, _text(text))

    def _log_exception(self, run: Run, exc: BaseException) -> None:
        """One log line for a handler's exception: the command, and where it was raised."""
        where = ""
        frames = traceback.extract_tb(exc.__traceback__)
        if frames:
            last = frames[-1]
            where = f" (at {last.filename.rsplit('/', 1)[-1]}:{last.lineno} in {last.name})"
        self.out.log(f"{run.cmd.cmd_id}: {run.cmd.subsystem}/{run.entry.name}: handler raised "
                     f"{type(exc).__name__}: {_text(exc)[:300]}{where}")

    # ---- told to stop: the stop bound ---------------------------------------------------------
    def bound_ms(self, run: Run) -> int:
        return run.entry.stop_timeout_ms or self.stop_timeout_ms

    def _tell_stop(self, run: Run) -> None:
        """Tell a running handler to stop (ctx.cancelled) and start its stop bound: if it has not
        returned by then, _overdue answers the command. Told again: the first deadline stays."""
        if run.ctx is None or run.done:
            return
        run.ctx.cancelled.set()
        if not run.running or run.stop_by is not None:
            return
        run.stop_by = time.monotonic() + self.bound_ms(run) / 1000.0
        self._stopping.add(run)
        if self._watchdog is None:
            self._watchdog = threading.Thread(target=self._watch_loop, daemon=True, name="rapid-stop-bound")
            self._watchdog.start()
        self._watch.notify_all()

    def _watch_loop(self) -> None:
        """The one watchdog thread: sleeps until the earliest stop deadline, answers what is overdue;
        it ends when no handler is being stopped (the next _tell_stop makes another), so a
        manager that is dropped leaves no thread behind."""
        while True:
            with self.lock:
                while True:
                    now = time.monotonic()
                    due = [r for r in self._stopping if r.stop_by is not None and r.stop_by <= now]
                    if due:
                        break
                    nearest = min((r.stop_by for r in self._stopping if r.stop_by is not None), default=None)
                    if nearest is None:
                        self._watchdog = None  # (under the lock _tell_stop takes: it starts a new one)
                        return
                    self._watch.wait(max(0.001, nearest - now))
            with self.batch():
                for run in sorted(due, key=lambda r: r.stop_by or 0.0):
                    self._overdue(run)

    def _overdue(self, run: Run) -> None:
        """A told-to-stop handler still running at its bound: the command's final ack now, its
        place in the queue freed; the handler's later return is ignored (run.done)."""
        self._stopping.discard(run)
        if run.done or not run.running:
            return
        run.requeue = False
        if run in self.bypass:
            self.bypass.remove(run)
        self.out.log(f"{run.cmd.cmd_id}: {run.cmd.subsystem}/{run.entry.name}: handler did not stop within "
                     f"{self.bound_ms(run)} ms of being told to; answered EXEC_FAILED \"{DID_NOT_STOP}\"; "
                     f"the robot must stop it in hardware")
        self._complete(run, EXEC_FAILED, DID_NOT_STOP, suspend=False)
        self._service()

    def _stop_all_motion_outcome(self, run: Run, outcome: tuple[str, str]) -> tuple[str, str]:
        """stopAllMotion's answer: the generated stub (or no method) is no failure, the runtime
        has canceled the motion commands; motion handlers still running are said."""
        if outcome == (EXEC_FAILED, NOT_IMPLEMENTED):
            outcome = OK, NO_HARDWARE_STOP
        left = sum(1 for r in run.stopped if r.running and not r.done)
        if left:
            outcome = outcome[0], "; ".join(p for p in (outcome[1], texts.motion_not_stopped(left)) if p)
        return outcome

    def _complete(self, run: Run, completion: str, message: str, suspend: bool = True) -> None:
        run.done = True
        self._stopping.discard(run)
        self._ack(run.cmd, COMPLETED, completion, message)
        if self.shutdown_after is run and self.on_shutdown is not None:  # once its COMPLETED ack is written
            self._emit(threading.Thread(target=self.on_shutdown, daemon=True, name="shutdown").start)
        if run.queued:
            if self.active is run:
                self.active = None
            self._record_done(run, completion)
            if completion == EXEC_FAILED and suspend and not self.closing:
                self.suspended = True  # a failed step stops the plan; Queue/cancelAll resumes
        if self.active is None:
            self.idle.notify_all()

    def _finish_unstarted(self, run: Run, why: str) -> None:
        """A pending command removed before it ran (DELETE, REPLACE, cancelAll, stopAllMotion)."""
        run.done = True
        self._ack(run.cmd, COMPLETED, CANCELED, why)
        self._record_done(run, CANCELED)

    def _record_done(self, run: Run, completion: str) -> None:
        self.completed.append((self.clock(), run, completion))
        while len(self.completed) > RECORDS:
            self.completed.popleft()

    @staticmethod
    def _abortable(run: Run) -> bool:
        return run.entry is not None and run.entry.abortable

    def _cancel(self, run: Run) -> None:
        if run.ctx is not None:
            run.requeue = False
            self._tell_stop(run)

    # ---- state topics ------------------------------------------------------------------------
    def _ack(self, cmd: Cmd, status: str, completed: str, message: str, journal: bool = True) -> None:
        """Every ack goes out here, its message clipped (acks.clip: at most 127 UTF-8 bytes,
        nothing cyclonedds cannot encode), whoever wrote it: the runtime's reasons, handler
        results, progress texts. A write that still fails is logged: the command's state
        moves on all the same (a lost ack must not leave the queue stuck). With a journal, the
        step the ack promises is recorded first (written out after the batch's sync)."""
        message = clip(message)
        noted = None
        if self.journal is not None and journal:
            step = {QUEUED: "q", EXECUTING: "x", COMPLETED: "c"}.get(status)
            if step is not None:
                noted = self.journal.note(cmd, step, completed, message)
        self._emit(lambda: self._write_ack(cmd, status, completed, message))
        if status == COMPLETED:  # each command's last ack: keep the last `window` commands' acks
            # the journal's entry for its outcome when there is one (the journal keeps it too)
            kept = noted if noted is not None else _Kept(cmd.cmd_id, cmd.src_name, cmd.asset_name, cmd.serial,
                                                         completed, message)
            self._keep(kept)
            self.seen.answered(kept)  # a resend of its cmdId gets this final ack again

    def _write_ack(self, cmd: Cmd, status: str, completed: str, message: str) -> None:
        try:
            self.out.ack(cmd, status, completed, message)
        except Exception as exc:  # DDS refusing a write: the commander hears nothing of this one
            self.out.log(f"{status} ack of {cmd.cmd_id!r} not written: {type(exc).__name__}: {str(exc)[:120]}")

    def _keep(self, key) -> None:
        """key: a _Kept or a journal.Entry (what retiring the acks needs: cmd_id, src_name,
        asset_name, serial)."""
        self.acked.append(key)
        while len(self.acked) > self.window:
            old = self.acked.popleft()
            if not self._live(old.cmd_id):  # its id sent again (after the window) and still running
                self._emit(functools.partial(self.out.retire, _entry_cmd(old)))

    def _publish_queue(self) -> None:
        if not self.has_queue:
            return
        now = self.clock()
        while self.completed and now - self.completed[0][0] > COMPLETED_KEEP_S:
            self.completed.popleft()
        pending = [(r.cmd, "Q_RESULT_INIT", r.record_status) for r in list(self.pending)[:RECORDS]]
        active = [(self.active.cmd, "Q_RESULT_INIT", "Q_STATUS_INPROCESS")] if self.active else []
        done = [(r.cmd, RESULT_OF_COMPLETION[c], STATUS_OF_COMPLETION[c]) for _, r, c in self.completed]
        code = -1 if self.suspended else (1 if self.active else 0)
        self._emit(lambda: self.out.queue_state(code, pending, active, done))

    def publish_states(self) -> None:
        """Publish QueueState and AccessControlState as they are (at start-up)."""
        with self.batch():
            self._publish_queue()
            if self.has_control:
                self._access_state()

    def _access_state(self) -> None:
        controller, requestors = self.control.controller, list(self.control.requestors)
        self._emit(lambda: self.out.access_state(controller, requestors))

    def restore(self, recovered) -> tuple[int, int]:
        """After a crash (journal.Recovered): answer what was accepted and not finished (never
        run again), write the last outcomes' final acks again, remember their cmdIds. Returns
        (commands answered now, final acks written again)."""
        with self.batch():
            for e in recovered.finished:
                self.seen.add(e.cmd_id)
                self.seen.answered(e)
                self._emit(functools.partial(self._write_ack, _entry_cmd(e), COMPLETED, e.completion, e.message))
                self._keep(e)
            for e in recovered.unfinished:
                self.seen.add(e.cmd_id)
                completion, why = (CANCELED, RESTARTED_QUEUED) if e.state == "q" else (EXEC_FAILED, RESTARTED_RUNNING)
                self._ack(_entry_cmd(e), COMPLETED, completion, why)
        return len(recovered.unfinished), len(recovered.finished)

    def shutdown(self, timeout: float) -> tuple[int, int]:
        """The bridge stops (Admin/shutdown, a signal): nothing starts any more; every pending
        command is answered COMPLETED/CANCELED "asset shutting down", every running handler told
        to stop; their handlers get up to `timeout` seconds to return (their own outcome), then
        each one still running is answered EXEC_FAILED "handler did not stop" (its thread ends
        with the process). Returns (commands in flight at the start, handlers that did not stop)."""
        end = time.monotonic() + max(0.0, timeout)
        with self.batch():
            self.closing = True
            runs = [*self.pending, *([self.active] if self.active else []), *self.bypass]
            for r in list(self.pending):
                self.pending.remove(r)
                r.done = True
                self._ack(r.cmd, COMPLETED, CANCELED, SHUTTING_DOWN)
                self._record_done(r, CANCELED)
            for r in [*([self.active] if self.active else []), *self.bypass]:
                r.requeue = False
                if r.ctx is not None:
                    r.ctx.cancelled.set()  # told to stop; the shutdown's bound, not the command's
            self._publish_queue()
        with self.lock:
            while any(r.running and not r.done for r in runs):
                left = end - time.monotonic()
                if left <= 0:
                    break
                self.idle.wait(min(left, 0.05))
        with self.batch():
            stuck = [r for r in runs if not r.done]
            for r in stuck:
                if r in self.bypass:
                    self.bypass.remove(r)
                self.out.log(f"{r.cmd.cmd_id}: {r.cmd.subsystem}/{r.entry.name}: handler did not stop within the "
                             f"shutdown bound ({timeout * 1000:.0f} ms); answered EXEC_FAILED \"{DID_NOT_STOP}\"; "
                             f"the robot must stop it in hardware")
                self._complete(r, EXEC_FAILED, DID_NOT_STOP, suspend=False)
            self.active = None
            self.bypass.clear()
            self._publish_queue()
            self.idle.notify_all()
        return len(runs), len(stuck)

    def abandon(self) -> int:
        """Answer every pending and running command now, not waiting for any handler (shutdown(0))."""
        return self.shutdown(0.0)[0]

    def handlers_running(self) -> int:
        """Handler methods called and not returned, answered or not (threads a stop leaves behind)."""
        with self.lock:
            return self._handlers_running

    def wait_idle(self, timeout: float) -> bool:
        """True once no queued or bypass command runs (tests, shutdown)."""
        end = time.monotonic() + timeout
        with self.lock:
            while self.active is not None or self.bypass or len(self.pending) and not self.closing:
                left = end - time.monotonic()
                if left <= 0 or self.suspended and self.active is None and not self.bypass:
                    return not (self.active or self.bypass)
                self.idle.wait(min(left, 0.05))
            return True


class _Recent:
    """The last `size` cmdIds, the oldest forgotten first: `in` and len(). A dict and a deque
    (about 60 bytes an id; an OrderedDict costs about 115). The dict's value is the command's
    final outcome once it has one (a _Kept or journal Entry, the object the window keeps
    anyway): a resend of the cmdId is answered with it."""
    __slots__ = ("ids", "order", "size")

    def __init__(self, size: int) -> None:
        self.ids: dict[str, object] = {}
        self.order: collections.deque[str] = collections.deque()
        self.size = size

    def add(self, cmd_id: str) -> None:
        if cmd_id in self.ids:
            return  # it keeps its place (as an OrderedDict's key does)
        self.ids[cmd_id] = None
        self.order.append(cmd_id)
        while len(self.order) > self.size:
            del self.ids[self.order.popleft()]

    def __contains__(self, cmd_id: object) -> bool:
        return cmd_id in self.ids

    def answered(self, kept) -> None:
        """The cmdId's final outcome (when the id is still among the last `size`)."""
        if kept.cmd_id in self.ids:
            self.ids[kept.cmd_id] = kept

    def final(self, cmd_id: str):
        """The stored final outcome (completion, message, header names), or None."""
        return self.ids.get(cmd_id)

    def __len__(self) -> int:
        return len(self.ids)

    def __iter__(self):
        return iter(self.ids)


class _Kept(NamedTuple):
    """A completed command as the window keeps it without a journal (with one, the journal's
    Entry of its outcome, which has the same fields): what retiring its acks needs (the ack
    key: header names and cmdId; the header's serial), not the received sample and arguments,
    and a tuple (a Cmd costs twice as much)."""
    cmd_id: str
    src_name: str
    asset_name: str
    serial: int
    completion: str  # the final ack, written again when the cmdId is sent again
    message: str


def _text(x: object) -> str:
    """str(x) for a message, never raising (a handler's exception or result may not print)."""
    if isinstance(x, str):
        return x
    try:
        return str(x)
    except Exception as exc:
        return f"<unprintable {type(x).__name__}: {type(exc).__name__}>"


def _is_stop_all_motion(entry: CommandEntry) -> bool:
    return entry.standard and (entry.subsystem_type, entry.name) == ("Mobility", "stopAllMotion")


def _entry_cmd(e) -> Cmd:
    """A journal entry (or a _Kept) as the Cmd its acks need (header names, serial, cmdId)."""
    return Cmd(e.cmd_id, "", "", "", src_name=e.src_name, asset_name=e.asset_name, serial=e.serial)


def _as_sender(delete: Cmd, target: Cmd) -> Cmd:
    """The DELETE checked as its sender sending the target's command."""
    from dataclasses import replace
    return replace(target, cmd_src=delete.cmd_src)


# ---- built-in commands: the protocol's own (Admin, Queue, AccessControl, stopAllMotion) ----------
# Each returns (completion, message), or None to go on to the handler method.

def _echo(m: CommandManager, run: Run):
    return OK, str(run.kwargs.get(run.entry.params[0].arg, "")) if run.entry.params else ""


def _noop(m: CommandManager, run: Run):
    return OK, ""


def _shutdown(m: CommandManager, run: Run):
    m.shutdown_after = run  # once its COMPLETED ack is out
    return OK, texts.SHUTTING_DOWN


def _cancel_all(m: CommandManager, run: Run):
    for r in list(m.pending):
        m.pending.remove(r)
        m._finish_unstarted(r, texts.CANCELED_BY_CANCEL_ALL)
    kept = asked = 0
    for r in [m.active, *m.bypass]:
        if r is None or r is run or r.done:
            continue
        if m._abortable(r):
            m._cancel(r)
            asked += 1
        else:
            kept += 1
    m.suspended = False
    parts = [texts.handlers_asked_to_stop(asked) if asked else "", texts.non_abortable_running(kept) if kept else ""]
    return OK, "; ".join(p for p in parts if p)


def _stop_all_motion(m: CommandManager, run: Run):
    """Motion stops first (every Mobility command canceled, abortable or not), then the
    handler method stops the hardware."""
    mobility = set(m.tables.subsystems_of_type("Mobility"))
    for r in list(m.pending):
        if r.cmd.subsystem in mobility:
            m.pending.remove(r)
            m._finish_unstarted(r, texts.CANCELED_BY_STOP_ALL_MOTION)
    for r in [m.active, *m.bypass]:
        if r is not None and r is not run and r.cmd.subsystem in mobility and not r.done:
            m._cancel(r)
            run.stopped += (r,)
    return None


def _control(op: str):
    def run_op(m: CommandManager, run: Run):
        src = run.cmd.cmd_src
        if op == "transfer":
            err, note = m.control.transfer(src, str(next(iter(run.kwargs.values()), "")))
        else:
            err, note = getattr(m.control, op)(src)
        if err is None:
            m._access_state()
        return (EXEC_FAILED, err) if err else (OK, note)
    return run_op


BUILTINS: dict[tuple[str, str], Callable] = {
    ("Admin", "echo"): _echo,
    ("Admin", "noOp"): _noop,
    ("Admin", "shutdown"): _shutdown,
    ("Queue", "cancelAll"): _cancel_all,
    ("Mobility", "stopAllMotion"): _stop_all_motion,
    ("AccessControl", "requestControl"): _control("request"),
    ("AccessControl", "grabControl"): _control("grab"),
    ("AccessControl", "releaseControl"): _control("release"),
    ("AccessControl", "transferControl"): _control("transfer"),
}
