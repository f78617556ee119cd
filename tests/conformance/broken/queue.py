"""Broken assets: the command queue (conformance/queue.py)."""
from __future__ import annotations

import dataclasses
import threading

from . import kind


@kind("queue-status-code", "QUE-01")
def queue_status_code(a):
    """statusCode 2: none of suspended (-1), idle (0), active (1). QUE-05 is then BLOCKED."""
    queue_state = a.bridge.queue_state
    a.bridge.queue_state = lambda code, *lists: queue_state(2, *lists)


def _serviced_at_10hz(a, newest_first: bool) -> None:
    """The queue started by an executive tick at 10 Hz, as soraCore does (rapid-protocol.md 5b),
    instead of at once: commands appended within a tick wait in the queue together."""
    m = a.manager
    service = m._service
    m._service = m._publish_queue  # intake and completions only publish the state
    if newest_first:
        items = m.pending.items
        m.pending.pop_ready = lambda busy: items.pop() if items and not busy(items[-1].cmd.subsystem) else None

    def tick():
        while not a.bridge.stopped.wait(0.1):
            with m.lock:
                service()
    threading.Thread(target=tick, daemon=True, name="queue-tick").start()


@kind("queue-10hz", None)
def queue_10hz(a):
    """soraCore's queue servicing (10 Hz tick), in order: must pass."""
    _serviced_at_10hz(a, newest_first=False)


@kind("queue-lifo", "QUE-02")
def queue_lifo(a):
    """A 10 Hz queue kept as a stack: of the commands waiting, the newest runs first."""
    _serviced_at_10hz(a, newest_first=True)


@kind("append-target-ignored", "QUE-03")
def append_target_ignored(a):
    """APPEND with a targetCmdId is appended anyway (the target is never looked at)."""
    m = a.manager
    intake = m._intake
    m._intake = lambda cmd: intake(dataclasses.replace(cmd, target="") if cmd.action == "QUEUE_APPEND" else cmd)


@kind("delete-wrong-command", "QUE-04")
def delete_wrong_command(a):
    """DELETE of a pending command cancels the running one instead (the queue's head);
    the named command stays and runs."""
    m = a.manager
    delete = m._delete

    def head_instead(cmd):
        if m.active is not None and m._queued_run(cmd.target) is not None:
            cmd = dataclasses.replace(cmd, target=m.active.cmd.cmd_id)
        return delete(cmd)
    m._delete = head_instead


@kind("queue-record-status", "QUE-05")
def queue_record_status(a):
    """Pending commands reported as already succeeded."""
    records = a.M.queue_state

    def succeeded(rapid, hdr, pending, active, completed):
        return records(rapid, hdr, [(c, r, "Q_STATUS_SUCCEEDED") for c, r, _ in pending], active, completed)
    a.M.queue_state = succeeded


@kind("queue-parallel", "QUE-02")
def queue_parallel(a):
    """Queued commands acknowledged QUEUED, then all started at once (each on its own
    thread, none waiting for the one before): an instant command behind a long drive
    executes while the drive still runs. QUE-04 and QUE-05 are then BLOCKED."""
    m = a.manager

    def start_all():
        while not m.suspended:
            run = m.pending.pop_ready(lambda subsystem: False)
            if run is None:
                break
            m.active = run
            m._start(run)
            if not run.done and run not in m.bypass:  # where cancelAll and stopAllMotion still reach it
                m.bypass.append(run)
        m._publish_queue()
    m._service = start_all


@kind("queue-state-stale", "QUE-07")
def queue_state_stale(a):
    """QueueState is not republished when a handler finishes: the finished drive stays listed
    active until the next command changes the queue (instant built-ins, done before intake
    republishes, look right)."""
    m = a.manager
    execute, publish = m._execute, m._publish_queue
    finishing = threading.local()

    def quiet_execute(run):
        finishing.on = True  # the handler's thread: its completion publishes nothing
        try:
            execute(run)
        finally:
            finishing.on = False
    m._execute = quiet_execute
    m._publish_queue = lambda: None if getattr(finishing, "on", False) else publish()


@kind("insert-at-back", "QUE-06")
def insert_at_back(a):
    """QUEUE_INSERT is appended at the back of the queue instead of after its target."""
    pending = a.manager.pending

    def at_back(target, run):
        pending.append(run)
        return True
    pending.insert_after = at_back


@kind("replace-at-back", "QUE-06")
def replace_at_back(a):
    """QUEUE_REPLACE cancels its target but puts the new command at the back."""
    pending = a.manager.pending

    def at_back(target, run):
        old = pending.find(target)
        if old is not None:
            pending.remove(old)
            pending.append(run)
        return old
    pending.replace = at_back
